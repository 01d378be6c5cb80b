"""Campaign kinds cmm_acceptance and cmm_probing: the figures equal what the commands print, the maker's MPE
as tolerances give the verdict under the campaign's rule, the report has their section; a bad option or
tolerance names campaign.toml and the test's line."""

from __future__ import annotations

import json
import shutil

import pytest

from axiscal.campaign import run_campaign
from axiscal.errors import AxiscalError
from axiscal.report import report_campaign


@pytest.fixture
def campaign(tmp_path, examples):
    for name in ("e0_gauge_blocks.csv", "sphere_single.csv", "sphere_five_styli.csv", "campaign.toml"):
        shutil.copy(examples / "cmm" / name, tmp_path / name)
    return tmp_path


def command_json(run_cli, *argv):
    status, out, err = run_cli(*argv, "--json")
    assert status == 0, err
    return json.loads(out)


def test_figures_equal_the_commands_and_the_verdicts_follow(campaign, run_cli):
    results = run_campaign(campaign)
    length, single, multi = results.tests
    assert results.decision_rule == "guard-band"
    e0 = command_json(run_cli, "cmm", "acceptance", campaign / "e0_gauge_blocks.csv", "--mpe-a-um", "1.8", "--mpe-k", "300",
                      "--e150-mpe-a-um", "2.2", "--e150-mpe-k", "250", "--r0-mpl-um", "1.2", "--uncertainty-um", "0.3",
                      "--uncertainty-um-per-m", "1")
    assert {k: length.figures[k] for k in e0} == e0
    probing = command_json(run_cli, "cmm", "probing", campaign / "sphere_five_styli.csv", "--diameter-mm", "25.00018",
                           "--pform-mpe-um", "1.7", "--psize-mpe-um", "1.0", "--pform-ms-mpe-um", "2.0",
                           "--psize-ms-mpe-um", "1.2", "--ploc-mpe-um", "2.0", "--uncertainty-um", "0.1")
    assert multi.figures == probing
    # the decisive E0 value: position 5, 400 mm, E 1.68 um against MPE 1.8 + 400/300 = 3.133 um with U = 0.7 um
    check = next(c for c in length.checks if c.figure == "E0_decisive_um")
    assert (check.value, check.limit, check.U) == pytest.approx((1.68, 3.1333, 0.7), abs=1e-3)
    assert [c.figure for c in length.checks] == ["E0_decisive_um", "E150_decisive_um", "R0_um"]
    assert [c.figure for c in multi.checks] == ["pform_um", "psize_um", "pform_ms_um", "psize_ms_um", "ploc_um"]
    assert [t.verdict for t in results.tests] == ["pass", "pass", "pass"]
    assert all(test.plots and test.plots[0].svg.startswith("<svg") for test in results.tests)


def test_a_tight_mpe_gives_no_decision_then_failure(campaign):
    toml = campaign / "campaign.toml"
    text = toml.read_text().split("[[tests]]\nkind = \"cmm_probing\"")[0]  # the length test alone
    # 2.72 um at 700 mm: MPE 0.5 + 700/300 = 2.83 um, U = 1.0 um: no decision
    toml.write_text(text.replace("cmm_e150_a_um = 2.2", "cmm_e150_a_um = 0.5").replace("cmm_e150_k = 250", "cmm_e150_k = 300"))
    length = run_campaign(campaign).tests[0]
    assert length.verdict == "inconclusive"
    toml.write_text(text.replace("cmm_r0_um = 1.2", "cmm_r0_um = 0.5"))
    assert run_campaign(campaign).tests[0].verdict == "fail"


def test_the_report_has_the_cmm_section(campaign, tmp_path):
    files = report_campaign(campaign, tmp_path / "report")
    html = files.html.read_text(encoding="utf-8")
    assert 'id="cmm"' in html and "CMM tests (ISO 10360)" in html
    assert "PLoc.Sph.5x25::MS:Tact" in html and "ISO 10360-2:2009" in html
    data = json.loads(files.results.read_text())
    assert [t["kind"] for t in data["tests"]] == ["cmm_acceptance", "cmm_probing", "cmm_probing"]
    assert data["tests"][0]["tolerances"]["R0_um"] == 1.2


@pytest.mark.parametrize(("old", "new", "words", "line"), [
    ("uncertainty_um = 0.3", "uncertainty_um = -0.3", "uncertainty_um must be 0 to 10000, not -0.3", 18),
    ("uncertainty_um = 0.3", "uncertainty_um = 1e300", "uncertainty_um must be 0 to 10000, not 1e+300", 18),
    ("cmm_e0_a_um = 1.8", "cmm_e0_a_um = 1e300", "tolerances: cmm_e0_a_um must be above 0 and at most 10000", 18),
    ("cmm_e0_k = 300", "cmm_e0_k = 0.01", "tolerances: cmm_e0_k must be 1 to 1e+06, not 0.01", 18),
    ("pform_um = 1.7, psize_um = 1.0 }", "pform_um = 1e300, psize_um = 1.0 }", "pform_um must be above 0 and at most 10000",
     26),
    ('file = "sphere_single.csv"\ndiameter_mm = 25.00018\nuncertainty_um = 0.1',
     'file = "sphere_single.csv"\ndiameter_mm = 25.00018\nuncertainty_um = 1e300', "uncertainty_um must be 0 to 10000", 26),
    ("cmm_e0_a_um = 1.8, ", "", "cmm_e0_k and cmm_e0_b_um need cmm_e0_a_um", 18),
    ("cmm_e0_k = 300,", "cmm_e0_k = 300, cmm_e0_b_um = 1.0,", "cmm_e0_b_um (the cap B, 1 um) must not be below", 18),
    ('file = "sphere_single.csv"\ndiameter_mm = 25.00018', 'file = "sphere_single.csv"\ndiameter_mm = -25',
     "diameter_mm must be a positive number", 26),
    ("tolerances = { pform_um = 1.7, psize_um = 1.0 }", "tolerances = { ploc_um = 1.0 }", "needs points of several styli", 26),
    ('id = "probing-single"\n', 'id = "probing-single"\nfoot_mm = 3\n', "unknown key 'foot_mm'", 29),
    # E150's MPE stated for a file without E150 values (the rows with a ram offset taken out below)
    ("cmm_e150_k = 250,", "cmm_e150_k = 250,", "tolerances: cmm_e150_a_um is given, but the measurements hold no E150 value", 18),
])
def test_bad_options_name_campaign_toml_and_the_line(campaign, examples, old, new, words, line):
    toml = campaign / "campaign.toml"
    text = (examples / "cmm" / "campaign.toml").read_text()
    assert old in text
    toml.write_text(text.replace(old, new, 1))
    if "E150" in words:
        e0 = campaign / "e0_gauge_blocks.csv"
        e0.write_text("".join(row for row in e0.read_text().splitlines(keepends=True) if not row.rstrip().endswith(",150")))
    with pytest.raises(AxiscalError) as caught:
        run_campaign(campaign)
    assert words in caught.value.message and caught.value.path == str(toml)
    assert caught.value.line == line


def test_a_sphere_given_in_another_unit_names_diameter_mm_and_the_points_file(campaign):
    toml = campaign / "campaign.toml"
    toml.write_text(toml.read_text().replace("diameter_mm = 25.00018", "diameter_mm = 2500", 1))
    with pytest.raises(AxiscalError) as caught:
        run_campaign(campaign)
    assert "(diameter_mm 2500 mm)" in caught.value.message and caught.value.path.endswith("sphere_single.csv")
