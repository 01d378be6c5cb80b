"""Every public callable of the workbench room refuses bad arguments with AxiscalError naming them."""

from __future__ import annotations

import tempfile
from pathlib import Path

from api_cases import EXAMPLES, CaseTable, api

NEVER = Path("/tmp/axiscal-never-written")
NAN, INF = float("nan"), float("inf")
W = "workbench"
wb = api(W)
TABLE = CaseTable((W,))
bad = TABLE.bad
PLAN = EXAMPLES / "capture" / "plan_x.csv"
BENCH = wb.Workbench(Path(tempfile.mkdtemp(prefix="axiscal-bench-")) / "data")

bad(W, "checked", "form must be one of", lambda: wb.checked("campaign", {}), lambda: wb.checked(None, {}))
bad(W, "checked", "json object", lambda: wb.checked("visit", 5), lambda: wb.checked("plan", None))
bad(W, "checked", "targets", lambda: wb.checked("plan", {"start_mm": 0, "end_mm": 10, "targets": "many", "runs": 1,
                                                          "overrun_mm": 1, "dwell_s": 1}))
bad(W, "checked", "finite", lambda: wb.checked("plan", {"start_mm": 0, "end_mm": 10, "targets": 3, "runs": 1,
                                                         "overrun_mm": 1, "dwell_s": NAN}))
bad(W, "connect", "use one of", lambda: wb.connect("laser:/dev/ttyUSB0"), lambda: wb.connect("sim", "fanuc:localhost"))
bad(W, "connect", "no serial port", lambda: wb.connect("umd:/dev/axiscal-no-such-port"))
bad(W, "connect", "cannot reach linuxcncrsh", lambda: wb.connect("sim", "linuxcnc:127.0.0.1:1"))
bad(W, "connect", "controller", lambda: wb.connect("sim", ""), lambda: wb.connect("sim", None))
bad(W, "connect", "seed", lambda: wb.connect(seed=-1), lambda: wb.connect(seed=1.5))
bad(W, "PlanRun", "plan_csv", lambda: wb.PlanRun(None, NEVER / "run.csv"))
bad(W, "PlanRun", "output", lambda: wb.PlanRun(PLAN, None))
bad(W, "PlanRun", "speed", lambda: wb.PlanRun(PLAN, NEVER / "run.csv", speed=NAN), lambda: wb.PlanRun(PLAN, NEVER / "run.csv", speed=0))
bad(W, "PlanRun", "dwell_s", lambda: wb.PlanRun(PLAN, NEVER / "run.csv", dwell_s=-1.0))
bad(W, "PlanRun", "resume", lambda: wb.PlanRun(PLAN, NEVER / "run.csv", resume="yes"))
bad(W, "PlanRun", "nothing to resume", lambda: wb.PlanRun(PLAN, NEVER / "run.csv", resume=True))
bad(W, "PlanRun", "use one of", lambda: wb.PlanRun(PLAN, NEVER / "run.csv", instrument="laser:/dev/ttyUSB0"))
bad(W, "DevicePlanRun", "no serial port", lambda: wb.PlanRun(PLAN, NEVER / "run.csv", instrument="sylvac:/dev/axiscal-no-such-port"))
bad(W, "DevicePlanRun", "nothing to resume", lambda: wb.DevicePlanRun(PLAN, NEVER / "run.csv", instrument="sim:umd", resume=True))
bad(W, "Workbench", "data", lambda: wb.Workbench(None), lambda: wb.Workbench(5))
bad(W, "Workbench", "speed", lambda: wb.Workbench(NEVER, speed=INF), lambda: wb.Workbench(NEVER, speed=-1.0))
bad(W, "Workbench", "db", lambda: wb.Workbench(NEVER, db=""), lambda: wb.Workbench(NEVER, db=3))
bad(W, "create_workbench_app", "bench", lambda: wb.create_workbench_app(None))
bad(W, "create_workbench_app", "update_hz", lambda: wb.create_workbench_app(BENCH, update_hz=NAN),
    lambda: wb.create_workbench_app(BENCH, update_hz=500.0))
bad(W, "create_workbench_app", "token", lambda: wb.create_workbench_app(BENCH, token="short"),
    lambda: wb.create_workbench_app(BENCH, allowed_hosts=None))
bad(W, "create_workbench_app", "allowed_hosts", lambda: wb.create_workbench_app(BENCH, allowed_hosts="localhost"))
bad(W, "serve_workbench", "host", lambda: wb.serve_workbench(NEVER, host=""), lambda: wb.serve_workbench(NEVER, host=None))
bad(W, "serve_workbench", "port", lambda: wb.serve_workbench(NEVER, port=-1), lambda: wb.serve_workbench(NEVER, port=70000))
bad(W, "serve_workbench", "update_hz", lambda: wb.serve_workbench(NEVER, update_hz=INF))

bad(W, "check_spec", "role", lambda: wb.check_spec("laser", "sim"))
bad(W, "check_spec", "instrument", lambda: wb.check_spec("instrument", None), lambda: wb.check_spec("instrument", " "))
bad(W, "is_virtual", "instrument", lambda: wb.is_virtual(None, "sim"))
bad(W, "is_virtual", "controller", lambda: wb.is_virtual("sim", 5))
bad(W, "read_saved", "folder", lambda: wb.read_saved(None))
bad(W, "write_saved", "folder", lambda: wb.write_saved(None, None))
bad(W, "write_saved", "saved", lambda: wb.write_saved(NEVER, {"visit": {}}))
bad(W, "remember_open", "data", lambda: wb.remember_open(None, None))
bad(W, "remember_open", "folder", lambda: wb.remember_open(NEVER, 5))
bad(W, "open_folder", "data", lambda: wb.open_folder(None))
bad(W, "unfinished_visits", "data", lambda: wb.unfinished_visits(5))
bad(W, "next_number", "number", lambda: wb.next_number(None), lambda: wb.next_number(" "))
bad(W, "remember_laboratory", "data", lambda: wb.remember_laboratory(None, {}))
bad(W, "remember_laboratory", "form", lambda: wb.remember_laboratory(NEVER, ["lab"]))
bad(W, "laboratory_defaults", "data", lambda: wb.laboratory_defaults(None))
bad(W, "budget_tables", "form", lambda: wb.budget_tables(None), lambda: wb.budget_tables(["eve_um"]))
bad(W, "write_budget", "folder", lambda: wb.write_budget(None, {}))
bad(W, "write_budget", "form", lambda: wb.write_budget(NEVER, None))
bad(W, "remember_budget", "data", lambda: wb.remember_budget(None, {}))
bad(W, "remember_budget", "form", lambda: wb.remember_budget(NEVER, ["eve_um"]))
bad(W, "budget_defaults", "data", lambda: wb.budget_defaults(None, "Laser"))
bad(W, "budget_defaults", "instrument", lambda: wb.budget_defaults(NEVER, None))
bad(W, "budget_defaults", "serial", lambda: wb.budget_defaults(NEVER, "Laser", 5))
bad(W, "decision_of", "campaign", lambda: wb.decision_of(None), lambda: wb.decision_of("campaign.toml"))

# result and error types: made by the room, not by a user's arguments; the visit's record and the tabs'
# book-keeping (no user values); the computer's serial ports (no arguments)
EXEMPT = {W: {"Connection", "FormErrors", "WorkbenchServer", "new_token", "OpenElsewhere", "SavedVisit", "Tabs",
              "serial_ports"}}

test_bad_arguments_raise_axiscal_error_naming_them, test_every_public_callable_has_a_bad_argument_case = TABLE.tests(EXEMPT)


def test_nothing_was_written_where_no_call_may_write():
    assert not NEVER.exists()
