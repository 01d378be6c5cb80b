"""A visit that survives: opened again after a server restart at the step it was at, listed while unfinished,
resumed after a run cut short, and held by one tab at a time."""

from __future__ import annotations

import time
import warnings

import pytest

from axiscal.errors import AxiscalError
from axiscal.workbench import TAB_HEADER, Workbench, create_workbench_app

with warnings.catch_warnings():  # Starlette's notice that its test client will move to httpx2
    warnings.simplefilter("ignore")
    from starlette.testclient import TestClient

VISIT = {"title": "Visit", "date": "2026-11-26", "operator": "J. Doe", "machine": "VMC 1", "serial": "S1",
         "instrument": "Laser", "A_um": 45, "E_um": 40, "R_um": 5, "B_um": 6, "tests": ["positioning-X"]}
PLAN = {"start_mm": 20, "end_mm": 170, "targets": 5, "runs": 1, "overrun_mm": 5, "dwell_s": 1}
SIM = {"instrument": "sim", "controller": "sim"}


def _bench(tmp_path, speed=80.0):
    return Workbench(tmp_path / "data", db=str(tmp_path / "h.sqlite"), speed=speed)


def test_a_restarted_workbench_opens_the_visit_at_its_step_and_goes_on(tmp_path):
    first = _bench(tmp_path)
    first.new_visit(VISIT)
    plan = first.make_plan(PLAN)
    first.connect(SIM)
    first.start_run("as-found")
    assert first.run.wait(30) == "done"
    table = first.compensate()
    first.set_step("compensate")

    again = _bench(tmp_path)  # the server restarted
    state = again.state()
    assert state["open"] and state["folder"] == "vmc-1-2026-11-26" and state["step"] == "compensate"
    assert state["visit"]["machine"] == "VMC 1" and state["plan_form"]["runs"] == 1 and state["connection"] == SIM | {"ini": ""}
    assert state["plan"]["steps"] == plan["steps"] and state["plan"]["targets_mm"] == pytest.approx(plan["targets_mm"])
    assert state["compensation"]["text"] == table["text"] and state["runs"] == {"as-found": True, "as-left": False}
    assert state["connected"] is None  # devices are connected again by hand
    with pytest.raises(AxiscalError, match="connect the instrument"):
        again.start_run("as-left")
    again.connect(SIM)
    again.start_run("as-left")
    assert again.run.wait(30) == "done"
    assert len(again.before_after()["changes"]) == 4


def test_unfinished_visits_are_listed_until_finished_and_can_be_continued(tmp_path):
    bench = _bench(tmp_path)
    bench.new_visit(VISIT)
    bench.make_plan(PLAN)
    bench.new_visit(VISIT | {"machine": "Lathe 2", "serial": ""})
    listed = {v["folder"]: v for v in bench.unfinished()}
    assert set(listed) == {"vmc-1-2026-11-26", "lathe-2-2026-11-26"}
    assert listed["vmc-1-2026-11-26"]["step"] == "visit" and listed["vmc-1-2026-11-26"]["machine"] == "VMC 1"
    state = bench.open_visit("vmc-1-2026-11-26")
    assert state["folder"] == "vmc-1-2026-11-26" and state["plan"] is not None
    assert _bench(tmp_path).state()["folder"] == "vmc-1-2026-11-26"  # the one continued is the one reopened
    for bad in ("../x", "", "nosuch", ".hidden"):
        with pytest.raises(AxiscalError):
            bench.open_visit(bad)
    bench.connect(SIM)
    bench.start_run("as-found")
    assert bench.run.wait(30) == "done"
    bench.finish(pdf=False)
    assert [v["folder"] for v in bench.unfinished()] == ["lathe-2-2026-11-26"]


def test_a_run_cut_short_before_a_restart_is_resumed_after_it(tmp_path):
    first = _bench(tmp_path, speed=20.0)
    first.new_visit(VISIT)
    first.make_plan(PLAN)
    first.connect(SIM)
    first.start_run("as-found")
    while len(first.run.stops) < 3:
        time.sleep(0.01)
    first.run.abort()
    first.run.wait(10)
    again = _bench(tmp_path)
    assert again.run_state() == {"state": "idle", "phase": "as-found", "resumable": True}
    again.connect(SIM)
    again.start_run("as-found", resume=True)
    assert again.run.wait(30) == "done" and len(again.run.stops) == 10


def test_a_damaged_state_file_is_said_and_the_workbench_starts(tmp_path):
    bench = _bench(tmp_path)
    bench.new_visit(VISIT)
    (bench.folder / "workbench.json").write_text("{ not json")
    again = _bench(tmp_path)
    state = again.state()
    assert not state["open"] and state["notice"].startswith("the visit that was open is not opened again: ")
    assert "workbench.json" in state["notice"] and state["unfinished"][0]["problem"]


def test_one_tab_holds_the_visit_and_another_follows_it_read_only(tmp_path):
    bench = _bench(tmp_path)
    with TestClient(create_workbench_app(bench), base_url="http://127.0.0.1:8770") as client:
        first, second = {TAB_HEADER: "tab-a"}, {TAB_HEADER: "tab-b"}
        assert client.post("/api/visit", json=VISIT, headers=first).status_code == 200
        with client.websocket_connect("ws://127.0.0.1:8770/ws?tab=tab-a") as socket:
            socket.receive_json()
            refused = client.post("/api/plan", json=PLAN, headers=second)
            assert refused.status_code == 409 and refused.json()["readonly"] is True
            assert "open in another tab" in refused.json()["error"]
            assert client.get("/api/state", headers=second).json()["readonly"] is True
            assert client.get("/api/state", headers=first).json()["readonly"] is False
            assert client.post("/api/step", json={"step": "run"}, headers=second).json()["readonly"] is True
            assert client.post("/api/plan", json=PLAN, headers=first).status_code == 200
            assert client.post("/api/step", json={"step": "plan"}, headers=first).json() == {"step": "plan"}
        # the first tab closed: the second takes the visit over
        for _ in range(100):
            if client.post("/api/plan", json=PLAN, headers=second).status_code == 200:
                break
            time.sleep(0.05)
        else:
            pytest.fail("the second tab never took the visit over")
        assert bench.tabs.owner == "tab-b" and bench.saved.step == "plan"
