"""End-to-end: volumetric, diagonal, inverse and demo commands, and every bad-input case."""

from __future__ import annotations

import json
import shutil

import numpy as np
import pytest

from axiscal.io.tabular import read_csv


@pytest.fixture
def module(tmp_path, examples):
    """A writable copy of the XZ module example."""
    folder = tmp_path / "xz"
    shutil.copytree(examples / "xz_module", folder)
    return folder


def test_volumetric_grid_matches_the_api(run_cli, module, tmp_path):
    out = tmp_path / "map.csv"
    status, _, err = run_cli("volumetric", "--machine", module / "machine.toml", "--grid", "X=0:190:95,Z=0:190:95", "-o", out, "--plot", tmp_path / "map.png")
    assert status == 0, err
    table = read_csv(out)
    assert table.header == ("x_mm", "z_mm", "ex_um", "ey_um", "ez_um", "e_um")
    import axiscal

    machine = axiscal.load_machine(module / "machine.toml")
    q = {"X": table.numeric("x_mm") * 1e-3, "Z": table.numeric("z_mm") * 1e-3}
    np.testing.assert_allclose(table.numeric("ex_um"), machine.volumetric_error(q)[:, 0] * 1e6, atol=1e-4)
    assert (tmp_path / "map.png").stat().st_size > 10_000


def test_volumetric_points_to_stdout(run_cli, module, tmp_path):
    points = tmp_path / "p.csv"
    points.write_text("x_mm,z_mm\n0,0\n100,50\n")
    status, out, _ = run_cli("volumetric", "--machine", module / "machine.toml", "--points", points)
    assert status == 0
    assert out.splitlines()[0] == "x_mm,z_mm,ex_um,ey_um,ez_um,e_um" and len(out.splitlines()) == 3


def test_diagonal_with_interferometer(run_cli, module, tmp_path):
    status, out, err = run_cli(
        "diagonal", "--machine", module / "machine.toml", "--from", "X=0,Z=0", "--to", "X=190,Z=190",
        "--interferometer", module / "diagonal_laser.csv", "--json", "--plot", tmp_path / "d.png",
    )
    assert status == 0, err
    payload = json.loads(out)
    assert payload["E_AD_range_um"] < payload["E_BD_range_um"] / 4
    assert len(payload["points"]["E_BD_um"]) == 20


def test_inverse_round_trip(run_cli, module, tmp_path):
    import axiscal

    machine = axiscal.load_machine(module / "machine.toml")
    actual = machine.actual_point({"X": np.array([0.05, 0.12]), "Z": np.array([0.1, 0.17])})
    points = tmp_path / "targets.csv"
    points.write_text("x_mm,y_mm,z_mm\n" + "\n".join(",".join(f"{v * 1e3:.9f}" for v in p) for p in actual))
    status, out, _ = run_cli("inverse", "--machine", module / "machine.toml", "--points", points)
    assert status == 0
    rows = [line.split(",") for line in out.splitlines()[1:]]
    np.testing.assert_allclose([float(r[3]) for r in rows], [50.0, 120.0], atol=1e-6)
    np.testing.assert_allclose([float(r[4]) for r in rows], [100.0, 170.0], atol=1e-6)


def test_every_csv_written_reads_plainly_with_pandas(run_cli, module, tmp_path):
    import pandas as pd

    machine = module / "machine.toml"
    targets = tmp_path / "targets.csv"
    targets.write_text("x_mm,y_mm,z_mm\n50,-40,150\n")
    runs = {
        "map.csv": (["volumetric", "--machine", machine, "--grid", "X=0:190:95,Z=0:190:95"], ["x_mm", "z_mm", "ex_um", "ey_um", "ez_um", "e_um"]),
        "diagonal.csv": (
            ["diagonal", "--machine", machine, "--from", "X=0,Z=0", "--to", "X=190,Z=190", "--interferometer", module / "diagonal_laser.csv"],
            ["x_mm", "z_mm", "nominal_mm", "measured_mm", "model_error_um", "E_BD_um", "E_AD_um"],
        ),
        "commands.csv": (["inverse", "--machine", machine, "--points", targets], ["x_mm", "y_mm", "z_mm", "x_command_mm", "z_command_mm"]),
    }
    for name, (args, columns) in runs.items():
        status, _, err = run_cli(*args, "-o", tmp_path / name)
        assert status == 0, err
        assert list(pd.read_csv(tmp_path / name).columns) == columns
        sidecar = json.loads((tmp_path / name).with_suffix(".json").read_text())
        assert str(machine) in sidecar["sources"]


def test_diagonal_text_and_sign(run_cli, module):
    status, out, _ = run_cli(
        "diagonal", "--machine", module / "machine.toml", "--from", "X=0,Z=0", "--to", "X=190,Z=190",
        "--interferometer", module / "diagonal_laser.csv",
    )
    assert status == 0
    lines = out.splitlines()
    assert lines[0] == "diagonal of XZ linear module (paper 000): 20 points, length 268.701 mm"
    assert lines[2] == "  E_BD (before model): P-V 56.42 um" and lines[3] == "  E_AD (after model):  P-V 11.08 um"
    status, out, _ = run_cli("diagonal", "--machine", module / "machine.toml", "--from", "X=0,Z=0", "--to", "X=190,Z=190",
                             "--interferometer", module / "diagonal_laser.csv", "--json")
    points = json.loads(out)["points"]
    # actual minus nominal: the laser reads short of nominal at the far end, so E_BD is negative there
    assert points["measured_mm"][-1] < points["nominal_mm"][-1] and points["E_BD_um"][-1] < 0
    assert points["E_BD_um"][-1] == pytest.approx((points["measured_mm"][-1] - points["nominal_mm"][-1]) * 1e3, abs=2e-3)


def edit(path, old, new):
    path.write_text(path.read_text().replace(old, new))


def set_first_value(path, position, value):
    lines = path.read_text().splitlines()
    for k, line in enumerate(lines):
        if line.startswith(position + ","):
            cells = line.split(",")
            cells[1] = value
            lines[k] = ",".join(cells)
    path.write_text("\n".join(lines) + "\n")


@pytest.mark.parametrize(
    "change, where, message",
    [
        (lambda m: edit(m / "machine.toml", 'chain = "FXZ"', 'chain = "FXZ'), "machine.toml:3", "malformed TOML"),
        (lambda m: edit(m / "machine.toml", 'chain = "FXZ"', 'chain = "FX"'), "machine.toml", "[axes.Z] is not an axis of chain"),
        (lambda m: edit(m / "machine.toml", '[axes.Z]\nerrors = "z_errors.csv"', '[axes.Q]\nerrors = "z_errors.csv"'), "machine.toml", "no [axes.Z] section"),
        (lambda m: edit(m / "machine.toml", "EB0Z_arcsec", "EB0Z_furlong"), "machine.toml", "unknown angle unit 'furlong'"),
        (lambda m: edit(m / "x_errors.csv", "EYX_um", "EYY_um"), "x_errors.csv:1", "unknown column 'EYY_um'"),
        (lambda m: edit(m / "x_errors.csv", "EXX_um", "EXX_inch"), "x_errors.csv:1", "unknown length unit 'inch'"),
        (lambda m: edit(m / "x_errors.csv", "\n20.000,", "\n5.000,"), "x_errors.csv:4", "not strictly increasing"),
        (lambda m: edit(m / "z_errors.csv", "\n30.000,", "\n30.000,nan,"), "z_errors.csv:5", "cells where the header has"),
        (lambda m: set_first_value(m / "z_errors.csv", "30.000", "nan"), "z_errors.csv:5", "nan is not a finite number"),
        (lambda m: edit(m / "z_errors.csv", "\n30.000,", "\n30.000,abc"), "z_errors.csv:5", "is not a number"),
    ],
)
def test_bad_input_is_one_line_exit_2(run_cli, module, change, where, message):
    change(module)
    status, out, err = run_cli("volumetric", "--machine", module / "machine.toml", "--grid", "X=0:190:95,Z=0:190:95")
    assert status == 2
    assert "Traceback" not in err
    assert len(err.strip().splitlines()) == 1
    assert where in err and message in err, err


def test_point_outside_the_tables_names_its_line(run_cli, module, tmp_path):
    points = tmp_path / "p.csv"
    points.write_text("x_mm,z_mm\n0,0\n# a comment\n200,50\n")
    status, _, err = run_cli("volumetric", "--machine", module / "machine.toml", "--points", points)
    assert status == 2
    assert f"{points}:4: X = 200 mm is outside the error table" in err


@pytest.mark.parametrize(
    "args, message",
    [
        (["--grid", "X=0:190:10"], "no positions for axis Z"),
        (["--grid", "X=0:190:10,Z=0:190:10,Y=0"], "not in chain"),
        (["--grid", "X=0:190"], "expected parts like"),
        (["--grid", "Z=0:300:100,X=0"], "Z = 200 mm is outside"),
        ([], "exactly one of --points FILE or --grid SPEC"),
    ],
)
def test_bad_grids(run_cli, module, args, message):
    status, _, err = run_cli("volumetric", "--machine", module / "machine.toml", *args)
    assert status == 2 and message in err, err


def test_missing_machine_file_and_missing_points_column(run_cli, module, tmp_path):
    status, _, err = run_cli("volumetric", "--machine", tmp_path / "nope.toml", "--grid", "X=0")
    assert status == 2 and "nope.toml: file not found" in err
    points = tmp_path / "p.csv"
    points.write_text("x_mm\n0\n")
    status, _, err = run_cli("volumetric", "--machine", module / "machine.toml", "--points", points)
    assert status == 2 and "missing column 'z_mm' for axis Z" in err


def test_diagonal_readings_that_do_not_match(run_cli, module, tmp_path):
    readings = tmp_path / "r.csv"
    readings.write_text("nominal_mm,measured_mm\n0,0\n15,15\n")
    status, _, err = run_cli("diagonal", "--machine", module / "machine.toml", "--from", "X=0,Z=0", "--to", "X=190,Z=190", "--steps", "1", "--interferometer", readings)
    assert status == 2 and "r.csv:3: nominal_mm" in err
    status, _, err = run_cli("diagonal", "--machine", module / "machine.toml", "--from", "X=0;Z=0", "--to", "X=190,Z=190")
    assert status == 2 and "--from" in err


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (("volumetric", "--grid", "X=nan,Z=0"), "finite"),
        (("volumetric", "--grid", "X=0:190:1e-9,Z=0"), "more than"),
        (("diagonal", "--from", "X=0,Z=0", "--to", "X=190,Z=190", "--steps", "100000000"), "steps from 1 to"),
    ],
)
def test_unbounded_or_non_finite_requests_are_one_line_errors(run_cli, module, args, words):
    status, out, err = run_cli(args[0], "--machine", module / "machine.toml", *args[1:])
    assert status == 2 and out == ""
    assert err.startswith("axiscal: error: ") and words in err and len(err.strip().splitlines()) == 1


def test_inverse_names_the_line_of_an_unreachable_point(run_cli, module, tmp_path):
    points = tmp_path / "targets.csv"
    points.write_text("x_mm,y_mm,z_mm\n10,0,100\n10,0,900\n")
    status, _, err = run_cli("inverse", "--machine", module / "machine.toml", "--points", points)
    assert status == 2
    assert f"{points}:3: " in err and "outside the error table of axis Z" in err


def test_five_axis_trunnion_map_in_degrees_with_tool_axis_orientation(run_cli, examples, tmp_path):
    import pandas

    out = tmp_path / "trunnion.csv"
    machine = examples / "trunnion_machine" / "machine.toml"
    status, _, err = run_cli(
        "volumetric", "--machine", machine, "--grid", "A=-90:30:30,C=0:360:90,X=100,Y=50,Z=-200", "-o", out, "--plot", tmp_path / "t.png"
    )
    assert status == 0, err
    frame = pandas.read_csv(out)
    assert list(frame.columns) == [
        "a_deg", "c_deg", "x_mm", "y_mm", "z_mm", "ex_um", "ey_um", "ez_um", "e_um", "ei_urad", "ej_urad"
    ]
    assert len(frame) == 5 * 5 and frame["c_deg"].max() == 360.0
    import axiscal

    model = axiscal.load_machine(machine)
    q = {"A": np.radians(frame["a_deg"]), "C": np.radians(frame["c_deg"])}
    q |= {k: frame[f"{k.lower()}_mm"].to_numpy() * 1e-3 for k in "XYZ"}
    error, orientation = model.pose_error(q)
    np.testing.assert_allclose(frame["ex_um"], error[:, 0] * 1e6, atol=1e-4)
    np.testing.assert_allclose(frame["ej_urad"], orientation[:, 1] * 1e6, atol=1e-4)
    # the periodic C table: 0 and 360 deg are the same place
    at = frame.set_index(["a_deg", "c_deg"])
    np.testing.assert_allclose(at.xs(0.0, level="c_deg")["e_um"], at.xs(360.0, level="c_deg")["e_um"], atol=1e-4)
    assert (tmp_path / "t.png").stat().st_size > 10_000


def test_five_axis_points_file_takes_degree_columns(run_cli, examples, tmp_path):
    points = tmp_path / "p.csv"
    points.write_text("a_deg,c_deg,x_mm,y_mm,z_mm\n0,0,0,0,-100\n-45,90,10,20,-100\n")
    status, out, err = run_cli("volumetric", "--machine", examples / "trunnion_machine" / "machine.toml", "--points", points)
    assert status == 0, err
    assert out.splitlines()[0].endswith("e_um,ei_urad,ej_urad") and len(out.splitlines()) == 3
    points.write_text("a_deg,c_deg,x_mm,y_mm,z_mm\n-150,0,0,0,-100\n")
    status, _, err = run_cli("volumetric", "--machine", examples / "trunnion_machine" / "machine.toml", "--points", points)
    assert status == 2 and f"{points}:2: A = -150 deg is outside the error table of axis A" in err
