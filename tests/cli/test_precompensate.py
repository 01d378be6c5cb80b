"""End-to-end runs of `axiscal precompensate`: the program written, the summary, the one-line errors."""

from __future__ import annotations

import json


PART = "%\n(part)\nG21 G90 G94\nN10 G0 X100 Y100 Z150\nN20 G1 X300 Y150 Z120 F800 (cut)\nG2 X340 Y190 I0 J40\nM2\n%\n"


def test_precompensate_writes_the_program_and_a_summary(run_cli, tmp_path, examples):
    program = tmp_path / "part.ngc"
    program.write_text(PART)
    out = tmp_path / "out" / "part.ngc"
    status, stdout, err = run_cli("precompensate", program, "--machine", examples / "xfyz_machine" / "machine.toml",
                                  "--dialect", "linuxcnc", "-o", out, "--json")
    assert status == 0 and err.count("\n") == 1 and "largest predicted residual along the path" in err
    summary = json.loads(stdout)
    assert summary["lines_in"] == 8 and summary["lines_out"] == len(out.read_text().splitlines())
    assert summary["largest_residual_um"] <= 0.5 and summary["largest_correction_um"] > 1
    text = out.read_text().splitlines()
    assert text[0] == "%" and text[1].startswith("(axiscal") and "tolerance 0.5 um" in text[1]
    assert any(line.startswith("N20 G1 X") and line.endswith("F800 (cut)") for line in text)


def test_bad_programs_are_one_line_with_exit_2(run_cli, tmp_path, examples):
    machine = examples / "xfyz_machine" / "machine.toml"
    cases = {
        "unknown word": ("G21 G90\nG0 X100 Y100 Z150\nG1 X200 Q5 F100\nM2\n", ":3: Q is not a word"),
        "arc off its circle": ("G21 G90\nG0 X100 Y100 Z150\nG2 X120 Y100 I5 J0 F100\nM2\n", ":3: the arc's end point is not on its circle"),
        "macro": ("G21 G90\nG0 X100 Y100 Z150\nG65 P9010 A1\nM2\n", ":3: a macro call (G65)"),
    }
    for name, (text, message) in cases.items():
        program = tmp_path / f"{name}.ngc"
        program.write_text(text)
        status, stdout, err = run_cli("precompensate", program, "--machine", machine, "--dialect", "linuxcnc",
                                      "-o", tmp_path / "out.ngc")
        assert status == 2 and stdout == "" and err.count("\n") == 1, name
        assert err.startswith(f"axiscal: error: {program}{message}"), err
    assert not (tmp_path / "out.ngc").exists()
    status, _, err = run_cli("precompensate", tmp_path / "macro.ngc", "--machine", machine, "--dialect", "grbl",
                             "-o", tmp_path / "o.nc", "--tool-mm", "1,2")
    assert status == 2 and "--tool-mm needs three numbers" in err
    status, _, err = run_cli("precompensate", tmp_path / "macro.ngc", "--machine", machine, "--dialect", "grbl",
                             "-o", tmp_path / "o.nc", "--tolerance-um", "0.05")
    assert status == 2 and err.startswith("axiscal: error: --tolerance-um must be at least 0.2 um")


def test_export_grid_writes_the_csv_and_its_sidecar(run_cli, tmp_path, examples):
    out = tmp_path / "grid.csv"
    status, stdout, err = run_cli("export", "grid", "--machine", examples / "xfyz_machine" / "machine.toml",
                                  "--grid", "X=50:750:100,Y=50:450:100,Z=50:350:100", "-o", out)
    assert status == 0 and stdout == "" and "160 grid points" in err
    assert out.read_text().splitlines()[0] == "x_mm,y_mm,z_mm,x_correction_um,y_correction_um,z_correction_um"
    assert json.loads((tmp_path / "grid.json").read_text())["kind"] == "pre-compensation grid"
    status, _, err = run_cli("export", "grid", "--machine", examples / "xfyz_machine" / "machine.toml",
                             "--grid", "X=0:800:100,Y=0:500:100,Z=0:300:100", "-o", out)
    assert status == 2 and err.count("\n") == 1 and "keep the grid inside the error tables" in err


def test_hidden_cases_of_issue_28_are_one_line_with_exit_2(run_cli, tmp_path, examples):
    machine = examples / "xfyz_machine" / "machine.toml"
    huge = tmp_path / "huge.ngc"
    huge.write_text("G21 G90\nG0 X400 Y250 Z200\nG1 X1" + "0" * 400 + " F100\nM2\n")
    plain = tmp_path / "plain.ngc"
    plain.write_text("G21 G90\nG0 X400 Y250 Z200\nG1 X410 F100\nM2\n")
    no_end = tmp_path / "no_end.nc"
    no_end.write_text("%\nO1000\nG21 G90\nG0 X400. Y250. Z200.\nG1 X401. F100.\n%\n")
    cases = [
        ((huge, "--dialect", "linuxcnc"), f"{huge}:3: X is not a finite number"),
        ((plain, "--dialect", "linuxcnc", "--max-segment-mm", "1e-12"),
         "--max-segment-mm must be at least 0.001 mm (pieces shorter than 1 um are not cut again), not 1e-12 mm"),
        ((no_end, "--dialect", "fanuc"), f"{no_end}:6: the program has no end (M2, M30)"),
    ]
    for argv, message in cases:
        status, stdout, err = run_cli("precompensate", *argv, "--machine", machine, "-o", tmp_path / "out.ngc")
        assert status == 2 and stdout == "" and err.count("\n") == 1, err
        assert err.startswith(f"axiscal: error: {message}"), err
    assert not (tmp_path / "out.ngc").exists()
