"""End to end: ``axiscal export skew`` on the 3D-printer example (two straightness runs of its XY plane)."""

from __future__ import annotations

import json
import math

import pytest

from axiscal.positioning import iso230_2, read_positioning_run
from axiscal.units import ARCSEC, UM


def _squareness_json(run_cli, examples, tmp_path):
    status, out, err = run_cli("squareness", "--first", examples / "printer" / "x_run.csv",
                               "--second", examples / "printer" / "y_run.csv", "--json")
    assert status == 0, err
    path = tmp_path / "xy.json"
    path.write_text(out)
    return path, json.loads(out)


def test_printer_example_to_three_firmwares(run_cli, examples, tmp_path):
    path, result = _squareness_json(run_cli, examples, tmp_path)
    # the example is built with 150 arcsec (examples/printer/make_printer_example.py); the indicator's
    # 1 um steps and scatter leave it within 1 arcsec
    assert result["squareness_arcsec"] == pytest.approx(150.0, abs=1.0)
    s = result["squareness_arcsec"] * ARCSEC
    lines = {}
    for firmware in ("klipper", "marlin", "rrf"):
        status, out, err = run_cli("export", "skew", "--firmware", firmware, "--from", path)
        assert status == 0, err
        lines[firmware] = [line for line in out.splitlines() if not line.startswith(";")]
    assert lines["klipper"][0].startswith("SET_SKEW XY=141.3")
    assert lines["marlin"] == [f"M852 I{-math.tan(s):.8f}"]
    assert lines["rrf"] == [f"M556 S100 X{100 * math.tan(s):.6f}"]
    # the same from the angle given by hand
    status, out, _ = run_cli("export", "skew", "--firmware", "marlin", "--xy-arcsec", repr(result["squareness_arcsec"]))
    assert out.splitlines()[-1] == lines["marlin"][0]


def test_export_skew_json_and_options(run_cli):
    status, out, err = run_cli("export", "skew", "--firmware", "klipper", "--xy-arcsec", "20", "--xz-arcsec", "-10",
                               "--square-mm", "50", "--json")
    assert status == 0, err
    body = json.loads(out)
    assert body["square_mm"] == 50 and set(body["factors"]) == {"xy", "xz"}
    assert body["lines"][0].startswith("SET_SKEW XY=") and " XZ=" in body["lines"][0]
    status, out, _ = run_cli("export", "skew", "--firmware", "marlin", "--xz-arcsec", "10", "--convention", "iso")
    assert out.splitlines()[-1] == f"M852 J{math.tan(10 * ARCSEC):.8f}"


def test_export_skew_errors(run_cli, tmp_path):
    status, _, err = run_cli("export", "skew", "--firmware", "klipper")
    assert status == 2 and err == "axiscal: error: no squareness given: give at least one of XY, XZ, YZ\n"
    bad = tmp_path / "r.json"
    bad.write_text('{"plane": "XY"}')
    status, _, err = run_cli("export", "skew", "--firmware", "rrf", "--from", bad)
    assert status == 2 and err.startswith(f"axiscal: error: {bad}: not a squareness result") and err.count("\n") == 1
    status, _, err = run_cli("export", "skew", "--firmware", "rrf", "--from", bad, "--xy-arcsec", "3")
    assert status == 2 and "not both" in err


def test_export_backlash(run_cli, examples):
    status, out, err = run_cli("export", "backlash", examples / "positioning_run.csv", "--controller", "siemens", "--json")
    assert status == 0, err
    body = json.loads(out)
    b_mean = iso230_2(read_positioning_run(examples / "positioning_run.csv").run).B_mean
    assert body["backlash_um"] == pytest.approx(-b_mean / UM, abs=1e-9)
    assert body["lines"][0].startswith("$MA_BACKLASH[0,AX1]=0.004")
    status, out, _ = run_cli("export", "backlash", "--backlash-um", "12", "--controller", "grblhal", "--axis", "Y")
    assert out.splitlines()[-1] == "$161=0.012"


def test_export_backlash_errors(run_cli, examples):
    status, _, err = run_cli("export", "backlash", "--controller", "rrf")
    assert status == 2 and "either a positioning run CSV or --backlash-um" in err
    status, _, err = run_cli("export", "backlash", "--backlash-um", "-3", "--controller", "rrf")
    assert status == 2 and err.count("\n") == 1 and "only a positive distance" in err


def test_export_screwmap(run_cli, examples, tmp_path):
    out = tmp_path / "X.lst"
    status, _, err = run_cli("export", "screwmap", examples / "positioning_run.csv", "--controller", "twincat",
                             "--interval-mm", "100", "-o", out)
    assert status == 0, err
    text = out.read_text()
    assert "kw.ssfk.interval 1000000" in text and "kw.ssfk.kw_nr_max 9" in text
    status, _, err = run_cli("export", "screwmap", examples / "positioning_run.csv", "--controller", "twincat",
                             "--interval-mm", "1", "--max-points", "100")
    assert status == 2 and "P-COMP-00059" in err and err.count("\n") == 1


def test_export_sag(run_cli, examples, tmp_path):
    out = tmp_path / "cec.ini"
    status, _, err = run_cli("export", "sag", examples / "squareness_y.csv", "--controller", "siemens",
                             "--base-axis", "AX2", "--compensation-axis", "AX1", "--step-mm", "25",
                             "--reference", "least-squares", "-o", out)
    assert status == 0 and err == ""
    lines = out.read_text().splitlines()
    assert lines[0] == "%_N_NC_CEC_INI" and "$AN_CEC_STEP[0]=25.0000" in lines and lines[-1] == "M17"
    status, _, err = run_cli("export", "sag", examples / "squareness_y.csv", "--controller", "siemens",
                             "--base-axis", "AX2", "--compensation-axis", "AX1", "--step-mm", "30")
    assert status == 0 and err.startswith("axiscal: note: the run was resampled onto 18 points 30 mm apart")


def test_export_sag_heidenhain(run_cli, examples, tmp_path):
    out = tmp_path / "YX.COM"
    status, _, err = run_cli("export", "sag", examples / "squareness_y.csv", "--controller", "heidenhain",
                             "--base-axis", "Y", "--compensation-axis", "X", "--reference", "least-squares", "-o", out)
    assert status == 0 and err.count("\n") == 1 and "enter YX.COM in column Y of the .CMA table" in err
    lines = out.read_text().splitlines()
    assert lines[0] == "BEGIN YX.COM MM" and lines[1].split() == ["NR", "AXISPOS", "X"] and lines[-1] == "[END]"
    status, _, err = run_cli("export", "sag", examples / "squareness_y.csv", "--controller", "heidenhain",
                             "--base-axis", "Y", "--compensation-axis", "X", "--table", "2")
    assert status == 2 and err.count("\n") == 1 and "SINUMERIK settings" in err


def test_export_screwmap_mach4(run_cli, examples):
    status, out, err = run_cli("export", "screwmap", examples / "positioning_run.csv", "--controller", "mach4",
                               "--points", "17")
    assert status == 0 and "resampled onto 17 evenly spaced points" in err
    lines = out.splitlines()
    assert lines[1].split()[-2:] == ["0.0000", "mm"] and lines[2].split()[-2:] == ["800.0000", "mm"]
    assert lines[3].split()[-1] == "17" and len(lines) == 5 + 17
    status, _, err = run_cli("export", "screwmap", examples / "positioning_run.csv", "--controller", "mach4",
                             "--interval-mm", "50")
    assert status == 2 and err.count("\n") == 1 and "TwinCAT settings" in err


@pytest.mark.parametrize("command", [
    ["sag", "--controller", "heidenhain", "--base-axis", "Y", "--compensation-axis", "Z"],
    ["sag", "--controller", "siemens", "--base-axis", "AX2", "--compensation-axis", "AX3", "--step-mm", "10"],
    ["screwmap", "--controller", "mach4"],
    ["screwmap", "--controller", "twincat"],
])
def test_export_writers_refuse_a_bad_file_in_one_line_and_keep_the_old_output(run_cli, tmp_path, command):
    bad = tmp_path / "bad.csv"
    if command[0] == "sag":
        bad.write_text("position_mm,deviation_um\n0,1.0\n10,abc\n20,0.5\n")
    else:
        bad.write_text("target_mm,run,direction,deviation_um\n0,1,+,1.0\n10,1,+,1_0\n")
    out = tmp_path / "table.txt"
    out.write_text("the old table\n")
    status, stdout, err = run_cli("export", command[0], bad, *command[1:], "-o", out)
    assert status == 2 and stdout == "" and err.count("\n") == 1 and f"{bad}:3:" in err and "Traceback" not in err
    assert out.read_text() == "the old table\n"
