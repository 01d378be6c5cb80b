"""The capture's readers fed mutated files: a clean AxiscalError naming the file, or a correct parse."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from axiscal.capture import plan_steps, read_recording
from axiscal.errors import AxiscalError
from axiscal.positioning.plan import plan_test, write_plan

RECORDING = "time_s,reading_mm,air_temperature_c,pressure_pa,humidity_pct\n" + "".join(
    f"{k / 100:.2f},{0.001 * (k // 20):.6f},20.1,101300,45\n" for k in range(60)
)


def mutations():
    return st.one_of(
        st.tuples(st.just("delete"), st.integers(0, 10_000), st.integers(1, 40)),
        st.tuples(st.just("insert"), st.integers(0, 10_000), st.text(alphabet=",.-+e0123456789 \nnaif\t\r\"x", min_size=1, max_size=12)),
        st.tuples(st.just("replace"), st.integers(0, 10_000), st.text(min_size=1, max_size=6)),
    )


def mutate(text: str, edits) -> str:
    for kind, at, what in edits:
        at = at % (len(text) + 1)
        if kind == "delete":
            text = text[:at] + text[at + what:]
        elif kind == "insert":
            text = text[:at] + what + text[at:]
        else:
            text = text[:at] + what + text[at + len(what):]
    return text


@settings(max_examples=120, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(st.lists(mutations(), min_size=1, max_size=3))
def test_a_mutated_recording_is_read_or_refused_cleanly(tmp_path, edits):
    path = tmp_path / "rec.csv"
    path.write_text(mutate(RECORDING, edits), encoding="utf-8", errors="surrogatepass")
    try:
        rec = read_recording(path)
    except AxiscalError as exc:
        assert exc.path is not None and str(path) in str(exc)
        return
    assert rec.time_s.shape == rec.reading_m.shape and np.all(np.diff(rec.time_s) >= 0)
    assert np.all(np.isfinite(rec.time_s)) and np.all(np.isfinite(rec.reading_m))


@settings(max_examples=80, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(st.lists(mutations(), min_size=1, max_size=3))
def test_a_mutated_plan_is_read_or_refused_cleanly(tmp_path, edits):
    write_plan(plan_test(0.0, 0.2, 5, runs=1, seed=1), tmp_path / "plan.csv")
    text = (tmp_path / "plan.csv").read_text()
    (tmp_path / "plan.csv").write_text(mutate(text, edits), encoding="utf-8", errors="surrogatepass")
    try:
        steps = plan_steps(tmp_path / "plan.csv")
    except AxiscalError as exc:
        assert "plan.csv" in str(exc)
        return
    assert steps.readings >= 1 and np.all(np.diff(steps.step) > 0)


@pytest.mark.parametrize("text, unit, channel, message", [
    ("t,reading_mm\n0,1\n", None, None, "no time column"),
    ("time_s,a_mm,b_mm\n0,1,2\n", None, None, "channel must name the column"),
    ("time_s,reading\n0,1\n", None, None, "unit must be given"),
    ("time_s,reading_mm\n0,1\n", "um", None, "in mm, not in um"),
    ("time_s,reading_mm\n0,1\n", None, "laser_um", "no column 'laser_um'"),
    ("time_s,reading_mm\n1,1\n0,1\n", None, None, "goes back"),
])
def test_bad_recordings_name_the_file(tmp_path, text, unit, channel, message):
    (tmp_path / "r.csv").write_text(text)
    with pytest.raises(AxiscalError, match=message) as info:
        read_recording(tmp_path / "r.csv", unit=unit, channel=channel)
    assert "r.csv" in str(info.value)


def test_an_rtx_recording_needs_its_unit(tmp_path):
    from axiscal.io.importers.rtx import write_rtx

    write_rtx(tmp_path / "c.rtx", [0.0, 1.0, 2.0], sample_rate_hz=10.0, unit="mm")
    with pytest.raises(AxiscalError, match="unit must be given"):
        read_recording(tmp_path / "c.rtx")
    rec = read_recording(tmp_path / "c.rtx", unit="um")
    assert rec.reading_m.tolist() == pytest.approx([0.0, 1e-6, 2e-6]) and rec.time_s.tolist() == pytest.approx([0, 0.1, 0.2])
