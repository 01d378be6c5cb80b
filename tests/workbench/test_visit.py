"""A visit through the Workbench's calls: each controller's table corrects the virtual machine it is loaded in."""

from __future__ import annotations

import math
import shutil
import time
import warnings
from importlib import resources
from pathlib import Path

import pytest

from axiscal.errors import AxiscalError
from axiscal.workbench import Workbench, create_workbench_app

with warnings.catch_warnings():  # Starlette's notice that its test client will move to httpx2
    warnings.simplefilter("ignore")
    from starlette.testclient import TestClient

VISIT = {"title": "Visit", "date": "2026-11-26", "operator": "J. Doe", "machine": "VMC 1", "instrument": "Laser",
         "A_um": 45, "E_um": 40, "R_um": 5, "B_um": 6, "tests": ["positioning-X"]}
XZ = Path(str(resources.files("axiscal") / "data" / "xz_module"))
# one run each way: A and R are not defined (ISO 230-2 needs runs to scatter), E and B are
PLAN = {"start_mm": 20, "end_mm": 170, "targets": 5, "runs": 1, "overrun_mm": 5, "dwell_s": 1}


def _with_the_xz_module(data):
    """The built-in XZ module (its X axis 34 um out over 190 mm) as a machine of the data folder."""
    folder = data / "machines" / "xz"
    folder.mkdir(parents=True)
    for name in ("machine.toml", "x_errors.csv", "z_errors.csv"):
        shutil.copyfile(XZ / name, folder / name)
    return {"machine_choice": "machines/xz/machine.toml"}


@pytest.mark.parametrize("controller", ["fanuc", "siemens", "heidenhain"])
def test_the_as_left_run_with_the_table_loaded(tmp_path, controller):
    bench = Workbench(tmp_path / "data", db=str(tmp_path / "h.sqlite"), speed=80.0)
    bench.new_visit(VISIT | {"controller": controller} | _with_the_xz_module(bench.data))
    bench.make_plan(PLAN)
    bench.connect({"instrument": "sim", "controller": "sim"})
    bench.start_run("as-found")
    assert bench.run.wait(30) == "done"
    table = bench.compensate()
    assert (bench.data / table["file"]).is_file() and table["controller"] == controller
    bench.start_run("as-left")
    assert bench.run.wait(30) == "done"
    changes = {c["figure"]: c for c in bench.before_after()["changes"]}
    assert math.isnan(changes["A"]["before"])
    # the table takes the systematic error away; tables of one curve leave the reversal (B) where it was
    assert changes["E"]["after"] < changes["E"]["before"] / 4
    if controller == "heidenhain":  # a table per direction
        assert changes["B"]["after"] < changes["B"]["before"] / 4
    with TestClient(create_workbench_app(bench), base_url="http://127.0.0.1:8770") as client:
        answer = client.get("/api/results", params={"phase": "as-left"})
    assert answer.status_code == 200
    checks = {c["figure"]: c for c in answer.json()["tests"][0]["checks"]}
    assert checks["A"]["value"] is None and checks["E"]["value"] > 0  # NaN is sent as null


def test_before_after_says_what_it_waits_for_until_the_as_left_run_has_ended(tmp_path):
    bench = Workbench(tmp_path / "data", db=str(tmp_path / "h.sqlite"), speed=80.0)
    bench.new_visit(VISIT)
    bench.make_plan(PLAN)
    bench.connect({"instrument": "sim", "controller": "sim"})
    bench.start_run("as-found")
    assert bench.run.wait(30) == "done"
    with pytest.raises(AxiscalError, match=r"^Before / after waits for the as-left run: make the table first"):
        bench.before_after()
    bench.compensate()
    with pytest.raises(AxiscalError, match=r"^Before / after waits for the as-left run: run as left with the table loaded"):
        bench.before_after()
    bench.speed = 2.0  # the as-left run takes some seconds: asked while it goes on
    bench.start_run("as-left")
    with pytest.raises(AxiscalError, match=r"^Before / after waits for the as-left run to end \(\d+ of 10 stops taken,"
                                           r" (running|ready)\): it is shown as soon as the run has ended$"):
        bench.before_after()
    while not bench.run.stops:
        time.sleep(0.02)
    bench.run.abort()
    assert bench.run.wait(30) == "aborted" and bench.run.resumable
    with pytest.raises(AxiscalError, match=r"ended short \(\d+ of 10 stops, aborted\): resume it \(Run\)$"):
        bench.before_after()
    bench.speed = 80.0
    bench.start_run("as-left", resume=True)
    assert bench.run.wait(30) == "done"
    assert len(bench.before_after()["changes"]) == 4
