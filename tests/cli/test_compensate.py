"""End-to-end runs of `axiscal compensate` on the shipped examples and bad input."""

from __future__ import annotations

import pytest

from axiscal.compensation import parse_linuxcnc


@pytest.mark.parametrize("fmt", ["linuxcnc", "fanuc", "siemens", "heidenhain"])
def test_compensate_command(run_cli, examples, tmp_path, fmt):
    out_file = tmp_path / f"table.{fmt}"
    status, out, err = run_cli("compensate", examples / "positioning_run.csv", "--format", fmt, "-o", out_file)
    assert status == 0 and out == ""
    assert "largest error left" in err
    assert out_file.read_text()
    status, out, _ = run_cli("compensate", examples / "positioning_run.csv", "--format", fmt)
    assert status == 0 and out == out_file.read_text()


def test_compensate_linuxcnc_output_is_readable_by_linuxcnc(run_cli, examples):
    status, out, _ = run_cli("compensate", examples / "laser_raw_run.csv", "--format", "linuxcnc", "--comp-type", "0")
    assert status == 0 and parse_linuxcnc(out).shape == (17, 3)


def test_compensate_bad_input(run_cli, examples, tmp_path):
    status, _, err = run_cli("compensate", examples / "positioning_run.csv", "--format", "fanuc", "--magnification", "0")
    assert status == 2 and "1..100" in err and err.count("\n") == 1
    status, _, err = run_cli("compensate", examples / "positioning_run.csv", "--format", "okuma")
    assert status == 2
    bad = tmp_path / "bad.csv"
    bad.write_text("target_mm,run,direction,deviation_um\n0,1,+,1\n0,1,-,x\n")
    status, _, err = run_cli("compensate", bad, "--format", "linuxcnc")
    assert status == 2 and err.startswith(f"axiscal: error: {bad}:3:")


@pytest.mark.parametrize(
    "fmt,option",
    [("linuxcnc", ["--bidirectional"]), ("heidenhain", ["--interval-mm", "10"]), ("fanuc", ["--no-backlash"]),
     ("siemens", ["--comp-type", "0"]), ("linuxcnc", ["--axis", "X"])],
)
def test_an_option_of_another_format_is_refused_not_ignored(run_cli, examples, fmt, option):
    status, out, err = run_cli("compensate", examples / "positioning_run.csv", "--format", fmt, *option)
    # the message names the flag as typed, not the library's keyword
    assert status == 2 and out == "" and f"{option[0]} applies to format" in err and err.count("\n") == 1


@pytest.mark.parametrize(
    ("option", "words"),
    [
        (("--detection-unit-um", "0"), "detection unit"),
        (("--detection-unit-um", "nan"), "--detection-unit-um must be a finite number"),
        (("--reference-position-mm", "nan"), "finite"),
        (("--axis-number", "-1"), "axis number"),
        (("--axis-number", "0"), "axis number"),
    ],
)
def test_a_table_that_would_be_zeros_or_nan_is_refused(run_cli, examples, tmp_path, option, words):
    target = tmp_path / "table.txt"
    target.write_text("old table\n")
    status, out, err = run_cli("compensate", examples / "positioning_run.csv", "--format", "fanuc", *option, "-o", target)
    assert status == 2 and words in err and err.count("\n") == 1
    assert target.read_text() == "old table\n"


def test_a_correction_beyond_the_bound_is_one_line_naming_the_flag_that_raises_it(run_cli, tmp_path):
    """A run read with --offset-mm 100 by mistake: every deviation -100 mm; the table would move the axis by 100 mm."""
    run = tmp_path / "run.csv"
    rows = [f"{t},{r},{d},{-100000 + r}" for t in (0, 50, 100) for r in (1, 2) for d in "+-"]
    run.write_text("target_mm,run,direction,deviation_um\n" + "\n".join(rows) + "\n")
    target = tmp_path / "table.txt"
    target.write_text("old table\n")
    status, out, err = run_cli("compensate", run, "--format", "linuxcnc", "-o", target)
    assert status == 2 and out == "" and err.count("\n") == 1
    assert err.startswith(f"axiscal: error: {run}: the mean deviation at 0 mm (+) is -99.9985 mm") and "--max-correction-mm" in err
    assert target.read_text() == "old table\n"
    status, _, err = run_cli("compensate", run, "--format", "linuxcnc", "-o", target, "--max-correction-mm", "101")
    assert status == 0 and target.read_text() != "old table\n"
    for bad in ("0", "-1", "1e300", "nan"):
        status, _, err = run_cli("compensate", run, "--format", "linuxcnc", "--max-correction-mm", bad)
        assert status == 2 and "--max-correction-mm" in err and err.count("\n") == 1, err
