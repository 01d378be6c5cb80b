"""A visit held by the workbench: each step one call into the library, its files in the data folder.

:class:`Workbench` is what the page's routes call. It keeps the visit in hand (the campaign
folder, the plan, the run going on) and turns what the library returns into JSON-able answers in
the units people read (mm, um, s). It computes no figure itself: the history's trends, the plan,
the capture, the evaluation, the compensation table and its residuals, the report and the
comparison are the library's.

The folder of a visit is ``DATA/<machine>-<date>``: ``campaign.toml``, the machine's description
(``machine.toml`` and its error tables), each linear axis's plan (``plan_x.csv`` and its program)
and as-found run (``positioning_x.csv``), ``files/`` with the data of the tests taken from files,
``compensation/``, and ``as-left/`` with the runs taken with the compensation loaded; the reports
go to ``report/`` and ``as-left/report/``. Every file is written atomically. The visit's machine and
tests are kept by :class:`~axiscal.workbench.visit_tests.VisitTests`, its connection by
:class:`~axiscal.workbench.visit_connection.VisitConnection`, the history's views by
:class:`~axiscal.workbench.history_views.HistoryViews`, all parts of :class:`Workbench`.
"""

from __future__ import annotations

import json
import re
import threading
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_path
from axiscal.io.atomic import write_text
from axiscal.io.templates import render_template
from axiscal.units import MM, UM
from axiscal.io.arguments import check_number
from axiscal.workbench.forms import FormErrors, PlanForm, VisitForm, checked
from axiscal.workbench.history_views import HistoryViews
from axiscal.workbench.suite import campaign_with_tests, checked_plan, plan_file, run_file, wanted_tests
from axiscal.workbench.visit_connection import VisitConnection
from axiscal.workbench.visit_tests import MACHINE_KEYS, VisitTests
from axiscal.workbench.machines import MACHINE_FILE, example_machine, machine_axes
from axiscal.workbench.budget import decision_of, remember_budget, write_budget
from axiscal.workbench.laboratory import laboratory_defaults, remember_laboratory
from axiscal.workbench.runner import PlanRun
from axiscal.workbench.tabs import Tabs
from axiscal.workbench.saved import (STEPS, SavedVisit, open_folder, read_saved, remember_open, unfinished_visits,
                                     write_saved)

__all__ = ["PHASES", "Workbench"]

#: the two runs of a visit: before and after the compensation
PHASES = ("as-found", "as-left")


def _toml(text: str) -> str:
    return json.dumps(text, ensure_ascii=False)


def _slug(text: str) -> str:
    return re.sub(r"[^A-Za-z0-9]+", "-", text).strip("-").lower()[:60] or "visit"


class Workbench(HistoryViews, VisitTests, VisitConnection):
    """The visit the page works on, and the history it reads.

    Parameters
    ----------
    data : str or Path
        The data folder: every file the workbench writes or serves lies inside it.
    db : str, optional, keyword-only
        The history's database URL (default: the user's SQLite file, or ``$AXISCAL_DB``).
    speed : float, keyword-only
        How many times faster than real time the virtual machine runs (default 1).

    Raises
    ------
    AxiscalError
        For a data folder that cannot be made.
    """

    def __init__(self, data: str | Path, *, db: str | None = None, speed: float = 1.0):
        data = check_path("data", data)
        if db is not None and (not isinstance(db, str) or not db.strip()):
            raise AxiscalError(f"db must be a database URL or SQLite file, not {db!r}")
        self.speed = check_number("speed", speed, positive=True, high=1000.0)
        self.db = db
        try:
            data.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise AxiscalError(f"cannot make the data folder ({exc.strerror or exc})", path=data) from None
        self.data = data.resolve()
        self.folder: Path | None = None
        self.visit: VisitForm | None = None
        self.plan: PlanForm | None = None
        self.connection = None
        self.run: PlanRun | None = None
        self.phase = "as-found"
        self.compensation: dict[str, Any] | None = None
        self._lock = threading.Lock()
        # the server's warm-up and the page's first request both read the history: the first reading
        # of a new SQLite file makes it, and two at once would find it half made ("database is locked")
        self._history_lock = threading.Lock()
        # the page evaluates a run that has just ended (Results, Before / after) while a click may ask again:
        # their plots are drawn one at a time (matplotlib's pyplot is not thread-safe)
        self._plot_lock = threading.Lock()
        self.saved: SavedVisit | None = None
        self.tabs = Tabs()  # which browser tab may change the visit
        self.notice = ""
        try:  # the visit that was open when the workbench stopped is open again, at the step it was at
            folder = open_folder(self.data)
            if folder is not None:
                self._restore(folder)
        except AxiscalError as exc:
            self.notice = f"the visit that was open is not opened again: {exc}"

    # -- 2. new visit ------------------------------------------------------------------------------
    def new_visit(self, data: Any) -> dict[str, Any]:
        """Check the campaign form, the machine and the tests wanted; write the machine and ``campaign.toml``.

        The machine (``machine_choice``: ``example``, a ``machine.toml`` of the data folder, or ``new``
        with ``machine_chain`` and ``machine_travels``) is copied into the visit's folder; ``tests``
        names the tests wanted (``positioning-X`` ...).
        """
        if not isinstance(data, dict):
            checked("visit", data)  # names what the page must send
        data = dict(data)
        chosen = {k: data.pop(k) for k in MACHINE_KEYS if k in data}
        fields: dict[str, str] = {}
        form = None
        try:
            form = checked("visit", data)
        except FormErrors as exc:
            fields |= exc.fields
        try:
            source, described, tests = self._checked_machine_and_tests(
                chosen, form.machine if form is not None else str(data.get("machine") or "machine"))
        except FormErrors as exc:
            fields |= exc.fields
        if fields:
            raise FormErrors(fields)
        folder = self.data / f"{_slug(form.machine)}-{form.date.isoformat()}"
        described = self._set_up_machine(folder, source, form.machine) | {"form": chosen}  # the form shown again
        write_budget(folder, form.model_dump(mode="json"))  # before campaign.toml, which names it
        remember_laboratory(self.data, form.model_dump(mode="json"))
        remember_budget(self.data, form.model_dump(mode="json"))
        with self._lock:
            self.folder, self.visit, self.plan, self.run, self.compensation = folder, form, None, None, None
            self.phase = "as-found"
            self.saved = SavedVisit(form.model_dump(mode="json"), step="visit", tests=tests, machine=described)
            self._save()
            remember_open(self.data, folder)
        text = self.write_campaign().read_text(encoding="utf-8")
        return {"folder": self._rel(folder), "campaign": self._rel(folder / "campaign.toml"), "text": text,
                "machine": described, "tests": self.tests()}

    def _render_campaign(self, **overrides: Any) -> str:
        """campaign.toml as the New visit form writes it, without its tests (the visit's list adds them)."""
        return render_template("workbench/campaign.toml.j2", filters={"toml": _toml}, keep_trailing_newline=True,
                               **(self.visit.model_dump() | overrides))

    def _visit_folder(self) -> Path:
        if self.folder is None or self.visit is None:
            raise AxiscalError("start a visit first (New visit)")
        return self.folder

    def _phase_folder(self, phase: str) -> Path:
        folder = self._visit_folder()
        if phase not in PHASES:
            raise AxiscalError(f"phase must be one of {', '.join(PHASES)}, not {phase!r}")
        return folder if phase == "as-found" else folder / "as-left"

    def _rel(self, path: Path) -> str:
        return path.resolve().relative_to(self.data).as_posix()

    # -- 3. plan -----------------------------------------------------------------------------------
    def make_plan(self, data: Any) -> dict[str, Any]:
        """Check the plan form of an axis, write its cycle CSV and program; return the table and the program."""
        from axiscal.io.gcode import dialect as find_dialect
        from axiscal.positioning.plan import plan_test, write_plan

        form = checked_plan(data, self._axes())
        folder = self._visit_folder()
        self._test(f"positioning-{form.axis}", run=True)
        plan = plan_test(form.start_mm * MM, form.end_mm * MM, form.targets, runs=form.runs,
                         overrun_m=form.overrun_mm * MM, seed=form.seed)
        self._within_told_limits(form, plan.moves)
        name = form.axis.lower()
        csv_path = folder / f"plan_{name}.csv"
        program = folder / f"{name}{find_dialect(form.dialect).extension}"
        write_plan(plan, csv_path, gcode_path=program, axis=form.axis, dwell_s=form.dwell_s, dialect=form.dialect)
        with self._lock:
            self.plan = form
            self.saved.plan = form.model_dump(mode="json")
            self.saved.plans[form.axis] = self.saved.plan
            self._save()
        return self._plan_view()

    def _plan_of(self, axis: str) -> Any:
        """The plan form of an axis planned (its files there), or None."""
        saved = self.saved.plans.get(axis) if self.saved is not None else None
        if saved is None or not (self._visit_folder() / plan_file(axis)).is_file():
            return None
        return checked_plan(saved, self._axes())

    def _plan_view(self, form: Any = None) -> dict[str, Any]:
        """The plan's table and program (the last planned, or ``form``'s), as the page shows them, read from the files."""
        from axiscal.capture.steps import plan_steps
        from axiscal.io.gcode import dialect as find_dialect

        form, folder = form or self.plan, self._visit_folder()
        name = form.axis.lower()
        csv_path = folder / f"plan_{name}.csv"
        program = folder / f"{name}{find_dialect(form.dialect).extension}"
        steps = plan_steps(csv_path)
        rows = [{"step": int(steps.step[k]), "run": int(steps.run[k]), "direction": str(steps.direction[k]),
                 "target_mm": None if not np.isfinite(steps.target_m[k]) else float(steps.target_m[k] / MM),
                 "move_to_mm": float(steps.move_to_m[k] / MM)} for k in range(steps.step.size)]
        targets = np.unique(np.round(steps.target_m[np.isfinite(steps.target_m)] / UM) * UM)
        return {"plan_csv": self._rel(csv_path), "program": self._rel(program),
                "program_text": program.read_text(encoding="utf-8"), "steps": rows,
                "targets_mm": [float(t / MM) for t in targets], "readings": int(steps.readings), "axis": form.axis,
                "form": form.model_dump(mode="json")}

    # -- 5. run ------------------------------------------------------------------------------------
    def start_run(self, phase: str = "as-found", *, resume: bool = False, test: str | None = None,
                  repeat: bool = False) -> dict[str, Any]:
        """Start (or resume after a broken connection, or repeat afresh) the run of a test (the last planned's by default)."""
        from axiscal.capture.files import partial_path

        folder = self._phase_folder(phase)
        if test is None and self.plan is None:
            raise AxiscalError("plan the test first (Plan)")
        test = self._test(test if test is not None else f"positioning-{self.plan.axis}", run=True)
        axis = test["axis"]
        plan = self._plan_of(axis)
        if plan is None:
            raise AxiscalError(f"plan the positioning of {axis} first (Plan)")
        if self.connection is None:
            raise AxiscalError("connect the instrument and the controller first (Connect)")
        if self.connection.refused:
            raise AxiscalError(f"the controller is not ready: {self.connection.refused}; connect again once it is")
        if self.run is not None and self.run.state in ("running", "paused"):
            raise AxiscalError("a run is going on: pause, abort or wait for it")
        compensation = None
        if phase == "as-left":
            if self.compensation is None:
                raise AxiscalError("write the compensation table first (Compensate)")
            if self.compensation.get("axis", "X") != axis:
                raise AxiscalError(f"the table is for {self.compensation.get('axis', 'X')}: make {axis}'s first (Compensate)")
            compensation = self.compensation["text"]
            self._write_as_left_campaign()
        output = folder / run_file(axis)
        if repeat and not resume:  # the test run again from its start: a run it left short is set aside
            partial_path(output).unlink(missing_ok=True)
        run = PlanRun(self._visit_folder() / plan_file(axis), output, instrument=self.connection.instrument,
                      controller=self.connection.controller, compensation=compensation,
                      controller_kind=self.visit.controller, resume=resume, speed=self.speed,
                      dwell_s=plan.dwell_s, seed=0 if phase == "as-found" else 1, axis=axis, machine=self.machine_file(),
                      ini=self.connection.ini or None)
        run.test, run.phase = test["id"], phase
        with self._lock:
            self.run, self.phase, self.plan = run, phase, plan
            self.saved.phase = phase
            self._save()
        run.start()
        return self.run_state()

    def control(self, action: str) -> dict[str, Any]:
        """``pause``, ``resume`` or ``abort`` the run going on."""
        if self.run is None:
            raise AxiscalError("no run is going on")
        if action not in ("pause", "resume", "abort"):
            raise AxiscalError(f"action must be pause, resume or abort, not {action!r}")
        getattr(self.run, action)()
        return self.run_state()

    def run_state(self) -> dict[str, Any]:
        """The run going on (or the last), as the page shows it."""
        if self.run is None:
            # a run ended short before the workbench stopped: its partial file is there to resume
            resumable = False
            if self.plan is not None and self.folder is not None:
                from axiscal.capture.files import partial_path

                output = self._phase_folder(self.phase) / f"positioning_{self.plan.axis.lower()}.csv"
                resumable = partial_path(output).is_file()
            return {"state": "idle", "phase": self.phase, "resumable": resumable}
        snap = self.run.snapshot()
        if snap["run_csv"]:
            snap["run_csv"] = self._rel(Path(snap["run_csv"]))
        return snap | {"phase": self.phase, "test": getattr(self.run, "test", None)}

    # -- 6. results --------------------------------------------------------------------------------
    def results(self, phase: str = "as-found", test: str | None = None) -> dict[str, Any]:
        """Evaluate the phase's tests (or one) as the campaign does: figures with U against the tolerance, the plots.

        A test whose evaluation fails is answered with its one line (``error``), the others evaluated.
        """
        from axiscal.campaign import load_campaign, run_test

        if phase == "as-found":
            self.write_campaign()
        elif phase == "as-left" and (self._phase_folder(phase) / "campaign.toml").is_file():
            self._write_as_left_campaign()
        campaign = load_campaign(self._phase_folder(phase))
        out = []
        for spec in campaign.tests:
            if test is not None and spec.id != test:
                continue
            try:
                with self._plot_lock:
                    result = run_test(campaign, spec)
            except AxiscalError as exc:
                out.append({"id": spec.id, "verdict": "error", "error": str(exc).replace(f"{self.data}/", ""),
                            "checks": [], "plots": [], "warnings": []})
                continue
            out.append({
                "id": result.id, "verdict": result.verdict, "method": result.method,
                "checks": [{"figure": c.figure, "value": c.value, "U": c.U, "limit": c.limit, "unit": c.unit,
                            "result": c.result} for c in result.checks],
                "plots": [{"title": p.title, "svg": p.svg} for p in result.plots], "warnings": result.warnings,
                "table": [{"label": f.label, "value": f.value, "unit": f.unit} for f in result.table],
            })
        return {"phase": phase, "tests": out, **decision_of(campaign)}

    # -- 7. compensate -----------------------------------------------------------------------------
    def compensate(self, axis: str | None = None) -> dict[str, Any]:
        """The controller's table from an axis's as-found run (the last planned by default), its file, the curves."""
        from axiscal.campaign.runner import COMPENSATION_FILES
        from axiscal.compensation import error_curve, residuals
        from axiscal.compensation.formats import compensation_table
        from axiscal.positioning.evaluation import target_statistics
        from axiscal.positioning.reader import read_positioning_run

        folder = self._visit_folder()
        if axis is None and self.plan is None:
            raise AxiscalError("plan and run the test first")
        axis = self._test(f"positioning-{axis or self.plan.axis}", run=True)["axis"]
        run_csv = folder / run_file(axis)
        if not run_csv.is_file():
            raise AxiscalError("run the as-found test first (Run)")
        controller = self.visit.controller
        run = read_positioning_run(run_csv).run
        options = {"axis": axis} if controller in ("siemens", "heidenhain") else {}
        result = compensation_table(run, controller, **options)
        curve = error_curve(target_statistics(run))
        x = run.targets
        directions = ("+", "-")
        left = {d: (residuals(result.table, curve, x, d if d in ("+", "-") else "mean", offset=result.reference_offset_m)
                    / UM).tolist() for d in directions}
        path = folder / "compensation" / COMPENSATION_FILES[controller].format(axis=axis)
        write_text(path, result.text)
        answer = {"controller": controller, "file": self._rel(path), "text": result.text, "description": result.description,
                  "largest_residual_um": result.largest_residual_m / UM, "targets_mm": (x / MM).tolist(),
                  "measured_um": {"+": (curve.up / UM).tolist(), "-": (curve.down / UM).tolist()},
                  "residual_um": left, "axis": axis}
        with self._lock:
            self.compensation = answer
            self.saved.compensation = answer
            self._save()
        return answer

    def _write_as_left_campaign(self) -> None:
        folder = self._visit_folder()
        text = self._render_campaign(title=f"{self.visit.title} (as left)")
        # the axis the table corrects, and every axis run as left before
        axis, left = (self.compensation or {}).get("axis", "X"), folder / "as-left"
        tests = [t for t in self._tests() if t["source"] == "run" and (t["axis"] == axis or (left / run_file(t["axis"])).is_file())]
        write_text(folder / "as-left" / "campaign.toml", campaign_with_tests(text, tests, left, model=None))

    def _as_left_run(self) -> Path:
        """The as-left run's file, or what Before / after waits for, in one line."""
        folder = self._visit_folder()
        name = run_file((self.compensation or {}).get("axis") or (self.plan.axis if self.plan is not None else "X"))
        run = self.run
        if self.phase == "as-left" and run is not None and run.state in ("ready", "running", "paused"):
            raise AxiscalError(f"Before / after waits for the as-left run to end ({len(run.stops)} of {run.total} stops"
                               f" taken, {run.state}): it is shown as soon as the run has ended")
        output = folder / "as-left" / name
        if output.is_file():
            return output
        if self.phase == "as-left" and run is not None and run.state in ("broken", "aborted", "failed"):
            raise AxiscalError(f"Before / after waits for the as-left run, which ended short ({len(run.stops)} of"
                               f" {run.total} stops, {run.state}): resume it (Run)")
        if self.compensation is None:
            raise AxiscalError("Before / after waits for the as-left run: make the table first (Compensate), then run"
                               " as left with it loaded")
        raise AxiscalError("Before / after waits for the as-left run: run as left with the table loaded (Compensate)")

    def before_after(self) -> dict[str, Any]:
        """The as-left campaign run against the as-found one: the overlays and the change of each figure.

        Raises
        ------
        AxiscalError
            Saying what it waits for: the as-left run going on, ended short, or not yet run.
        """
        from axiscal.campaign import load_campaign, results_payload, run_campaign

        folder = self._visit_folder()
        self._as_left_run()
        self.write_campaign()
        self._write_as_left_campaign()
        with self._plot_lock:
            before = results_payload(run_campaign(load_campaign(folder)))
            after = run_campaign(load_campaign(folder / "as-left"), compare=before)
        previous = {t["id"]: t["figures"] for t in before["tests"]}
        rows = []
        for test in after.tests:
            for c in test.checks:
                was = previous.get(test.id, {})
                old = _figure_of(was, c.figure)
                rows.append({"test": test.id, "figure": c.figure, "unit": c.unit, "before": old, "after": c.value,
                             "limit": c.limit, "result": c.result})
        return {"changes": rows, "plots": [{"title": p.title, "svg": p.svg} for t in after.tests for p in t.plots]}

    # -- 8. finish ---------------------------------------------------------------------------------
    def finish(self, *, pdf: bool = True) -> dict[str, Any]:
        """The reports (HTML, PDF) of both runs made and stored in the history; links to each file."""
        from axiscal.report import report_campaign

        folder = self._visit_folder()
        links = []
        with self._plot_lock:
            # the visit's last report is its calibration certificate, when the New visit form stated one
            certify = bool(self.visit.certificate_number)
            self.write_campaign()
            left_run = any((folder / "as-left" / run_file(t["axis"])).is_file() for t in self._tests() if t["source"] == "run")
            if left_run:
                self._write_as_left_campaign()
            found = report_campaign(folder, pdf=pdf, history=True, db=self.db, certificate=certify and not left_run)
            links += self._links(found, "as-found")
            if left_run:
                left = report_campaign(folder / "as-left", compare=found.results, pdf=pdf, history=True, db=self.db,
                                       certificate=certify)
                links += self._links(left, "as-left")
        answer = {"files": links, "verdict": found.results_data.verdict,
                  "tests": [{"id": t.id, "verdict": t.verdict} for t in found.results_data.tests]}
        with self._lock:
            self.saved.finished = answer
            self._save()
        return answer

    def _links(self, files: Any, phase: str) -> list[dict[str, str]]:
        out = []
        named = [(name, getattr(files, name, None)) for name in ("html", "pdf", "results")]
        named += [("certificate " + Path(path).suffix.lstrip("."), path) for path in getattr(files, "certificate", ())]
        named.append(("dcc", getattr(files, "dcc", None)))
        for name, path in named:
            if path is not None and Path(path).is_file():
                out.append({"phase": phase, "kind": name, "path": self._rel(Path(path))})
        return out

    def certificate_defaults(self) -> dict[str, Any]:
        """The New visit form's certificate fields as the last visit left them, with the next number."""
        return laboratory_defaults(self.data)

    # -- the visit kept: reload, restart, another tab ------------------------------------------------
    def _save(self) -> None:
        """Write the open visit's ``workbench.json`` (the caller holds the lock)."""
        if self.saved is not None and self.folder is not None:
            write_saved(self.folder, self.saved)

    def _restore(self, folder: Path) -> None:
        """Open the visit kept in ``folder`` at the step it was at (its devices are connected again by hand)."""
        saved = read_saved(folder)
        tested = saved.visit.pop("axes", None) or ["X"]  # the axes a visit kept before it listed its tests named
        visit = checked("visit", saved.visit)
        if saved.machine is None:  # a visit kept before it named its machine: the example's, its axes tested
            saved.machine = machine_axes(folder / MACHINE_FILE if (folder / MACHINE_FILE).is_file() else example_machine())
        if not saved.tests:
            saved.tests = wanted_tests([f"positioning-{a}" for a in tested], saved.machine["axes"])
        if saved.plan is not None and not saved.plans:
            saved.plans = {saved.plan.get("axis", "X"): saved.plan}
        plan = checked_plan(saved.plan, saved.machine["axes"]) if saved.plan is not None else None
        if plan is not None and not (folder / plan_file(plan.axis)).is_file():
            plan = None
        with self._lock:
            same = folder == self.folder
            if not same and self.run is not None and self.run.state in ("running", "paused"):
                raise AxiscalError("a run is going on: pause, abort or wait for it before opening another visit")
            self.folder, self.visit, self.plan, self.saved = folder, visit, plan, saved
            self.compensation, self.phase = saved.compensation, saved.phase
            if not same:
                self.run, self.connection = None, None

    def open_visit(self, name: Any) -> dict[str, Any]:
        """Continue an unfinished visit of the data folder, named by its folder; the page's state."""
        if not isinstance(name, str) or not name or "/" in name or "\\" in name or name.startswith("."):
            raise AxiscalError(f"name a visit's folder of the data folder, not {name!r}")
        folder = self.data / name
        self._restore(folder)
        with self._lock:
            remember_open(self.data, folder)
        return self.state()

    def set_step(self, step: Any) -> dict[str, Any]:
        """Remember the step the page is at, so that it is opened there again."""
        if step not in STEPS:
            raise AxiscalError(f"step must be one of {', '.join(STEPS)}, not {step!r}")
        with self._lock:
            if self.saved is not None and self.saved.step != step:
                self.saved.step = step
                self._save()
        return {"step": step}

    def state(self, tab: str | None = None) -> dict[str, Any]:
        """What the page needs to show the open visit again: its forms, plan, connection, compensation, step.

        Parameters
        ----------
        tab : str, optional
            The asking tab's id: ``readonly`` says whether another tab holds the visit.
        """
        readonly = not self.tabs.may_act(tab)
        if self.saved is None or self.folder is None:
            return {"open": False, "notice": self.notice, "readonly": readonly, "unfinished": self.unfinished()}
        c = self.connection
        return {
            "open": True, "notice": self.notice, "readonly": readonly, "folder": self._rel(self.folder),
            "step": self.saved.step, "phase": self.phase, "visit": self.saved.visit, "plan_form": self.saved.plan,
            "plan": None if self.plan is None else self._plan_view(),
            "connection": self.saved.connection,
            "connected": None if c is None else {
                "lights": {"instrument": c.instrument_state, "controller": c.controller_state}, "description": c.description,
                "told": {"instrument": [list(t) for t in c.instrument_told], "controller": [list(t) for t in c.controller_told]}},
            "compensation": self.compensation, "finished": self.saved.finished,
            "runs": {phase: (self._phase_folder(phase) / run_file(self.plan.axis if self.plan else "X")).is_file()
                     for phase in PHASES},
            "machine": self.saved.machine, "tests": self.tests(),
            "plans": {axis: self._plan_view(plan) for axis in self.saved.plans if (plan := self._plan_of(axis)) is not None},
        }

    def unfinished(self) -> list[dict[str, Any]]:
        """The data folder's visits not yet finished, each with the step it was left at."""
        return unfinished_visits(self.data)

    # -- files -------------------------------------------------------------------------------------
    def file(self, relative: str) -> Path:
        """A file of the data folder named by its relative path (never one outside it)."""
        if not isinstance(relative, str) or not relative or "\x00" in relative:
            raise AxiscalError("name a file of the data folder")
        path = (self.data / relative).resolve()
        if path != self.data and self.data not in path.parents:
            raise AxiscalError(f"{relative}: not inside the data folder")
        if not path.is_file():
            raise AxiscalError(f"{relative}: no such file in the data folder")
        return path


def _figure_of(figures: dict[str, Any], name: str) -> float | None:
    for key in (name, f"{name}_um", f"{name}_arcsec"):
        value = figures.get(key)
        if isinstance(value, (int, float)):
            return float(value)
    return None
