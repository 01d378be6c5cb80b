"""What the workbench keeps on disk so that a visit survives a reload, a closed tab and a server restart.

Each visit's folder holds ``workbench.json``: the forms as the page sent them (campaign, plan,
connection), the step the page is at, the phase, the compensation's answer and, once the visit is
finished, the reports' links. The data folder holds ``workbench-open.json`` naming the visit that
is open, which a restarted workbench opens again. Both are written atomically at every step.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_instance, check_path
from axiscal.io.jsonio import read_json, write_json

__all__ = ["STATE_FILE", "OPEN_FILE", "STEPS", "SavedVisit", "read_saved", "write_saved", "unfinished_visits",
           "open_folder", "remember_open"]

#: the visit's state in its folder
STATE_FILE = "workbench.json"
#: the open visit's folder, in the data folder
OPEN_FILE = "workbench-open.json"
#: the page's steps, in their order
STEPS = ("machines", "visit", "plan", "connect", "run", "results", "compensate", "finish")


@dataclass
class SavedVisit:
    """A visit as ``workbench.json`` keeps it (the forms as JSON, as the page sent them).

    Attributes
    ----------
    visit : dict
        The campaign form.
    plan : dict or None
        The plan form, once planned.
    connection : dict or None
        The instrument's and the controller's specs and LinuxCNC's INI file (``ini``, empty without one), once connected.
    step : str
        The step the page was at (one of :data:`STEPS`).
    phase : str
        ``as-found`` or ``as-left``: the run last started.
    compensation : dict or None
        What Compensate answered (the table's text, file, curves).
    finished : dict or None
        What Finish answered (the reports' links), once finished.
    tests : list of dict
        The visit's tests (:mod:`axiscal.workbench.suite`): those asked for and those added from files.
    plans : dict
        The plan form of each axis planned, by axis letter.
    machine : dict or None
        The visit's machine: its name, chain and axes with their travels.
    """

    visit: dict[str, Any]
    plan: dict[str, Any] | None = None
    connection: dict[str, str] | None = None
    step: str = "visit"
    phase: str = "as-found"
    compensation: dict[str, Any] | None = None
    finished: dict[str, Any] | None = field(default=None)
    tests: list[dict[str, Any]] = field(default_factory=list)
    plans: dict[str, Any] = field(default_factory=dict)
    machine: dict[str, Any] | None = None

    def as_json(self) -> dict[str, Any]:
        """The fields as ``workbench.json`` holds them.

        Returns
        -------
        dict
        """
        return {"visit": self.visit, "plan": self.plan, "connection": self.connection, "step": self.step,
                "phase": self.phase, "compensation": self.compensation, "finished": self.finished,
                "tests": self.tests, "plans": self.plans, "machine": self.machine}


def read_saved(folder: Path) -> SavedVisit:
    """The visit kept in ``folder/workbench.json``.

    Parameters
    ----------
    folder : Path
        The visit's folder.

    Returns
    -------
    SavedVisit

    Raises
    ------
    AxiscalError
        For a missing or malformed file, or one whose fields are not a visit's (naming the file).
    """
    folder = check_path("folder", folder)
    path = folder / STATE_FILE
    data = read_json(path)
    if not isinstance(data, dict) or not isinstance(data.get("visit"), dict):
        raise AxiscalError("not a workbench visit: no campaign form ('visit')", path=path)
    step, phase = data.get("step", "visit"), data.get("phase", "as-found")
    if step not in STEPS or phase not in ("as-found", "as-left"):
        raise AxiscalError(f"step {step!r} or phase {phase!r} is not the workbench's", path=path)
    kinds = {"plan": dict, "connection": dict, "compensation": dict, "finished": dict, "plans": dict, "machine": dict}
    for name, kind in kinds.items():
        if data.get(name) is not None and not isinstance(data[name], kind):
            raise AxiscalError(f"'{name}' must be an object or null", path=path)
    tests = data.get("tests") or []
    if not isinstance(tests, list) or not all(isinstance(t, dict) and isinstance(t.get("id"), str)
                                              and isinstance(t.get("entry"), dict) for t in tests):
        raise AxiscalError("'tests' must be a list of the visit's tests", path=path)
    return SavedVisit(data["visit"], data.get("plan"), data.get("connection"), step, phase, data.get("compensation"),
                      data.get("finished"), tests, data.get("plans") or {}, data.get("machine"))


def write_saved(folder: Path, saved: SavedVisit) -> None:
    """Write ``folder/workbench.json`` atomically.

    Parameters
    ----------
    folder : Path
        The visit's folder.
    saved : SavedVisit

    Returns
    -------
    None
    """
    folder = check_path("folder", folder)
    check_instance("saved", saved, SavedVisit)
    write_json(folder / STATE_FILE, saved.as_json())


def remember_open(data: Path, folder: Path | None) -> None:
    """Name ``folder`` (relative to the data folder) as the open visit, in ``data/workbench-open.json``.

    Parameters
    ----------
    data : Path
        The data folder.
    folder : Path or None
        The visit's folder, inside ``data``; None: no visit open.

    Returns
    -------
    None
    """
    data = check_path("data", data)
    folder = None if folder is None else check_path("folder", folder)
    write_json(data / OPEN_FILE, {"folder": None if folder is None else folder.relative_to(data).as_posix()})


def open_folder(data: Path) -> Path | None:
    """The folder of the visit that was open, or None (none named, or it is gone).

    Parameters
    ----------
    data : Path
        The data folder.

    Returns
    -------
    Path or None

    Raises
    ------
    AxiscalError
        For a malformed ``workbench-open.json`` or one naming a folder outside the data folder.
    """
    data = check_path("data", data)
    path = data / OPEN_FILE
    if not path.is_file():
        return None
    named = read_json(path)
    if not isinstance(named, dict) or not (named.get("folder") is None or isinstance(named.get("folder"), str)):
        raise AxiscalError("must name the open visit's folder: {\"folder\": \"...\"}", path=path)
    if named["folder"] is None:
        return None
    folder = (data / named["folder"]).resolve()
    if data not in folder.parents:
        raise AxiscalError(f"folder {named['folder']!r} is not inside the data folder", path=path)
    return folder if (folder / STATE_FILE).is_file() else None


def unfinished_visits(data: Path) -> list[dict[str, Any]]:
    """Every visit of the data folder not yet finished: folder, machine, serial, date, title, step.

    A folder whose ``workbench.json`` cannot be read is listed with the reason, so that it is seen.

    Parameters
    ----------
    data : Path
        The data folder.

    Returns
    -------
    list of dict
        ``folder``, ``machine``, ``serial``, ``date``, ``title``, ``step`` and ``problem`` (None, or
        why its state cannot be read), by folder name.
    """
    data = check_path("data", data)
    out = []
    for path in sorted(data.glob(f"*/{STATE_FILE}")):
        folder = path.parent
        try:
            saved = read_saved(folder)
        except AxiscalError as exc:
            out.append({"folder": folder.name, "machine": "", "serial": "", "date": "", "title": "", "step": "",
                        "problem": str(exc)})
            continue
        if saved.finished is not None:
            continue
        v = saved.visit
        out.append({"folder": folder.name, "machine": str(v.get("machine", "")), "serial": str(v.get("serial", "")),
                    "date": str(v.get("date", "")), "title": str(v.get("title", "")), "step": saved.step,
                    "problem": None})
    return out
