"""ISO 10360-2 length test: E0, E150, R0 and the ISO 14253-1 decision, on hand-computed examples."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.cmm import LengthMeasurements, Mpe, evaluate_acceptance, length_acceptance, read_length_measurements
from axiscal.errors import AxiscalError

UM, MM = 1e-6, 1e-3


def _measurements(rows, offset_mm=0.0):
    """rows: (position, length, nominal_mm, error_um, repeat)."""
    position, length, nominal, error, repeat = zip(*rows)
    nominal_m = np.array(nominal) * MM
    return LengthMeasurements(tuple(position), tuple(length), nominal_m, nominal_m + np.array(error) * UM,
                              list(repeat), [offset_mm * MM] * len(rows))


HAND = _measurements([
    ("1", "L5", 500.0, 2.0, 1), ("1", "L5", 500.0, 2.6, 2), ("1", "L5", 500.0, 3.4, 3),
    ("1", "L2", 100.0, -1.0, 1), ("1", "L2", 100.0, -1.9, 2), ("1", "L2", 100.0, -2.5, 3),
])


def test_mpe_forms_as_data_sheets_state_them():
    """E0,MPE = ±(1.5 + L/333) um, L in mm: 3.0015 um at 500 mm; capped at B = 2.5 um; constant ±B."""
    assert Mpe(1.5 * UM, k=333.0).at([0.5])[0] / UM == pytest.approx(1.5 + 500 / 333)
    assert Mpe(1.5 * UM, k=333.0, b_m=2.5 * UM).at([0.1, 0.5]) / UM == pytest.approx([1.5 + 100 / 333, 2.5])
    assert Mpe(2.5 * UM).at([0.02, 1.0]) / UM == pytest.approx([2.5, 2.5])
    assert Mpe(1.5 * UM, k=333.0, b_m=2.5 * UM).statement() == "±min(1.5 + L/333, 2.5) um, L in mm"


def test_hand_computed_guard_band():
    """Worked by hand with MPE = 1.5 + L/333 um and U = 0.2 um + 1 um/m x L (ISO 14253-1 guard band).

    L = 500 mm: MPE 3.0015 um, U 0.7 um: conformance proven for |E| <= 2.3015, non-conformance
    beyond 3.7015: 2.0 pass, 2.6 and 3.4 no decision.
    L = 100 mm: MPE 1.8003 um, U 0.3 um: pass up to 1.5003, fail beyond 2.1003: 1.0 pass, 1.9 no
    decision, 2.5 fail. R0 = the larger range, 1.5 um (the 100 mm set; the 500 mm set ranges 1.4).
    """
    r = length_acceptance(HAND, mpe=Mpe(1.5 * UM, k=333.0), r0_mpl_m=1.6 * UM, uncertainty_m=0.2 * UM,
                          uncertainty_per_m=1.0 * UM)
    assert r.verdicts == ("pass", "inconclusive", "inconclusive", "pass", "inconclusive", "fail")
    assert r.mpe_m[:3] / UM == pytest.approx([3.0015015] * 3)
    assert r.U_m / UM == pytest.approx([0.7] * 3 + [0.3] * 3)
    assert r.r0_m / UM == pytest.approx(1.5)
    assert r.r0_verdict == "pass"
    assert r.verdict_of("E0") == "fail" and r.verdict == "fail"
    assert r.decisive("E0") == 5
    summary = r.summary("E0")
    assert summary["max_abs_um"] == pytest.approx(3.4) and summary["at_nominal_mm"] == pytest.approx(500.0)
    assert summary["counts"] == {"pass": 2, "inconclusive": 3, "fail": 1}
    assert r.summary("E150") is None and r.verdict_of("E150") == "not assessed"


def test_hand_computed_simple_rule_and_cap():
    """Simple acceptance: |E| <= MPE. With the cap B = 2.5 um the 500 mm MPE is 2.5, not 3.0015."""
    r = length_acceptance(HAND, mpe=Mpe(1.5 * UM, k=333.0), rule="simple")
    assert r.verdicts == ("pass", "pass", "fail", "pass", "fail", "fail")
    capped = length_acceptance(HAND, mpe=Mpe(1.5 * UM, k=333.0, b_m=2.5 * UM), rule="simple")
    assert capped.verdicts[:3] == ("pass", "fail", "fail")


def test_r0_beyond_its_limit_fails_alone():
    ok = _measurements([("1", "L1", 20.0, e, i + 1) for i, e in enumerate((0.1, 0.9, 0.4))])
    r = length_acceptance(ok, mpe=Mpe(1.5 * UM, k=333.0), r0_mpl_m=0.5 * UM)
    assert r.verdict_of("E0") == "pass" and r.r0_m / UM == pytest.approx(0.8) and r.verdict == "fail"


def test_e150_is_kept_apart_and_needs_its_own_mpe():
    e0 = _measurements([("1", "L1", 100.0, 1.0, 1)])
    e150 = _measurements([("1", "L1", 100.0, 3.1, 1)], offset_mm=150.0)
    both = LengthMeasurements(e0.position + e150.position, e0.length + e150.length,
                              np.r_[e0.nominal_m, e150.nominal_m], np.r_[e0.measured_m, e150.measured_m],
                              [1, 1], np.r_[e0.ram_offset_m, e150.ram_offset_m])
    r = length_acceptance(both, mpe=Mpe(1.5 * UM, k=333.0))
    assert r.test == ("E0", "E150") and r.verdicts == ("pass", "not assessed")
    r = length_acceptance(both, mpe=Mpe(1.5 * UM, k=333.0), mpe_150=Mpe(2.5 * UM, k=250.0))
    assert r.verdicts == ("pass", "fail")  # 3.1 um > 2.5 + 100/250 = 2.9 um
    assert r.summary("E150")["mpe"]["statement"] == "±(2.5 + L/250) um, L in mm"


def test_retest_sets_of_iso_10360_2():
    """At most five sets with one value, and only one, outside: those may be measured again."""
    rows = [("1", "L1", 100.0, e, i + 1) for i, e in enumerate((0.5, 2.0, 0.4))]
    rows += [("2", "L1", 100.0, e, i + 1) for i, e in enumerate((0.5, 0.6, 0.4))]
    r = length_acceptance(_measurements(rows), mpe=Mpe(1.5 * UM, k=333.0), rule="simple")
    assert r.retest_sets() == [{"test": "E0", "position": "1", "length": "L1"}]
    rows[0] = ("1", "L1", 100.0, 2.1, 1)
    r = length_acceptance(_measurements(rows), mpe=Mpe(1.5 * UM, k=333.0), rule="simple")
    assert r.retest_sets() == []


@settings(max_examples=60, deadline=None)
@given(st.floats(-5, 5), st.floats(0, 2), st.floats(0.01, 1.0))
def test_guard_band_never_contradicts_the_simple_rule(error_um, u_um, length_m):
    """A value the guard band passes passes the simple rule; one it fails fails the simple rule too."""
    m = _measurements([("1", "L", length_m / MM, error_um, 1)])
    guard = length_acceptance(m, mpe=Mpe(1.5 * UM, k=333.0), uncertainty_m=u_um * UM, rule="guard-band").verdicts[0]
    simple = length_acceptance(m, mpe=Mpe(1.5 * UM, k=333.0), rule="simple").verdicts[0]
    assert guard == "inconclusive" or guard == simple


def test_the_example_file(examples):
    r = evaluate_acceptance(examples / "cmm" / "e0_gauge_blocks.csv", mpe=Mpe(1.8 * UM, k=300.0),
                            mpe_150=Mpe(2.2 * UM, k=250.0), r0_mpl_m=1.2 * UM, uncertainty_m=0.3 * UM,
                            uncertainty_per_m=1.0 * UM)
    assert r.summary("E0")["count"] == 105 and r.summary("E150")["count"] == 30
    assert r.warnings == ()
    assert r.verdict == "pass"
    assert "verdict: pass" in r.report()


def test_bad_files_name_the_line(tmp_path):
    path = tmp_path / "e0.csv"
    path.write_text("position,length,nominal_mm,measured_mm,repeat\n1,L1,100,100.001,1\n1,L1,100,100.002,1\n")
    with pytest.raises(AxiscalError, match="given twice") as caught:
        read_length_measurements(path)
    assert caught.value.line == 3
    path.write_text("position,length,nominal_mm,measured_mm,repeat\n1,L1,-100,100.001,1\n")
    with pytest.raises(AxiscalError, match="nominal_mm must be positive"):
        read_length_measurements(path)
    path.write_text("position,length,nominal_mm,measured_mm,repeat\n1,L1,100,100.001,1.5\n")
    with pytest.raises(AxiscalError, match="repeat must be a whole number"):
        read_length_measurements(path)
    path.write_text("position,length,nominal_mm,repeat\n1,L1,100,1\n")
    with pytest.raises(AxiscalError, match="missing column 'measured_mm'"):
        read_length_measurements(path)
    path.write_text("position,length,nominal_mm,measured_mm,repeat\n1,L1,100,100.001,1\n1,L1,100.5,100.001,2\n")
    with pytest.raises(AxiscalError, match="nominal length differs") as caught:
        evaluate_acceptance(path)
    assert caught.value.line == 3


def test_the_warnings_of_a_short_test():
    r = length_acceptance(HAND)
    assert "7 positions x 5 lengths x 3 repeats" in r.warnings[0]
    assert r.verdict == "not assessed"


@pytest.mark.parametrize(("nominal_mm", "measured_mm"), [(100.0, 100001.2), (0.1, 100.0012), (100.0, 125.0)])
def test_a_measured_length_in_another_unit_is_refused_naming_its_line(tmp_path, nominal_mm, measured_mm):
    """An error of indication is micrometres: a value in um under measured_mm, a nominal in metres or another gauge
    is refused (it gave 'E0 largest |E| 699302399.520 um, verdict: fail' before)."""
    path = tmp_path / "e0.csv"
    path.write_text("position,length,nominal_mm,measured_mm,repeat\n1,L1,100,100.001,1\n"
                    f"1,L2,{nominal_mm},{measured_mm},1\n")
    with pytest.raises(AxiscalError, match="times the nominal") as caught:
        read_length_measurements(path)
    assert caught.value.line == 3 and caught.value.path == str(path)
    with pytest.raises(AxiscalError, match="another unit"):
        _measurements([("1", "L1", 100.0, 1e4 * 1e3, 1)])


def test_a_close_error_is_read():
    """Ten per cent of the nominal is the bound: a gross but plausible error still reads."""
    m = _measurements([("1", "L1", 100.0, 9.9e3, 1)])
    assert m.error_m[0] == pytest.approx(9.9 * MM)


@pytest.mark.parametrize(("stated", "words"), [
    (dict(mpe_150=Mpe(2.5 * UM)), "mpe_150 is given, but the measurements hold no E150 value"),
    (dict(r0_mpl_m=1 * UM), "r0_mpl_m is given, but the measurements hold no E0 value"),
    (dict(mpe=Mpe(2.5 * UM)), "mpe is given, but the measurements hold no E0 value"),
])
def test_a_limit_of_a_test_without_values_is_refused(stated, words):
    only = _measurements([("1", "L1", 100.0, 1.0, 1)], offset_mm=0.0 if "150" in words else 150.0)
    with pytest.raises(AxiscalError, match=words):
        length_acceptance(only, **stated)


@pytest.mark.parametrize(("call", "words"), [
    (lambda: Mpe(1e300), "a_m must be at most 0.01"),
    (lambda: Mpe(1e-6, b_m=1.0), "b_m must be at most 0.01"),
    (lambda: Mpe(1e-6, k=0.5), r"k must be between 1 and 1e\+06"),
    (lambda: length_acceptance(HAND, uncertainty_m=1e300), "uncertainty_m must be at most 0.01"),
    (lambda: length_acceptance(HAND, uncertainty_per_m=1.0), "uncertainty_per_m must be at most 0.01"),
    (lambda: length_acceptance(HAND, r0_mpl_m=1e300), "r0_mpl_m must be at most 0.01"),
])
def test_limits_beyond_ten_millimetres_are_refused(call, words):
    with pytest.raises(AxiscalError, match=words):
        call()
    assert length_acceptance(HAND, mpe=Mpe(10e-3), uncertainty_m=10e-3).verdict == "inconclusive"
