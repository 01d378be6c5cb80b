"""Every public callable of the uncertainty, live, campaign, report and io rooms refuses bad
arguments with AxiscalError naming the argument: never an AttributeError or TypeError from deep
inside, a NumPy broadcast error, an ambiguous truth value, a stray RuntimeWarning or a silent NaN.

The table lists, per public name, calls with the kinds of bad values a user passes: None where an
object (a Budget, a Campaign, a CampaignResults, a LiveState) is expected, NaN and inf, empty and
mismatched arrays, a string for a number, unknown option strings, values out of range. A coverage
check fails when a public callable of these rooms has no case (or an explicit exemption below).
"""

from __future__ import annotations

from importlib import import_module
from pathlib import Path

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as hs

from api_cases import EXAMPLES, CaseTable, api, finite_or_refused

from axiscal.io.templates import render_template

NEVER = "/tmp/axiscal-never-written"

ROOMS = ("uncertainty", "live", "campaign", "report", "io")
NAN, INF = float("nan"), float("inf")

TABLE = CaseTable(ROOMS)
bad = TABLE.bad
CASES = TABLE.cases


# ---------------------------------------------------------------- io
io = api("io")
O = "io"

bad(O, "check_number", "spacing_m", lambda: io.check_number("spacing_m", NAN), lambda: io.check_number("spacing_m", None), lambda: io.check_number("spacing_m", -1.0, positive=True))
bad(O, "check_count", "trials", lambda: io.check_count("trials", 0), lambda: io.check_count("trials", 2.5), lambda: io.check_count("trials", True))
bad(O, "check_array", "position_m", lambda: io.check_array("position_m", [NAN]), lambda: io.check_array("position_m", "x"), lambda: io.check_array("position_m", [[0.0]], ndim=1))
bad(O, "check_same_length", "same length", lambda: io.check_same_length(a_m=[1.0], b_m=[1.0, 2.0]))
bad(O, "check_broadcast", "do not match", lambda: io.check_broadcast(a_m=np.zeros(2), b_m=np.zeros(3)))
bad(O, "check_choice", "plane", lambda: io.check_choice("plane", "XX", ("XY", "YZ")), lambda: io.check_choice("plane", None, ("XY",)))
bad(O, "check_mapping", "report", lambda: io.check_mapping("report", None), lambda: io.check_mapping("report", {}, ("a",)))
bad(O, "check_path", "path", lambda: io.check_path("path", None), lambda: io.check_path("path", 5), lambda: io.check_path("path", " "))
bad(O, "render_checked", "template", lambda: io.render_checked(render_template, None), lambda: io.render_checked(render_template, "none/none.j2"))
bad(O, "atomic_write", "path", lambda: io.atomic_write(None, lambda p: None), lambda: io.atomic_write(5, lambda p: None))
bad(O, "atomic_write", "write", lambda: io.atomic_write(NEVER, None), lambda: io.atomic_write(NEVER, "text"))
bad(O, "atomic_write", "make_parents", lambda: io.atomic_write(NEVER, lambda p: None, make_parents="no"))
bad(O, "remove_stale_temporaries", "path", lambda: io.remove_stale_temporaries(None), lambda: io.remove_stale_temporaries(5))
bad(O, "write_text", "path", lambda: io.write_text(None, "a"))
bad(O, "write_text", "text", lambda: io.write_text(NEVER, None), lambda: io.write_text(NEVER, b"a"))
bad(O, "atomic_folder", "path", lambda: io.atomic_folder(None, lambda p: None), lambda: io.atomic_folder(5, lambda p: None))
bad(O, "atomic_folder", "fill", lambda: io.atomic_folder(NEVER, None), lambda: io.atomic_folder(NEVER, "text"))
bad(O, "atomic_folder", "marker", lambda: io.atomic_folder(NEVER, lambda p: None, marker=5))
bad(O, "stale_temporaries", "path", lambda: io.stale_temporaries(None), lambda: io.stale_temporaries(3.5))
bad(O, "read_json", "path", lambda: io.read_json(None), lambda: io.read_json(5))
bad(O, "write_json", "path", lambda: io.write_json(None, {}))
bad(O, "json_line", "text", lambda: io.json_line(None, "a"), lambda: io.json_line(b"{}", "a"))
bad(O, "sidecar_path", "csv_path", lambda: io.sidecar_path(None), lambda: io.sidecar_path(NAN))
bad(O, "write_sidecar", "csv_path", lambda: io.write_sidecar(None, kind="x"))
bad(O, "write_sidecar", "kind", lambda: io.write_sidecar(NEVER + ".csv", kind=None), lambda: io.write_sidecar(NEVER + ".csv", kind=""))
bad(O, "write_sidecar", "units", lambda: io.write_sidecar(NEVER + ".csv", kind="x", units=["mm"]))
bad(O, "write_sidecar", "sources", lambda: io.write_sidecar(NEVER + ".csv", kind="x", sources="a.csv"), lambda: io.write_sidecar(NEVER + ".csv", kind="x", sources=5))
bad(O, "Lines", "data", lambda: io.Lines(None), lambda: io.Lines("text"))
bad(O, "CsvTable", "header", lambda: io.CsvTable("a.csv", None), lambda: io.CsvTable("a.csv", (1, 2)), lambda: io.CsvTable("a.csv", "ab"))
bad(O, "CsvTable", "path", lambda: io.CsvTable(None, ("a",)))
bad(O, "CsvTable", "same length", lambda: io.CsvTable("a.csv", ("a",), rows=(("1",),), lines=()))
bad(O, "parse_csv", "lines", lambda: io.parse_csv(None), lambda: io.parse_csv("a,b\n1,2"), lambda: io.parse_csv([1, 2]))
bad(O, "parse_csv", "min_rows", lambda: io.parse_csv(["a", "1"], min_rows=-1), lambda: io.parse_csv(["a", "1"], min_rows=NAN))
bad(O, "parse_csv", "path", lambda: io.parse_csv(["a", "1"], path=None))
bad(O, "read_csv", "path", lambda: io.read_csv(None), lambda: io.read_csv(NAN))
bad(O, "read_text", "path", lambda: io.read_text(None), lambda: io.read_text(np.array([])))
bad(O, "read_toml", "path", lambda: io.read_toml(None))
bad(O, "parse_toml", "text", lambda: io.parse_toml(None), lambda: io.parse_toml(b"a = 1"))
bad(O, "write_csv", "columns", lambda: io.write_csv(None, None), lambda: io.write_csv(None, {"a_mm": 5.0}), lambda: io.write_csv(None, {"a_mm": "abc"}))
bad(O, "write_csv", "same length", lambda: io.write_csv(None, {"a_mm": [1.0], "b_mm": [1.0, 2.0]}))
bad(O, "write_csv", "fmt", lambda: io.write_csv(None, {"a_mm": [1.0]}, fmt=None), lambda: io.write_csv(None, {"a_mm": [1.0]}, fmt="{:d}"))
bad(O, "write_csv", "fmt", lambda: io.write_csv(None, {"a_mm": [1.0]}, fmt={"a_mm": 5}))
bad(O, "write_csv", "path", lambda: io.write_csv(5, {"a_mm": [1.0]}))
bad(O, "ColumnMap", "layout", lambda: io.ColumnMap(np.array([]), "t"), lambda: io.ColumnMap(None, "t"), lambda: io.ColumnMap("grid", "t"))
bad(O, "ColumnMap", "sign", lambda: io.ColumnMap("rows", "t", reading="r", sign=NAN), lambda: io.ColumnMap("rows", "t", reading="r", sign=2))
bad(O, "ColumnMap", "run_labels", lambda: io.ColumnMap("runs", "t", readings=("a",), run_labels=5), lambda: io.ColumnMap("runs", "t", readings=("a",), run_labels=(1,)))
bad(O, "ColumnMap", "header", lambda: io.ColumnMap("rows", "t", reading="r", header="no"))
bad(O, "ColumnMap", "units.target", lambda: io.ColumnMap("rows", "t", reading="r", target_unit="furlong"), lambda: io.ColumnMap("rows", "t", reading="r", target_unit=None))
bad(O, "ColumnMap", "skip_lines", lambda: io.ColumnMap("rows", "t", reading="r", skip_lines=-1))
bad(O, "ColumnMap", "direction_values", lambda: io.ColumnMap("rows", "t", reading="r", direction_values=None))
bad(O, "ColumnMap", "delimiter", lambda: io.ColumnMap("rows", "t", reading="r", delimiter=5))
bad(O, "ColumnMap", "column", lambda: io.ColumnMap("rows", None, reading="r"), lambda: io.ColumnMap("rows", 0, reading="r"))
bad(O, "import_readings", "cmap", lambda: io.import_readings(None, EXAMPLES / "positioning_run.csv"))
bad(O, "import_readings", "path", lambda: io.import_readings(io.ColumnMap("rows", "t", reading="r"), None))
bad(O, "read_column_map", "path", lambda: io.read_column_map(None))
bad(O, "write_positioning_csv", "readings", lambda: io.write_positioning_csv(None, NEVER + ".csv"), lambda: io.write_positioning_csv({}, NEVER + ".csv"))
bad(O, "read_rtx", "path", lambda: io.read_rtx(None, unit="mm"), lambda: io.read_rtx(np.array([]), unit="mm"))
bad(O, "read_rtx", "unit", lambda: io.read_rtx(NEVER + ".rtx", unit="furlong"), lambda: io.read_rtx(NEVER + ".rtx", unit=None))
bad(O, "write_rtx", "path", lambda: io.write_rtx(np.array([]), [0.0], sample_rate_hz=1.0, unit="mm"), lambda: io.write_rtx(None, [0.0], sample_rate_hz=1.0, unit="mm"))
bad(O, "write_rtx", "sample_rate_hz", lambda: io.write_rtx(NEVER, [0.0], sample_rate_hz=NAN, unit="mm"), lambda: io.write_rtx(NEVER, [0.0], sample_rate_hz="1", unit="mm"),
    lambda: io.write_rtx(NEVER, [0.0], sample_rate_hz=0.0, unit="mm"))
bad(O, "write_rtx", "samples", lambda: io.write_rtx(NEVER, [NAN], sample_rate_hz=1.0, unit="mm"), lambda: io.write_rtx(NEVER, "abc", sample_rate_hz=1.0, unit="mm"),
    lambda: io.write_rtx(NEVER, None, sample_rate_hz=1.0, unit="mm"))
bad(O, "write_rtx", "unit", lambda: io.write_rtx(NEVER, [0.0], sample_rate_hz=1.0, unit="furlong"))
bad(O, "write_rtx", "header", lambda: io.write_rtx(NEVER, [0.0], sample_rate_hz=1.0, unit="mm", header=["Owner"]))
bad(O, "write_rtx", "header", lambda: io.write_rtx(NEVER, [0.0], sample_rate_hz=1.0, unit="mm", header={5: "a"}))
bad(O, "write_rtx_csv", "capture", lambda: io.write_rtx_csv(None, NEVER + ".csv"), lambda: io.write_rtx_csv({"samples_m": []}, NEVER + ".csv"))
bad(O, "dumps", "payload", lambda: io.dumps(object()), lambda: io.dumps({"a": {1, 2}}), lambda: io.dumps(b"x"))
bad(O, "write_json", "payload", lambda: io.write_json(NEVER + ".json", {"a": object()}))
bad(O, "check_instance", "run must be a Path, not None", lambda: io.check_instance("run", None, Path))
bad(O, "check_instance", "budget must be a float", lambda: io.check_instance("budget", "x", (float, int)))
if hasattr(io, "check_integer"):  # the further shared checks io.arguments provides
    bad(O, "check_integer", "axis_number", lambda: io.check_integer("axis_number", 1.5), lambda: io.check_integer("axis_number", None))
if hasattr(io, "check_optional_number"):
    bad(O, "check_optional_number", "step_m", lambda: io.check_optional_number("step_m", NAN), lambda: io.check_optional_number("step_m", "1"))


# ---------------------------------------------------------------- uncertainty
un = api("uncertainty")
U = "uncertainty"
BUDGET = un.Budget(length_U_rel=0.5e-6)
BUDGET_FILE = EXAMPLES / "uncertainty_budget.toml"
PU = un.positioning_uncertainty(BUDGET, 1.0)
EVALUATION = import_module("axiscal.positioning").evaluate_positioning_file(EXAMPLES / "positioning_run.csv")
MACHINE_U = EXAMPLES / "xfyz_machine_u" / "machine.toml"
MACHINE, MU = un.load_machine_uncertainty(MACHINE_U)
Q3 = {"X": np.array([0.1, 0.2]), "Y": np.array([0.1, 0.1]), "Z": np.array([0.05, 0.05])}
VU = un.volumetric_monte_carlo(MACHINE, MU, Q3, 40, seed=1)
LINE_X, LINE_Y = np.linspace(0.0, 0.1, 5), np.array([0.0, 1e-6, 0.0, -1e-6, 0.0])

bad(U, "Budget", "length_U_rel", lambda: un.Budget(length_U_rel=NAN), lambda: un.Budget(length_U_rel="1"), lambda: un.Budget(length_U_rel=-1.0))
bad(U, "Budget", "method", lambda: un.Budget(method="magic"))
bad(U, "budget_from_dict", "data", lambda: un.budget_from_dict(None), lambda: un.budget_from_dict([("air", {})]))
bad(U, "budget_from_dict", "unknown key", lambda: un.budget_from_dict({"weather": {}}), lambda: un.budget_from_dict({5: {}}))
bad(U, "budget_from_tables", "tables", lambda: un.budget_from_tables(None), lambda: un.budget_from_tables({"setup": {}}))
bad(U, "budget_from_dict", "eve_um", lambda: un.budget_from_dict({"setup": {"eve_um": NAN}}), lambda: un.budget_from_dict({"setup": {"eve_um": -1.0}}))
bad(U, "budget_from_dict", "locate", lambda: un.budget_from_dict({}, locate=5))
bad(U, "budget_from_dict", "text", lambda: un.budget_from_dict({}, text=5))
bad(U, "budget_from_dict", "source", lambda: un.budget_from_dict({}, source=None))
bad(U, "read_budget", "path", lambda: un.read_budget(None), lambda: un.read_budget(NAN))
bad(U, "air_sensitivities", "budget must be a Budget", lambda: un.air_sensitivities(None), lambda: un.air_sensitivities({"air": {}}))
for _fn in ("length_model", "length_components"):
    bad(U, _fn, "budget must be a Budget", lambda _f=getattr(un, _fn): _f(None, 1.0), lambda _f=getattr(un, _fn): _f("budget.toml", 1.0))
    bad(U, _fn, "length_m", lambda _f=getattr(un, _fn): _f(BUDGET, NAN), lambda _f=getattr(un, _fn): _f(BUDGET, None), lambda _f=getattr(un, _fn): _f(BUDGET, "1"))
bad(U, "decide", "value", lambda: un.decide(NAN, 10.0), lambda: un.decide(None, 10.0), lambda: un.decide("9", 10.0))
bad(U, "decide", "limit", lambda: un.decide(9.0, INF), lambda: un.decide(9.0, None))
bad(U, "decide", "U must be a non-negative", lambda: un.decide(9.0, 10.0, -1.0), lambda: un.decide(9.0, 10.0, NAN))
bad(U, "decide", "decision rule", lambda: un.decide(9.0, 10.0, rule="strict"), lambda: un.decide(9.0, 10.0, rule=None))
bad(U, "figure_uncertainties", "kind", lambda: un.figure_uncertainties("ballbar", EVALUATION, BUDGET), lambda: un.figure_uncertainties(None, EVALUATION, BUDGET))
bad(U, "figure_uncertainties", "evaluation", lambda: un.figure_uncertainties("positioning", None, BUDGET), lambda: un.figure_uncertainties("straightness", EVALUATION, BUDGET))
bad(U, "figure_uncertainties", "budget", lambda: un.figure_uncertainties("positioning", EVALUATION, None), lambda: un.figure_uncertainties("positioning", EVALUATION, 5))
bad(U, "figure_uncertainties", "run", lambda: un.figure_uncertainties("positioning", {"E": 5.0}, BUDGET), lambda: un.figure_uncertainties("positioning", {"E": 5.0}, BUDGET, run="x"),
    lambda: un.figure_uncertainties("positioning", {"E": 5.0}, BUDGET, run=NAN))
bad(U, "figure_verdicts", "tolerances", lambda: un.figure_verdicts("positioning", EVALUATION, BUDGET, None), lambda: un.figure_verdicts("positioning", EVALUATION, BUDGET, [("E_um", 5.0)]))
bad(U, "figure_verdicts", "tolerance 'E_um'", lambda: un.figure_verdicts("positioning", EVALUATION, BUDGET, {"E_um": NAN}), lambda: un.figure_verdicts("positioning", EVALUATION, BUDGET, {"E_um": "5"}))
bad(U, "figure_verdicts", "figure 'E'", lambda: un.figure_verdicts("positioning", {"E": "x"}, BUDGET, {"E_um": 5.0}, run=1.0))
bad(U, "figure_verdicts", "decision rule", lambda: un.figure_verdicts("positioning", EVALUATION, BUDGET, {"E_um": 5.0}, rule=None))
bad(U, "figure_verdicts", "tolerance 'Q_um'", lambda: un.figure_verdicts("positioning", EVALUATION, BUDGET, {"Q_um": 5.0}))
bad(U, "coverage_interval", "samples", lambda: un.coverage_interval(None), lambda: un.coverage_interval([]), lambda: un.coverage_interval("abc"),
    lambda: un.coverage_interval(np.array(3.0)), lambda: un.coverage_interval([NAN] * 100), lambda: un.coverage_interval([True] * 100))
bad(U, "coverage_interval", "probability", lambda: un.coverage_interval(np.zeros(100), NAN), lambda: un.coverage_interval(np.zeros(100), 1.0), lambda: un.coverage_interval(np.zeros(100), "0.95"))
bad(U, "coverage_interval", "axis", lambda: un.coverage_interval(np.zeros(100), axis=1), lambda: un.coverage_interval(np.zeros(100), axis=0.5))
bad(U, "coverage_interval", "shortest", lambda: un.coverage_interval(np.zeros(100), shortest="yes"))
bad(U, "coverage_interval", "too few", lambda: un.coverage_interval(np.zeros(5)))
bad(U, "evaluate_positioning_with_uncertainty", "budget", lambda: un.evaluate_positioning_with_uncertainty(EXAMPLES / "positioning_run.csv", None))
bad(U, "evaluate_positioning_with_uncertainty", "path", lambda: un.evaluate_positioning_with_uncertainty(None, BUDGET))
bad(U, "evaluate_positioning_with_uncertainty", "monte_carlo", lambda: un.evaluate_positioning_with_uncertainty(EXAMPLES / "positioning_run.csv", BUDGET, monte_carlo=-1))
bad(U, "positioning_uncertainty", "budget", lambda: un.positioning_uncertainty(None, 1.0), lambda: un.positioning_uncertainty(1.0, 1.0))
bad(U, "positioning_uncertainty", "run", lambda: un.positioning_uncertainty(BUDGET, None), lambda: un.positioning_uncertainty(BUDGET, NAN), lambda: un.positioning_uncertainty(BUDGET, -1.0),
    lambda: un.positioning_uncertainty(BUDGET, "1"))
bad(U, "positioning_uncertainty", "monte_carlo", lambda: un.positioning_uncertainty(BUDGET, 1.0, monte_carlo=NAN), lambda: un.positioning_uncertainty(BUDGET, 1.0, monte_carlo=2.5),
    lambda: un.positioning_uncertainty(BUDGET, 1.0, monte_carlo="100"))
bad(U, "positioning_uncertainty", "seed", lambda: un.positioning_uncertainty(BUDGET, 1.0, monte_carlo=100, seed=-1), lambda: un.positioning_uncertainty(BUDGET, 1.0, monte_carlo=100, seed="a"))
bad(U, "positioning_monte_carlo", "budget", lambda: un.positioning_monte_carlo(None, 1.0, 100))
bad(U, "positioning_monte_carlo", "length_m", lambda: un.positioning_monte_carlo(BUDGET, None, 100), lambda: un.positioning_monte_carlo(BUDGET, NAN, 100))
bad(U, "positioning_monte_carlo", "draws", lambda: un.positioning_monte_carlo(BUDGET, 1.0, 0), lambda: un.positioning_monte_carlo(BUDGET, 1.0, None))
bad(U, "positioning_monte_carlo", "seed", lambda: un.positioning_monte_carlo(BUDGET, 1.0, 100, seed=1.5))
bad(U, "positioning_monte_carlo", "probability", lambda: un.positioning_monte_carlo(BUDGET, 1.0, 100, probability=NAN), lambda: un.positioning_monte_carlo(BUDGET, 1.0, 100, probability=2.0))
for _fn in ("uncertainty_payload", "budget_report"):
    bad(U, _fn, "result must be a PositioningUncertainty", lambda _f=getattr(un, _fn): _f(None), lambda _f=getattr(un, _fn): _f({"k": 2}))
bad(U, "positioning_decisions", "result", lambda: un.positioning_decisions(None, PU, {"E": 1e-5}))
bad(U, "positioning_decisions", "uncertainty", lambda: un.positioning_decisions(EVALUATION.result, None, {"E": 1e-5}))
bad(U, "positioning_decisions", "limits", lambda: un.positioning_decisions(EVALUATION.result, PU, None), lambda: un.positioning_decisions(EVALUATION.result, PU, {"E": NAN}),
    lambda: un.positioning_decisions(EVALUATION.result, PU, {"E": "1"}))
bad(U, "positioning_decisions", "figure", lambda: un.positioning_decisions(EVALUATION.result, PU, {"Q": 1e-5}), lambda: un.positioning_decisions(EVALUATION.result, PU, {5: 1e-5}))
bad(U, "positioning_decisions", "decision rule", lambda: un.positioning_decisions(EVALUATION.result, PU, {}, rule="strict"))
bad(U, "straightness_uncertainty", "budget", lambda: un.straightness_uncertainty(None, LINE_X, LINE_Y))
bad(U, "straightness_uncertainty", "position_m", lambda: un.straightness_uncertainty(BUDGET, None, LINE_Y), lambda: un.straightness_uncertainty(BUDGET, "x", LINE_Y),
    lambda: un.straightness_uncertainty(BUDGET, [NAN] * 5, LINE_Y))
bad(U, "straightness_uncertainty", "deviation_m", lambda: un.straightness_uncertainty(BUDGET, LINE_X, [[0.0]]))
bad(U, "straightness_uncertainty", "same length", lambda: un.straightness_uncertainty(BUDGET, LINE_X, LINE_Y[:3]))
bad(U, "straightness_uncertainty", "reference", lambda: un.straightness_uncertainty(BUDGET, LINE_X, LINE_Y, reference="best"))
bad(U, "squareness_uncertainty", "budget", lambda: un.squareness_uncertainty(None, LINE_X, LINE_Y, LINE_X, LINE_Y))
bad(U, "squareness_uncertainty", "second_deviation_m", lambda: un.squareness_uncertainty(BUDGET, LINE_X, LINE_Y, LINE_X, None),
    lambda: un.squareness_uncertainty(BUDGET, LINE_X, LINE_Y, LINE_X, [INF] * 5))
bad(U, "squareness_uncertainty", "plane", lambda: un.squareness_uncertainty(BUDGET, LINE_X, LINE_Y, LINE_X, LINE_Y, plane="XX"))
bad(U, "squareness_uncertainty", "prism_deviation_rad", lambda: un.squareness_uncertainty(BUDGET, LINE_X, LINE_Y, LINE_X, LINE_Y, prism_deviation_rad=NAN))
bad(U, "MachineUncertainty", "tables", lambda: un.MachineUncertainty(None, {}), lambda: un.MachineUncertainty({"X": "a"}, {}), lambda: un.MachineUncertainty({"X": np.full((6, 2), NAN)}, {}),
    lambda: un.MachineUncertainty({"X": -np.ones((6, 2))}, {}))
bad(U, "MachineUncertainty", "squareness", lambda: un.MachineUncertainty({}, None), lambda: un.MachineUncertainty({}, {"EQ0Y": 1e-6}), lambda: un.MachineUncertainty({}, {"EC0Y": NAN}))
bad(U, "load_machine_uncertainty", "path", lambda: un.load_machine_uncertainty(None), lambda: un.load_machine_uncertainty(5))
bad(U, "volumetric_monte_carlo", "machine", lambda: un.volumetric_monte_carlo(None, MU, Q3, 40))
bad(U, "volumetric_monte_carlo", "uncertainty", lambda: un.volumetric_monte_carlo(MACHINE, None, Q3, 40))
bad(U, "volumetric_monte_carlo", "positions", lambda: un.volumetric_monte_carlo(MACHINE, MU, None, 40))
bad(U, "volumetric_monte_carlo", "draws", lambda: un.volumetric_monte_carlo(MACHINE, MU, Q3, 0), lambda: un.volumetric_monte_carlo(MACHINE, MU, Q3, NAN), lambda: un.volumetric_monte_carlo(MACHINE, MU, Q3, "40"))
bad(U, "volumetric_monte_carlo", "draws: 1 are too few", lambda: un.volumetric_monte_carlo(MACHINE, MU, Q3, 1, probability=0.01))
bad(U, "volumetric_monte_carlo", "chunk_draws", lambda: un.volumetric_monte_carlo(MACHINE, MU, Q3, 40, chunk_draws=0))
bad(U, "volumetric_monte_carlo", "probability", lambda: un.volumetric_monte_carlo(MACHINE, MU, Q3, 40, probability=NAN), lambda: un.volumetric_monte_carlo(MACHINE, MU, Q3, 40, probability=None))
bad(U, "volumetric_monte_carlo", "seed", lambda: un.volumetric_monte_carlo(MACHINE, MU, Q3, 40, seed=-1), lambda: un.volumetric_monte_carlo(MACHINE, MU, Q3, 40, seed="a"))
bad(U, "volumetric_monte_carlo", "progress", lambda: un.volumetric_monte_carlo(MACHINE, MU, Q3, 40, progress="bar"))
bad(U, "volumetric_monte_carlo", "scheduler", lambda: un.volumetric_monte_carlo(MACHINE, MU, Q3, 40, scheduler=5))
bad(U, "write_volumetric_uncertainty", "path", lambda: un.write_volumetric_uncertainty(None, Q3, VU))
bad(U, "write_volumetric_uncertainty", "result", lambda: un.write_volumetric_uncertainty(NEVER + ".csv", Q3, None))
bad(U, "write_volumetric_uncertainty", "positions", lambda: un.write_volumetric_uncertainty(NEVER + ".csv", None, VU))
bad(U, "write_volumetric_uncertainty", "sources", lambda: un.write_volumetric_uncertainty(NEVER + ".csv", Q3, VU, sources=None), lambda: un.write_volumetric_uncertainty(NEVER + ".csv", Q3, VU, sources="a.toml"))
bad(U, "volumetric_uncertainty_columns", "result", lambda: un.volumetric_uncertainty_columns(Q3, None))
bad(U, "volumetric_uncertainty_columns", "positions", lambda: un.volumetric_uncertainty_columns(None, VU), lambda: un.volumetric_uncertainty_columns({"X": [NAN, 0.1]}, VU),
    lambda: un.volumetric_uncertainty_columns({"X": "ab"}, VU), lambda: un.volumetric_uncertainty_columns({"X": [0.1]}, VU))
bad(U, "volumetric_uncertainty_map", "machine", lambda: un.volumetric_uncertainty_map(None, positions=Q3), lambda: un.volumetric_uncertainty_map((MACHINE,), positions=Q3),
    lambda: un.volumetric_uncertainty_map(5, positions=Q3))
bad(U, "volumetric_uncertainty_map", "exactly one", lambda: un.volumetric_uncertainty_map(MACHINE_U))
bad(U, "volumetric_uncertainty_map", "draws", lambda: un.volumetric_uncertainty_map((MACHINE, MU), positions=Q3, draws=-5))
bad(U, "volumetric_uncertainty_map", "seed", lambda: un.volumetric_uncertainty_map((MACHINE, MU), positions=Q3, draws=40, seed=NAN))
bad(U, "plot_volumetric_uncertainty", "result", lambda: un.plot_volumetric_uncertainty(Q3, None, NEVER + ".png"))
bad(U, "plot_volumetric_uncertainty", "positions_m", lambda: un.plot_volumetric_uncertainty(None, VU, NEVER + ".png"), lambda: un.plot_volumetric_uncertainty({}, VU, NEVER + ".png"),
    lambda: un.plot_volumetric_uncertainty({"X": [NAN, 0.0]}, VU, NEVER + ".png"), lambda: un.plot_volumetric_uncertainty({"X": [0.0]}, VU, NEVER + ".png"))
bad(U, "plot_volumetric_uncertainty", "title", lambda: un.plot_volumetric_uncertainty(Q3, VU, NEVER + ".png", title=5))
bad(U, "plot_volumetric_uncertainty", "path", lambda: un.plot_volumetric_uncertainty(Q3, VU, None))

VMAP = un.volumetric_uncertainty_map((MACHINE, MU), positions=Q3, draws=40, seed=1)
bad(U, "VolumetricUncertaintyMap", "path", lambda: VMAP.write_csv(None), lambda: VMAP.plot(None))
bad(U, "VolumetricUncertaintyMap", "figure format", lambda: VMAP.plot(NEVER + ".txt"))
bad(U, "VolumetricUncertaintyMap", "title", lambda: VMAP.plot(NEVER + ".png", title=5))


# ---------------------------------------------------------------- live
lv = api("live")
L = "live"
VM = import_module("axiscal.measurement").VirtualModule(seed=0)
SYS = VM.measurement_system()
CH = SYS.channels
STATE = lv.LiveState(SYS)
APP = lv.create_app(STATE)
REPLAY = EXAMPLES / "xz_module" / "sensors_frames.csv"
SIM = lv.SimSource(VM, CH, rate_hz=1000.0)

bad(L, "Pipeline", "system", lambda: lv.Pipeline(None, SIM), lambda: lv.Pipeline("machine.toml", SIM))
bad(L, "Pipeline", "source", lambda: lv.Pipeline(SYS, "sim"), lambda: lv.Pipeline(SYS, None).run(duration_s=0.0))
bad(L, "Pipeline", "recorder", lambda: lv.Pipeline(SYS, SIM, recorder="rec.csv"))
bad(L, "Pipeline", "state", lambda: lv.Pipeline(SYS, SIM, state={}))
bad(L, "Pipeline", "latency_capacity", lambda: lv.Pipeline(SYS, SIM, latency_capacity=0), lambda: lv.Pipeline(SYS, SIM, latency_capacity=2.5))
bad(L, "Pipeline", "duration_s", lambda: lv.Pipeline(SYS, SIM).run(duration_s=NAN), lambda: lv.Pipeline(SYS, SIM).run(duration_s="1"))
bad(L, "Pipeline", "progress_interval_s", lambda: lv.Pipeline(SYS, SIM).run(duration_s=0.0, progress_interval_s=0.0))
bad(L, "Pipeline", "progress", lambda: lv.Pipeline(SYS, SIM).run(duration_s=0.0, progress="bar"))
bad(L, "Pipeline", "stop", lambda: lv.Pipeline(SYS, SIM).run(stop=True))
bad(L, "LineDecoder", "channels", lambda: lv.LineDecoder(None), lambda: lv.LineDecoder("a_mm"), lambda: lv.LineDecoder([1, 2]))
bad(L, "LineDecoder", "max_line_bytes", lambda: lv.LineDecoder(CH, max_line_bytes=0), lambda: lv.LineDecoder(CH, max_line_bytes=NAN))
bad(L, "LineDecoder", "data", lambda: lv.LineDecoder(CH).feed(None), lambda: lv.LineDecoder(CH).feed("0.1,1\n"))
bad(L, "LineDecoder", "lines", lambda: lv.LineDecoder(CH).decode_lines(None), lambda: lv.LineDecoder(CH).decode_lines("0.1,1"))
bad(L, "encode_lines", "t_s", lambda: lv.encode_lines(None, np.zeros((1, 1))), lambda: lv.encode_lines("a", np.zeros((1, 1))), lambda: lv.encode_lines(np.zeros((1, 1)), np.zeros((1, 1))))
bad(L, "encode_lines", "values", lambda: lv.encode_lines(np.zeros(1), np.zeros(1)), lambda: lv.encode_lines(np.zeros(1), None))
bad(L, "encode_lines", "same length", lambda: lv.encode_lines(np.zeros(2), np.zeros((3, 1))))
bad(L, "header_line", "channels", lambda: lv.header_line(None), lambda: lv.header_line("a_mm"), lambda: lv.header_line([""]))
bad(L, "Recorder", "path", lambda: lv.Recorder(None, CH, ()))
bad(L, "raise_priority", "realtime_priority", lambda: lv.raise_priority(realtime_priority=0), lambda: lv.raise_priority(realtime_priority=100))
bad(L, "raise_priority", "nice", lambda: lv.raise_priority(nice=0), lambda: lv.raise_priority(nice=21))
bad(L, "restore_priority", "priority", lambda: lv.restore_priority(None), lambda: lv.restore_priority("real-time"))
bad(L, "python_format", "kinds", lambda: lv.python_format([9], [3]), lambda: lv.python_format([lv.FIXED], [0]),
    lambda: lv.python_format([lv.FIXED, lv.GENERAL], [3]), lambda: lv.python_format("x", [3]))
bad(L, "format_rows", "table", lambda: lv.format_rows("rows", [lv.FIXED], [3]), lambda: lv.format_rows([1.0, 2.0], [lv.FIXED], [3]))
bad(L, "format_rows", "kinds", lambda: lv.format_rows([[1.0, 2.0]], [lv.FIXED], [3]), lambda: lv.format_rows([[1.0]], [7], [3]))
bad(L, "Recorder", "channels", lambda: lv.Recorder(NEVER + ".csv", None, ()))
bad(L, "Recorder", "result_columns", lambda: lv.Recorder(NEVER + ".csv", CH, None), lambda: lv.Recorder(NEVER + ".csv", CH, [5]))
bad(L, "Recorder", "sync_interval_s", lambda: lv.Recorder(NEVER + ".csv", CH, (), sync_interval_s=0.0), lambda: lv.Recorder(NEVER + ".csv", CH, (), sync_interval_s=NAN))
bad(L, "Recorder", "metadata", lambda: lv.Recorder(NEVER + ".csv", CH, (), metadata=["a"]))
bad(L, "Recorder", "overwrite", lambda: lv.Recorder(NEVER + ".csv", CH, (), overwrite="yes"))
bad(L, "read_record", "path", lambda: lv.read_record(None), lambda: lv.read_record(5))
bad(L, "build_system", "machine", lambda: lv.build_system(5, "sim"))
bad(L, "build_system", "source_kind", lambda: lv.build_system(None, "magic"), lambda: lv.build_system(None, None))
bad(L, "build_system", "seed", lambda: lv.build_system(None, "sim", seed=-1), lambda: lv.build_system(None, "sim", seed=1.5))
bad(L, "build_system", "load_kg", lambda: lv.build_system(None, "sim", load_kg=NAN), lambda: lv.build_system(None, "sim", load_kg=-1.0))
bad(L, "check_record_target", "record", lambda: lv.check_record_target(None, []))
bad(L, "check_record_target", "inputs", lambda: lv.check_record_target(NEVER + ".csv", None), lambda: lv.check_record_target(NEVER + ".csv", "machine.toml"),
    lambda: lv.check_record_target(NEVER + ".csv", [None]))
bad(L, "check_record_target", "force", lambda: lv.check_record_target(NEVER + ".csv", [], force="yes"))
bad(L, "LiveSession", "rate_hz", lambda: lv.LiveSession(rate_hz=NAN, server=False), lambda: lv.LiveSession(rate_hz="fast", server=False))
bad(L, "LiveSession", "port", lambda: lv.LiveSession(port="80", server=False), lambda: lv.LiveSession(port=-1, server=False))
bad(L, "LiveSession", "seed", lambda: lv.LiveSession(seed="a", server=False), lambda: lv.LiveSession(seed=-1, server=False))
bad(L, "LiveSession", "update_hz", lambda: lv.LiveSession(update_hz=None, server=False))
bad(L, "LiveSession", "load_kg", lambda: lv.LiveSession(load_kg=NAN, server=False))
bad(L, "LiveSession", "duration_s", lambda: lv.LiveSession(duration_s=NAN, server=False))
bad(L, "LiveSession", "path", lambda: lv.LiveSession(path="circle", server=False), lambda: lv.LiveSession(path=None, server=False))
bad(L, "LiveSession", "source", lambda: lv.LiveSession(source="magic", server=False), lambda: lv.LiveSession(source=None, server=False))
bad(L, "LiveSession", "pace", lambda: lv.LiveSession(pace="no", server=False))
bad(L, "LiveSession", "server", lambda: lv.LiveSession(server="no"))
bad(L, "LiveSession", "bind", lambda: lv.LiveSession(bind=None, server=False))
bad(L, "LiveSession", "allowed_hosts", lambda: lv.LiveSession(server=False, allowed_hosts=5), lambda: lv.LiveSession(server=False, allowed_hosts="monitor.lan"))
bad(L, "LiveSession", "duration_s", lambda: lv.LiveSession(server=False).run(duration_s=NAN))
bad(L, "Backoff", "initial_s", lambda: lv.Backoff(initial_s=0.0), lambda: lv.Backoff(initial_s=NAN), lambda: lv.Backoff(initial_s="1"))
bad(L, "Backoff", "factor", lambda: lv.Backoff(factor=0.5), lambda: lv.Backoff(factor=None))
bad(L, "Backoff", "maximum_s", lambda: lv.Backoff(maximum_s=INF), lambda: lv.Backoff(initial_s=1.0, maximum_s=0.5))
bad(L, "SimSource", "module", lambda: lv.SimSource(None, CH), lambda: lv.SimSource("virtual", CH))
bad(L, "SimSource", "channels", lambda: lv.SimSource(VM, None))
bad(L, "SimSource", "rate_hz", lambda: lv.SimSource(VM, CH, rate_hz=NAN), lambda: lv.SimSource(VM, CH, rate_hz="fast"), lambda: lv.SimSource(VM, CH, rate_hz=None))
bad(L, "SimSource", "max_batch_s", lambda: lv.SimSource(VM, CH, max_batch_s=0.0), lambda: lv.SimSource(VM, CH, max_batch_s="0.1"))
bad(L, "SimSource", "path", lambda: lv.SimSource(VM, CH, path="circle"), lambda: lv.SimSource(VM, CH, path=None))
bad(L, "ReplaySource", "path", lambda: lv.ReplaySource(None, CH), lambda: lv.ReplaySource(NAN, CH))
bad(L, "ReplaySource", "channels", lambda: lv.ReplaySource(REPLAY, None), lambda: lv.ReplaySource(REPLAY, "x_mm"))
bad(L, "ReplaySource", "pace", lambda: lv.ReplaySource(REPLAY, CH, pace="no"))
bad(L, "ReplaySource", "max_batch", lambda: lv.ReplaySource(REPLAY, CH, max_batch=0), lambda: lv.ReplaySource(REPLAY, CH, max_batch=NAN))
bad(L, "RtxSource", "path", lambda: lv.RtxSource(None, "mm", CH[0], CH))
bad(L, "RtxSource", "channel", lambda: lv.RtxSource(NEVER + ".rtx", "mm", None, CH), lambda: lv.RtxSource(NEVER + ".rtx", "mm", "nope_mm", CH))
bad(L, "RtxSource", "channels", lambda: lv.RtxSource(NEVER + ".rtx", "mm", CH[0], None))
bad(L, "RtxSource", "unit", lambda: lv.RtxSource(NEVER + ".rtx", None, "x_scale_mm", CH))
bad(L, "RtxSource", "max_batch", lambda: lv.RtxSource(NEVER + ".rtx", "mm", CH[0], CH, max_batch=-1))
bad(L, "TcpSource", "host", lambda: lv.TcpSource(None, 9000, CH), lambda: lv.TcpSource("", 9000, CH))
bad(L, "TcpSource", "port", lambda: lv.TcpSource("127.0.0.1", 0, CH), lambda: lv.TcpSource("127.0.0.1", "9000", CH), lambda: lv.TcpSource("127.0.0.1", 70000, CH))
bad(L, "TcpSource", "channels", lambda: lv.TcpSource("127.0.0.1", 9000, None))
bad(L, "TcpSource", "backoff", lambda: lv.TcpSource("127.0.0.1", 9000, CH, backoff=1.0))
bad(L, "TcpSource", "clock_offset_s", lambda: lv.TcpSource("127.0.0.1", 9000, CH, clock_offset_s=NAN))
bad(L, "TcpSource", "connect_timeout_s", lambda: lv.TcpSource("127.0.0.1", 9000, CH, connect_timeout_s=0.0))
bad(L, "SerialSource", "device", lambda: lv.SerialSource(None, CH), lambda: lv.SerialSource(5, CH))
bad(L, "SerialSource", "baud", lambda: lv.SerialSource("/dev/ttyUSB0", CH, baud=0), lambda: lv.SerialSource("/dev/ttyUSB0", CH, baud="fast"))
bad(L, "SerialSource", "channels", lambda: lv.SerialSource("/dev/ttyUSB0", None))
bad(L, "parse_source", "spec", lambda: lv.parse_source(None), lambda: lv.parse_source(5))
bad(L, "parse_source", "unknown source", lambda: lv.parse_source("magic"))
bad(L, "parse_source", "port 1-65535", lambda: lv.parse_source("tcp:host:99999"))
bad(L, "rtx_parts", "argument", lambda: lv.rtx_parts(None), lambda: lv.rtx_parts(b"a:mm:x"))
bad(L, "open_source", "spec", lambda: lv.open_source(None, CH))
bad(L, "open_source", "channels", lambda: lv.open_source("sim", None, virtual_module=lambda: VM))
bad(L, "open_source", "virtual_module", lambda: lv.open_source("sim", CH), lambda: lv.open_source("sim", CH, virtual_module=VM))
bad(L, "open_source", "pace", lambda: lv.open_source("sim", CH, virtual_module=lambda: VM, pace=None))
bad(L, "open_source", "rate_hz", lambda: lv.open_source("sim", CH, virtual_module=lambda: VM, rate_hz=NAN))
bad(L, "axis_error_columns", "letter", lambda: lv.axis_error_columns(None), lambda: lv.axis_error_columns("XY"), lambda: lv.axis_error_columns(1), lambda: lv.axis_error_columns("x"))
bad(L, "result_columns", "axes", lambda: lv.result_columns(None), lambda: lv.result_columns(("X", None)), lambda: lv.result_columns(5))
bad(L, "LiveState", "system", lambda: lv.LiveState(None), lambda: lv.LiveState("machine.toml"))
bad(L, "LiveState", "bins", lambda: lv.LiveState(SYS, bins=0), lambda: lv.LiveState(SYS, bins=2.5))
bad(L, "LiveState", "history_s", lambda: lv.LiveState(SYS, history_s=NAN), lambda: lv.LiveState(SYS, history_s=0.0))
bad(L, "LiveState", "history_points", lambda: lv.LiveState(SYS, history_points=0))
bad(L, "Broadcaster", "state", lambda: lv.Broadcaster(None))
bad(L, "Broadcaster", "update_hz", lambda: lv.Broadcaster(STATE, update_hz=NAN), lambda: lv.Broadcaster(STATE, update_hz="10"), lambda: lv.Broadcaster(STATE, update_hz=1e9))
bad(L, "Broadcaster", "title", lambda: lv.Broadcaster(STATE, title=None))
bad(L, "request_allowed", "headers", lambda: lv.request_allowed(None), lambda: lv.request_allowed([("host", "localhost")]))
bad(L, "request_allowed", "allowed_hosts", lambda: lv.request_allowed({"host": "localhost"}, None), lambda: lv.request_allowed({"host": "localhost"}, "localhost"))
bad(L, "create_app", "state", lambda: lv.create_app(None), lambda: lv.create_app(SYS))
bad(L, "create_app", "update_hz", lambda: lv.create_app(STATE, update_hz=NAN))
bad(L, "create_app", "allowed_hosts", lambda: lv.create_app(STATE, allowed_hosts="monitor.lan"), lambda: lv.create_app(STATE, allowed_hosts=[None]))
bad(L, "create_app", "allowed host", lambda: lv.create_app(STATE, allowed_hosts=["a:80"]))
bad(L, "create_board_app", "snapshot", lambda: lv.create_board_app(None, page="capture.html"))
bad(L, "create_board_app", "page", lambda: lv.create_board_app(dict, page="nothing.html"), lambda: lv.create_board_app(dict, page=None))
bad(L, "create_board_app", "allowed_hosts", lambda: lv.create_board_app(dict, page="capture.html", allowed_hosts="monitor.lan"))
bad(L, "LiveServer", "app", lambda: lv.LiveServer(None), lambda: lv.LiveServer(STATE))
bad(L, "LiveServer", "port", lambda: lv.LiveServer(APP, port=-1), lambda: lv.LiveServer(APP, port="80"), lambda: lv.LiveServer(APP, port=NAN))
bad(L, "LiveServer", "host", lambda: lv.LiveServer(APP, host=None))
bad(L, "DashboardProcess", "state", lambda: lv.DashboardProcess(None), lambda: lv.DashboardProcess(SYS))
bad(L, "DashboardProcess", "port", lambda: lv.DashboardProcess(STATE, port=-1), lambda: lv.DashboardProcess(STATE, port="80"))
bad(L, "DashboardProcess", "update_hz", lambda: lv.DashboardProcess(STATE, update_hz=NAN))
bad(L, "DashboardProcess", "allowed host", lambda: lv.DashboardProcess(STATE, allowed_hosts=["a:80"]))


# ---------------------------------------------------------------- campaign
ca = api("campaign")
C = "campaign"
CAMPAIGN = ca.load_campaign(EXAMPLES / "campaign")
SPEC = CAMPAIGN.tests[0]
RESULTS = ca.CampaignResults({"title": "t"}, {}, {}, [ca.TestResult("t1", "positioning", "X", ["x.csv"], {"E": 5.0})])


bad(C, "read_campaign", "no such campaign folder", lambda: ca.read_campaign(Path("no/such/campaign")))


bad(C, "load_campaign", "folder", lambda: ca.load_campaign(None), lambda: ca.load_campaign(NAN))
bad(C, "key_line", "campaign", lambda: ca.key_line(None, None, "window_ms"))
bad(C, "key_line", "spec", lambda: ca.key_line(CAMPAIGN, None, "window_ms"))
bad(C, "key_line", "key", lambda: ca.key_line(CAMPAIGN, CAMPAIGN.tests[0], 5))
bad(C, "check_figures", "figures", lambda: ca.check_figures(None, {}, {}), lambda: ca.check_figures({"E": "big"}, {"E_um": 5.0}, {}))
bad(C, "check_figures", "tolerance", lambda: ca.check_figures({"E": 1.0}, None, {}), lambda: ca.check_figures({"E": 1.0}, {"E_um": NAN}, {}),
    lambda: ca.check_figures({"E": 1.0}, {"E_um": "5"}, {}), lambda: ca.check_figures({"E": 1.0}, {"E_um": -1.0}, {}))
bad(C, "check_figures", "units", lambda: ca.check_figures({"E": 1.0}, {"E_um": 5.0}, None))
bad(C, "check_figures", "uncertainty", lambda: ca.check_figures({"E": 1.0}, {"E_um": 5.0}, {}, uncertainty=5.0))
bad(C, "check_figures", "uncertainty['E']", lambda: ca.check_figures({"E": 1.0}, {"E_um": 5.0}, {}, uncertainty={"E": "x"}), lambda: ca.check_figures({"E": 1.0}, {"E_um": 5.0}, {}, uncertainty={"E": NAN}))
bad(C, "check_figures", "units['E_um']", lambda: ca.check_figures({"E": 1.0}, {"E_um": 5.0}, {"E_um": 5}))
bad(C, "check_figures", "decision rule", lambda: ca.check_figures({"E": 1.0}, {"E_um": 5.0}, {}, rule="strict"))
bad(C, "overall_verdict", "verdict", lambda: ca.overall_verdict(None), lambda: ca.overall_verdict("pass"), lambda: ca.overall_verdict(["ok"]), lambda: ca.overall_verdict([None]))
bad(C, "results_payload", "results must be a CampaignResults", lambda: ca.results_payload(None), lambda: ca.results_payload(CAMPAIGN))
bad(C, "evaluation_is_raw", "path", lambda: ca.evaluation_is_raw(None), lambda: ca.evaluation_is_raw(5))
bad(C, "run_campaign", "campaign", lambda: ca.run_campaign(None), lambda: ca.run_campaign(5))
bad(C, "run_campaign", "progress", lambda: ca.run_campaign(CAMPAIGN, progress="bar"))
bad(C, "run_campaign", "compare", lambda: ca.run_campaign(CAMPAIGN, compare=["a"]))
bad(C, "run_test", "campaign must be a Campaign", lambda: ca.run_test(None, SPEC), lambda: ca.run_test(EXAMPLES / "campaign", SPEC))
bad(C, "run_test", "spec must be a TestSpec", lambda: ca.run_test(CAMPAIGN, None), lambda: ca.run_test(CAMPAIGN, {"kind": "positioning"}))
bad(C, "run_test", "compare", lambda: ca.run_test(CAMPAIGN, SPEC, compare=5))
bad(C, "svg_of", "draw", lambda: ca.svg_of(None), lambda: ca.svg_of("plot.svg"))
bad(C, "volumetric_section", "model", lambda: ca.volumetric_section(None, ca.svg_of))
bad(C, "volumetric_section", "svg_of", lambda: ca.volumetric_section(EXAMPLES / "xfyz_machine_u" / "machine.toml", None))
bad(C, "volumetric_section", "compensation files need the controller",
    lambda: ca.volumetric_section(EXAMPLES / "xfyz_machine" / "machine.toml", ca.svg_of, compensation={"X": NEVER + ".comp"}))
bad(C, "volumetric_section", "unknown controller", lambda: ca.volumetric_section(EXAMPLES / "xfyz_machine" / "machine.toml", ca.svg_of, compensation={"X": NEVER}, controller="magic"))
LOADED = ca.compensated_machine.__globals__["ControllerCompensation"]("linuxcnc", np.array([0.0, 0.2]), np.zeros(2), np.zeros(2))
bad(C, "compensated_machine", "machine must be a Machine", lambda: ca.compensated_machine(None, {}), lambda: ca.compensated_machine(MACHINE_U, {}))
bad(C, "compensated_machine", "corrections", lambda: ca.compensated_machine(MACHINE, None), lambda: ca.compensated_machine(MACHINE, [LOADED]))
bad(C, "compensated_machine", "corrections['X'] must be a ControllerCompensation", lambda: ca.compensated_machine(MACHINE, {"X": "X.comp"}))
bad(C, "compensated_machine", "a compensation for axis", lambda: ca.compensated_machine(MACHINE, {"A": LOADED}),
    lambda: ca.compensated_machine(MACHINE, {5: LOADED}))
bad(C, "read_loaded_compensation", "files", lambda: ca.read_loaded_compensation(None, "linuxcnc"),
    lambda: ca.read_loaded_compensation({"X": None}, "linuxcnc"))
bad(C, "read_loaded_compensation", "file not found", lambda: ca.read_loaded_compensation({"X": NEVER}, "linuxcnc"))
bad(C, "read_loaded_compensation", "controller", lambda: ca.read_loaded_compensation({"X": NEVER}, "magic"),
    lambda: ca.read_loaded_compensation({"X": NEVER}, None))
bad(C, "plot_volume", "machine", lambda: ca.plot_volume(None, NEVER + ".svg"), lambda: ca.plot_volume("machine.toml", NEVER + ".svg"))
bad(C, "plot_volume", "path", lambda: ca.plot_volume(MACHINE, None))
bad(C, "plot_volume", "figure format", lambda: ca.plot_volume(MACHINE, NEVER + ".txt"))
bad(C, "plot_volume", "count", lambda: ca.plot_volume(MACHINE, NEVER + ".svg", count=1), lambda: ca.plot_volume(MACHINE, NEVER + ".svg", count=NAN))
MAP2 = {"axes": ["X", "Z"], "grid_mm": {"X": [0.0, 1.0], "Z": [0.0, 1.0]}, "e_um": [[0.0, 1.0], [1.0, 2.0]]}
bad(C, "volumetric_section", "before", lambda: ca.volumetric_section(EXAMPLES / "xfyz_machine_u" / "machine.toml", ca.svg_of, before=[1]))
bad(C, "same_grid", "now", lambda: ca.same_grid(None, MAP2), lambda: ca.same_grid({"axes": ["X"]}, MAP2))
bad(C, "same_grid", "before", lambda: ca.same_grid(MAP2, {**MAP2, "e_um": [[0.0]]}), lambda: ca.same_grid(MAP2, {**MAP2, "axes": "XZ"}))
bad(C, "plot_volume_change", "now", lambda: ca.plot_volume_change(5, MAP2, NEVER + ".svg"),
    lambda: ca.plot_volume_change({**MAP2, "grid_mm": {"X": [0.0, NAN], "Z": [0.0, 1.0]}}, MAP2, NEVER + ".svg"))
bad(C, "plot_volume_change", "different grids", lambda: ca.plot_volume_change(MAP2, {**MAP2, "grid_mm": {"X": [0.0, 2.0], "Z": [0.0, 1.0]}}, NEVER + ".svg"))
bad(C, "plot_volume_change", "figure format", lambda: ca.plot_volume_change(MAP2, MAP2, NEVER + ".txt"))
bad(C, "plot_volume_change", "label", lambda: ca.plot_volume_change(MAP2, MAP2, NEVER + ".svg", label=3))


# ---------------------------------------------------------------- report
rp = api("report")
R = "report"

bad(R, "decision_statement", "decision rule", lambda: rp.decision_statement("strict"), lambda: rp.decision_statement(None))
bad(R, "render_html", "results", lambda: rp.render_html(None), lambda: rp.render_html(CAMPAIGN))
bad(R, "report_facts", "results", lambda: rp.report_facts(None), lambda: rp.report_facts(CAMPAIGN))
bad(R, "render_html", "compare", lambda: rp.render_html(RESULTS, compare=5), lambda: rp.render_html(RESULTS, compare={"tests": "all"}))
bad(R, "render_html", "volumetric", lambda: rp.render_html(RESULTS, volumetric=["plot"]))
bad(R, "render_html", "generated", lambda: rp.render_html(RESULTS, generated=5))
bad(R, "format_number", "value", lambda: rp.format_number([1.0]), lambda: rp.format_number(object()))
bad(R, "display_unit", "unit", lambda: rp.display_unit(None), lambda: rp.display_unit(5))
bad(R, "format_number", "digits", lambda: rp.format_number(1.0, -1), lambda: rp.format_number(1.0, NAN), lambda: rp.format_number(1.0, "3"))
bad(R, "previous_figures", "compare", lambda: rp.previous_figures(NAN), lambda: rp.previous_figures("results.json"))
bad(R, "compare_label", "compare", lambda: rp.compare_label(NAN), lambda: rp.compare_label([]))
bad(R, "verdict_rows", "results", lambda: rp.verdict_rows(None, None))
bad(R, "verdict_rows", "before", lambda: rp.verdict_rows(RESULTS, ["E"]))
bad(R, "verdict_rows", "before_uncertainty", lambda: rp.verdict_rows(RESULTS, None, before_uncertainty=["E"]))
bad(R, "previous_uncertainty", "compare", lambda: rp.previous_uncertainty(NAN), lambda: rp.previous_uncertainty({"tests": "all"}))
bad(R, "sections", "tests", lambda: rp.sections(None), lambda: rp.sections([None]), lambda: rp.sections("tests"))
bad(R, "write_report", "results", lambda: rp.write_report(None, NEVER))
bad(R, "write_report", "out_dir", lambda: rp.write_report(RESULTS, None))
bad(R, "write_report", "compare", lambda: rp.write_report(RESULTS, NEVER, compare=5))
bad(R, "write_report", "pdf", lambda: rp.write_report(RESULTS, NEVER, pdf="yes"))
bad(R, "write_report", "extra_files", lambda: rp.write_report(RESULTS, NEVER, extra_files=["a"]), lambda: rp.write_report(RESULTS, NEVER, extra_files={"../a.txt": "x"}),
    lambda: rp.write_report(RESULTS, NEVER, extra_files={"a.txt": None}))
bad(R, "report_campaign", "campaign_dir", lambda: rp.report_campaign(None))
bad(R, "report_campaign", "out_dir", lambda: rp.report_campaign(EXAMPLES / "campaign", 5))
bad(R, "report_campaign", "compare", lambda: rp.report_campaign(EXAMPLES / "campaign", NEVER, compare=5))
bad(R, "report_campaign", "pdf", lambda: rp.report_campaign(EXAMPLES / "campaign", NEVER, pdf=None))
bad(R, "write_pdf", "results", lambda: rp.write_pdf(None, NEVER + ".pdf"))
bad(R, "write_pdf", "path", lambda: rp.write_pdf(RESULTS, None))
bad(R, "write_pdf", "compare", lambda: rp.write_pdf(RESULTS, NEVER + ".pdf", compare="old.json"))
bad(R, "write_pdf", "generated", lambda: rp.write_pdf(RESULTS, NEVER + ".pdf", generated=5))
bad(R, "run_demo", "output_dir", lambda: rp.run_demo(None), lambda: rp.run_demo(5))
bad(R, "run_demo", "seed", lambda: rp.run_demo(NEVER, seed=-1), lambda: rp.run_demo(NEVER, seed=NAN))
bad(R, "write_as_found_campaign", "folder", lambda: rp.write_as_found_campaign(None))
bad(R, "write_as_found_campaign", "seed", lambda: rp.write_as_found_campaign(NEVER, seed=-1))
bad(R, "write_as_left_campaign", "folder", lambda: rp.write_as_left_campaign(None, NEVER))
bad(R, "write_as_left_campaign", "compensation", lambda: rp.write_as_left_campaign(NEVER, None))
bad(R, "write_as_left_campaign", "seed", lambda: rp.write_as_left_campaign(NEVER, NEVER, seed=1.5))
bad(R, "history_section", "results", lambda: rp.history_section(None), lambda: rp.history_section({}))


# ---------------------------------------------------------------- the check
bad(R, "CycleSettings", "fmt", lambda: rp.CycleSettings(fmt="fanuc"))
bad(R, "CycleSettings", "restart_command", lambda: rp.CycleSettings(restart_command=["linuxcnc", "-r"]))
bad(R, "CycleSettings", "restart", lambda: rp.CycleSettings(restart="restart.sh"))
bad(R, "CycleSettings", "tolerance_e_um", lambda: rp.CycleSettings(tolerance_e_um=-1.0), lambda: rp.CycleSettings(tolerance_e_um="20"))
bad(R, "closed_cycle", "controller", lambda: rp.closed_cycle(CAMPAIGN, None, "sim", CAMPAIGN))
bad(R, "closed_cycle", "source", lambda: rp.closed_cycle(CAMPAIGN, "sim", 5, CAMPAIGN))
bad(R, "closed_cycle", "cycle", lambda: rp.closed_cycle(CAMPAIGN, "sim", "sim", CAMPAIGN, {"fmt": "linuxcnc"}))
bad(R, "closed_cycle", "output_dir", lambda: rp.closed_cycle(CAMPAIGN, "sim", "sim", None))
# the certificate and the DCC: a campaign without the certificate's fields is refused, naming them
bad(R, "missing_certificate_fields", "results", lambda: rp.missing_certificate_fields(None), lambda: rp.missing_certificate_fields(CAMPAIGN))
bad(R, "check_certificate", "a calibration certificate needs", lambda: rp.check_certificate(RESULTS))
bad(R, "check_certificate", "results", lambda: rp.check_certificate(None))
bad(R, "certificate_context", "a calibration certificate needs", lambda: rp.certificate_context(RESULTS, "en"))
bad(R, "render_certificate_html", "a calibration certificate needs", lambda: rp.render_certificate_html(RESULTS, language="en"))
bad(R, "figure_rows", "results", lambda: rp.figure_rows(None), lambda: rp.figure_rows(CAMPAIGN))
bad(R, "figure_rows", "gettext", lambda: rp.figure_rows(RESULTS, "de"))
bad(R, "localised_rows", "rows", lambda: rp.localised_rows(None, "de"), lambda: rp.localised_rows(["E"], "de"))
bad(R, "localised_rows", "translation", lambda: rp.localised_rows([], "fr"))
bad(R, "certificate_environment", "language", lambda: rp.certificate_environment(None), lambda: rp.certificate_environment("german"))
bad(R, "translations", "translation", lambda: rp.translations("fr"))
bad(R, "translations", "language", lambda: rp.translations(5), lambda: rp.translations("../de"))
bad(R, "catalog_path", "language", lambda: rp.catalog_path(None), lambda: rp.catalog_path("../../x"))
bad(R, "format_decimal_for", "digits", lambda: rp.format_decimal_for(1.0, -1, "de"), lambda: rp.format_decimal_for(1.0, 99, "de"))
bad(R, "format_decimal_for", "value", lambda: rp.format_decimal_for([1.0], 3, "de"), lambda: rp.format_decimal_for(True, 3, "de"))
bad(R, "format_decimal_for", "translation", lambda: rp.format_decimal_for(1.0, 3, "fr"))
bad(R, "format_date_for", "value", lambda: rp.format_date_for("yesterday", "de"), lambda: rp.format_date_for(5, "en"))
bad(R, "format_date_for", "translation", lambda: rp.format_date_for("2026-11-28", "fr"))
bad(R, "dcc_xml", "a calibration certificate needs", lambda: rp.dcc_xml(RESULTS))
bad(R, "dcc_xml", "results", lambda: rp.dcc_xml(None))
bad(R, "dsi_unit", "key", lambda: rp.dsi_unit(None), lambda: rp.dsi_unit(""))
bad(R, "dsi_unit", "unit", lambda: rp.dsi_unit("E", 5))
bad(R, "read_dcc", "path", lambda: rp.read_dcc(None))
bad(R, "read_dcc", "not a readable XML file", lambda: rp.read_dcc(NEVER))
bad(R, "dcc_summary", "read", lambda: rp.dcc_summary(None), lambda: rp.dcc_summary({"tests": [{"figures": {}}]}))
bad(R, "sign_dcc", "dcc", lambda: rp.sign_dcc(None, NEVER, NEVER, NEVER))
bad(R, "sign_dcc", "not a readable XML file", lambda: rp.sign_dcc(NEVER, NEVER, NEVER, NEVER))
bad(R, "sign_dcc", "passphrase", lambda: rp.sign_dcc(NEVER, NEVER, NEVER, NEVER, passphrase="secret"))
bad(R, "verify_dcc", "dcc", lambda: rp.verify_dcc(None))
bad(R, "verify_dcc", "cert", lambda: rp.verify_dcc(NEVER, 5))
bad(R, "page_context", "results", lambda: rp.page_context(None))
bad(R, "read_compared", "path", lambda: rp.read_compared(None))
bad(R, "read_compared", "not an axiscal results.json", lambda: rp.read_compared(EXAMPLES / "positioning_run.json"))

EXEMPT: dict[str, set[str]] = {
    # result records: the library fills them with what a function computed; a user reads them and
    # does not build them, so they take no user values to check
    "uncertainty": {"Decision", "CoverageInterval", "PositioningUncertainty", "PositioningWithUncertainty", "LineUncertainty",
                    "VolumetricUncertainty"},
    "live": {"RunSummary", "FrameBatch", "Record", "SourceStatus", "ClientStats", "Priority",
             "below_the_loop"},  # a function of no arguments
    "campaign": {"Check", "Figure", "Plot", "TestResult", "CampaignResults",
                 # made by load_campaign from the validated campaign.toml (axiscal.io.formats.CampaignFile),
                 # where every value was checked once; a user reads them and does not build them
                 "Campaign", "TestSpec"},
    "report": {"ReportFiles", "DemoResult", "CycleResult", "Verification",
               # functions of no arguments
               "template_environment", "builtin_example",
               # print any value (with str; None as empty): every value is a valid argument
               "typst_string", "typst_text"},
    # result records of import_readings and read_rtx; a predicate and a pass-through that take any
    # value (type_name too); unit_words reads the name of an argument, which the library's own code gives
    "io": {"ImportedReadings", "RtxCapture", "is_real", "to_plain", "unit_words", "type_name"},
}


test_bad_arguments_raise_axiscal_error_naming_them, test_every_public_callable_has_a_bad_argument_case = TABLE.tests(EXEMPT)


# ---------------------------------------------------------------- properties: finite in, finite out or AxiscalError
_ANY_FLOAT = hs.floats(allow_nan=True, allow_infinity=True, width=64)


_finite_or_refused = finite_or_refused


@settings(max_examples=150, deadline=None)
@given(_ANY_FLOAT, _ANY_FLOAT, _ANY_FLOAT, hs.sampled_from(("simple", "guard-band")))
def test_decide_on_any_numbers_is_a_verdict_or_refused(value, limit, U, rule):
    decision = _finite_or_refused(lambda: un.decide(value, limit, U, rule=rule))
    if decision is not None:
        assert decision.verdict in ("pass", "fail", "inconclusive")
        assert np.isfinite([value, limit, U]).all() and U >= 0


@settings(max_examples=100, deadline=None)
@given(hs.lists(_ANY_FLOAT, min_size=0, max_size=60), _ANY_FLOAT)
def test_coverage_interval_of_any_draws_is_finite_or_refused(draws, probability):
    interval = _finite_or_refused(lambda: un.coverage_interval(draws, probability))
    if interval is not None:
        assert np.isfinite([interval.low, interval.high, interval.mean]).all()
        assert interval.low <= interval.high


@settings(max_examples=100, deadline=None)
@given(hs.dictionaries(hs.sampled_from(("E", "R", "B")), hs.one_of(_ANY_FLOAT, hs.none(), hs.text(max_size=2))),
       hs.dictionaries(hs.sampled_from(("E_um", "R_um", "B_um")), hs.one_of(_ANY_FLOAT, hs.text(max_size=2))))
def test_check_figures_of_any_values_is_checks_or_refused(figures, tolerances):
    checks = _finite_or_refused(lambda: ca.check_figures(figures, tolerances, {}))
    if checks is not None:
        assert all(np.isfinite(c.limit) and c.limit >= 0 for c in checks)
