"""The demo job in one call: the closed cycle (as found, compensated, as left) written, loaded, reported, and reported again the same."""

from __future__ import annotations

import json

import pytest

from axiscal.campaign import load_campaign
from axiscal.measurement.campaign_sim import write_campaign
from axiscal.report import DEMO_FILES, report_campaign, run_demo

pytestmark = pytest.mark.filterwarnings("ignore::UserWarning")

VERDICTS = {
    "sensor-calibration": "pass",
    "sixdof-2kg": "not assessed",
    "positioning-X-1": "fail",
    "positioning-Z-1": "fail",
    "separation-X-1": "pass",
    "squareness-XZ-1": "fail",
    "diagonal-0kg": "fail",
    "diagonal-2kg": "fail",
    "sixdof-diagonal-0kg": "not assessed",
    "sixdof-diagonal-2kg": "not assessed",
}


@pytest.fixture(scope="module")
def demo(tmp_path_factory):
    return run_demo(tmp_path_factory.mktemp("demo") / "out")


def test_the_main_files_are_written(demo):
    for name in DEMO_FILES:
        assert (demo.folder / name).is_file() and (demo.folder / name).stat().st_size > 0, name
    assert sorted(p.name for p in demo.files["compensation"].iterdir()) == ["X.comp", "Z.comp"]
    assert demo.report.html.stat().st_size > 100_000  # the plots are inline
    for axis in "xz":
        for name in (f"plan_{axis}.csv", f"{axis}.ngc", f"recording_{axis}.csv", f"positioning_{axis}.csv"):
            assert (demo.campaign.folder / name).is_file() and (demo.as_left.folder / name).is_file(), name


def test_the_campaign_folder_loads(demo):
    campaign = load_campaign(demo.folder / "as-found" / "campaign")
    assert campaign.model == demo.folder / "as-found" / "campaign" / "machine.toml"
    assert campaign.budget is not None
    assert campaign.controller == "linuxcnc"
    assert [t.kind for t in campaign.tests] == ["sensor_calibration", "sixdof", "positioning", "positioning", "separation",
                                                "squareness", "diagonal", "diagonal", "sixdof_diagonal", "sixdof_diagonal"]


def test_results_json_verdicts(demo):
    results = json.loads(demo.files["results"].read_text())
    assert results["schema"] == "axiscal-results/1"
    assert results["verdict"] == "fail"
    assert {t["id"]: t["verdict"] for t in results["tests"]} == VERDICTS
    assert results["campaign"]["machine"]["name"] == "XZ linear module (paper 000)"
    assert [c["file"] for c in results["compensation"]] == ["compensation/X.comp", "compensation/Z.comp"]
    assert results["warnings"] == []
    positioning = {t["id"]: t for t in results["tests"]}["positioning-X-1"]
    assert set(positioning["environment"]) == {"air temperature", "air pressure", "relative humidity"}
    assert positioning["uncertainty"]["E"] > 0  # the campaign carries a budget: U beside every figure
    # the diagonal's measured ranges: the laser's U over the diagonal's length (190 mm * sqrt 2), more than over X's 190 mm
    diagonal = {t["id"]: t for t in results["tests"]}["diagonal-0kg"]["uncertainty"]
    assert diagonal["E_BD_range_um"] == diagonal["E_AD_range_um"] > positioning["uncertainty"]["E"]
    assert "model_error_range_um" not in diagonal  # predicted by the model, not measured


def test_the_closed_cycle_as_left_is_within_a_fifth_of_as_found(demo):
    summary = json.loads(demo.files["summary"].read_text())
    assert summary["as_left"]["verdict"] == "pass"
    for test_id in ("positioning-X-1", "positioning-Z-1"):
        e = summary["cycle"][test_id]["E_um"]
        assert e["after"] <= 0.2 * e["before"] and e["change"] == pytest.approx(e["after"] - e["before"])
        assert e["U_before"] > 0 and e["U_after"] > 0
    left = json.loads(demo.files["as_left_results"].read_text())
    assert left["campaign"]["campaign"]["title"].startswith("XZ module of paper 000: as-left")
    # the as-left report is compared with the as-found one: the before column and the overlay are there
    html = demo.files["as_left_report"].read_text()
    assert "compared" in html


def test_the_report_again_on_the_written_campaign_gives_the_same_figures(demo, tmp_path):
    again = report_campaign(demo.folder / "as-found" / "campaign", tmp_path / "again")
    first = json.loads(demo.files["results"].read_text())
    second = json.loads(again.results.read_text())
    assert second["verdict"] == first["verdict"]
    assert [t["figures"] for t in second["tests"]] == [t["figures"] for t in first["tests"]]
    assert second["compensation"] == first["compensation"]


def test_the_numbers_tell_paper_000_s_story(demo):
    summary = json.loads(demo.files["summary"].read_text())
    assert summary["tests"] == VERDICTS
    # paper 000 section 5 with the 6-DOF sensors read at the diagonal's stops: the campaign's own tests
    experiment = summary["experiment"]
    assert round(experiment["0kg"]["before_max_um"], 1) == 67.5 and round(experiment["0kg"]["after_max_um"], 2) == 0.60
    assert round(experiment["2kg"]["before_max_um"], 1) == 56.4 and round(experiment["2kg"]["after_max_um"], 2) == 0.60
    results = {t.id: t.figures for t in demo.report.results_data.tests}
    assert experiment["2kg"]["after_max_um"] == results["sixdof-diagonal-2kg"]["E_AD_max_um"]
    # the sensors' calibration runs: within paper 000's +-1 um and +-1 arcsec (section 4.1)
    calibration = results["sensor-calibration"]
    assert calibration["channels"] == 10 and calibration["calibration_um"] < 1.0 and calibration["calibration_arcsec"] < 1.0
    # the offline model, taken unloaded, explains the unloaded diagonal but not the loaded one
    check = summary["diagonal_check"]
    assert round(check["0kg"]["E_BD_range_um"], 1) == 67.5 and check["0kg"]["E_AD_range_um"] < 0.1
    assert round(check["2kg"]["E_BD_range_um"], 2) == 56.42 and round(check["2kg"]["E_AD_range_um"], 2) == 11.08
    results = {t.id: t.figures for t in demo.report.results_data.tests}
    assert round(results["squareness-XZ-1"]["iso_value_arcsec"], 1) == -42.4  # paper 000 section 5


def test_console_text(demo):
    lines = demo.text().splitlines()
    found = demo.folder / "as-found"
    assert lines[:7] == [
        f"campaign      {found / 'campaign' / 'campaign.toml'}",
        f"report        {found / 'report' / 'report.html'}",
        f"results       {found / 'report' / 'results.json'}",
        f"compensation  {found / 'report' / 'compensation'}",
        f"as left       {demo.folder / 'as-left' / 'report' / 'report.html'}",
        f"certificate   {demo.folder / 'as-left' / 'report' / 'certificate.pdf'} (its DCC: dcc.xml)",
        f"summary       {demo.folder / 'summary.json'}",
    ]
    assert lines[7] == "AS FOUND FAIL: 10 tests, 2 pass, 5 fail, 3 not assessed"
    assert lines[8] == "AS LEFT PASS: the 2 positioning tests again with the compensation loaded"
    assert lines[9].startswith("  positioning-X-1: E ") and lines[10].startswith("  positioning-Z-1: E ")
    assert lines[11] == "  diagonal check, offline model (taken unloaded): 67.5 -> 0.02 um, 2 kg: 56.4 -> 11.08 um"
    assert lines[12] == "  paper 000 experiment, live 6-DOF measurement: 67.5 -> 0.60 um, 2 kg: 56.4 -> 0.60 um"
    assert len(lines) == 13


def test_the_shipped_example_is_the_simulated_campaign(examples, tmp_path, same_text_to_precision):
    # examples/campaign is the measurement room's simulated campaign (laser runs as raw readings);
    # the demo's as-found campaign is the same with the positioning runs captured by axiscal
    shipped = examples / "campaign"
    written = write_campaign(tmp_path / "campaign", seed=0)
    assert sorted(p.name for p in shipped.iterdir()) == sorted(written.files)
    for name in written.files:
        # the same to the precision printed (another CPU changes a float's 16th digit), not byte for byte
        same_text_to_precision((shipped / name).read_text(), (written.folder / name).read_text(),
                               name=f"{name} (run python examples/make_campaign_example.py)")


def test_the_as_found_campaign_differs_from_the_example_only_by_its_captured_runs(demo, examples):
    shipped = {p.name for p in (examples / "campaign").iterdir()}
    captured = {f"{kind}_{axis}.{ext}" for axis in "xz" for kind, ext in
                (("plan", "csv"), ("plan", "json"), ("recording", "csv"), ("recording", "json"))} | {"x.ngc", "z.ngc"}
    assert set(demo.campaign.files) == shipped | captured | {"uncertainty_budget.toml"}


def test_the_as_left_volumetric_section_is_the_compensated_machine_s(demo):
    """The as-left report showed the as-found model (largest |e| 84.3 um in both) and a blank change map. Its
    campaign now names the files the controller loaded, and the section draws what is left: EXX and EZZ
    compensated, the 42.4 arcsec squareness of paper 000 left (42.4 arcsec over Z's 190 mm: 39.06 um)."""
    found = json.loads(demo.files["results"].read_text())["volumetric"]
    left = json.loads(demo.files["as_left_results"].read_text())["volumetric"]
    campaign = load_campaign(demo.as_left.folder)
    assert campaign.compensation == {a: demo.as_left.folder / f"{a}.comp" for a in "XZ"}
    assert found["max_um"] == pytest.approx(84.33, abs=0.01)
    assert left["max_um"] == pytest.approx(190.0 * 42.4 / 206.264806, abs=1.0)  # the squareness alone, to 1 um
    change = [b - a for row_a, row_b in zip(found["map"]["e_um"], left["map"]["e_um"]) for a, b in zip(row_a, row_b)]
    assert max(change) < -10.0 and min(change) < -40.0  # |e| smaller everywhere: the change map is not blank
    html = demo.files["as_left_report"].read_text()
    assert "with the linuxcnc compensation loaded (X: X.comp, Z: Z.comp): what is left" in html
    assert "Change of the volumetric error since the compared campaign" in html
    assert "Compensation loaded" in html and "X X.comp, Z Z.comp" in html


def test_the_demo_s_certificate_and_its_dcc(demo, dcc_schema):
    import pypdf

    dcc = demo.as_left_report.dcc
    assert list(dcc_schema.iter_errors(str(dcc))) == []
    reader = pypdf.PdfReader(demo.folder / "as-left" / "report" / "certificate.pdf")
    assert reader.attachments["dcc.xml"] == [dcc.read_bytes()]
    assert all("AX-2026-0042" in page.extract_text() for page in reader.pages)
