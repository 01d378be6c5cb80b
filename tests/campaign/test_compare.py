"""``axiscal report --compare``: every plot kind draws the compared campaign, results.json carries the
series it needs, and a results.json without them (an earlier release's) still compares.

Each campaign is compared with a modified copy of itself: every deviation in its data files scaled
by 1.6 (and the machine model's error tables with them), so the compared series differ from this
campaign's and are known from it.
"""

from __future__ import annotations

import copy
import csv
import json
import shutil
from importlib import resources
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as hs

from axiscal.campaign import load_campaign, plot_volume, plot_volume_change, run_test, same_grid
from axiscal.errors import AxiscalError
from axiscal.model import load_machine
from axiscal.report import report_campaign

pytestmark = pytest.mark.filterwarnings("ignore::UserWarning")

VMC850 = Path(__file__).parent / "data" / "vmc850"
XZ = Path(str(resources.files("axiscal") / "data" / "xz_module"))
EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
SCALE = 1.6

#: a campaign of the XZ module's model: a diagonal test and the volumetric map
XZ_CAMPAIGN = """\
[campaign]
title = "XZ module"
date = 2026-11-20
operator = "A. Technician"

[machine]
name = "XZ linear module"
model = "machine.toml"

[tolerances]
diagonal_um = 50.0

[[tests]]
kind = "diagonal"
from = "X=0,Z=0"
to = "X=190,Z=190"
interferometer = "diagonal_laser.csv"
"""

#: test id -> the legend entries its plot shows for the compared campaign
LEGENDS = {
    "positioning-X-1": ("as found: mean x̄↑", "as found: mean x̄↓"),
    "positioning-Y-1": ("as found: mean x̄↑", "as found: mean x̄↓"),
    "straightness-X-1": ("before: profile", "before: about its line"),
    "separation-X-1": ("before: profile R", "before: motion S", "before: yaw"),
    "squareness-XY-1": ("before: measured", "before: line"),
    "ballbar-XY-1": ("before: ccw", "before: cw"),
    "diagonal-1": ("before: model prediction", "before: E_BD", "before: E_AD"),
}
#: the series each kind adds to its figures (absent from an earlier release's results.json)
SERIES_KEYS = {"straightness": "profile", "separation": "columns", "squareness": "runs", "ballbar": "trace", "diagonal": "points"}


def _scaled_copy(source: Path, target: Path) -> Path:
    """A copy of a campaign folder with every deviation (columns in um or urad, and a laser's reading
    about its nominal) scaled by :data:`SCALE`; comment lines kept."""
    shutil.copytree(source, target)
    for path in target.glob("*.csv"):
        lines = path.read_text().splitlines()
        comments = [line for line in lines if line.startswith("#")]
        rows = list(csv.reader(line for line in lines if not line.startswith("#")))
        header = rows[0]
        scaled = [i for i, name in enumerate(header) if name.endswith(("_um", "_urad")) and not name.startswith("position")]
        for row in rows[1:]:
            for i in scaled:
                if row[i]:
                    row[i] = repr(float(row[i]) * SCALE)
            if header[:2] == ["nominal_mm", "measured_mm"]:
                nominal = float(row[0])
                row[1] = repr(nominal + (float(row[1]) - nominal) * SCALE)
        with path.open("w", newline="") as handle:
            handle.write("".join(f"{line}\n" for line in comments))
            csv.writer(handle).writerows(rows)
    return target


def _xz_campaign(folder: Path) -> Path:
    folder.mkdir()
    for name in ("machine.toml", "x_errors.csv", "z_errors.csv", "diagonal_laser.csv"):
        shutil.copy(XZ / name, folder / name)
    (folder / "campaign.toml").write_text(XZ_CAMPAIGN)
    return folder


@pytest.fixture(scope="module")
def compared(tmp_path_factory):
    """Both campaigns reported against their scaled copies: id -> TestResult, the written results, folders."""
    root = tmp_path_factory.mktemp("compare")
    out = {"tests": {}, "written": {}, "before": {}, "root": root}
    for name, make in (("vmc850", lambda f: shutil.copytree(VMC850, f)), ("xz", _xz_campaign)):
        folder = root / name
        make(folder)
        _scaled_copy(folder, root / f"{name}-scaled")
        before = report_campaign(root / f"{name}-scaled", root / f"{name}-before")
        after = report_campaign(folder, root / f"{name}-after", compare=before.results)
        out["tests"].update({t.id: t for t in after.results_data.tests})
        out["written"][name] = json.loads(after.results.read_text())
        out["before"][name] = json.loads(before.results.read_text())
        out[name] = after
    return out


@pytest.mark.parametrize("test_id", LEGENDS)
def test_every_plot_kind_draws_the_compared_campaign(compared, test_id):
    test = compared["tests"][test_id]
    (plot,) = test.plots
    for label in LEGENDS[test_id]:
        assert label in plot.svg, (test_id, label)


def test_the_page_shows_the_overlays_and_the_volumetric_change(compared):
    vmc850 = compared["vmc850"].html.read_text()
    for test_id in ("straightness-X-1", "separation-X-1", "squareness-XY-1", "ballbar-XY-1"):
        article = vmc850.split(f'id="{test_id}"', 1)[1].split("</article>", 1)[0]
        assert LEGENDS[test_id][0] in article
    xz = compared["xz"]
    change = xz.results_data.model["plots"][1]
    assert change.title.startswith("Change of the volumetric error")
    assert "|e| now − |e| before / µm" in change.svg  # the colour scale's label
    assert change.title in xz.html.read_text()
    assert xz.results_data.warnings == []


def _series(written, test_id):
    return next(t for t in written["tests"] if t["id"] == test_id)["figures"]


def test_results_json_carries_the_series_of_each_plot(compared, run_cli):
    root, written = compared["root"], compared["written"]
    folder = root / "vmc850"
    profile = _series(written["vmc850"], "straightness-X-1")["profile"]
    x = np.loadtxt(folder / "straightness_x.csv", delimiter=",", skiprows=2)
    assert profile["position_mm"] == pytest.approx(x[:, 0], abs=1e-4)  # rounded to SERIES_DECIMALS
    assert profile["deviation_um"] == pytest.approx(x[:, 1], abs=1e-4)
    figures = _series(written["vmc850"], "straightness-X-1")
    assert np.ptp(profile["residual_um"]) == pytest.approx(figures["straightness_um"], abs=2e-4)

    status, _, _ = run_cli("separate", folder / "probes_x.csv", "--spacing-mm", "15", "-o", root / "sep.csv")
    assert status == 0
    columns = _series(written["vmc850"], "separation-X-1")["columns"]
    with (root / "sep.csv").open() as handle:
        table = list(csv.DictReader(handle))
    for key in ("position_mm", "profile_um", "motion_um", "yaw_urad"):
        expected = [float(row[key]) if row[key] else None for row in table]
        got = columns[key]
        assert [v is None for v in got] == [v is None for v in expected], key
        assert [v for v in got if v is not None] == pytest.approx([v for v in expected if v is not None], abs=1e-4), key

    square = _series(written["vmc850"], "squareness-XY-1")
    for which in ("first", "second"):
        run = square["runs"][which]
        slope_um_per_mm = np.polyfit(run["position_mm"], run["line_um"], 1)[0]
        assert slope_um_per_mm == pytest.approx(square[f"slope_{which}"] * 1e3, rel=1e-6)
        assert len(run["deviation_um"]) == len(run["position_mm"])

    trace = _series(written["vmc850"], "ballbar-XY-1")["trace"]
    assert set(trace) == {"ccw", "cw"}
    assert all(len(path["angle_deg"]) == len(path["deviation_um"]) == 360 for path in trace.values())

    _, out, _ = run_cli("diagonal", "--machine", root / "xz" / "machine.toml", "--from", "X=0,Z=0", "--to", "X=190,Z=190",
                        "--interferometer", root / "xz" / "diagonal_laser.csv", "--json")
    points, single = _series(written["xz"], "diagonal-1")["points"], json.loads(out)["points"]
    assert set(points) == set(single)
    for key, values in single.items():
        assert points[key] == pytest.approx(values, abs=1e-9), key

    drawn = written["xz"]["volumetric"]["map"]
    assert drawn["axes"] == ["X", "Z"] and np.shape(drawn["e_um"]) == (21, 21)
    assert np.max(drawn["e_um"]) == pytest.approx(written["xz"]["volumetric"]["max_um"], abs=1e-4)


def test_the_compared_series_are_the_other_campaigns(compared):
    """The scaled copy's series are this campaign's times the scale: what the overlay draws is the other campaign."""
    now, before = compared["written"], compared["before"]
    assert np.array(_series(before["vmc850"], "straightness-X-1")["profile"]["deviation_um"]) == pytest.approx(
        SCALE * np.array(_series(now["vmc850"], "straightness-X-1")["profile"]["deviation_um"]), abs=1e-3)
    assert np.array(_series(before["xz"], "diagonal-1")["points"]["E_BD_um"]) == pytest.approx(
        SCALE * np.array(_series(now["xz"], "diagonal-1")["points"]["E_BD_um"]), abs=1e-3)


def _earlier_release(results: dict) -> dict:
    """A results.json as the release before these series wrote it."""
    old = copy.deepcopy(results)
    for test in old["tests"]:
        test["figures"].pop(SERIES_KEYS.get(test["kind"], ""), None)
    old.get("volumetric", {}).pop("map", None)
    return old


@pytest.mark.parametrize("name", ["vmc850", "xz"])
def test_an_earlier_results_json_still_compares(compared, tmp_path, name):
    old = tmp_path / "old.json"
    old.write_text(json.dumps(_earlier_release(compared["before"][name])))
    files = report_campaign(compared["root"] / name, tmp_path / "report", compare=old)
    for test in files.results_data.tests:
        overlaid = "before:" in test.plots[0].svg or "as found:" in test.plots[0].svg  # positioning names it "as found"
        assert overlaid == (test.kind == "positioning"), test.id  # positioning's targets were there already
    assert len(files.results_data.model.get("plots", [])) == (1 if name == "xz" else 0)
    assert "Change" in files.html.read_text()  # the verdict table still compares the figures
    assert files.results_data.warnings == []


def test_tests_are_matched_by_id(compared, tmp_path):
    renamed = copy.deepcopy(compared["before"]["vmc850"])
    for test in renamed["tests"]:
        test["id"] = "other-" + test["id"]
    path = tmp_path / "renamed.json"
    path.write_text(json.dumps(renamed))
    files = report_campaign(compared["root"] / "vmc850", tmp_path / "report", compare=path)
    assert all("before:" not in t.plots[0].svg for t in files.results_data.tests)


def test_the_volumetric_change_needs_the_same_grid(compared, tmp_path):
    moved = copy.deepcopy(compared["before"]["xz"])
    moved["volumetric"]["map"]["grid_mm"]["X"] = [v + 1.0 for v in moved["volumetric"]["map"]["grid_mm"]["X"]]
    path = tmp_path / "moved.json"
    path.write_text(json.dumps(moved))
    files = report_campaign(compared["root"] / "xz", tmp_path / "report", compare=path)
    assert len(files.results_data.model["plots"]) == 1
    assert any("another grid" in w for w in files.results_data.warnings)


def test_a_malformed_compared_series_is_one_line(compared, tmp_path, run_cli):
    broken = copy.deepcopy(compared["before"]["vmc850"])
    _series(broken, "ballbar-XY-1")["trace"]["ccw"]["deviation_um"] = "large"
    path = tmp_path / "broken.json"
    path.write_text(json.dumps(broken))
    status, _, err = run_cli("report", compared["root"] / "vmc850", "-o", tmp_path / "report", "--compare", path)
    assert status == 2 and err.count("\n") == 1 and "Traceback" not in err
    assert "ballbar-XY-1" in err and "compared results.json" in err and f"{path}: " in err
    assert not (tmp_path / "report").exists()


def _maps(count: int, letters: str) -> tuple[dict, dict]:
    rng = np.random.default_rng(7)
    grid = {k: list(np.linspace(0.0, 100.0, count)) for k in letters}
    shape = (count,) * len(letters) if len(letters) < 3 else (count, count, 3)
    if len(letters) == 3:
        grid[letters[2]] = [0.0, 50.0, 100.0]
    now = {"axes": list(letters), "grid_mm": grid, "e_um": rng.uniform(0, 10, shape).tolist()}
    before = {**now, "e_um": rng.uniform(0, 10, shape).tolist()}
    if len(letters) == 1:
        for m in (now, before):
            m["components_um"] = {k: rng.normal(0, 5, count).tolist() for k in ("ex", "ey", "ez")}
    return now, before


@pytest.mark.parametrize("letters", ["X", "XY", "XYZ"])
def test_the_change_is_drawn_for_one_two_and_three_axes(tmp_path, letters):
    now, before = _maps(5, letters)
    assert same_grid(now, before)
    path = plot_volume_change(now, before, tmp_path / "change.svg", label="as found")
    text = path.read_text()
    assert "|e| now − |e| as found" in text
    other = {**before, "grid_mm": {**before["grid_mm"], letters[0]: [v * 2 for v in before["grid_mm"][letters[0]]]}}
    assert not same_grid(now, other)
    with pytest.raises(AxiscalError, match="different grids"):
        plot_volume_change(now, other, tmp_path / "never.svg")


def test_a_three_axis_map_keeps_three_slices_of_the_third_axis(tmp_path):
    machine = load_machine(EXAMPLES / "xfyz_machine" / "machine.toml")
    drawn = plot_volume(machine, tmp_path / "map.png", count=4)["map"]
    assert drawn["axes"] == ["X", "Y", "Z"] and np.shape(drawn["e_um"]) == (4, 4, 3)
    z = np.linspace(*machine.travel_m("Z"), 4) * 1e3
    assert drawn["grid_mm"]["Z"] == pytest.approx([z[0], z[2], z[3]])  # start, middle and end, as drawn
    assert drawn["grid_mm"]["X"] == pytest.approx(np.linspace(*machine.travel_m("X"), 4) * 1e3)


_series_values = hs.one_of(
    hs.none(), hs.text(max_size=3), hs.integers(-5, 5), hs.floats(allow_nan=True),
    hs.lists(hs.one_of(hs.none(), hs.booleans(), hs.floats(allow_nan=True, allow_infinity=True), hs.text(max_size=2)), max_size=40),
    hs.dictionaries(hs.sampled_from(["position_mm", "deviation_um", "x"]), hs.lists(hs.floats(-1e3, 1e3), max_size=3), max_size=2),
)


def _paths(series, prefix=()):
    """Every key path into a nested series object (mappings only; lists are leaves)."""
    out = []
    for key, value in series.items():
        out.append((*prefix, key))
        if isinstance(value, dict):
            out.extend(_paths(value, (*prefix, key)))
    return out


#: test id -> the series key its plot reads from the compared results.json
MUTATED = {"straightness-X-1": "profile", "squareness-XY-1": "runs", "separation-X-1": "columns", "ballbar-XY-1": "trace"}


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(data=hs.data())
def test_a_mutated_compared_series_draws_or_is_refused_cleanly(compared, data):
    test_id = data.draw(hs.sampled_from(sorted(MUTATED)), label="test")
    campaign = load_campaign(compared["root"] / "vmc850")
    spec = next(s for s in campaign.tests if s.id == test_id)
    series = copy.deepcopy(_series(compared["before"]["vmc850"], test_id)[MUTATED[test_id]])
    *parents, leaf = data.draw(hs.sampled_from(_paths(series)), label="path")
    target = series
    for key in parents:
        target = target[key]
    target[leaf] = data.draw(_series_values, label="value")
    try:
        result = run_test(campaign, spec, compare={spec.id: {MUTATED[test_id]: series}})
    except AxiscalError as exc:
        assert test_id in exc.message and "compared results.json" in exc.message
    else:
        assert result.plots[0].svg.startswith("<svg")


def test_the_verdict_table_says_before_after_and_change(compared):
    from axiscal.report import previous_figures, verdict_rows

    html = compared["vmc850"].html.read_text()
    head = html.split('id="verdict-table"', 1)[1].split("</thead>", 1)[0]
    columns = [cell.rsplit(">", 1)[1] for cell in head.split("</th>")[:-1]]
    assert columns == ["Test", "Axis", "Figure", "Before", "After", "Change", "Tolerance", "Result"]
    rows = verdict_rows(compared["vmc850"].results_data, previous_figures(compared["before"]["vmc850"]))
    row = next(r for r in rows if r["test_id"] == "straightness-X-1")
    after, before = float(row["value"]), float(row["before"])
    assert before == pytest.approx(SCALE * after, abs=2e-3)  # the scaled copy's straightness
    assert float(row["change"]) == pytest.approx(after - before, abs=2e-3)


def test_u_stands_beside_before_when_the_compared_results_have_it(compared):
    from axiscal.report import render_html

    other = copy.deepcopy(compared["before"]["vmc850"])
    results = compared["vmc850"].results_data
    assert "U before" not in render_html(results, compare=other)
    other["tests"][0]["uncertainty"] = {"k": 2, "E": 1.25, "A": 2.5}
    html = render_html(results, compare=other)
    head = html.split('id="verdict-table"', 1)[1].split("</thead>", 1)[0]
    assert "<th class=\"num\">Before</th><th class=\"num\">U before (k=2)</th><th class=\"num\">After</th>" in head
    body = html.split('id="verdict-table"', 1)[1].split("</table>", 1)[0]
    assert "1.250" in body and "2.500" in body


def test_the_pdf_prints_before_after_and_the_volumetric_change(compared, tmp_path):
    from axiscal.report.pdf import write_pdf

    for name in ("vmc850", "xz"):
        other = copy.deepcopy(compared["before"][name])
        other["tests"][0]["uncertainty"] = {"k": 2, "E": 1.25}
        path = write_pdf(compared[name].results_data, tmp_path / f"{name}.pdf", compare=other)
        assert path.read_bytes().startswith(b"%PDF-")


def test_the_diagonal_check_compares_with_the_diagonal_before(compared):
    from axiscal.report import previous_figures, verdict_rows

    rows = verdict_rows(compared["xz"].results_data, previous_figures(compared["before"]["xz"]))
    (row,) = [r for r in rows if r["test_id"] == "diagonal-1"]
    assert row["figure"] == "diagonal_error / µm"
    assert float(row["before"]) == pytest.approx(SCALE * float(row["value"]), abs=0.05)


def test_a_malformed_compared_map_is_named(compared, tmp_path):
    broken = copy.deepcopy(compared["before"]["xz"])
    broken["volumetric"]["map"]["e_um"] = [[1.0, 2.0]]
    path = tmp_path / "broken.json"
    path.write_text(json.dumps(broken))
    with pytest.raises(AxiscalError, match="compared results.json's volumetric map: before e_um must have shape"):
        report_campaign(compared["root"] / "xz", tmp_path / "report", compare=path)
    assert not (tmp_path / "report").exists()
