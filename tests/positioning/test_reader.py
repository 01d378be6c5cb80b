"""read_positioning_run: rotary axes (round the circle), one-direction tests, inch columns, interleaved
runs and hand-edited files that fail on their line."""

from __future__ import annotations

import json
import random
import tempfile
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.errors import AxiscalError
from axiscal.io.jsonio import dumps
from axiscal.positioning import (
    BIDIRECTIONAL_SYMBOLS,
    ISO_SYMBOLS,
    evaluate_positioning_file,
    iso230_2,
    read_positioning_run,
)
from axiscal.units import ARCSEC, DEG, INCH, MM, UM


def write(tmp_path, lines, name="run.csv"):
    path = tmp_path / name
    path.write_text("\n".join(lines) + "\n")
    return path


def linear_rows(examples):
    return (examples / "positioning_run.csv").read_text().splitlines()[1:]


def relabel(rows, target_factor=1.0, value_factor=1.0, header="target_deg,run,direction,deviation_arcsec"):
    out = [header]
    for row in rows:
        t, r, d, v = row.split(",")
        out.append(f"{float(t) * target_factor!r},{r},{d},{float(v) * value_factor!r}")
    return out


def test_a_linear_run_relabelled_in_degrees_and_arcseconds_gives_the_same_numbers(tmp_path, examples):
    # 0..800 mm read as 0..800 * 0.4 deg = 0..320 deg, so that no target meets another round the circle
    rows = linear_rows(examples)
    rotary = evaluate_positioning_file(write(tmp_path, relabel(rows, 0.4)))
    linear = evaluate_positioning_file(examples / "positioning_run.csv")
    assert rotary.run.rotary and not linear.run.rotary
    body, reference = rotary.to_dict(), linear.to_dict()
    assert body["unit"] == "arcsec" and reference["unit"] == "um" and body["axis"] == "rotary"
    for name in ISO_SYMBOLS:
        assert body[name] == pytest.approx(reference[name], rel=1e-12)
        assert getattr(rotary.result, name) / ARCSEC == pytest.approx(getattr(linear.result, name) / UM, rel=1e-12)
    assert np.asarray(body["targets"]["target_deg"]) == pytest.approx(0.4 * np.asarray(reference["targets"]["target_mm"]))
    assert np.asarray(body["targets"]["R_arcsec"]) == pytest.approx(np.asarray(reference["targets"]["R_um"]))
    report = rotary.report()
    assert "axis figures (arcsec):" in report and "target_deg" in report


def test_deviations_in_deg_and_arcmin_and_positions_reached_in_deg(tmp_path):
    rows_arcsec = ["target_deg,run,direction,deviation_arcsec"]
    rows_deg = ["target_deg,run,direction,actual_deg"]
    rows_arcmin = ["target_deg,run,direction,deviation_arcmin"]
    rng = np.random.default_rng(1)
    for t in range(0, 360, 45):
        for run in (1, 2, 3):
            for d in "+-":
                v = round(float(rng.normal(0, 5)), 3)
                rows_arcsec.append(f"{t},{run},{d},{v}")
                rows_deg.append(f"{t},{run},{d},{t + v / 3600!r}")
                rows_arcmin.append(f"{t},{run},{d},{v / 60!r}")
    a = read_positioning_run(write(tmp_path, rows_arcsec, "a.csv")).run
    for other in (write(tmp_path, rows_deg, "b.csv"), write(tmp_path, rows_arcmin, "c.csv")):
        b = read_positioning_run(other).run
        assert b.rotary
        assert b.deviations_up == pytest.approx(a.deviations_up, abs=1e-6 * ARCSEC)
        assert b.deviations_down == pytest.approx(a.deviations_down, abs=1e-6 * ARCSEC)


def full_circle_rows(last=360, step=30, runs=3, closure=0.0):
    rows = ["target_deg,run,direction,deviation_arcsec"]
    for run in range(1, runs + 1):
        for d, sign in (("+", 1), ("-", -1)):
            for t in range(0, last + 1, step):
                value = sign * 2.0 + 5.0 * np.sin(np.radians(t)) + 0.1 * run
                if t == 360:
                    value += closure
                rows.append(f"{t},{run},{d},{value:.3f}")
    return rows


def test_0_and_360_deg_are_the_same_target(tmp_path):
    data = read_positioning_run(write(tmp_path, full_circle_rows(closure=0.5)))
    assert data.run.targets.size == 12 and data.run.targets[0] == 0.0
    assert data.run.targets[-1] == pytest.approx(330 * DEG)
    assert any("0 and 360 deg are the same target" in w and "0.50 arcsec" in w for w in data.warnings)
    # a test from 0 to 330 deg covers the circle: no warning about coverage
    plain = read_positioning_run(write(tmp_path, full_circle_rows(last=330), "b.csv"))
    assert plain.warnings == ()
    assert plain.run.deviations_up == pytest.approx(data.run.deviations_up)


def test_targets_beyond_a_turn_are_taken_round_the_circle(tmp_path):
    rows = ["target_deg,run,direction,deviation_arcsec"]
    for run in (1, 2):
        for d in "+-":
            rows += [f"{t},{run},{d},1.0" for t in (-90, 0, 90, 180)]
    data = read_positioning_run(write(tmp_path, rows))
    assert (data.run.targets / DEG).tolist() == pytest.approx([0, 90, 180, 270])


def test_a_test_that_does_not_cover_the_circle_warns(tmp_path):
    data = read_positioning_run(write(tmp_path, full_circle_rows(last=90, step=15)))
    assert any("not the full circle" in w and "0..90 deg" in w for w in data.warnings)
    evaluation = evaluate_positioning_file(write(tmp_path, full_circle_rows(last=90, step=15), "b.csv"))
    assert any("not the full circle" in w for w in evaluation.warnings)
    assert any("not the full circle" in w for w in evaluation.to_dict()["warnings"])


def test_two_targets_at_one_place_of_the_circle_other_than_0_and_360_fail_on_their_line(tmp_path):
    rows = full_circle_rows(last=330) + ["390,1,+,0.0"]
    with pytest.raises(AxiscalError, match="390 deg is 30 deg on the circle") as info:
        read_positioning_run(write(tmp_path, rows))
    assert info.value.line == len(rows)


def test_inch_columns(tmp_path, examples):
    rows = linear_rows(examples)
    inch = relabel(rows, MM / INCH, UM / INCH, header="target_in,run,direction,deviation_in")
    a = read_positioning_run(examples / "positioning_run.csv").run
    b = read_positioning_run(write(tmp_path, inch)).run
    assert not b.rotary
    assert b.targets == pytest.approx(a.targets, abs=1e-12)
    assert b.deviations_up == pytest.approx(a.deviations_up, abs=1e-12)
    actual = ["target_in,run,direction,actual_in"] + [
        f"{float(t) * MM / INCH!r},{r},{d},{(float(t) * MM + float(v) * UM) / INCH!r}"
        for t, r, d, v in (row.split(",") for row in rows)
    ]
    c = read_positioning_run(write(tmp_path, actual, "actual.csv")).run
    assert c.deviations_down == pytest.approx(a.deviations_down, abs=1e-12)
    assert iso230_2(c).A == pytest.approx(iso230_2(a).A, abs=1e-11)


def test_interleaved_runs_read_as_sorted_ones(tmp_path, examples):
    rows = linear_rows(examples)
    shuffled = rows[:]
    random.Random(7).shuffle(shuffled)
    a = read_positioning_run(examples / "positioning_run.csv")
    b = read_positioning_run(write(tmp_path, ["target_mm,run,direction,deviation_um"] + shuffled))
    assert b.run_labels == a.run_labels
    assert np.array_equal(b.run.deviations_up, a.run.deviations_up)
    assert np.array_equal(b.run.deviations_down, a.run.deviations_down)


def one_direction_rows(examples, direction):
    return ["target_mm,run,direction,deviation_um"] + [r for r in linear_rows(examples) if r.split(",")[2] == direction]


@pytest.mark.parametrize("direction, symbol", [("+", "up"), ("-", "down")])
def test_one_direction_test_gives_the_figures_of_that_direction(tmp_path, examples, direction, symbol):
    evaluation = evaluate_positioning_file(write(tmp_path, one_direction_rows(examples, direction)))
    full = evaluate_positioning_file(examples / "positioning_run.csv")
    assert evaluation.run.directions == (direction,)
    other = "down" if symbol == "up" else "up"
    for name in ("A", "E", "R", "S"):
        assert getattr(evaluation.result, f"{name}_{symbol}") == pytest.approx(getattr(full.result, f"{name}_{symbol}"))
        assert np.isnan(getattr(evaluation.result, f"{name}_{other}"))
    for name in BIDIRECTIONAL_SYMBOLS:
        assert np.isnan(getattr(evaluation.result, name))
    assert evaluation.to_dict()["directions"] == [direction]
    plain = json.loads(dumps(evaluation.to_dict()))
    assert all(plain[name] is None for name in BIDIRECTIONAL_SYMBOLS)
    assert plain[f"A_{symbol}"] == pytest.approx(full.result.figures()[f"A_{symbol}"] / UM)
    assert any("one-direction test" in w for w in plain["warnings"])
    report = evaluation.report()
    assert f"5 runs in the {direction} direction only" in report.splitlines()[0]
    figure_lines = {line.split()[0]: line.split()[1] for line in report.splitlines()[-len(ISO_SYMBOLS):]}
    assert all(figure_lines[name] == "n/a" for name in BIDIRECTIONAL_SYMBOLS)


def test_one_direction_test_plots(tmp_path, examples):
    evaluation = evaluate_positioning_file(write(tmp_path, one_direction_rows(examples, "-")))
    assert evaluation.plot(tmp_path / "one.svg").exists()


def test_rotary_plot_in_degrees(tmp_path, examples):
    evaluation = evaluate_positioning_file(examples / "rotary_run.csv")
    text = evaluation.plot(tmp_path / "rotary.svg").read_text()
    assert "degree" in text and "arcsec" in text


def test_vdi_3441_refuses_a_one_direction_test(tmp_path, examples):
    with pytest.raises(AxiscalError, match="VDI/DGQ 3441 evaluates a bidirectional test"):
        evaluate_positioning_file(write(tmp_path, one_direction_rows(examples, "+")), standard="vdi3441")


def test_the_rotary_example_is_a_plain_csv_with_a_sidecar(examples):
    frame = pd.read_csv(examples / "rotary_run.csv")
    assert list(frame.columns) == ["target_deg", "run", "direction", "deviation_arcsec"]
    assert json.loads((examples / "rotary_run.json").read_text())["kind"] == "positioning run"


HEADER = "target_mm,run,direction,deviation_um"
GOOD = [f"{t},{r},{d},0.5" for r in (1, 2) for d in "+-" for t in (0, 100, 200)]

BAD = {
    "missing direction": (GOOD[:4] + ["100,2,,0.5"] + GOOD[5:], "missing direction", 6),
    "unknown direction word": (GOOD[:4] + ["100,2,backwards,0.5"] + GOOD[5:], "'backwards' is not a direction", 6),
    "run not a whole number": (GOOD[:2] + ["200,1.5,+,0.5"] + GOOD[3:], "'1.5' is not a run number", 4),
    "run not a number": (GOOD[:2] + ["200,first,+,0.5"] + GOOD[3:], "'first' is not a run number", 4),
    "empty run": (GOOD[:2] + ["200,,+,0.5"] + GOOD[3:], "empty run number", 4),
    "target spelled twice": (GOOD + ["100.0,1,up,0.7"], r"written '100.0' here and '100' there", 14),
    "run spelled twice": (GOOD + ["0,2.0,-,0.7"], "appears twice", 14),
    "length target, angle deviation": (GOOD, "a linear axis gives both in lengths", 1),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_hand_edited_run_files_fail_on_their_line(tmp_path, case):
    rows, message, line = BAD[case]
    header = "target_mm,run,direction,deviation_arcsec" if "angle" in case else HEADER
    path = write(tmp_path, [header] + rows)
    with pytest.raises(AxiscalError, match=message) as info:
        read_positioning_run(path)
    assert info.value.line == line and info.value.path == str(path)
    assert "\n" not in str(info.value)


def test_a_whole_run_number_may_be_written_with_a_decimal_point(tmp_path):
    rows = [row.replace(",2,", ",2.0,") for row in GOOD]
    assert read_positioning_run(write(tmp_path, [HEADER] + rows)).run_labels == ("1", "2")


def test_a_rotary_file_with_environment_columns_is_refused(tmp_path):
    rows = ["target_deg,run,direction,actual_deg,air_temperature_c,pressure_pa,humidity_pct"]
    rows += [f"{t},1,{d},{t},20,101325,50" for t in (0, 90) for d in "+-"]
    with pytest.raises(AxiscalError, match="raw laser readings of a length") as info:
        read_positioning_run(write(tmp_path, rows))
    assert info.value.line == 1


@settings(max_examples=15, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), turns=st.lists(st.integers(-2, 2), min_size=72, max_size=72))
def test_whole_turns_added_to_rotary_targets_change_nothing(seed, turns):
    rng = np.random.default_rng(seed)
    rows = [(t, r, d, round(float(rng.normal(0, 4)), 3)) for r in (1, 2, 3) for d in "+-" for t in range(0, 360, 30)]
    with tempfile.TemporaryDirectory() as folder:
        folder = Path(folder)
        plain = write(folder, ["target_deg,run,direction,deviation_arcsec"] + [f"{t},{r},{d},{v}" for t, r, d, v in rows], "a.csv")
        turned = write(folder, ["target_deg,run,direction,deviation_arcsec"]
                       + [f"{t + 360 * k},{r},{d},{v}" for (t, r, d, v), k in zip(rows, turns)], "b.csv")
        a, b = read_positioning_run(plain), read_positioning_run(turned)
    assert np.array_equal(a.run.targets, b.run.targets)
    assert np.array_equal(a.run.deviations_up, b.run.deviations_up)
    assert np.array_equal(a.run.deviations_down, b.run.deviations_down)
    assert iso230_2(a.run).figures() == iso230_2(b.run).figures()
