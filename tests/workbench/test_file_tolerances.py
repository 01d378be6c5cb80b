"""A test taken from a file states its tolerance in the unit it reports (µm, or arcsec for a squareness and a rotary
axis): it is written as the test's own tolerances in campaign.toml, and the campaign's evaluation assesses it."""

from __future__ import annotations

import shutil
import tomllib
from pathlib import Path

import pytest

from axiscal.workbench import FormErrors, Workbench
from axiscal.workbench.added import tolerance_of

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
VISIT = {"title": "Visit", "date": "2026-11-27", "operator": "J. Doe", "machine": "Mill", "instrument": "Laser",
         "A_um": 45, "E_um": 40, "R_um": 5, "B_um": 6}
STRAIGHTNESS = {"kind": "straightness", "file": "straightness_profile.csv", "axis": "X", "direction": "Y"}
SQUARENESS = {"kind": "squareness", "file": "squareness_x.csv", "second": "squareness_y.csv", "plane": "XY"}
BALLBAR = {"kind": "ballbar", "file": "ballbar_run.csv", "radius_mm": 100, "plane": "XY"}
ROTARY = {"kind": "positioning", "file": "rotary_run.csv", "axis": "C"}


@pytest.fixture
def bench(tmp_path):
    bench = Workbench(tmp_path / "data", db=str(tmp_path / "h.sqlite"))
    for path in ("straightness_profile.csv", "squareness_x.csv", "squareness_y.csv", "ballbar/ballbar_run.csv",
                 "rotary_run.csv"):
        shutil.copyfile(EXAMPLES / path, bench.data / Path(path).name)
    bench.new_visit(VISIT | {"machine_choice": "new", "machine_chain": "CFXYZ",
                             "machine_travels": "X=0:600, Y=0:400, Z=0:300, C=0:360", "tests": ["positioning-C"]})
    return bench


def _figure(result: dict, unit: str) -> float:
    return next(c["value"] for c in result["checks"] if c["unit"] == unit)


def test_each_test_from_a_file_is_assessed_against_the_tolerance_stated(bench):
    """Without a tolerance a test is not assessed; with one, its figure is held against it: a limit above the
    figure passes, one below fails, as the campaign's rule decides."""
    bench.add_file_test(STRAIGHTNESS)
    plain = {t["id"]: t for t in bench.results()["tests"]}["straightness-X"]
    assert plain["verdict"] == "not assessed"
    bench.remove_test("straightness-X")

    for form, field in ((STRAIGHTNESS, "tolerance_um"), (SQUARENESS, "tolerance_arcsec"), (BALLBAR, "tolerance_um"),
                        (ROTARY, "tolerance_arcsec")):
        bench.add_file_test(form | {field: 1e5})  # far above any figure: passes
    results = {t["id"]: t for t in bench.results()["tests"]}
    assert {i: results[i]["verdict"] for i in results} == {"positioning-C": "pass", "straightness-X": "pass",
                                                           "squareness-XY": "pass", "ballbar-XY": "pass"}
    entries = {t["id"]: t for t in tomllib.loads((bench.folder / "campaign.toml").read_text())["tests"]}
    assert entries["straightness-X"]["tolerances"] == {"straightness_um": 1e5}
    assert entries["squareness-XY"]["tolerances"] == {"squareness_arcsec": 1e5}
    assert entries["ballbar-XY"]["tolerances"] == {"circular_deviation_um": 1e5}
    assert entries["positioning-C"]["tolerances"] == {"E_arcsec": 1e5}  # the rotary axis's waiting test took it
    rotary = results["positioning-C"]
    assert [c["limit"] for c in rotary["checks"] if c["figure"] == "E"] == [1e5] and all(
        c["unit"] == "arcsec" for c in rotary["checks"])

    # a limit below the figure fails it
    straightness = _figure(results["straightness-X"], "um")
    bench.remove_test("straightness-X")
    bench.add_file_test(STRAIGHTNESS | {"tolerance_um": round(abs(straightness) / 2, 3)})
    assert {t["id"]: t["verdict"] for t in bench.results()["tests"]}["straightness-X"] == "fail"


def test_a_tolerance_in_the_wrong_unit_is_named_beside_its_field(bench):
    with pytest.raises(FormErrors) as refused:
        bench.add_file_test(SQUARENESS | {"tolerance_um": 5})
    assert refused.value.fields == {"tolerance_um": "this test's tolerance (squareness_arcsec) is in arcsec: give it as"
                                                    " tolerance_arcsec"}
    with pytest.raises(FormErrors) as refused:
        bench.add_file_test(ROTARY | {"tolerance_um": 5})
    assert refused.value.fields == {"tolerance_um": "this test's tolerance (E_arcsec) is in arcsec: give it as tolerance_arcsec"}
    with pytest.raises(FormErrors) as refused:
        bench.add_file_test(STRAIGHTNESS | {"tolerance_um": -1})
    assert set(refused.value.fields) == {"tolerance_um"}
    assert [t["id"] for t in bench.tests()] == ["positioning-C"]  # nothing added
    assert tolerance_of("diagonal") == ("diagonal_um", "tolerance_um") and tolerance_of("rtx", "X") is None
