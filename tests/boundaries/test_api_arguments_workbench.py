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
bad(W, "PlanRun", "axis must be a linear axis", lambda: wb.PlanRun(PLAN, NEVER / "run.csv", axis="C"),
    lambda: wb.PlanRun(PLAN, NEVER / "run.csv", axis=None))
bad(W, "PlanRun", "machine", lambda: wb.PlanRun(PLAN, NEVER / "run.csv", machine=5))
bad(W, "DevicePlanRun", "axis must be a linear axis", lambda: wb.DevicePlanRun(PLAN, NEVER / "run.csv", instrument="sim:umd",
                                                                               axis="B"))
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
bad(W, "check_ini", "the INI file must be a path", lambda: wb.check_ini(None), lambda: wb.check_ini("  "))
bad(W, "check_ini", "no INI file at", lambda: wb.check_ini("/nonexistent/axiscal/machine.ini"))
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
bad(W, "machine_axes", "path", lambda: wb.machine_axes(None))
bad(W, "machine_axes", "file not found", lambda: wb.machine_axes(NEVER / "machine.toml"))
bad(W, "machine_choices", "data", lambda: wb.machine_choices(5))
bad(W, "copy_machine", "source", lambda: wb.copy_machine(None, NEVER))
bad(W, "copy_machine", "folder", lambda: wb.copy_machine(wb.example_machine(), None))
bad(W, "parse_travels", "LETTER=START:END", lambda: wb.parse_travels("X 0-600"))
bad(W, "parse_travels", "name each axis", lambda: wb.parse_travels(None), lambda: wb.parse_travels(" "))
bad(W, "parse_travels", "beyond its start", lambda: wb.parse_travels("X=5:1"))
bad(W, "parse_travels", "given twice", lambda: wb.parse_travels("X=0:1,X=0:2"))
bad(W, "write_new_machine", "folder", lambda: wb.write_new_machine(None, "Mill", "XFYZ", "X=0:1,Y=0:1,Z=0:1"))
bad(W, "write_new_machine", "chain", lambda: wb.write_new_machine(NEVER, "Mill", "XYZ", "X=0:1"),
    lambda: wb.write_new_machine(NEVER, "Mill", None, "X=0:1"))
bad(W, "write_new_machine", "name the machine", lambda: wb.write_new_machine(NEVER, " ", "XFY", "X=0:1,Y=0:1"))
bad(W, "write_new_machine", "Z missing", lambda: wb.write_new_machine(NEVER, "Mill", "XFYZ", "X=0:1,Y=0:1"))
AXES = [{"axis": "X", "rotary": False, "unit": "mm", "start": 0.0, "end": 800.0}]
bad(W, "checked_plan", "axes", lambda: wb.checked_plan({}, None), lambda: wb.checked_plan({}, [{"axis": "X"}]))
bad(W, "checked_plan", "json object", lambda: wb.checked_plan(5, AXES))
bad(W, "checked_plan", "beyond the travel", lambda: wb.checked_plan({"start_mm": 0, "end_mm": 900, "targets": 5, "runs": 1,
                                                                      "overrun_mm": 1, "dwell_s": 1}, AXES))
bad(W, "wanted_tests", "axes", lambda: wb.wanted_tests(["positioning-X"], None))
bad(W, "wanted_tests", "tick at least one test", lambda: wb.wanted_tests([], AXES), lambda: wb.wanted_tests("X", AXES))
bad(W, "wanted_tests", "not a test of the machine's axes", lambda: wb.wanted_tests(["positioning-Y"], AXES))
TEST = {"id": "positioning-X", "kind": "positioning", "axis": "X", "source": "run", "label": "X", "entry": {}}
bad(W, "state_of", "test", lambda: wb.state_of(None, NEVER), lambda: wb.state_of({"id": "x"}, NEVER))
bad(W, "state_of", "folder", lambda: wb.state_of(TEST, None))
bad(W, "campaign_with_tests", "text", lambda: wb.campaign_with_tests(None, [], NEVER, model=None))
bad(W, "campaign_with_tests", "tests", lambda: wb.campaign_with_tests("", None, NEVER, model=None),
    lambda: wb.campaign_with_tests("", [5], NEVER, model=None))
bad(W, "campaign_with_tests", "folder", lambda: wb.campaign_with_tests("", [], None, model=None))
bad(W, "campaign_with_tests", "model", lambda: wb.campaign_with_tests("", [], NEVER, model=5))
bad(W, "checked_file_form", "json object", lambda: wb.checked_file_form(None))
bad(W, "checked_file_form", "radius_mm", lambda: wb.checked_file_form({"kind": "ballbar", "file": "b.csv", "plane": "XY"}),
    lambda: wb.checked_file_form({"kind": "ballbar", "file": "b.csv", "plane": "XY", "radius_mm": NAN}))
bad(W, "checked_file_form", "kind", lambda: wb.checked_file_form({"kind": "scan", "file": "b.csv"}))
bad(W, "store_upload", "folder", lambda: wb.store_upload(None, "a.csv", b"1"))
bad(W, "store_upload", "name the uploaded file", lambda: wb.store_upload(NEVER, None, b"1"))
bad(W, "store_upload", "empty", lambda: wb.store_upload(NEVER, "a.csv", b""), lambda: wb.store_upload(NEVER, "a.csv", "1"))
bad(W, "store_upload", "not a file name", lambda: wb.store_upload(NEVER, "...", b"1"))
bad(W, "data_files", "data", lambda: wb.data_files(None, None))
bad(W, "data_files", "folder", lambda: wb.data_files(NEVER, 5))
FORM = wb.checked_file_form({"kind": "straightness", "file": "p.csv", "axis": "X", "direction": "Y"})
bad(W, "file_test", "data", lambda: wb.file_test(None, NEVER, FORM, set()))
bad(W, "file_test", "form", lambda: wb.file_test(NEVER, NEVER, {"kind": "straightness"}, set()))
bad(W, "file_test", "taken", lambda: wb.file_test(NEVER, NEVER, FORM, None))
bad(W, "file_test", "no such file in the data folder", lambda: wb.file_test(NEVER, NEVER, FORM, set()))
bad(W, "tolerance_of", "kind", lambda: wb.tolerance_of(None), lambda: wb.tolerance_of(5, "X"))
bad(W, "tolerance_of", "axis", lambda: wb.tolerance_of("straightness", None))

# result and error types: made by the room, not by a user's arguments; the visit's record and the tabs'
# book-keeping (no user values); the computer's serial ports (no arguments)
# the forms' models (read through checked_plan and checked_file_form, whose cases are above); the parts of Workbench
# (no arguments of their own); the example machine (no arguments)
EXEMPT = {W: {"Connection", "FormErrors", "WorkbenchServer", "new_token", "OpenElsewhere", "SavedVisit", "Tabs",
              "serial_ports", "AxisPlanForm", "FileTestForm", "HistoryViews", "VisitTests", "VisitConnection",
              "example_machine"}}

test_bad_arguments_raise_axiscal_error_naming_them, test_every_public_callable_has_a_bad_argument_case = TABLE.tests(EXEMPT)


def test_nothing_was_written_where_no_call_may_write():
    assert not NEVER.exists()
