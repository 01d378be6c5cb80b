"""``axiscal report``: the report folder, results.json equal to the single commands, atomic writes."""

from __future__ import annotations

import contextlib
import io
import json
import shutil
from pathlib import Path

import pytest

from axiscal.campaign import run_campaign

pytestmark = pytest.mark.filterwarnings("ignore::UserWarning")

#: a campaign of a 3-axis machining centre with every kind of file but the model's (test data)
VMC850 = Path(__file__).parent / "data" / "vmc850"


@pytest.fixture
def campaign(tmp_path):
    folder = tmp_path / "campaign"
    shutil.copytree(VMC850, folder)
    return folder


@pytest.fixture(scope="module")
def reported(tmp_path_factory):
    """``axiscal report`` of a copy of the campaign, run once for the tests that read what it wrote:
    (status, stdout, stderr, the campaign folder)."""
    from axiscal.cli.main import main

    folder = tmp_path_factory.mktemp("reported") / "campaign"
    shutil.copytree(VMC850, folder)
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        status = main(["report", str(folder)])
    return status, out.getvalue(), err.getvalue(), folder


@pytest.fixture(scope="module")
def figures(tmp_path_factory):
    """Each test's figures as run_campaign gives them, run once for the tests that hold them against the commands."""
    folder = tmp_path_factory.mktemp("figures") / "campaign"
    shutil.copytree(VMC850, folder)
    return {t.id: t.figures for t in run_campaign(folder).tests}


def test_report_writes_the_page_and_results(reported):
    status, out, err, campaign = reported
    assert status == 0, err
    folder = campaign / "report"
    assert (folder / "report.html").is_file() and (folder / "results.json").is_file()
    assert out.startswith("FAIL: 6 tests")
    results = json.loads((folder / "results.json").read_text())
    assert results["schema"] == "axiscal-results/1"
    assert results["software"]["name"] == "axiscal"
    assert results["verdict"] == "fail"
    assert {t["id"]: t["verdict"] for t in results["tests"]} == {
        "positioning-X-1": "pass",
        "positioning-Y-1": "pass",
        "straightness-X-1": "pass",
        "squareness-XY-1": "fail",
        "separation-X-1": "pass",
        "ballbar-XY-1": "pass",
    }
    assert results["campaign"]["machine"]["name"] == "VMC 850"


def test_positioning_figures_equal_the_positioning_command(run_cli, figures):
    status, out, _ = run_cli("positioning", VMC850 / "positioning_x.csv", "--json")
    assert status == 0
    single = json.loads(out)
    figures = figures["positioning-X-1"]
    for key in ("A", "A_up", "A_down", "B", "B_mean", "E", "E_up", "E_down", "M", "R", "R_up", "R_down"):
        assert figures[key] == pytest.approx(single[key], rel=1e-12, abs=1e-12), key


def test_straightness_and_squareness_equal_their_commands(run_cli, figures, campaign):
    results = figures
    _, out, _ = run_cli("straightness", campaign / "straightness_x.csv", "--json")
    assert results["straightness-X-1"]["straightness_um"] == pytest.approx(json.loads(out)["straightness_um"], rel=1e-12)
    _, out, _ = run_cli("separate", campaign / "probes_x.csv", "--spacing-mm", "15", "-o", campaign / "sep.csv")
    separated = run_cli("straightness", campaign / "sep.csv", "--json")[1]
    # the slide's straightness is the motion column: the separated profile file read with motion as deviation
    assert results["separation-X-1"]["points"] > 200
    assert json.loads(separated)["straightness_um"] == pytest.approx(results["separation-X-1"]["profile_straightness_um"], abs=1e-5)  # CSV rounding
    _, out, _ = run_cli("squareness", "--first", campaign / "square_first.csv", "--second", campaign / "square_second.csv", "--json")
    assert results["squareness-XY-1"]["squareness_arcsec"] == pytest.approx(json.loads(out)["squareness_arcsec"], rel=1e-12)


def test_a_bad_campaign_writes_nothing(run_cli, campaign):
    text = (campaign / "campaign.toml").read_text()
    (campaign / "campaign.toml").write_text(text.replace('file = "positioning_x.csv"', 'file = "../positioning_x.csv"'))
    status, out, err = run_cli("report", campaign)
    assert status == 2
    assert err.count("\n") == 1 and "campaign.toml:" in err and "Traceback" not in err
    assert not (campaign / "report").exists()


def test_a_failed_run_keeps_the_previous_report(run_cli, campaign, reported, monkeypatch):
    assert reported[0] == 0
    shutil.copytree(reported[3] / "report", campaign / "report")  # the report this command wrote before
    before = (campaign / "report" / "results.json").read_text()

    import axiscal.report.writer as writer

    def broken(*args, **kwargs):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(writer, "render_html", broken)
    status, _, err = run_cli("report", campaign)
    assert status == 2 and "No space left" in err
    assert (campaign / "report" / "results.json").read_text() == before
    assert sorted(p.name for p in campaign.iterdir() if p.name.startswith(".")) == []


def test_compare_shows_the_change(run_cli, campaign, reported):
    assert reported[0] == 0  # the same campaign reported before
    status, _, err = run_cli("report", campaign, "--compare", reported[3] / "report" / "results.json")
    assert status == 0, err
    html = (campaign / "report" / "report.html").read_text()
    assert "Compared with" in html and "+0.000" in html
    assert "as found: mean x̄↑" in html  # the positioning plots draw the other campaign's means behind, as found


def test_compare_refuses_a_file_that_is_not_results(run_cli, campaign, tmp_path):
    other = tmp_path / "other.json"
    other.write_text('{"hello": 1}')
    status, _, err = run_cli("report", campaign, "--compare", other)
    assert status == 2 and "results.json" in err


def test_pdf_is_a_print_of_the_report(run_cli, campaign):
    status, out, err = run_cli("report", campaign, "--pdf")
    assert status == 0, err
    pdf = (campaign / "report" / "report.pdf").read_bytes()
    assert pdf.startswith(b"%PDF-") and b"/Type/Pages" in pdf
    assert "pdf " in out


def test_typst_text_cannot_inject_markup():
    from axiscal.report.pdf import typst_string, typst_text

    assert typst_text('#set "x" \\ = *bold*') == '#"#set \\"x\\" \\\\ = *bold*"'
    assert typst_string("a\nb") == '"a b"'


def test_compensation_files_are_what_compensate_writes(run_cli, reported):
    status, _, _, campaign = reported
    assert status == 0
    results = json.loads((campaign / "report" / "results.json").read_text())
    assert results["compensation"] == [
        {"controller": "linuxcnc", "axis": "X", "file": "compensation/X.comp"},
        {"controller": "linuxcnc", "axis": "Y", "file": "compensation/Y.comp"},
    ]
    status, table, _ = run_cli("compensate", campaign / "positioning_x.csv", "--format", "linuxcnc")
    assert status == 0
    assert (campaign / "report" / "compensation" / "X.comp").read_text() == table


def test_ballbar_figures_equal_the_ballbar_command(run_cli, figures):
    results = figures
    status, out, _ = run_cli("ballbar", VMC850 / "ballbar_xy.csv", "--radius-mm", "100", "--plane", "XY",
                             "--feed-mm-min", "1000", "--json")
    assert status == 0
    single = json.loads(out)
    for key in ("G_ccw_um", "G_cw_um", "H_um", "squareness_urad", "scale_mismatch_ppm", "servo_mismatch_ms"):
        assert results["ballbar-XY-1"][key] == pytest.approx(single[key], rel=1e-12), key


def test_a_rotary_positioning_test_is_judged_in_arcseconds(tmp_path, examples):
    folder = tmp_path / "rotary"
    folder.mkdir()
    shutil.copy(examples / "rotary_run.csv", folder / "c_axis.csv")
    shutil.copy(examples / "positioning_run.csv", folder / "x_axis.csv")
    (folder / "campaign.toml").write_text(
        '[campaign]\ntitle = "Rotary table"\ndate = 2026-11-20\noperator = "A. Technician"\n\n'
        '[machine]\nname = "4-axis mill"\ncontroller = "heidenhain"\n\n'
        "[tolerances]\npositioning = { E_um = 20.0, E_arcsec = 15.0 }\n\n"
        '[[tests]]\nkind = "positioning"\naxis = "C"\nfile = "c_axis.csv"\n\n'
        '[[tests]]\nkind = "positioning"\naxis = "X"\nfile = "x_axis.csv"\n'
    )
    rotary, linear = run_campaign(folder).tests
    assert rotary.tolerances == {"E_arcsec": 15.0} and linear.tolerances == {"E_um": 20.0}
    assert rotary.figures["unit"] == "arcsec" and rotary.figures["E"] == pytest.approx(18.746, abs=5e-4)
    assert rotary.verdict == "fail" and linear.verdict == "pass"
    assert rotary.compensation[0]["file"] == "compensation/C.COM"
