"""Every axis and every test of a visit: the machine chosen or described, each test's state, the tests from files."""

from __future__ import annotations

import shutil
import time
import tomllib
import warnings
from pathlib import Path

import pytest

from axiscal.campaign import load_campaign
from axiscal.errors import AxiscalError
from axiscal.workbench import FormErrors, Workbench, create_workbench_app
from axiscal.workbench.added import MAX_UPLOAD
from axiscal.workbench.machines import machine_choices, parse_travels

with warnings.catch_warnings():  # Starlette's notice that its test client will move to httpx2
    warnings.simplefilter("ignore")
    from starlette.testclient import TestClient

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
VISIT = {"title": "Visit", "date": "2026-11-26", "operator": "J. Doe", "machine": "VMC 1", "instrument": "Laser",
         "A_um": 45, "E_um": 40, "R_um": 5, "B_um": 6}
SIM = {"instrument": "sim", "controller": "sim"}


def plan(axis: str) -> dict:
    return {"axis": axis, "start_mm": 20, "end_mm": 120, "targets": 5, "runs": 1, "overrun_mm": 5, "dwell_s": 1}


@pytest.fixture
def bench(tmp_path):
    return Workbench(tmp_path / "data", db=str(tmp_path / "h.sqlite"), speed=80.0)


def states(bench) -> dict[str, str]:
    return {t["id"]: t["state"] for t in bench.tests()}


def test_a_three_axis_visit_runs_each_axis_and_repeats_one_without_losing_the_others(bench):
    answer = bench.new_visit(VISIT | {"tests": ["positioning-X", "positioning-Y", "positioning-Z"]})
    assert [a["axis"] for a in answer["machine"]["axes"]] == ["X", "Y", "Z"]  # the example machine, XFYZ
    assert states(bench) == dict.fromkeys(["positioning-X", "positioning-Y", "positioning-Z"], "planned")
    assert (bench.folder / "machine.toml").is_file() and (bench.folder / "y_errors.csv").is_file()
    for axis in "XYZ":
        assert bench.make_plan(plan(axis))["axis"] == axis
    bench.connect(SIM)
    assert "X 0 to 800 mm, Y 0 to 500 mm, Z 0 to 400 mm" in bench.connection.description
    for axis in "XYZ":
        bench.start_run("as-found", test=f"positioning-{axis}")
        assert bench.run.wait(30) == "done", bench.run.message
    assert set(states(bench).values()) == {"done"}
    campaign = load_campaign(bench.folder)  # the campaign room reads what the workbench wrote
    assert [t.id for t in campaign.tests] == ["positioning-X", "positioning-Y", "positioning-Z"]
    assert campaign.model == bench.folder / "machine.toml"
    results = bench.results()
    assert [t["id"] for t in results["tests"]] == ["positioning-X", "positioning-Y", "positioning-Z"]
    assert all(t["checks"] and t["plots"] for t in results["tests"])
    assert [t["id"] for t in bench.results(test="positioning-Y")["tests"]] == ["positioning-Y"]

    # Y run again and aborted: Y failed, X and Z kept; then Y repeated afresh, the others untouched
    x_before = (bench.folder / "positioning_x.csv").read_bytes()
    bench.speed = 5.0
    bench.start_run("as-found", test="positioning-Y", repeat=True)
    assert states(bench)["positioning-Y"] == "running"
    while not bench.run.stops:
        time.sleep(0.01)
    bench.run.abort()
    bench.run.wait(10)
    assert states(bench) == {"positioning-X": "done", "positioning-Y": "failed", "positioning-Z": "done"}
    assert [t["id"] for t in bench.tests() if t["resumable"]] == ["positioning-Y"]  # its stops are kept
    with pytest.raises(AxiscalError, match="a broken run left its stops here"):
        bench.start_run("as-found", test="positioning-Y")
    bench.speed = 80.0
    bench.start_run("as-found", test="positioning-Y", repeat=True)
    assert bench.run.wait(30) == "done"
    assert set(states(bench).values()) == {"done"} and (bench.folder / "positioning_x.csv").read_bytes() == x_before
    # the table and the as-left run of one axis; the report of every axis
    table = bench.compensate("Z")
    assert table["axis"] == "Z" and table["file"].endswith("Z.comp")
    with pytest.raises(AxiscalError, match="the table is for Z"):
        bench.start_run("as-left", test="positioning-X")
    bench.start_run("as-left", test="positioning-Z")
    assert bench.run.wait(30) == "done"
    assert {c["test"] for c in bench.before_after()["changes"]} == {"positioning-Z"}
    finished = bench.finish(pdf=False)
    assert {f["phase"] for f in finished["files"]} == {"as-found", "as-left"}


def test_a_test_not_asked_for_a_plan_beyond_the_travel_and_a_test_from_a_file_are_refused_with_their_reason(bench):
    bench.new_visit(VISIT | {"tests": ["positioning-X"]})
    with pytest.raises(AxiscalError, match="the visit has no test 'positioning-Y'"):
        bench.make_plan(plan("Y"))
    with pytest.raises(FormErrors) as refused:
        bench.make_plan(plan("X") | {"end_mm": 900})
    assert refused.value.fields == {"end_mm": "beyond the travel of X (0 to 800 mm)"}
    with pytest.raises(FormErrors) as refused:
        bench.make_plan(plan("Q"))
    assert "axis" in refused.value.fields
    with pytest.raises(FormErrors) as refused:
        bench.new_visit(VISIT | {"tests": []})
    assert set(refused.value.fields) == {"tests"}
    with pytest.raises(FormErrors) as refused:
        bench.new_visit(VISIT | {"tests": ["positioning-C"], "title": ""})
    assert set(refused.value.fields) == {"tests", "title"}  # every mistake of the form at once


def test_a_new_machine_from_the_short_form_and_one_of_the_data_folder(bench):
    answer = bench.new_visit(VISIT | {"machine": "Mill 5", "machine_choice": "new", "machine_chain": "CFXYZ",
                                      "machine_travels": "X=0:600, Y=0:400, Z=-300:0, C=0:360",
                                      "tests": ["positioning-X", "positioning-C"]})
    axes = {a["axis"]: a for a in answer["machine"]["axes"]}
    assert axes["Z"]["start"] == -300 and axes["C"]["rotary"] and axes["C"]["unit"] == "deg"
    assert {t["id"]: t["source"] for t in answer["tests"]} == {"positioning-X": "run", "positioning-C": "file"}
    assert states(bench)["positioning-C"] == "planned"
    for bad, field in (({"machine_chain": "XYZ"}, "machine_chain"), ({"machine_travels": "X=0:600"}, "machine_travels"),
                       ({"machine_travels": "X=5:1, Y=0:1, Z=0:1, C=0:1"}, "machine_travels")):
        with pytest.raises(FormErrors) as refused:
            bench.new_visit(VISIT | {"machine_choice": "new", "machine_chain": "CFXYZ",
                                     "machine_travels": "X=0:600, Y=0:400, Z=-300:0, C=0:360"} | bad)
        assert set(refused.value.fields) == {field}, refused.value.fields
    with pytest.raises(AxiscalError, match="write each axis as LETTER=START:END"):
        parse_travels("X from 0 to 600")
    # the trunnion example put in the data folder is offered, and chosen
    shutil.copytree(EXAMPLES / "trunnion_machine", bench.data / "machines" / "trunnion")
    offered = {m["choice"]: m for m in machine_choices(bench.data)}
    assert "example" in offered and offered["mill-5-2026-11-26/machine.toml"]["label"] == "earlier visit: Mill 5, 2026-11-26, CFXYZ"
    assert [a["axis"] for a in offered["machines/trunnion/machine.toml"]["axes"]] == ["A", "C", "X", "Y", "Z"]
    answer = bench.new_visit(VISIT | {"machine_choice": "machines/trunnion/machine.toml", "tests": ["positioning-Y"]})
    assert answer["machine"]["chain"] == "CAFXYZ"
    with pytest.raises(FormErrors) as refused:
        bench.new_visit(VISIT | {"machine_choice": "../../etc/machine.toml", "tests": ["positioning-X"]})
    assert set(refused.value.fields) == {"machine_choice"}


def _instrument_files(data: Path) -> None:
    folder = data / "instrument"
    folder.mkdir(parents=True)
    for path in ("straightness_profile.csv", "squareness_x.csv", "squareness_y.csv", "ballbar/ballbar_run.csv",
                 "rotary_run.csv", "imports/runs_per_column.toml", "imports/runs_per_column.csv", "imports/capture.rtx"):
        shutil.copyfile(EXAMPLES / path, folder / Path(path).name)
    (folder / "bad.csv").write_text("position_mm,deviation_um\n0,1\n10,abc\n20,2\n")


def test_tests_from_files_are_checked_at_once_and_evaluated_with_the_rest(bench):
    _instrument_files(bench.data)
    bench.new_visit(VISIT | {"machine_choice": "new", "machine_chain": "CFXYZ",
                             "machine_travels": "X=0:600, Y=0:400, Z=0:300, C=0:360", "tests": ["positioning-C"]})
    for form in ({"kind": "straightness", "file": "instrument/straightness_profile.csv", "axis": "X", "direction": "Y"},
                 {"kind": "squareness", "file": "instrument/squareness_x.csv", "second": "instrument/squareness_y.csv",
                  "plane": "XY"},
                 {"kind": "ballbar", "file": "instrument/ballbar_run.csv", "radius_mm": 100, "plane": "XY"},
                 {"kind": "positioning", "file": "instrument/rotary_run.csv", "axis": "C"},
                 {"kind": "columnmap", "file": "instrument/runs_per_column.toml", "second": "instrument/runs_per_column.csv",
                  "axis": "Y"},
                 {"kind": "rtx", "file": "instrument/capture.rtx", "unit": "um", "axis": "X"}):
        bench.add_file_test(form)
    assert states(bench) == {"positioning-C": "done", "straightness-X": "done", "squareness-XY": "done",
                             "ballbar-XY": "done", "positioning-Y": "done", "dynamics-X": "done"}
    # the rotary axis's test took its run from the file; the others were added
    entries = {t["id"]: t for t in tomllib.loads((bench.folder / "campaign.toml").read_text())["tests"]}
    assert entries["positioning-C"]["file"] == "files/rotary_run.csv" and entries["dynamics-X"]["kind"] == "dynamics"
    assert entries["positioning-Y"]["file"] == "files/runs_per_column_imported.csv"
    results = {t["id"]: t for t in bench.results()["tests"]}
    assert set(results) == set(entries) and all(t["verdict"] != "error" for t in results.values())
    assert results["squareness-XY"]["table"] and results["ballbar-XY"]["plots"]

    # a bad file: the reader's one line, naming the file as the form named it; the test is not added
    with pytest.raises(AxiscalError) as refused:
        bench.add_file_test({"kind": "straightness", "file": "instrument/bad.csv", "axis": "X", "direction": "Z"})
    assert str(refused.value) == "instrument/bad.csv:3: column 'deviation_um': 'abc' is not a number"
    with pytest.raises(AxiscalError, match="^instrument/straightness_profile.csv:1: missing column 'nominal_mm'"):
        bench.add_file_test({"kind": "diagonal", "file": "instrument/straightness_profile.csv", "from": "X=0,Y=0,Z=0",
                             "to": "X=600,Y=400,Z=300"})
    for form, fields in (({"kind": "ballbar", "file": "instrument/ballbar_run.csv"}, {"radius_mm", "plane"}),
                         ({"kind": "straightness", "file": "../h.sqlite", "axis": "X", "direction": "Y"}, {"file"}),
                         ({"kind": "scan", "file": "instrument/bad.csv"}, {"kind"})):
        with pytest.raises(FormErrors) as refused:
            bench.add_file_test(form)
        assert set(refused.value.fields) == fields
    assert len(states(bench)) == 6 and len(load_campaign(bench.folder).tests) == 6
    bench.remove_test("ballbar-XY")
    assert "ballbar-XY" not in states(bench) and len(load_campaign(bench.folder).tests) == 5


def test_a_file_uploaded_is_kept_in_the_visit_and_added_from_there(bench):
    bench.new_visit(VISIT | {"tests": ["positioning-X"]})
    with TestClient(create_workbench_app(bench), base_url="http://127.0.0.1:8770") as client:
        assert [m["choice"] for m in client.get("/api/machine-choices").json()] == ["example", "vmc-1-2026-11-26/machine.toml"]
        content = (EXAMPLES / "straightness_profile.csv").read_bytes() + b"\n" * (70 * 1024)  # beyond a form's 64 KiB
        answer = client.post("/api/upload", params={"name": "C:\\readings\\profile x.csv"}, content=content)
        assert answer.status_code == 200 and answer.json() == {"file": "vmc-1-2026-11-26/files/profile_x.csv"}
        offered = client.get("/api/data-files").json()
        assert offered[0] == "vmc-1-2026-11-26/files/profile_x.csv"  # the visit's own first
        assert not [f for f in offered if f.endswith(("campaign.toml", "machine.toml", "_errors.csv"))]
        added = client.post("/api/tests/add", json={"kind": "straightness", "file": answer.json()["file"], "axis": "X",
                                                    "direction": "Z"})
        assert added.status_code == 200 and added.json()["added"] == "straightness-X"
        assert [t["state"] for t in client.get("/api/tests").json()] == ["planned", "done"]
        assert client.post("/api/upload", params={"name": "big.csv"}, content=b"x" * (MAX_UPLOAD + 1)).status_code == 413
        assert client.post("/api/upload", params={"name": "empty.csv"}, content=b"").json()["error"].endswith("empty")
        bad = client.post("/api/tests/add", json={"kind": "ballbar", "file": answer.json()["file"], "radius_mm": 50,
                                                  "plane": "XY"})
        assert bad.status_code == 400 and "\n" not in bad.json()["error"]
        assert client.post("/api/tests/remove", json={"test": "positioning-X"}).status_code == 400


def test_the_example_machine_shipped_in_the_package_is_the_examples_one():
    from axiscal.workbench.machines import example_machine

    shipped = example_machine().parent
    for name in ("machine.toml", "x_errors.csv", "y_errors.csv", "z_errors.csv"):
        assert (shipped / name).read_bytes() == (EXAMPLES / "xfyz_machine" / name).read_bytes(), name


def test_the_visit_s_tests_and_plans_survive_a_restart_and_an_older_visit_gets_its_tests(tmp_path, bench):
    import json

    bench.new_visit(VISIT | {"tests": ["positioning-X", "positioning-Y"]})
    bench.make_plan(plan("Y"))
    bench.make_plan(plan("X") | {"runs": 2})
    again = Workbench(bench.data, db=bench.db, speed=80.0)  # the workbench started again
    state = again.state()
    assert [t["id"] for t in state["tests"]] == ["positioning-X", "positioning-Y"]
    assert set(state["plans"]) == {"X", "Y"} and state["plans"]["Y"]["axis"] == "Y"
    assert state["plans"]["X"]["form"]["runs"] == 2 and state["machine"]["chain"] == "XFYZ"
    assert state["machine"]["form"] == {"tests": ["positioning-X", "positioning-Y"]}  # the form as it was sent
    # a visit kept before the workbench knew its tests: the positioning of its axes, on the example machine
    saved = json.loads((bench.folder / "workbench.json").read_text())
    for key in ("tests", "plans", "machine"):
        saved.pop(key)
    saved["visit"]["axes"] = ["X"]  # as its form named them then
    (bench.folder / "workbench.json").write_text(json.dumps(saved))
    (bench.folder / "machine.toml").unlink()
    state = Workbench(bench.data, db=bench.db).state()
    assert [t["id"] for t in state["tests"]] == ["positioning-X"] and state["plans"]["X"]["axis"] == "X"


def test_a_diagonal_from_a_file_is_evaluated_on_the_visit_s_machine(bench):
    shutil.copytree(EXAMPLES / "xz_module", bench.data / "machines" / "xz")
    shutil.copyfile(EXAMPLES / "campaign" / "diagonal_0kg.csv", bench.data / "diagonal_0kg.csv")
    bench.new_visit(VISIT | {"machine_choice": "machines/xz/machine.toml", "tests": ["positioning-X"]})
    bench.add_file_test({"kind": "diagonal", "file": "diagonal_0kg.csv", "from": "X=0,Z=0", "to": "X=190,Z=190"})
    result = {t["id"]: t for t in bench.results()["tests"]}["diagonal-file"]
    assert result["verdict"] != "error" and result["plots"]
    with pytest.raises(AxiscalError, match="diagonal_0kg.csv"):  # the readings do not lie on this diagonal
        bench.add_file_test({"kind": "diagonal", "file": "diagonal_0kg.csv", "from": "X=0,Z=0", "to": "X=100,Z=190"})


def test_the_devices_run_moves_the_test_s_axis_of_the_visit_s_machine(tmp_path):
    from axiscal.positioning.plan import plan_test, write_plan
    from axiscal.workbench import DevicePlanRun, PlanRun, example_machine

    write_plan(plan_test(0.02, 0.12, 5, runs=1, seed=1), tmp_path / "plan_y.csv", axis="Y", dwell_s=1.0)
    run = PlanRun(tmp_path / "plan_y.csv", tmp_path / "positioning_y.csv", instrument="sim:umd", controller="sim",
                  axis="Y", machine=example_machine())
    try:
        assert isinstance(run, DevicePlanRun) and run.axis == "Y" and run._device.axis == "Y"
        assert run._device.limits("Y")[1] == pytest.approx(0.5)  # Y's travel on the example machine
    finally:
        run._instrument.close()
        run._device.close()
    with pytest.raises(AxiscalError, match="axis must be a linear axis letter"):
        PlanRun(tmp_path / "plan_y.csv", tmp_path / "positioning_y.csv", axis="C", machine=example_machine())


def test_a_file_refused_says_what_the_command_says(bench, run_cli, monkeypatch):
    _instrument_files(bench.data)
    (bench.data / "instrument" / "export.csv").write_text("Title\nMachine: X\n\nTarget (mm);Run 1\n0,000;1,5\nten;2,0\n")
    bench.new_visit(VISIT | {"tests": ["positioning-X"]})
    monkeypatch.chdir(bench.data)
    for form, command in (
        ({"kind": "straightness", "file": "instrument/bad.csv", "axis": "X", "direction": "Y"},
         ("straightness", "instrument/bad.csv")),
        ({"kind": "ballbar", "file": "instrument/straightness_profile.csv", "radius_mm": 100, "plane": "XY"},
         ("ballbar", "instrument/straightness_profile.csv", "--radius-mm", "100", "--plane", "XY")),
        ({"kind": "columnmap", "file": "instrument/runs_per_column.toml", "second": "instrument/export.csv", "axis": "X"},
         ("import", "map", "instrument/runs_per_column.toml", "instrument/export.csv")),
        ({"kind": "rtx", "file": "instrument/bad.csv", "unit": "um", "axis": "X"},
         ("import", "rtx", "instrument/bad.csv", "--unit", "um")),
    ):
        with pytest.raises(AxiscalError) as refused:
            bench.add_file_test(form)
        status, _, err = run_cli(*command)
        assert status == 2 and err.strip() == f"axiscal: error: {refused.value}", (err, str(refused.value))
    assert len(bench.tests()) == 1
