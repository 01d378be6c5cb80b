"""The tests of a visit: what the New visit form asked for and the files added, each with its state.

A visit holds a list of tests. A linear axis's positioning (ISO 230-2) is planned and run by the
workbench itself: its plan ``plan_<axis>.csv``, its program, its run ``positioning_<axis>.csv``. A
rotary axis's positioning and every test taken from a file (straightness, squareness, diagonal,
ballbar, an instrument's export) have their data added from a file. Each test is one ``[[tests]]``
entry of the campaign (docs/campaign.md), spelled as :data:`axiscal.io.formats.campaign.KINDS` spells
it, so the campaign room evaluates it and the report room reports it. :func:`state_of` tells
where a test is (``planned``, ``running``, ``done``, ``failed``); :func:`campaign_with_tests` writes
the campaign's text with the tests whose data is in the folder.
"""

from __future__ import annotations

import json
import re
from pathlib import Path
from typing import Any

from pydantic import Field, ValidationError

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_instance, check_path
from axiscal.workbench.forms import FormErrors, PlanForm

__all__ = ["AxisPlanForm", "checked_plan", "wanted_tests", "state_of", "campaign_with_tests"]

#: the kind of the tests the workbench runs itself
RUN_KIND = "positioning"
_STANDARD = "iso230-2:2014"


class AxisPlanForm(PlanForm):
    """A positioning plan of any linear axis (its travel checked against the machine by :func:`checked_plan`).

    Attributes
    ----------
    axis : str
        X, Y or Z.
    start_mm, end_mm : float
        The travel tested, mm.
    targets, runs, overrun_mm, dwell_s, dialect, seed :
        As :class:`~axiscal.workbench.forms.PlanForm`.
    """

    axis: str = Field(default="X", pattern=r"^[XYZ]$")
    start_mm: float = Field(ge=-1.0e5, le=1.0e5)
    end_mm: float = Field(ge=-1.0e5, le=1.0e5)


def checked_plan(data: Any, axes: list[dict[str, Any]]) -> AxisPlanForm:
    """The plan form, each mistake named by its field; the travel within the axis's.

    Parameters
    ----------
    data : Any
        What the page sent (a JSON object; ``axis`` names the axis, X by default).
    axes : list of dict
        The machine's axes (:func:`axiscal.workbench.machines.machine_axes`).

    Returns
    -------
    AxisPlanForm

    Raises
    ------
    FormErrors
        Naming each field that is missing or wrong.
    """
    if not isinstance(axes, list) or not all(isinstance(a, dict) and {"axis", "rotary", "start", "end"} <= set(a)
                                               for a in axes):
        raise AxiscalError("axes must be the machine's axes as machine_axes gives them")
    if not isinstance(data, dict):
        raise FormErrors({"form": "the page must send the form's fields as a JSON object"})
    try:
        form = AxisPlanForm.model_validate(data)
    except ValidationError as exc:
        fields: dict[str, str] = {}
        for error in exc.errors():
            where = str(error["loc"][0]) if error["loc"] else ""
            message = str(error["msg"]).removeprefix("Value error, ")
            if not where and ": " in message:
                where, message = message.split(": ", 1)
            fields.setdefault(where or "form", message)
        raise FormErrors(fields) from None
    axis = next((a for a in axes if a["axis"] == form.axis), None)
    if axis is None or axis["rotary"]:
        raise FormErrors({"axis": f"{form.axis} is not a linear axis of the visit's machine"})
    low, high = axis["start"], axis["end"]
    outside = {name: f"beyond the travel of {form.axis} ({low:g} to {high:g} mm)"
               for name in ("start_mm", "end_mm") if not low - 1e-9 <= getattr(form, name) <= high + 1e-9}
    if outside:
        raise FormErrors(outside)
    return form


def _check_test(test: Any) -> None:
    if not isinstance(test, dict) or not {"id", "kind", "source", "label", "entry"} <= set(test) or not isinstance(
            test["entry"], dict):
        raise AxiscalError(f"test must be one of the visit's tests (id, kind, source, label, entry), not {test!r:.60}")


def run_file(axis: str) -> str:
    """The run file of an axis's positioning test, in the visit's (or as-left) folder."""
    return f"positioning_{axis.lower()}.csv"


def plan_file(axis: str) -> str:
    """The plan's cycle CSV of an axis, in the visit's folder."""
    return f"plan_{axis.lower()}.csv"


def wanted_tests(wanted: Any, axes: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """The tests the New visit form asked for: ``positioning-X`` for each linear axis, ``positioning-C`` for a rotary one.

    Parameters
    ----------
    wanted : list of str
        Test ids, as the form's boxes name them.
    axes : list of dict
        The machine's axes.

    Returns
    -------
    list of dict
        Each test: ``id``, ``kind``, ``axis``, ``source`` (``run`` or ``file``), ``label``, ``entry``
        (its campaign keys, files relative to the visit's folder).

    Raises
    ------
    FormErrors
        ``tests``: none asked for, or one the machine does not have.
    """
    if not isinstance(axes, list) or not all(isinstance(a, dict) and {"axis", "rotary"} <= set(a) for a in axes):
        raise AxiscalError("axes must be the machine's axes as machine_axes gives them")
    if not isinstance(wanted, list) or not wanted or not all(isinstance(w, str) for w in wanted):
        raise FormErrors({"tests": "tick at least one test (a test from a file is added once the visit is written)"})
    by_axis = {a["axis"]: a for a in axes}
    out = []
    for test_id in dict.fromkeys(wanted):
        match = re.fullmatch(r"positioning-([XYZABC])", test_id)
        if match is None or match.group(1) not in by_axis:
            raise FormErrors({"tests": f"{test_id!r} is not a test of the machine's axes ({', '.join(by_axis)})"})
        axis = by_axis[match.group(1)]
        letter = axis["axis"]
        if axis["rotary"]:
            out.append({"id": test_id, "kind": RUN_KIND, "axis": letter, "source": "file",
                        "label": f"Rotary positioning of {letter} (ISO 230-2)", "entry": {}})
        else:
            out.append({"id": test_id, "kind": RUN_KIND, "axis": letter, "source": "run",
                        "label": f"Positioning of {letter} (ISO 230-2)",
                        "entry": {"axis": letter, "file": run_file(letter), "standard": _STANDARD}})
    return out


def files_of(test: dict[str, Any]) -> list[str]:
    """The files of the visit's folder a test's entry names (none while a rotary run waits for its file)."""
    from axiscal.io.formats.campaign import KINDS

    keys = KINDS.get(test["kind"], {})
    return [value for key, value in test["entry"].items() if keys.get(key) == "file" and isinstance(value, str)]


def state_of(test: dict[str, Any], folder: Path, run: Any = None) -> dict[str, Any]:
    """Where a test is: its id, label, source, axis and ``state`` with a ``message``.

    Parameters
    ----------
    test : dict
        One of the visit's tests.
    folder : Path
        The visit's folder (as found).
    run : PlanRun, optional
        The run going on or last run (``run.test`` names its test).

    Returns
    -------
    dict
        ``state``: ``running`` (its run goes on), ``failed`` (its run ended short: resume or repeat
        it), ``done`` (its data is in the folder), else ``planned``; ``resumable`` when a run ended
        short left its stops in its partial file.
    """
    from axiscal.capture.files import partial_path

    _check_test(test)
    folder = check_path("folder", folder)
    files = files_of(test)
    have = bool(files) and all((folder / name).is_file() for name in files)
    state, message = ("done" if have else "planned"), ""
    if test["source"] == "run":
        ours = run is not None and getattr(run, "test", None) == test["id"] and getattr(run, "phase", "as-found") == "as-found"
        if ours and run.state in ("ready", "running", "paused"):
            state = "running"
        elif ours and run.state in ("broken", "aborted", "failed"):
            state, message = "failed", run.message
        elif partial_path(folder / run_file(test["axis"])).is_file():
            state, message = "failed", "ended short: its stops are kept; resume it"
    elif not have:
        message = "waiting for its file (add it below)"
    planned = test["source"] == "run" and (folder / plan_file(test["axis"])).is_file()
    resumable = test["source"] == "run" and state == "failed" and partial_path(folder / run_file(test["axis"])).is_file()
    return {"id": test["id"], "label": test["label"], "kind": test["kind"], "axis": test.get("axis"),
            "source": test["source"], "state": state, "message": message, "planned": planned,
            "resumable": resumable, "files": files if have else []}


def _value(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        return repr(value)
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_value(v) for v in value) + "]"
    if isinstance(value, dict):  # an inline table: a test's own tolerances
        return "{ " + ", ".join(f"{key} = {_value(v)}" for key, v in value.items()) + " }"
    return json.dumps(str(value), ensure_ascii=False)


def campaign_with_tests(text: str, tests: list[dict[str, Any]], folder: Path, *, model: str | None) -> str:
    """The campaign's text with the machine's model and a ``[[tests]]`` entry for each test whose data is there.

    Parameters
    ----------
    text : str
        campaign.toml as the New visit form wrote it, without tests.
    tests : list of dict
        The visit's tests.
    folder : Path
        The folder whose files say which tests have their data (the visit's, or its as-left one).
    model : str, optional, keyword-only
        The machine description, relative to the folder (``[machine] model``).

    Returns
    -------
    str
        The whole campaign.toml; while no test has its data, the tests the visit runs are named
        with the files they will write.
    """
    check_instance("text", text, str, what="campaign.toml's text")
    if not isinstance(tests, list):
        raise AxiscalError(f"tests must be a list of the visit's tests, not {type(tests).__name__}")
    for test in tests:
        _check_test(test)
    folder = check_path("folder", folder)
    if model is not None:
        check_instance("model", model, str, what="the machine description's file name")
        text = re.sub(r"(?m)^(\[machine\]\nname = .*\n)", lambda m: m.group(1) + f"model = {_value(model)}\n", text, count=1)
    ready = [t for t in tests if files_of(t) and all((folder / f).is_file() for f in files_of(t))]
    chosen = ready or [t for t in tests if t["source"] == "run"]
    blocks = []
    for test in chosen:
        lines = ["[[tests]]", f"id = {_value(test['id'])}", f"kind = {_value(test['kind'])}"]
        lines += [f"{key} = {_value(value)}" for key, value in test["entry"].items() if value is not None]
        blocks.append("\n".join(lines))
    return text.rstrip("\n") + "\n\n" + "\n\n".join(blocks) + "\n"
