"""End-to-end runs of `axiscal positioning` on the shipped examples and bad input (and output files and bad numbers of positioning, plan and compensate)."""

from __future__ import annotations

import json

import numpy as np
import pytest

from axiscal.positioning.evaluation import ISO_SYMBOLS, VDI_SYMBOLS


def test_positioning_table(run_cli, examples):
    status, out, err = run_cli("positioning", examples / "positioning_run.csv")
    assert status == 0 and err == ""
    assert "iso230-2:2014" in out and "axis figures (um)" in out
    for name in ISO_SYMBOLS:
        assert f"\n  {name} " in out


def test_positioning_json_has_every_symbol_and_the_arrays(run_cli, examples):
    status, out, _ = run_cli("positioning", examples / "positioning_run.csv", "--json")
    assert status == 0
    body = json.loads(out)
    assert body["unit"] == "um" and body["coverage_factor"] == 2 and body["runs"] == 5
    for name in ISO_SYMBOLS:
        assert isinstance(body[name], float)
    targets = body["targets"]
    assert len(targets["target_mm"]) == 17
    assert max(abs(b) for b in targets["B_um"]) == pytest.approx(body["B"])
    assert max(targets["R_um"]) == pytest.approx(body["R"])


def test_positioning_json_vdi(run_cli, examples):
    status, out, _ = run_cli("positioning", examples / "positioning_run.csv", "--json", "--standard", "vdi3441")
    body = json.loads(out)
    assert status == 0 and body["standard"] == "vdi3441"
    for name in VDI_SYMBOLS:
        assert isinstance(body[name], float)
    assert max(body["targets"]["Ps_um"]) == pytest.approx(body["Ps_max"])


def test_1988_and_jis_give_the_3_sigma_figures(run_cli, examples):
    figures = {}
    for standard in ("iso230-2:2014", "iso230-2:1988", "jis-b6192"):
        status, out, _ = run_cli("positioning", examples / "positioning_run.csv", "--json", "--standard", standard)
        assert status == 0
        figures[standard] = json.loads(out)
    assert figures["iso230-2:1988"]["R_up"] == pytest.approx(1.5 * figures["iso230-2:2014"]["R_up"])
    assert figures["jis-b6192"]["A"] == figures["iso230-2:1988"]["A"]


def test_raw_laser_file_gives_the_same_figures(run_cli, examples):
    _, plain, _ = run_cli("positioning", examples / "positioning_run.csv", "--json")
    _, raw, _ = run_cli("positioning", examples / "laser_raw_run.csv", "--json")
    plain, raw = json.loads(plain), json.loads(raw)
    assert raw["compensated"] is True
    for name in ISO_SYMBOLS:
        assert raw[name] == pytest.approx(plain[name], abs=2e-3)


def test_plot_is_written(run_cli, examples, tmp_path):
    out = tmp_path / "plots" / "positioning.png"
    status, _, _ = run_cli("positioning", examples / "positioning_run.csv", "--plot", out)
    assert status == 0 and out.stat().st_size > 10_000
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.parametrize("standard", ["iso230-2:1988", "vdi3441"])
def test_plot_of_raw_readings_and_other_standards(run_cli, examples, tmp_path, standard):
    out = tmp_path / "raw.svg"
    status, _, _ = run_cli("positioning", examples / "laser_raw_run.csv", "--standard", standard, "--plot", out)
    assert status == 0 and out.read_text().lstrip().startswith("<?xml")


def test_one_run_is_flagged_not_invented(run_cli, tmp_path):
    lines = ["target_mm,run,direction,deviation_um"]
    for d, v in (("+", 1.0), ("-", -1.0)):
        lines += [f"{t},1,{d},{v + t / 1000}" for t in (0, 100, 200)]
    path = tmp_path / "one.csv"
    path.write_text("\n".join(lines))
    status, out, err = run_cli("positioning", path, "--json")
    body = json.loads(out)
    assert status == 0
    assert body["R"] is None and body["A"] is None and body["S_up"] is None
    assert all(s is None for s in body["targets"]["s_up_um"])
    assert body["B"] == pytest.approx(2.0) and body["warnings"]
    assert "warning" in err and "cannot be estimated" in err
    status, out, err = run_cli("positioning", path)
    assert "n/a" in out and "warning" in err
    status, _, _ = run_cli("positioning", path, "--plot", tmp_path / "one.png")  # no bands, a note instead
    assert status == 0 and (tmp_path / "one.png").stat().st_size > 10_000


BAD = {
    "unequal": "target_mm,run,direction,deviation_um\n0,1,+,1\n0,1,-,1\n0,2,+,1\n0,2,-,1\n10,1,+,1\n10,1,-,1\n10,2,+,1\n",
    "missing direction": "target_mm,run,direction,deviation_um\n0,1,+,1\n0,1,-,1\n10,1,+,1\n10,2,+,1\n0,2,+,1\n0,2,-,1\n",
    "mixed units": "target_mm,run,direction,deviation_um,deviation_nm\n0,1,+,1,1\n",
    "nan": "target_mm,run,direction,deviation_um\n0,1,+,1\n0,1,-,nan\n10,1,+,1\n10,1,-,1\n",
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_input_exits_2_with_one_line(run_cli, tmp_path, case):
    path = tmp_path / "bad.csv"
    path.write_text(BAD[case])
    status, out, err = run_cli("positioning", path)
    assert status == 2 and out == ""
    assert err.startswith(f"axiscal: error: {path}:") and err.count("\n") == 1


def test_missing_file_and_unknown_standard(run_cli, tmp_path, examples):
    status, _, err = run_cli("positioning", tmp_path / "nope.csv")
    assert status == 2 and "file not found" in err
    status, _, err = run_cli("positioning", examples / "positioning_run.csv", "--standard", "iso9999")
    assert status == 2


def test_deviation_means_match_api(run_cli, examples):
    from axiscal.positioning.evaluation import iso230_2
    from axiscal.positioning.reader import read_positioning_run

    _, out, _ = run_cli("positioning", examples / "positioning_run.csv", "--json")
    body = json.loads(out)
    api = iso230_2(read_positioning_run(examples / "positioning_run.csv").run)
    assert np.array(body["targets"]["mean_up_um"]) == pytest.approx(api.stats.mean_up / 1e-6)


def test_plot_with_an_unknown_format_is_a_one_line_error(run_cli, examples, tmp_path):
    status, _, err = run_cli("positioning", examples / "positioning_run.csv", "--plot", tmp_path / "plot.xyz")
    assert status == 2 and "cannot write a plot as '.xyz'" in err and err.count("\n") == 1


@pytest.mark.parametrize(
    "args",
    [
        ("positioning", "{run}", "--plot", "{bad}/plot.png"),
        ("compensate", "{run}", "--format", "linuxcnc", "-o", "{bad}/x.comp"),
        ("plan", "--start-mm", "0", "--end-mm", "400", "--targets", "5", "-o", "{bad}/plan.csv"),
        ("plan", "--start-mm", "0", "--end-mm", "400", "--targets", "5", "--gcode", "{bad}/plan.ngc"),
    ],
    ids=["plot", "compensate", "plan-csv", "plan-gcode"],
)
def test_an_output_that_cannot_be_written_is_one_error_line(run_cli, examples, tmp_path, args):
    blocker = tmp_path / "a-file"  # a file where a folder would have to be
    blocker.write_text("")
    argv = [a.format(run=examples / "positioning_run.csv", bad=blocker) for a in args]
    status, _, err = run_cli(*argv)
    assert status == 2 and err.startswith(f"axiscal: error: {blocker}/") and "cannot write" in err
    assert err.count("\n") == 1


@pytest.mark.parametrize("option", [["--wavelength-nm", "632.99"], ["--expansion-per-k", "23e-6"]])
def test_raw_reading_options_on_a_deviation_file_are_refused_not_ignored(run_cli, examples, option):
    status, out, err = run_cli("positioning", examples / "positioning_run.csv", *option)
    assert status == 2 and out == "" and f"{option[0]} applies to raw laser readings" in err and err.count("\n") == 1
    status, _, _ = run_cli("positioning", examples / "laser_raw_run.csv", *option)
    assert status == 0


# ------------------------------------------------------------- rotary axes, one-direction tests, bad numbers


def one_direction_file(examples, tmp_path, sign):
    """The shipped run with the rows of one direction only."""
    lines = (examples / "positioning_run.csv").read_text().splitlines()
    path = tmp_path / f"only{sign}.csv"
    path.write_text("\n".join([lines[0]] + [line for line in lines[1:] if f",{sign}," in line]) + "\n")
    return path


def test_positioning_of_a_rotary_axis_speaks_arcseconds(run_cli, examples, tmp_path):
    status, out, err = run_cli("positioning", examples / "rotary_run.csv", "--json", "--plot", tmp_path / "r.png")
    assert status == 0 and (tmp_path / "r.png").exists()
    body = json.loads(out)
    assert body["unit"] == "arcsec" and body["axis"] == "rotary" and body["target_count"] == 12
    assert len(body["targets"]["target_deg"]) == 12 and "B_arcsec" in body["targets"]
    assert "axiscal: warning:" in err and "0 and 360 deg are the same target" in err
    status, out, _ = run_cli("positioning", examples / "rotary_run.csv")
    assert "axis figures (arcsec):" in out and "target_deg" in out


def test_positioning_of_a_one_direction_test_reports_n_a_and_null(run_cli, examples, tmp_path):
    path = one_direction_file(examples, tmp_path, "-")
    status, out, err = run_cli("positioning", path, "--json")
    body = json.loads(out)
    assert status == 0 and body["directions"] == ["-"] and "one-direction test" in err
    assert body["B"] is None and body["A"] is None and isinstance(body["A_down"], float) and body["A_up"] is None
    status, out, _ = run_cli("positioning", path)
    assert "5 runs in the - direction only" in out
    assert [line.split()[1] for line in out.splitlines() if line.startswith("  B ")] == ["n/a"]


@pytest.mark.parametrize("option", ["--wavelength-nm", "--expansion-per-k"])
@pytest.mark.parametrize("value", ["nan", "inf", "-inf"])
def test_positioning_refuses_non_finite_options(run_cli, examples, option, value):
    status, _, err = run_cli("positioning", examples / "laser_raw_run.csv", option, value)
    assert status == 2 and err == f"axiscal: error: {option} must be a finite number, got {value}\n"


@pytest.mark.parametrize("option", ["--start-mm", "--end-mm", "--overrun-mm", "--dwell-s", "--feed-mm-min"])
@pytest.mark.parametrize("value", ["nan", "inf"])
def test_plan_refuses_non_finite_options(run_cli, tmp_path, option, value):
    args = {"--start-mm": "0", "--end-mm": "500", "--overrun-mm": "5", "--dwell-s": "2", "--feed-mm-min": "2000"}
    args[option] = value
    argv = [item for pair in args.items() for item in pair]
    status, _, err = run_cli("plan", *argv, "--targets", "6", "--gcode", tmp_path / "p.gcode", "-o", tmp_path / "p.csv")
    assert status == 2 and err == f"axiscal: error: {option} must be a finite number, got {value}\n"
    assert not (tmp_path / "p.csv").exists()


@pytest.mark.parametrize(("run", "option"), [
    ("positioning_run.csv", "--interval-mm"), ("positioning_run.csv", "--detection-unit-um"),
    ("positioning_run.csv", "--reference-position-mm"), ("rotary_run.csv", "--interval-deg"),
    ("rotary_run.csv", "--detection-unit-deg"), ("rotary_run.csv", "--reference-position-deg"),
])
@pytest.mark.parametrize("value", ["nan", "-inf"])
def test_compensate_refuses_non_finite_options(run_cli, examples, run, option, value):
    status, out, err = run_cli("compensate", examples / run, "--format", "fanuc", option, value)
    assert status == 2 and out == "" and err == f"axiscal: error: {option} must be a finite number, got {value}\n"


@pytest.mark.parametrize("fmt", ["linuxcnc", "fanuc", "siemens", "heidenhain"])
def test_compensate_a_rotary_axis(run_cli, examples, fmt, tmp_path):
    status, out, err = run_cli("compensate", examples / "rotary_run.csv", "--format", fmt, "-o", tmp_path / "t.txt")
    assert status == 0 and out == "" and "arcsec" in err and (tmp_path / "t.txt").read_text()


def test_compensate_a_one_direction_test_says_which_formats_need_both(run_cli, examples, tmp_path):
    path = one_direction_file(examples, tmp_path, "+")
    status, _, err = run_cli("compensate", path, "--format", "linuxcnc")
    assert status == 2 and "needs a test in both directions" in err and err.count("\n") == 1
    status, _, err = run_cli("compensate", path, "--format", "heidenhain", "--no-backlash")
    assert status == 0 and "from the + direction only" in err


@pytest.mark.parametrize("kind", ["rotary", "one direction"])
def test_a_length_budget_is_refused_for_a_rotary_or_one_direction_test(run_cli, examples, tmp_path, kind):
    if kind == "rotary":
        path = examples / "rotary_run.csv"
    else:
        path = one_direction_file(examples, tmp_path, "+")
    status, out, err = run_cli("positioning", path, "--uncertainty", examples / "uncertainty_budget.toml")
    assert status == 2 and out == "" and err.count("\n") == 1 and kind in err
