"""End-to-end runs of `axiscal cmm acceptance` and `axiscal cmm probing` on the shipped examples."""

from __future__ import annotations

import json

import pytest

E0_ARGS = ["--mpe-a-um", "1.8", "--mpe-k", "300", "--e150-mpe-a-um", "2.2", "--e150-mpe-k", "250",
           "--r0-mpl-um", "1.2", "--uncertainty-um", "0.3", "--uncertainty-um-per-m", "1"]


def test_acceptance_json_and_plot(run_cli, examples, tmp_path):
    plot = tmp_path / "e0.png"
    status, out, err = run_cli("cmm", "acceptance", examples / "cmm" / "e0_gauge_blocks.csv", *E0_ARGS,
                               "--json", "--plot", plot)
    assert status == 0, err
    payload = json.loads(out)
    assert payload["E0"]["count"] == 105 and payload["E150"]["count"] == 30
    assert payload["E0"]["mpe"]["statement"] == "±(1.8 + L/300) um, L in mm"
    assert payload["verdict"] == "pass" and payload["R0_verdict"] == "pass"
    assert len(payload["measurements"]) == 135
    assert plot.stat().st_size > 0


def test_acceptance_text_with_a_tight_mpe(run_cli, examples):
    status, out, err = run_cli("cmm", "acceptance", examples / "cmm" / "e0_gauge_blocks.csv", "--mpe-a-um", "0.8",
                               "--mpe-k", "2000", "--uncertainty-um", "0.3")
    assert status == 0, err
    assert "E0    largest |E|" in out and "verdict: fail" in out and "E150" in out and "decisive:" in out and "not assessed" in out


def test_probing_json_of_five_styli(run_cli, examples, tmp_path):
    status, out, err = run_cli("cmm", "probing", examples / "cmm" / "sphere_five_styli.csv", "--diameter-mm", "25.00018",
                               "--pform-mpe-um", "1.0", "--ploc-mpe-um", "1.5", "--uncertainty-um", "0.1", "--json",
                               "--plot", tmp_path / "p.svg")
    assert status == 0, err
    payload = json.loads(out)
    assert payload["figures"]["ploc"]["name"] == "PLoc.Sph.5x25::MS:Tact"
    assert payload["figures"]["ploc"]["verdict"] == "pass"
    assert payload["ploc_um"] == pytest.approx(payload["figures"]["ploc"]["value_um"])
    assert set(payload["styli"]) == {"T1", "T2", "T3", "T4", "T5"}
    assert (tmp_path / "p.svg").stat().st_size > 0


@pytest.mark.parametrize("argv, words", [
    (["acceptance", "{ex}/cmm/e0_gauge_blocks.csv", "--mpe-k", "300"], "--mpe-k needs --mpe-a-um"),
    (["acceptance", "{ex}/cmm/e0_gauge_blocks.csv", "--mpe-a-um", "3", "--mpe-b-um", "2"], "--mpe-b-um (the cap B, 2 um)"),
    (["acceptance", "{ex}/cmm/e0_gauge_blocks.csv", "--r0-mpl-um", "0"], "--r0-mpl-um must be a positive number"),
    (["acceptance", "{ex}/cmm/e0_gauge_blocks.csv", "--uncertainty-um-per-m", "-1"], "micrometres per metre"),
    (["probing", "{ex}/cmm/sphere_single.csv", "--diameter-mm", "-25"], "--diameter-mm must be a positive number of millimetres"),
    (["probing", "{ex}/cmm/sphere_single.csv", "--diameter-mm", "25", "--ploc-mpe-um", "1"], "several styli"),
    (["probing", "{ex}/cmm/no_such.csv", "--diameter-mm", "25"], "no_such.csv"),
    # limits bounded as a budget file's (they gave verdicts)
    (["acceptance", "{ex}/cmm/e0_gauge_blocks.csv", "--mpe-a-um", "1e300"],
     "--mpe-a-um must be above 0 and at most 10000 micrometres, not 1e+300"),
    (["acceptance", "{ex}/cmm/e0_gauge_blocks.csv", "--mpe-a-um", "2", "--mpe-k", "0.5"], "--mpe-k must be 1 to 1e+06"),
    (["acceptance", "{ex}/cmm/e0_gauge_blocks.csv", "--uncertainty-um", "1e300"], "--uncertainty-um must be 0 to 10000"),
    (["probing", "{ex}/cmm/sphere_single.csv", "--diameter-mm", "25", "--pform-mpe-um", "1e300"],
     "--pform-mpe-um must be above 0 and at most 10000"),
    (["probing", "{ex}/cmm/sphere_single.csv", "--diameter-mm", "25", "--uncertainty-um", "1e300"],
     "--uncertainty-um must be 0 to 10000"),
    # points that cannot lie on the calibrated sphere (it gave 'PSize -2474999 um, verdict: pass')
    (["probing", "{ex}/cmm/sphere_single.csv", "--diameter-mm", "2500"], "not on the calibrated one (--diameter-mm 2500 mm)"),
])
def test_mistakes_are_one_line(run_cli, examples, argv, words):
    status, out, err = run_cli("cmm", *[a.format(ex=examples) for a in argv])
    assert status == 2 and out == ""
    assert err.startswith("axiscal: error: ") and words in err and err.count("\n") == 1


def test_a_bad_row_names_file_and_line(run_cli, tmp_path):
    path = tmp_path / "e0.csv"
    path.write_text("position,length,nominal_mm,measured_mm,repeat\n1,L1,100,100.001,1\n1,L1,100,abc,2\n")
    status, _, err = run_cli("cmm", "acceptance", path)
    assert status == 2 and f"{path}:3:" in err


def test_an_e150_mpe_without_e150_values_is_refused(run_cli, examples, tmp_path):
    """--e150-mpe-a-um on a file without E150 rows was ignored (verdict pass, no E150 line)."""
    path = tmp_path / "e0.csv"
    rows = (examples / "cmm" / "e0_gauge_blocks.csv").read_text().splitlines(keepends=True)
    path.write_text("".join(row for row in rows if not row.rstrip().endswith(",150")))
    status, out, err = run_cli("cmm", "acceptance", path, "--e150-mpe-a-um", "2.2")
    assert status == 2 and out == "" and err.count("\n") == 1
    assert err.startswith(f"axiscal: error: {path}: --e150-mpe-a-um is given, but the measurements hold no E150 value")


@pytest.mark.parametrize("column", ["measured_mm", "nominal_mm"])
def test_values_in_another_unit_are_refused_naming_the_line(run_cli, examples, tmp_path, column):
    """measured_mm in um gave 'E0 largest |E| 699302399.520 um, verdict: fail' (exit 0); nominals in metres likewise."""
    lines = (examples / "cmm" / "e0_gauge_blocks.csv").read_text().splitlines()
    header = lines[0].split(",")
    k = header.index(column)
    cells = lines[4].split(",")
    cells[k] = f"{float(cells[k]) * (1000 if column == 'measured_mm' else 0.001):.9g}"
    lines[4] = ",".join(cells)
    path = tmp_path / "e0.csv"
    path.write_text("\n".join(lines) + "\n")
    status, out, err = run_cli("cmm", "acceptance", path, "--mpe-a-um", "1.8")
    assert status == 2 and out == "" and err.count("\n") == 1
    assert err.startswith(f"axiscal: error: {path}:5: the measured length") and "times the nominal" in err
