"""ISO 230-2 / VDI 3441 positioning statistics and the run-file reader."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from axiscal.errors import AxiscalError
from axiscal.positioning.evaluation import (
    ISO_SYMBOLS,
    VDI_SYMBOLS,
    PositioningRun,
    iso230_2,
    iso_edition,
    paper003_table4_run,
    target_statistics,
    vdi3441,
)
from axiscal.positioning.reader import read_positioning_run
from axiscal.units import UM

# paper 003, Table 4: three runs at targets 0 and 20 mm (the columns under targets 1 and 2);
# the first column of each target is the approach marked "down", the second "up".
TABLE4_DOWN = np.array([[3.6, -0.2, 3.3], [4.1, 1.9, 2.2]])
TABLE4_UP = np.array([[0.0, 1.2, 1.0], [1.7, 2.0, 1.1]])


def table4_run() -> PositioningRun:
    return PositioningRun(np.array([0.0, 0.020]), TABLE4_UP * UM, TABLE4_DOWN * UM, source="paper 003")


def test_the_shipped_table_4_run_is_the_printed_one():
    shipped = paper003_table4_run()
    reference = table4_run()
    assert shipped.targets == pytest.approx(reference.targets, abs=1e-15)
    assert shipped.deviations_up == pytest.approx(reference.deviations_up, abs=1e-15)
    assert shipped.deviations_down == pytest.approx(reference.deviations_down, abs=1e-15)


def test_paper_003_table_4_per_direction_rows():
    # paper 003, Table 4, columns 1-4 (target 1 down/up, target 2 down/up) and column 5 (target 3 down)
    columns = np.array([[3.6, -0.2, 3.3], [0.0, 1.2, 1.0], [4.1, 1.9, 2.2], [1.7, 2.0, 1.1], [2.0, 1.7, 1.4]])
    targets = np.arange(5) * 0.02
    # one direction per column: put each column in both directions, only the means and s are used here
    st_ = target_statistics(PositioningRun(targets, columns * UM, columns * UM))
    printed_mean = [2.233, 0.733, 2.733, 1.600, 1.700]
    printed_s = [2.113, 0.643, 1.193, 0.458, 0.300]
    printed_2s = [4.225, 1.286, 2.386, 0.917, 0.600]
    printed_mean_minus_2s = [-1.992, -0.552, 0.347, 0.683, 1.100]
    printed_mean_plus_2s = [6.459, 2.019, 5.119, 2.517, 2.300]
    printed_4s = [8.451, 2.572, 4.772, 1.833, 1.200]
    mean, s = st_.mean_up / UM, st_.s_up / UM
    assert np.round(mean, 3) == pytest.approx(printed_mean, abs=1e-12)
    assert np.round(s, 3) == pytest.approx(printed_s, abs=1e-12)
    # the printed 2s/4s/mean+-2s are rounded from the unrounded s (2 x 2.1127 = 4.225, not 4.226)
    assert np.round(2 * s, 3) == pytest.approx(printed_2s, abs=1.01e-3)
    assert np.round(mean - 2 * s, 3) == pytest.approx(printed_mean_minus_2s, abs=1.01e-3)
    assert np.round(mean + 2 * s, 3) == pytest.approx(printed_mean_plus_2s, abs=1.01e-3)
    assert np.round(4 * s, 3) == pytest.approx(printed_4s, abs=1.01e-3)


def test_paper_003_table_4_per_target_rows():
    # paper 003, Table 4: reversal value B_i, bidirectional repeatability R_i, bidirectional mean
    result = iso230_2(table4_run())
    assert np.round(result.stats.reversal / UM, 3).tolist() == [-1.500, -1.133]
    assert np.round(result.repeatability / UM, 3).tolist() == [8.451, 4.772]
    assert np.round(result.stats.mean / UM, 3).tolist() == [1.483, 2.167]


def test_paper_003_table_4_target_3_is_consistent():
    # paper 003, Table 4, target 3: only the down column (2.0, 1.7, 1.4) is printed; B_3 = -0.400
    # and the bidirectional mean 1.500 give mean_up = 1.300, and R_3 = 2.498 then needs
    # 4 s_up = 2.498 (the 2 s + 2 s + |B| branch would give 4 s_up > R_3). Check that reading.
    mean_up, s_up = 1.3, 2.498 / 4
    down = np.array([2.0, 1.7, 1.4])
    s_down = down.std(ddof=1)
    b = mean_up - down.mean()
    r = max(2 * s_up + 2 * s_down + abs(b), 4 * s_up, 4 * s_down)
    assert round(b, 3) == -0.400 and round((mean_up + down.mean()) / 2, 3) == 1.500
    assert round(r, 3) == 2.498


def reference_iso(targets, up, down, k):
    """Plain loops over targets, straight from the ISO 230-2 definitions."""
    m, n = up.shape
    up, down = up.tolist(), down.tolist()
    mu = [sum(up[i]) / n for i in range(m)]
    md = [sum(down[i]) / n for i in range(m)]
    su = [math.sqrt(sum((x - mu[i]) ** 2 for x in up[i]) / (n - 1)) for i in range(m)]
    sd = [math.sqrt(sum((x - md[i]) ** 2 for x in down[i]) / (n - 1)) for i in range(m)]
    b = [mu[i] - md[i] for i in range(m)]
    ri = [max(k * su[i] + k * sd[i] + abs(b[i]), 2 * k * su[i], 2 * k * sd[i]) for i in range(m)]
    bi = [(mu[i] + md[i]) / 2 for i in range(m)]
    return {
        "A": max(max(mu[i] + k * su[i], md[i] + k * sd[i]) for i in range(m))
        - min(min(mu[i] - k * su[i], md[i] - k * sd[i]) for i in range(m)),
        "A_up": max(mu[i] + k * su[i] for i in range(m)) - min(mu[i] - k * su[i] for i in range(m)),
        "A_down": max(md[i] + k * sd[i] for i in range(m)) - min(md[i] - k * sd[i] for i in range(m)),
        "B": max(abs(x) for x in b),
        "B_mean": sum(b) / m,
        "E": max(mu + md) - min(mu + md),
        "E_up": max(mu) - min(mu),
        "E_down": max(md) - min(md),
        "M": max(bi) - min(bi),
        "R": max(ri),
        "R_up": max(2 * k * x for x in su),
        "R_down": max(2 * k * x for x in sd),
        "S_up": max(su),
        "S_down": max(sd),
    }


def reference_vdi(up, down):
    m, n = up.shape
    mu = up.mean(axis=1)
    md = down.mean(axis=1)
    su = np.array([math.sqrt(sum((x - mu[i]) ** 2 for x in up[i]) / (n - 1)) for i in range(m)])
    sd = np.array([math.sqrt(sum((x - md[i]) ** 2 for x in down[i]) / (n - 1)) for i in range(m)])
    u = np.abs(mu - md)
    ps = 6 * (su + sd) / 2
    mean = (mu + md) / 2
    return {
        "P": max(mean[i] + (u[i] + ps[i]) / 2 for i in range(m)) - min(mean[i] - (u[i] + ps[i]) / 2 for i in range(m)),
        "Pa": max(mean) - min(mean),
        "Ps_max": max(ps),
        "Ps_mean": sum(ps) / m,
        "U_max": max(u),
        "U_mean": sum(u) / m,
    }


def random_run(rng, m=None, n=None):
    m = m or int(rng.integers(2, 12))
    n = n or int(rng.integers(2, 7))
    targets = np.cumsum(rng.uniform(0.01, 0.1, m))
    up = rng.normal(0, 3e-6, (m, n)) + rng.normal(0, 5e-6, (m, 1))
    down = rng.normal(0, 3e-6, (m, n)) + rng.normal(0, 5e-6, (m, 1))
    return PositioningRun(targets, up, down)


@pytest.mark.parametrize("edition,k", [("2014", 2), ("2006", 2), ("1997", 2), ("1988", 3)])
def test_iso_matches_plain_reference(edition, k):
    rng = np.random.default_rng(0)
    for _ in range(40):
        run = random_run(rng)
        got = iso230_2(run, edition=edition).figures()
        want = reference_iso(run.targets, run.deviations_up, run.deviations_down, k)
        for name in ISO_SYMBOLS:
            assert got[name] == pytest.approx(want[name], rel=1e-12, abs=1e-18), name


def test_vdi_matches_plain_reference():
    rng = np.random.default_rng(0)
    for _ in range(40):
        run = random_run(rng)
        got = vdi3441(run).figures()
        want = reference_vdi(run.deviations_up, run.deviations_down)
        for name in VDI_SYMBOLS:
            assert got[name] == pytest.approx(want[name], rel=1e-12, abs=1e-18), name


def test_1988_edition_is_the_3_sigma_version():
    run = random_run(np.random.default_rng(1), 6, 5)
    new, old = iso230_2(run), iso230_2(run, edition="1988")
    assert old.coverage == 3 and new.coverage == 2
    assert old.R_up == pytest.approx(1.5 * new.R_up)
    assert old.A_up >= new.A_up
    for name in ("B", "B_mean", "E", "E_up", "E_down", "M", "S_up", "S_down"):
        assert getattr(old, name) == getattr(new, name)


def test_standard_names():
    assert iso_edition("iso230-2:2014") == "2014"
    assert iso_edition("jis-b6192") == "1988"
    with pytest.raises(AxiscalError, match="unknown standard"):
        iso_edition("iso230-2:2030")
    with pytest.raises(AxiscalError, match="unknown ISO 230-2 edition"):
        iso230_2(table4_run(), edition="2030")


def test_vdi_p_equals_primer_form_with_u_folded_into_ps():
    # DOMAIN.md writes Ps_j = 6 s_mean + U_j and P = max(mean + Ps/2) - min(mean - Ps/2): the same P
    run = random_run(np.random.default_rng(2), 8, 5)
    v = vdi3441(run)
    ps_with_u = v.scatter + v.reversal_span
    p = (v.stats.mean + ps_with_u / 2).max() - (v.stats.mean - ps_with_u / 2).min()
    assert v.P == pytest.approx(p, rel=1e-14)


deviation = st.floats(-50e-6, 50e-6, allow_nan=False)


@st.composite
def runs(draw):
    m = draw(st.integers(2, 6))
    n = draw(st.integers(2, 5))
    up = np.array(draw(st.lists(deviation, min_size=m * n, max_size=m * n))).reshape(m, n)
    down = np.array(draw(st.lists(deviation, min_size=m * n, max_size=m * n))).reshape(m, n)
    return PositioningRun(np.arange(m) * 0.05, up, down)


@settings(max_examples=60, deadline=None)
@given(runs(), st.floats(-1e-4, 1e-4))
def test_a_constant_offset_shifts_the_means_and_no_axis_figure(run, c):
    shifted = PositioningRun(run.targets, run.deviations_up + c, run.deviations_down + c)
    a, b = iso230_2(run), iso230_2(shifted)
    for name in ISO_SYMBOLS:
        assert getattr(b, name) == pytest.approx(getattr(a, name), abs=1e-15), name
    assert b.stats.mean_up == pytest.approx(a.stats.mean_up + c, abs=1e-15)
    va, vb = vdi3441(run), vdi3441(shifted)
    for name in VDI_SYMBOLS:
        assert getattr(vb, name) == pytest.approx(getattr(va, name), abs=1e-15), name


@settings(max_examples=60, deadline=None)
@given(runs(), st.randoms(use_true_random=False))
def test_run_order_does_not_matter(run, random):
    order = list(range(run.runs))
    random.shuffle(order)
    permuted = PositioningRun(run.targets, run.deviations_up[:, order], run.deviations_down[:, order])
    a, b = iso230_2(run), iso230_2(permuted)
    for name in ISO_SYMBOLS:
        assert getattr(b, name) == pytest.approx(getattr(a, name), rel=1e-12, abs=1e-18), name


@settings(max_examples=60, deadline=None)
@given(runs())
def test_swapping_directions_mirrors_the_unidirectional_figures(run):
    a = iso230_2(run)
    b = iso230_2(PositioningRun(run.targets, run.deviations_down, run.deviations_up))
    assert b.B_mean == pytest.approx(-a.B_mean, abs=1e-18)
    for same in ("A", "B", "E", "M", "R"):
        assert getattr(b, same) == pytest.approx(getattr(a, same), rel=1e-12, abs=1e-18)
    for x, y in (("A_up", "A_down"), ("E_up", "E_down"), ("R_up", "R_down"), ("S_up", "S_down")):
        assert getattr(b, x) == pytest.approx(getattr(a, y), rel=1e-12, abs=1e-18)


@settings(max_examples=60, deadline=None)
@given(runs())
def test_figure_relations_that_always_hold(run):
    r = iso230_2(run)
    tol = 1e-15
    assert r.R >= max(r.R_up, r.R_down) - tol
    assert r.A >= max(r.A_up, r.A_down) - tol
    assert r.E >= max(r.E_up, r.E_down) - tol
    assert r.E >= r.M - tol
    assert r.B >= abs(r.B_mean) - tol
    assert r.R_up == pytest.approx(4 * r.S_up, rel=1e-12, abs=1e-18)


def test_one_run_gives_no_s_and_says_so():
    run = PositioningRun(np.array([0.0, 0.1, 0.2]), np.array([[1e-6], [2e-6], [0.0]]), np.array([[3e-6], [2e-6], [1e-6]]))
    r = iso230_2(run)
    assert np.all(np.isnan(r.stats.s_up)) and math.isnan(r.R) and math.isnan(r.A) and math.isnan(r.A_up)
    assert r.B == pytest.approx(2e-6) and r.E == pytest.approx(3e-6) and not math.isnan(r.M)
    assert r.warnings and "cannot be estimated" in r.warnings[0]
    assert "2000 mm" not in r.warnings[0]
    v = vdi3441(run)
    assert math.isnan(v.P) and not math.isnan(v.Pa) and v.warnings


def test_one_run_on_a_long_axis_names_the_iso_rule():
    targets = np.linspace(0.0, 3.0, 13)
    run = PositioningRun(targets, np.zeros((13, 1)), np.full((13, 1), 1e-6))
    r = iso230_2(run)
    assert "2000 mm" in r.warnings[0] and math.isnan(r.R) and math.isnan(r.A)


@pytest.mark.parametrize(
    "targets,up,down,message",
    [
        ([0.0, 0.1], [[0.0, 1e-6], [0.0, np.nan]], [[0.0, 0.0], [0.0, 0.0]], "finite"),
        ([0.0, 0.1], [[0.0, 1e-6], [0.0, 0.0]], [[0.0], [0.0]], "unequal run counts"),
        ([0.1, 0.0], [[0.0], [0.0]], [[0.0], [0.0]], "strictly increasing"),
        ([0.0], [[0.0]], [[0.0]], "at least 2 target"),
    ],
)
def test_bad_arrays(targets, up, down, message):
    with pytest.raises(AxiscalError, match=message):
        PositioningRun(np.array(targets), np.array(up), np.array(down))


# ---------------------------------------------------------------- reader


def write(tmp_path, text, name="run.csv"):
    path = tmp_path / name
    path.write_text(text)
    return path


def rows(targets=(0.0, 100.0, 200.0), runs=(1, 2, 3), value=lambda t, r, d: 0.1 * r + (1.0 if d == "+" else -1.0)):
    out = ["target_mm,run,direction,deviation_um"]
    for r, d in itertools.product(runs, "+-"):
        for t in targets:
            out.append(f"{t},{r},{d},{value(t, r, d)}")
    return out


def test_a_raw_deviation_with_air_sensors_is_compensated_as_the_raw_reading(tmp_path):
    # deviation_um beside the air columns is the raw reading less the target (as a capture writes it)
    env = ",21.5,100500,40"
    raw = [r + env for r in rows()[1:]]
    as_deviation = write(tmp_path, "\n".join(["target_mm,run,direction,deviation_um,air_temperature_c,pressure_pa,humidity_pct"] + raw) + "\n")
    actual_rows = []
    for r in rows()[1:]:
        t, run, d, dev = r.split(",")
        actual_rows.append(f"{t},{run},{d},{float(t) + float(dev) / 1000:.7f}" + env)
    folder = tmp_path / "actual"
    folder.mkdir()
    as_actual = write(folder, "\n".join(["target_mm,run,direction,actual_mm,air_temperature_c,pressure_pa,humidity_pct"] + actual_rows) + "\n")
    a, b = read_positioning_run(as_deviation), read_positioning_run(as_actual)
    assert a.compensated and b.compensated
    assert a.run.deviations_up == pytest.approx(b.run.deviations_up, abs=1e-12)
    assert a.run.deviations_down == pytest.approx(b.run.deviations_down, abs=1e-12)


def test_reader_arranges_runs_per_target(tmp_path):
    data = read_positioning_run(write(tmp_path, "\n".join(rows()) + "\n"))
    assert data.run.targets == pytest.approx([0.0, 0.1, 0.2])
    assert data.run.deviations_up[:, 0] == pytest.approx([1.1e-6] * 3)
    assert data.run.deviations_down[:, 2] == pytest.approx([-0.7e-6] * 3)
    assert data.run_labels == ("1", "2", "3") and not data.compensated


def test_reader_actual_positions_and_direction_words(tmp_path):
    lines = ["target_mm,run,direction,actual_mm"]
    for r, d in itertools.product((1, 2), ("up", "DOWN")):
        for t in (0.0, 50.0):
            lines.append(f"{t},{r},{d},{t + (0.002 if d == 'up' else -0.001) + 0.0001 * r}")
    data = read_positioning_run(write(tmp_path, "\n".join(lines)))
    assert data.run.deviations_up == pytest.approx(np.array([[2.1e-6, 2.2e-6]] * 2), abs=1e-12)
    assert data.run.deviations_down == pytest.approx(np.array([[-0.9e-6, -0.8e-6]] * 2), abs=1e-12)


def test_shipped_raw_laser_run_reproduces_the_plain_run(examples):
    plain = read_positioning_run(examples / "positioning_run.csv")
    raw = read_positioning_run(examples / "laser_raw_run.csv")
    assert raw.compensated and not plain.compensated
    assert raw.run.targets == pytest.approx(plain.run.targets)
    # the raw readings are written to 0.1 nm; the example script builds them from the same deviations
    assert np.abs(raw.run.deviations_up - plain.run.deviations_up).max() < 2e-10
    assert np.abs(raw.run.deviations_down - plain.run.deviations_down).max() < 2e-10


def test_uncompensated_raw_readings_would_be_wrong_by_microns(examples, tmp_path):
    # the same file with its environment columns dropped: the readings are then taken as positions
    lines = (examples / "laser_raw_run.csv").read_text().splitlines()
    stripped = [",".join(line.split(",")[:4]) if not line.startswith("#") else line for line in lines]
    naive = read_positioning_run(write(tmp_path, "\n".join(stripped)))
    plain = read_positioning_run(examples / "positioning_run.csv")
    # the air index alone is about 270 ppm: some 200 um at 800 mm
    assert np.abs(naive.run.deviations_up - plain.run.deviations_up).max() > 100e-6


BAD_FILES = {
    "unequal run counts": (rows()[:-1], "unequal run counts", None),
    "target missing a direction": (
        [r for r in rows() if not (r.startswith("100.0,") and ",-," in r)],
        "measured in the \\+ direction only",
        None,
    ),
    "mixed units": (
        ["target_mm,run,direction,deviation_um,deviation_mm"] + [r + ",0" for r in rows()[1:]],
        "mixed units",
        1,
    ),
    "deviation and actual": (
        ["target_mm,run,direction,deviation_um,actual_mm"] + [r + ",0" for r in rows()[1:]],
        "keep exactly one",
        1,
    ),
    "NaN": (rows()[:3] + ["200.0,1,+,nan"] + rows()[4:], "not a finite number", 4),
    "text in a number": (rows()[:3] + ["200.0,1,+,abc"] + rows()[4:], "not a number", 4),
    "bad direction": (rows()[:2] + ["100.0,1,sideways,0.3"] + rows()[3:], "not a direction", 3),
    "duplicate": (rows() + ["0.0,1,+,0.5"], "appears twice", 20),
    "unknown unit": (["target_mm,run,direction,deviation_ft"] + rows()[1:], "unknown unit .ft.", 1),
    "no deviation": (["target_mm,run,direction,value"] + rows()[1:], "no deviation or actual position column", 1),
    "env in part": (
        ["target_mm,run,direction,actual_mm,air_temperature_c"] + [r + ",20" for r in rows()[1:]],
        "missing pressure_pa, humidity_pct",
        1,
    ),
    "env with a rotary deviation": (
        ["target_deg,run,direction,deviation_arcsec,air_temperature_c,pressure_pa,humidity_pct"]
        + [r + ",20,101325,50" for r in rows()[1:]],
        "give actual_<unit> or deviation_<unit>",
        1,
    ),
    # an environment value the refractive index refuses names the row it is on
    "pressure in hPa on one row": (
        ["target_mm,run,direction,actual_mm,air_temperature_c,pressure_pa,humidity_pct"]
        + [r + (",20,1013.2,50" if k == 6 else ",20,101320,50") for k, r in enumerate(rows()[1:])],
        "air pressure 1013.2 Pa is outside",
        8,
    ),
    "temperature in kelvin on one row": (
        ["target_mm,run,direction,actual_mm,air_temperature_c,pressure_pa,humidity_pct,material_temperature_c"]
        + [r + (",293.4,101320,50,20" if k == 11 else ",20,101320,50,20") for k, r in enumerate(rows()[1:])],
        "not kelvin",
        13,
    ),
}


@pytest.mark.parametrize("case", sorted(BAD_FILES))
def test_bad_files_name_file_and_line(tmp_path, case):
    lines, message, line = BAD_FILES[case]
    path = write(tmp_path, "\n".join(lines) + "\n")
    with pytest.raises(AxiscalError, match=message) as info:
        read_positioning_run(path)
    assert info.value.path == str(path)
    assert info.value.line is not None
    if line is not None:
        assert info.value.line == line
    assert "\n" not in str(info.value)


def test_one_run_file_is_read_and_flagged(tmp_path):
    data = read_positioning_run(write(tmp_path, "\n".join(rows(runs=(1,)))))
    r = iso230_2(data.run)
    assert data.run.runs == 1 and math.isnan(r.R) and r.warnings


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 17))
def test_dropping_any_row_is_an_error_with_file_and_line(tmp_path_factory, k):
    lines = rows()
    del lines[1 + k]
    path = write(tmp_path_factory.mktemp("drop"), "\n".join(lines))
    with pytest.raises(AxiscalError, match="unequal run counts|direction only") as info:
        read_positioning_run(path)
    assert info.value.path == str(path) and info.value.line is not None


@settings(max_examples=60, deadline=None)
@given(st.integers(0, 17), st.sampled_from(["nan", "inf", "-inf", "", "1.2.3", "x", "1e400"]))
def test_a_bad_number_anywhere_names_its_line(tmp_path_factory, k, cell):
    lines = rows()
    target, run, direction, _ = lines[1 + k].split(",")
    lines[1 + k] = f"{target},{run},{direction},{cell}"
    path = write(tmp_path_factory.mktemp("cell"), "\n".join(lines))
    # an empty cell beside a target is a reading not typed in yet (a plan half filled in)
    with pytest.raises(AxiscalError, match="no reading at target" if cell == "" else "number") as info:
        read_positioning_run(path)
    assert info.value.line == 2 + k


@settings(max_examples=60, deadline=None)
@given(st.integers(0, 17), st.text(alphabet="abcxyz+-<>0", min_size=1, max_size=4))
def test_an_unknown_direction_anywhere_names_its_line(tmp_path_factory, k, word):
    assume(word.lower() not in ("+", "-", "up", "down"))
    lines = rows()
    target, run, _, value = lines[1 + k].split(",")
    lines[1 + k] = f"{target},{run},{word},{value}"
    path = write(tmp_path_factory.mktemp("dir"), "\n".join(lines))
    with pytest.raises(AxiscalError, match="not a direction") as info:
        read_positioning_run(path)
    assert info.value.line == 2 + k


def test_several_material_sensors_are_averaged(examples, tmp_path):
    # split the one material column into two sensors 0.4 K apart around the same mean
    lines = (examples / "laser_raw_run.csv").read_text().splitlines()
    out = []
    for line in lines:
        if line.startswith("#"):
            continue
        cells = line.split(",")
        if cells[0] == "target_mm":
            out.append(",".join(cells[:7] + ["material_temperature_1_c", "material_temperature_2_c"]))
        else:
            t = float(cells[7])
            out.append(",".join(cells[:7] + [f"{t - 0.2:.3f}", f"{t + 0.2:.3f}"]))
    two = read_positioning_run(write(tmp_path, "\n".join(out)))
    one = read_positioning_run(examples / "laser_raw_run.csv")
    assert two.compensated
    assert np.abs(two.run.deviations_up - one.run.deviations_up).max() < 1e-10


def test_the_callers_arrays_stay_writable():
    up, down = np.zeros((2, 2)), np.ones((2, 2))
    PositioningRun(np.array([0.0, 0.1]), up, down)
    up[0, 0] = 1.0
    assert up.flags.writeable
