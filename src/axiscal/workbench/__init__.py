"""The workbench: one local web page that runs a whole visit at the machine.

It calls the library as the command line does and computes nothing itself. :func:`serve_workbench`
is ``axiscal workbench``; :class:`Workbench` holds the visit (each step one library call);
:func:`create_workbench_app` is the page's Starlette app; :mod:`axiscal.workbench.machines` offers and describes the visit's
machine, :mod:`axiscal.workbench.suite` its tests and their states, :mod:`axiscal.workbench.added` the tests taken from
files; :mod:`axiscal.workbench.connection` checks the
specs and LinuxCNC's INI file, lists the serial ports and connects (the soft limits of every axis the visit
tests); :mod:`axiscal.workbench.runner` is the one adapter that runs a
plan on the machine (the virtual machine, ``sim``, or the devices of ``axiscal run``).
"""

from __future__ import annotations

from axiscal.workbench.forms import (
    FORMS,
    FormErrors,
    checked,
)
from axiscal.workbench.connection import (
    CONTROLLERS,
    INSTRUMENTS,
    SIM_RATE_HZ,
    Connection,
    check_ini,
    check_spec,
    connect,
    is_virtual,
    serial_ports,
)
from axiscal.workbench.saved import (
    OPEN_FILE,
    STATE_FILE,
    STEPS,
    SavedVisit,
    open_folder,
    read_saved,
    remember_open,
    unfinished_visits,
    write_saved,
)
from axiscal.workbench.runner import (
    DevicePlanRun,
    PlanRun,
)
from axiscal.workbench.machines import (
    MACHINE_FILE,
    copy_machine,
    example_machine,
    machine_axes,
    machine_choices,
    parse_travels,
    write_new_machine,
)
from axiscal.workbench.suite import (
    AxisPlanForm,
    campaign_with_tests,
    checked_plan,
    state_of,
    wanted_tests,
)
from axiscal.workbench.added import (
    FILE_KINDS,
    MAX_UPLOAD,
    FileTestForm,
    checked_file_form,
    data_files,
    file_test,
    store_upload,
    tolerance_of,
)
from axiscal.workbench.laboratory import (
    LABORATORY_FILE,
    REMEMBERED,
    laboratory_defaults,
    next_number,
    remember_laboratory,
)
from axiscal.workbench.budget import (
    BUDGET_FIELDS,
    BUDGET_FILE,
    BUDGETS_FILE,
    budget_defaults,
    budget_tables,
    decision_of,
    remember_budget,
    write_budget,
)
from axiscal.workbench.tabs import (
    OpenElsewhere,
    Tabs,
)
from axiscal.workbench.history_views import (
    HistoryViews,
)
from axiscal.workbench.visit_tests import (
    VisitTests,
)
from axiscal.workbench.visit_connection import (
    VisitConnection,
)
from axiscal.workbench.visit import (
    PHASES,
    Workbench,
)
from axiscal.workbench.app import (
    MAX_BODY,
    TAB_HEADER,
    TOKEN_COOKIE,
    WEB,
    create_workbench_app,
    new_token,
)
from axiscal.workbench.server import (
    WorkbenchServer,
    serve_workbench,
)

__all__ = [
    "FORMS",
    "FormErrors",
    "checked",
    "CONTROLLERS",
    "INSTRUMENTS",
    "SIM_RATE_HZ",
    "Connection",
    "DevicePlanRun",
    "PlanRun",
    "check_ini",
    "connect",
    "check_spec",
    "is_virtual",
    "serial_ports",
    "OPEN_FILE",
    "STATE_FILE",
    "STEPS",
    "SavedVisit",
    "open_folder",
    "read_saved",
    "remember_open",
    "unfinished_visits",
    "write_saved",
    "MACHINE_FILE",
    "copy_machine",
    "example_machine",
    "machine_axes",
    "machine_choices",
    "parse_travels",
    "write_new_machine",
    "AxisPlanForm",
    "campaign_with_tests",
    "checked_plan",
    "state_of",
    "wanted_tests",
    "FILE_KINDS",
    "MAX_UPLOAD",
    "FileTestForm",
    "checked_file_form",
    "data_files",
    "file_test",
    "store_upload",
    "tolerance_of",
    "HistoryViews",
    "VisitTests",
    "VisitConnection",
    "PHASES",
    "OpenElsewhere",
    "Tabs",
    "Workbench",
    "MAX_BODY",
    "TAB_HEADER",
    "TOKEN_COOKIE",
    "WEB",
    "create_workbench_app",
    "new_token",
    "serve_workbench",
    "WorkbenchServer",
    "LABORATORY_FILE",
    "REMEMBERED",
    "laboratory_defaults",
    "next_number",
    "remember_laboratory",
    "BUDGET_FIELDS",
    "BUDGET_FILE",
    "BUDGETS_FILE",
    "budget_defaults",
    "budget_tables",
    "decision_of",
    "remember_budget",
    "write_budget",
]
