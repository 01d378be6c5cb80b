"""End-to-end runs of `axiscal plan`: the plan, filled in, is evaluated by `axiscal positioning` as it is."""

from __future__ import annotations

import json

import pandas
import pytest


def test_plan_then_positioning_round_trip(run_cli, tmp_path):
    cycle = tmp_path / "cycle.csv"
    gcode = tmp_path / "cycle.nc"
    status, out, err = run_cli(
        "plan", "--start-mm", 0, "--end-mm", 800, "--targets", 17, "--runs", 5, "--overrun-mm", 5,
        "--seed", 1, "--gcode", gcode, "-o", cycle,
    )
    assert status == 0 and out == ""
    assert err == "axiscal: note: ISO 230-2 linear cycle, 17 targets, 5 runs each way, overrun 5 mm, seed 1\n"
    assert json.loads((tmp_path / "cycle.json").read_text())["seed"] == 1
    frame = pandas.read_csv(cycle)
    assert list(frame.columns) == ["step", "run", "direction", "target_mm", "move_to_mm", "deviation_um"]
    readings = frame["target_mm"].notna()
    assert readings.sum() == 17 * 5 * 2 and frame["deviation_um"].isna().all()
    assert gcode.read_text().count("G4 P2") == readings.sum()
    # the technician types a pure scale error of 10 um/m into the plan itself, rows without a target left empty
    lines = cycle.read_text().splitlines()
    filled = [lines[0]]
    for line in lines[1:]:
        cells = line.split(",")
        filled.append(line + (f"{0.01 * float(cells[3]):.4f}" if cells[3] else ""))
    cycle.write_text("\n".join(filled) + "\n")
    status, out, _ = run_cli("positioning", cycle, "--json")
    body = json.loads(out)
    assert status == 0 and body["runs"] == 5 and body["target_count"] == 17
    assert body["E"] == pytest.approx(8.0, abs=1e-3) and body["B"] == pytest.approx(0.0, abs=1e-9)
    assert body["targets"]["target_mm"] == pytest.approx(sorted(set(frame["target_mm"].dropna())))


def test_a_plan_not_filled_in_is_one_error_line_naming_the_row(run_cli, tmp_path):
    cycle = tmp_path / "cycle.csv"
    assert run_cli("plan", "--start-mm", 0, "--end-mm", 400, "--targets", 5, "--seed", 1, "-o", cycle)[0] == 0
    status, out, err = run_cli("positioning", cycle)
    assert status == 2 and out == "" and err.count("\n") == 1
    assert err.startswith(f"axiscal: error: {cycle}:3: no reading at target 0.000 (run 1, direction +)")


def test_plan_to_stdout_and_bad_requests(run_cli):
    status, out, err = run_cli("plan", "--start-mm", 0, "--end-mm", 400, "--targets", 5, "--cycle", "pilgrim", "--seed", 3)
    assert status == 0 and out.count("\n") == 1 + 5 * 5 * 2 * 2 and not out.startswith("#")
    assert "seed 3" in err
    status, _, err = run_cli("plan", "--start-mm", 0, "--end-mm", 800, "--targets", 3)
    assert status == 2 and "at least 5" in err and err.count("\n") == 1
    status, _, err = run_cli("plan", "--start-mm", 0, "--end-mm", 800, "--targets", 17, "--overrun-mm", 0)
    assert status == 2 and "overrun" in err
    status, _, err = run_cli("plan", "--start-mm", 5, "--end-mm", 0, "--targets", 17)
    assert status == 2 and "beyond the start" in err
    status, _, err = run_cli("plan", "--start-mm", 0, "--end-mm", 100, "--targets", 5, "--gcode", "/tmp/x.nc", "--axis", "XY")
    assert status == 2 and "one letter" in err


@pytest.mark.parametrize("dialect", ["linuxcnc", "fanuc", "sinumerik", "heidenhain", "grbl", "marlin", "klipper"])
def test_plan_writes_the_program_in_the_controls_dialect(run_cli, tmp_path, dialect):
    from axiscal.io.gcode import program_motions

    gcode = tmp_path / "cycle.prog"
    status, out, _ = run_cli("plan", "--start-mm", 0, "--end-mm", 400, "--targets", 5, "--runs", 1, "--seed", 2,
                             "--gcode", gcode, "--dialect", dialect, "--dwell-s", 3, "-o", tmp_path / "cycle.csv")
    assert status == 0 and out == ""
    motions = program_motions(gcode.read_text(), dialect=dialect, source=str(gcode))
    dwells = [m.dwell_s for m in motions if m.kind == "dwell"]
    assert dwells == [3.0] * 10
    frame = pandas.read_csv(tmp_path / "cycle.csv")
    moves = [m.end_m["X"] * 1e3 for m in motions if m.kind == "feed"]
    assert moves == pytest.approx(list(frame["move_to_mm"]), abs=1e-9)


def test_plan_refuses_an_unknown_dialect(run_cli, tmp_path):
    status, _, err = run_cli("plan", "--start-mm", 0, "--end-mm", 400, "--targets", 5, "--gcode", tmp_path / "p.nc",
                             "--dialect", "haas")
    assert status == 2 and "haas" in err


@pytest.mark.parametrize("args", [
    ("--step-cycle", "--start-mm", "1e300", "--period-mm", "5"),
    ("--step-cycle", "--start-mm", "0", "--period-mm", "1e300"),
    ("--start-mm", "0", "--end-mm", "100", "--targets", "5", "--overrun-mm", "1e300"),
    ("--start-mm", "0", "--end-mm", "100", "--targets", "5", "--feed-mm-min", "1000000"),
    ("--start-mm", "0", "--end-mm", "100", "--targets", "5", "--dwell-s", "1e300"),
    ("--start-mm", "0", "--end-mm", "100", "--targets", "5", "--steps-per-period", "6"),
    ("--start-mm", "0", "--end-mm", "100", "--targets", "5", "--periods", "3"),
    ("--start-mm", "99990", "--end-mm", "99999", "--targets", "5"),
])
def test_every_number_that_reaches_the_program_is_bounded_and_a_step_cycle_flag_needs_the_step_cycle(run_cli, tmp_path, args):
    status, out, err = run_cli("plan", *args, "-o", tmp_path / "plan.csv", "--gcode", tmp_path / "plan.ngc")
    assert status == 2 and out == "" and err.count("\n") == 1 and err.startswith("axiscal: error: "), err
    assert not (tmp_path / "plan.ngc").exists() and not (tmp_path / "plan.csv").exists()
    flag = next((a for a in args if a.startswith("--") and a in err), None)
    assert flag is not None or "position word" in err, err
