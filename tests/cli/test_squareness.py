"""End to end: ``axiscal squareness``, ``axiscal optics pentaprism``, ``axiscal cmm ...`` on the shipped examples."""

from __future__ import annotations

import json
import math

import numpy as np
import pandas as pd
import pytest

from axiscal.io.tabular import read_csv


def _sq(examples, *extra):
    return ("squareness", "--first", examples / "squareness_x.csv", "--second", examples / "squareness_y.csv", *extra)


def test_squareness_reproduces_paper_002(run_cli, examples):
    # paper 002, section 4: the example runs carry its slopes; D = 2.7" -> 20.9" (20.954 unrounded)
    status, out, err = run_cli(*_sq(examples, "--prism-deviation-arcsec", "2.7", "--json"))
    assert status == 0, err
    body = json.loads(out)
    assert math.floor(body["squareness_arcsec"] * 10) / 10 == 20.9
    assert body["convention"] == "included-angle"  # the default: eq 21's value
    assert body["iso_term"] == "EC0Y" and body["iso_value_arcsec"] == body["squareness_arcsec"]
    assert body["included_angle_deg"] == pytest.approx(90 + body["squareness_arcsec"] / 3600, abs=1e-12)
    assert body["slope_first"] == pytest.approx(-0.00044783, abs=1e-11)
    assert body["slope_second"] == pytest.approx(1 / 3001.62173825, rel=1e-6)


def test_squareness_text_conventions_and_planes(run_cli, examples, tmp_path):
    status, out, _ = run_cli(*_sq(examples))
    assert status == 0 and "EC0Y" in out and "+23.65 arcsec" in out
    status, out, _ = run_cli(*_sq(examples, "--plane", "XZ", "--json", "--convention", "iso"))
    iso = json.loads(out)
    status, out, _ = run_cli(*_sq(examples, "--plane", "xz", "--json"))
    included = json.loads(out)
    assert iso["iso_term"] == "EB0Z" and included["convention"] == "included-angle"
    # XZ: the same axes, opposite signs (EB0Z = -(included angle - 90 deg))
    assert included["squareness_arcsec"] == pytest.approx(23.654, abs=1e-3)
    assert iso["squareness_arcsec"] == pytest.approx(-included["squareness_arcsec"])
    assert iso["iso_value_arcsec"] == included["iso_value_arcsec"] == iso["squareness_arcsec"]
    status, out, _ = run_cli(*_sq(examples, "--reference", "end-points", "--json"))
    assert json.loads(out)["reference"] == "end-points"
    plot = tmp_path / "plots" / "squareness.png"
    status, _, err = run_cli(*_sq(examples, "--plot", plot))
    assert status == 0, err
    assert plot.stat().st_size > 1000


def test_optics_pentaprism(run_cli, tmp_path):
    plot = tmp_path / "fig5.png"
    status, out, err = run_cli("optics", "pentaprism", "--steps", "11", "--range-arcmin", "5", "--json", "--plot", plot)
    assert status == 0, err
    body = json.loads(out)
    assert len(body["rotation_arcmin"]) == 11
    assert body["translation_mm"] == [-2.0, -1.0, 0.0, 1.0, 2.0]
    assert max(abs(v) for v in body["deviation_change_arcsec"]["X"]) < 1e-9
    assert max(abs(v) for v in body["deviation_change_arcsec"]["Y"]) < 1e-9
    assert all(abs(v) < 1e-9 for axis in "XYZ" for v in body["translation_deviation_change_arcsec"][axis])
    # paper 002 eq (12): 5' about Z -> 0.436" (the paper's "5 degrees -> 0.43"" is 5 arc minutes)
    assert body["deviation_change_arcsec"]["Z"][0] == pytest.approx(-0.4363, abs=1e-4)
    assert f"{body['quadratic_coefficient_arcsec']:.3e}" == "4.848e-06"
    assert plot.stat().st_size > 1000
    status, out, _ = run_cli("optics", "pentaprism", "--index", "1.8", "--steps", "3")
    assert status == 0 and "index 1.8" in out and "-1.7453" in out


def test_cmm_compensate(run_cli, examples, tmp_path):
    out_path = tmp_path / "corrected.csv"
    status, _, err = run_cli(
        "cmm", "compensate", "--squareness-arcmin", "8.05,27.1,-16.6", examples / "cmm_points.csv", "-o", out_path
    )
    assert status == 0, err
    table = read_csv(out_path)
    x, y, z = (table.numeric(f"{a}_mm") for a in "xyz")
    a_xy, a_xz, a_yz = (v * math.pi / 180 / 60 for v in (8.05, 27.1, -16.6))
    np.testing.assert_allclose(table.numeric("x_corrected_mm"), x - y * a_xy - z * a_xz, atol=1e-6)
    np.testing.assert_allclose(table.numeric("y_corrected_mm"), y - z * a_yz, atol=1e-6)
    np.testing.assert_allclose(table.numeric("z_corrected_mm"), z, atol=1e-6)
    readings = tmp_path / "readings.csv"
    status, _, err = run_cli(
        "cmm", "compensate", "--squareness-arcmin", "8.05,27.1,-16.6", "--inverse", examples / "cmm_points.csv", "-o", readings
    )
    assert status == 0, err
    inverse = read_csv(readings)
    xr, yr, zr = (inverse.numeric(f"{a}_reading_mm") for a in "xyz")
    # eq (6) applied to the readings gives back the points
    np.testing.assert_allclose(xr - yr * a_xy - zr * a_xz, x, atol=2e-6)
    np.testing.assert_allclose(yr - zr * a_yz, y, atol=2e-6)
    status, out, _ = run_cli("cmm", "compensate", "--squareness-arcmin=-8.05,27.1,-16.6", examples / "cmm_points.csv")
    assert status == 0 and out.startswith("x_mm,y_mm,z_mm,x_corrected_mm,y_corrected_mm,z_corrected_mm\n")
    frame = pd.read_csv(out_path)
    assert list(frame.columns)[-3:] == ["x_corrected_mm", "y_corrected_mm", "z_corrected_mm"]
    sidecar = json.loads(out_path.with_suffix(".json").read_text())
    assert sidecar["kind"] == "cmm compensation" and sidecar["model"] == "paper 004 eq (6)"
    assert sidecar["squareness_arcmin"]["a_xz"] == pytest.approx(27.1)
    assert sidecar["iso_terms_arcmin"]["EB0Z"] == pytest.approx(-27.1)
    assert list(pd.read_csv(readings).columns)[-1] == "z_reading_mm"


def test_cmm_gauge_blocks(run_cli):
    # paper 004 Table 2 text: 11 um and 5 um improvements; see docs/squareness.md for the comparison
    status, out, err = run_cli("cmm", "gauge-blocks", "--json")
    assert status == 0, err
    body = json.loads(out)["blocks"]
    assert round(body["X"]["unaligned_improvement_um"], 1) == 10.2
    assert round(body["Y"]["unaligned_improvement_um"], 1) == 4.8
    assert abs(body["X"]["aligned_before_um"]) < 0.05
    assert body["X"]["paper_004_improvement_um"] == 11.0
    status, out, _ = run_cli("cmm", "gauge-blocks", "--end-offset-mm", "0")
    assert status == 0 and "0.992 X" in out


@pytest.mark.parametrize(
    "args,message",
    [
        (("--plane", "XW"), "unknown plane"),
        (("--reference", "best"), "--reference"),
        (("--convention", "degrees"), "convention"),
        (("--prism-deviation-arcsec", "nan"), "finite"),
        (("--prism-deviation-arcsec", "3600"), "not a pentaprism"),
        (("--plot", "/proc/no-such-folder/plot.png"), "cannot write"),
    ],
)
def test_squareness_bad_options(run_cli, examples, args, message):
    status, _, err = run_cli(*_sq(examples, *args))
    assert status == 2 and message in err
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err


def test_squareness_bad_files(run_cli, examples, tmp_path):
    one = tmp_path / "one.csv"
    one.write_text("position_mm,deviation_um\n0,1\n")
    status, _, err = run_cli("squareness", "--first", one, "--second", examples / "squareness_y.csv")
    assert status == 2 and "one.csv" in err and "at least 2" in err and len(err.strip().splitlines()) == 1
    bad = tmp_path / "bad.csv"
    bad.write_text("position_mm,deviation_um\n0,1\n10,x\n")
    status, _, err = run_cli("squareness", "--first", bad, "--second", examples / "squareness_y.csv")
    assert status == 2 and "bad.csv:3:" in err
    status, _, err = run_cli("squareness", "--first", tmp_path / "missing.csv", "--second", bad)
    assert status == 2 and "file not found" in err
    # a run at 45 deg given twice: the two lines coincide
    parallel = tmp_path / "parallel.csv"
    parallel.write_text("position_mm,deviation_um\n0,0\n1,1000\n2,2000\n")
    status, _, err = run_cli("squareness", "--first", parallel, "--second", parallel)
    assert status == 2 and "parallel" in err and len(err.strip().splitlines()) == 1


@pytest.mark.parametrize("value", ["8.05,27.1", "a,b,c", "1,2,inf", "8.05,27.1,-996"])
def test_cmm_bad_squareness(run_cli, examples, value):
    status, _, err = run_cli("cmm", "compensate", "--squareness-arcmin", value, examples / "cmm_points.csv")
    assert status == 2 and "--squareness-arcmin" in err and len(err.strip().splitlines()) == 1


def test_cmm_bad_points_and_options(run_cli, tmp_path):
    points = tmp_path / "points.csv"
    points.write_text("x_mm,y_mm\n1,2\n")
    status, _, err = run_cli("cmm", "compensate", "--squareness-arcmin", "1,2,3", points)
    assert status == 2 and "missing column 'z_mm'" in err
    points.write_text("x_mm,y_mm,z_mm\n1,2,3\n1,two,3\n")
    status, _, err = run_cli("cmm", "compensate", "--squareness-arcmin", "1,2,3", points)
    assert status == 2 and "points.csv:3:" in err
    status, _, err = run_cli("cmm", "gauge-blocks", "--end-offset-mm", "1e9")
    assert status == 2 and "--end-offset-mm" in err
    status, _, err = run_cli("optics", "pentaprism", "--index", "0.9")
    assert status == 2 and "at least 1" in err and len(err.strip().splitlines()) == 1
    status, _, err = run_cli("optics", "pentaprism", "--steps", "1")
    assert status == 2 and "--steps" in err
    status, _, err = run_cli("optics", "pentaprism", "--plot", "/proc/no-such-folder/fig5.png")
    assert status == 2 and "cannot write" in err and len(err.strip().splitlines()) == 1
    points.write_text("x_mm,y_mm,z_mm\n1,2,3\n")
    status, _, err = run_cli(
        "cmm", "compensate", "--squareness-arcmin", "1,2,3", points, "-o", "/proc/no-such-folder/out.csv"
    )
    assert status == 2 and "cannot write" in err and len(err.strip().splitlines()) == 1
