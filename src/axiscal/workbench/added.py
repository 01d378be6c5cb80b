"""Tests taken from files: what the visit adds from the data folder or an upload, read by the commands' readers.

A test from a file is one ``[[tests]]`` entry of the campaign (docs/campaign.md) whose data the
technician brings: a straightness profile, the two runs of a squareness test, the interferometer's
readings along a diagonal (ISO 230-6), a ballbar trace, a positioning run (of a rotary axis, or
any axis measured elsewhere), or an instrument's export that axiscal imports: a column map with
its export (``axiscal import map``: a positioning run) or a Renishaw ``.rtx`` capture
(``axiscal import rtx``: a timebase recording, evaluated as a dynamics test).

:func:`store_upload` keeps an uploaded file in the visit's ``files/`` folder. :func:`file_test`
checks the form, copies the data into the visit's ``files/`` (imports are written there as
axiscal's CSV by the importer the command uses) and returns the test's entry; the visit then
evaluates it through the campaign at once (:func:`axiscal.campaign.run_test`, the readers of the
commands), and a mistake is the one line the command would print.

A test from a file may state its tolerance in the unit the test reports (:func:`tolerance_of`): µm for a
straightness, a diagonal, a ballbar's circular deviation and a linear axis's E, arcsec for a squareness
and a rotary axis's E. It is the test's own ``tolerances`` in campaign.toml (docs/campaign.md), so the
campaign's evaluation and decision rule assess it.
"""

from __future__ import annotations

import re
import shutil
from pathlib import Path
from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field, ValidationError

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_instance, check_path
from axiscal.workbench.forms import FormErrors

__all__ = ["FILE_KINDS", "MAX_UPLOAD", "FileTestForm", "checked_file_form", "store_upload", "file_test", "data_files",
           "tolerance_of"]

#: where a visit keeps the files its tests were taken from
FILES_FOLDER = "files"
#: largest file taken by upload, bytes
MAX_UPLOAD = 16 * 1024 * 1024
#: what each kind of the form takes from a file, as the page names it
FILE_KINDS = {
    "positioning": "positioning run (target_mm or target_deg, run, direction, deviation_um or deviation_arcsec)",
    "straightness": "straightness profile",
    "squareness": "squareness: the runs along both axes",
    "diagonal": "diagonal (ISO 230-6): the interferometer's readings",
    "ballbar": "ballbar trace (ISO 230-4)",
    "columnmap": "instrument export with its column map (TOML): a positioning run",
    "rtx": "Renishaw .rtx capture: a timebase recording (dynamics)",
}


class FileTestForm(BaseModel):
    """The form that adds a test from a file (lengths in mm, as the labels say).

    Attributes
    ----------
    kind : str
        One of :data:`FILE_KINDS`.
    file, second : str
        The data files, relative to the data folder (``second``: squareness's second run, a column map's export).
    axis, direction, plane : str
        The axis measured, the direction of a straightness, the plane of a squareness or a ballbar test.
    radius_mm : float or None
        The ballbar's length, mm.
    from_, to : str
        A diagonal's ends (``X=0,Y=0,Z=0``); ``from_`` is sent as ``from``.
    unit : str
        The unit of an .rtx capture's samples.
    tolerance_um, tolerance_arcsec : float or None
        The test's tolerance in the unit it reports (:func:`tolerance_of` says which applies); none: the campaign's.
    """

    model_config = ConfigDict(extra="forbid", str_strip_whitespace=True, allow_inf_nan=False)

    kind: Literal[tuple(FILE_KINDS)]  # type: ignore[valid-type]
    file: str = Field(min_length=1, max_length=500)
    second: str = Field(default="", max_length=500)
    axis: str = Field(default="", pattern=r"^[XYZABC]?$")
    direction: str = Field(default="", pattern=r"^[XYZ]?$")
    plane: Literal["", "XY", "XZ", "YZ"] = ""
    radius_mm: float | None = Field(default=None, gt=0.0, le=10000.0)
    from_: str = Field(default="", alias="from", max_length=200)
    to: str = Field(default="", max_length=200)
    unit: Literal["", "nm", "um", "mm", "m", "in"] = ""
    tolerance_um: float | None = Field(default=None, gt=0.0, le=1.0e6)
    tolerance_arcsec: float | None = Field(default=None, gt=0.0, le=1.0e6)


def _needs(form: FileTestForm) -> dict[str, str]:
    """The fields each kind cannot do without, named where they are missing."""
    needed = {"positioning": ("axis",), "straightness": ("axis", "direction"), "squareness": ("second", "plane"),
              "diagonal": ("from_", "to"), "ballbar": ("radius_mm", "plane"), "columnmap": ("second", "axis"),
              "rtx": ("unit", "axis")}[form.kind]
    words = {"second": "name the second file", "from_": "the diagonal's start, such as X=0,Y=0,Z=0",
             "to": "the diagonal's end, such as X=600,Y=400,Z=300"}
    return {("from" if n == "from_" else n): words.get(n, "needed for this kind") for n in needed
            if getattr(form, n) in ("", None)}


def checked_file_form(data: Any) -> FileTestForm:
    """The add-a-file form, each mistake named by its field.

    Parameters
    ----------
    data : Any
        What the page sent.

    Returns
    -------
    FileTestForm

    Raises
    ------
    FormErrors
    """
    if not isinstance(data, dict):
        raise FormErrors({"form": "the page must send the form's fields as a JSON object"})
    try:
        form = FileTestForm.model_validate(data)
    except ValidationError as exc:
        fields: dict[str, str] = {}
        for error in exc.errors():
            fields.setdefault(str(error["loc"][0]) if error["loc"] else "form", str(error["msg"]).removeprefix("Value error, "))
        raise FormErrors(fields) from None
    missing = _needs(form)
    if missing:
        raise FormErrors(missing)
    applies = tolerance_of(form.kind, form.axis)
    for field in ("tolerance_um", "tolerance_arcsec"):
        if getattr(form, field) is not None and (applies is None or applies[1] != field):
            raise FormErrors({field: "this kind takes no tolerance here (campaign.toml's [tolerances] gives it)"
                              if applies is None else f"this test's tolerance ({applies[0]}) is in"
                              f" {_UNIT_WORDS[applies[0].rsplit('_', 1)[1]]}: give it as {applies[1]}"})
    return form


_UNIT_WORDS = {"um": "µm", "arcsec": "arcsec"}
#: the campaign's tolerance key (docs/campaign.md) each kind's tolerance is, in the unit the test reports
_TOLERANCES = {"straightness": "straightness_um", "squareness": "squareness_arcsec", "diagonal": "diagonal_um",
               "ballbar": "circular_deviation_um"}


def tolerance_of(kind: str, axis: str = "") -> tuple[str, str] | None:
    """The tolerance a test from a file may state: the campaign's key and the form's field (None for none).

    Parameters
    ----------
    kind : str
        One of :data:`FILE_KINDS`.
    axis : str
        The axis of a positioning run (a rotary axis A, B or C reports arcsec).

    Returns
    -------
    tuple of (str, str) or None
        Such as ``("straightness_um", "tolerance_um")``; a positioning run's is its E (``E_um`` or ``E_arcsec``).
    """
    check_instance("kind", kind, str)
    check_instance("axis", axis, str)
    if kind in ("positioning", "columnmap"):
        return ("E_arcsec", "tolerance_arcsec") if axis in ("A", "B", "C") else ("E_um", "tolerance_um")
    key = _TOLERANCES.get(kind)
    return None if key is None else (key, f"tolerance_{key.rsplit('_', 1)[1]}")


def _safe_name(name: Any) -> str:
    if not isinstance(name, str):
        raise AxiscalError("name the uploaded file")
    base = re.sub(r"[^A-Za-z0-9._-]+", "_", Path(name.replace("\\", "/")).name).lstrip(".")
    if not base:
        raise AxiscalError(f"{name!r} is not a file name")
    return base[:120]


def store_upload(folder: Path, name: Any, content: bytes) -> Path:
    """Keep an uploaded file in the visit's ``files/`` folder (atomically).

    Parameters
    ----------
    folder : Path
        The visit's folder.
    name : str
        The file's name as the browser sent it (only its last part is kept).
    content : bytes
        At most :data:`MAX_UPLOAD` bytes.

    Returns
    -------
    Path
        Where it is kept.

    Raises
    ------
    AxiscalError
        For no name, an empty or too large file.
    """
    from axiscal.io.atomic import atomic_write

    folder = check_path("folder", folder)
    base = _safe_name(name)
    if not isinstance(content, bytes) or not content:
        raise AxiscalError(f"{base}: the file is empty")
    if len(content) > MAX_UPLOAD:
        raise AxiscalError(f"{base}: larger than {MAX_UPLOAD // (1024 * 1024)} MiB")
    path = folder / FILES_FOLDER / base
    path.parent.mkdir(parents=True, exist_ok=True)
    atomic_write(path, lambda temporary: temporary.write_bytes(content))
    return path


def data_files(data: Path, folder: Path | None) -> list[str]:
    """The data folder's files a test may be taken from (relative paths), the visit's own first.

    Parameters
    ----------
    data : Path
        The data folder.
    folder : Path, optional
        The open visit's folder.

    Returns
    -------
    list of str
        Files with the endings axiscal reads (.csv, .txt, .toml, .rtx), up to 500; the workbench's
        own state files, plans and reports left out.
    """
    data = check_path("data", data).resolve()
    folder = None if folder is None else check_path("folder", folder)
    read = (".csv", ".txt", ".toml", ".rtx")
    own = [] if folder is None else sorted(p for p in (folder / FILES_FOLDER).glob("*") if p.suffix.lower() in read)
    others = sorted(p for p in data.rglob("*") if p.suffix.lower() in read)
    out = []
    for path in [*own, *others]:
        relative = path.relative_to(data).as_posix()
        if not path.is_file() or relative in out or _workbench_own(path, relative):
            continue
        out.append(relative)
        if len(out) >= 500:
            break
    return out


#: what the workbench itself writes into a visit's folder: never the data of a test taken from a file
_OWN_NAMES = ("workbench.json", "campaign.toml", "budget.toml", "machine.toml")


def _workbench_own(path: Path, relative: str) -> bool:
    parts = f"/{relative}"
    return (path.name in _OWN_NAMES or "/report/" in parts or "/compensation/" in parts
            or (path.name.startswith("plan_") and path.suffix == ".csv") or path.name.endswith("_errors.csv"))


def _source(data: Path, relative: str, field: str) -> Path:
    path = (data / relative).resolve()
    if path != data and data not in path.parents:
        raise FormErrors({field: f"{relative}: not inside the data folder"})
    if not path.is_file():
        raise FormErrors({field: f"{relative}: no such file in the data folder"})
    return path


def _into(folder: Path, source: Path) -> str:
    """Copy ``source`` into the visit's ``files/`` (unless it is there), its path relative to the visit."""
    target = folder / FILES_FOLDER / source.name
    if source.resolve() != target.resolve():
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(source, target)
        sidecar = source.with_suffix(".json")
        if sidecar.is_file() and source.suffix.lower() == ".csv":
            shutil.copyfile(sidecar, target.with_suffix(".json"))
    return f"{FILES_FOLDER}/{source.name}"


def file_test(data: Path, folder: Path, form: FileTestForm, taken: set[str]) -> dict[str, Any]:
    """The test a file brings: its data copied (or imported) into the visit's ``files/``, its campaign entry.

    Parameters
    ----------
    data : Path
        The data folder (``form.file`` and ``form.second`` are relative to it).
    folder : Path
        The visit's folder.
    form : FileTestForm
    taken : set of str
        The ids the visit's tests have already.

    Returns
    -------
    dict
        A test as :mod:`axiscal.workbench.suite` holds it (``source`` ``file``).

    Raises
    ------
    FormErrors
        For a file that is not in the data folder.
    AxiscalError
        For an export the importer refuses (its one line: the file, the line, the problem).
    """
    data, folder = check_path("data", data).resolve(), check_path("folder", folder)
    check_instance("form", form, FileTestForm, what="the form checked_file_form gives")
    if not isinstance(taken, (set, frozenset)):
        raise AxiscalError(f"taken must be the set of the visit's test ids, not {type(taken).__name__}")
    first = _source(data, form.file, "file")
    second = _source(data, form.second, "second") if form.second else None
    kind, entry = form.kind, {}
    if kind == "positioning":
        entry = {"axis": form.axis, "file": _into(folder, first), "standard": "iso230-2:2014"}
        label = f"Positioning of {form.axis} from {first.name}"
    elif kind == "straightness":
        entry = {"axis": form.axis, "direction": form.direction, "file": _into(folder, first)}
        label = f"Straightness of {form.axis} in {form.direction} ({first.name})"
    elif kind == "squareness":
        entry = {"plane": form.plane, "first": _into(folder, first), "second": _into(folder, second)}
        label = f"Squareness {form.plane} ({first.name}, {second.name})"
    elif kind == "diagonal":
        entry = {"from": form.from_, "to": form.to, "interferometer": _into(folder, first)}
        label = f"Diagonal {form.from_} to {form.to} ({first.name})"
    elif kind == "ballbar":
        entry = {"plane": form.plane, "file": _into(folder, first), "radius_mm": form.radius_mm}
        label = f"Ballbar {form.plane}, {form.radius_mm:g} mm ({first.name})"
    elif kind == "columnmap":
        from axiscal.io.importers import import_readings, read_column_map, write_positioning_csv

        readings = import_readings(read_column_map(first), second)
        name = f"{FILES_FOLDER}/{second.stem}_imported.csv"
        (folder / FILES_FOLDER).mkdir(parents=True, exist_ok=True)
        write_positioning_csv(readings, folder / name, map_path=first)
        kind, entry = "positioning", {"axis": form.axis, "file": name, "standard": "iso230-2:2014"}
        label = f"Positioning of {form.axis} imported from {second.name}"
    else:  # rtx
        from axiscal.io.importers import read_rtx, write_rtx_csv

        capture = read_rtx(first, unit=form.unit)
        name = f"{FILES_FOLDER}/{first.stem}_rtx.csv"
        (folder / FILES_FOLDER).mkdir(parents=True, exist_ok=True)
        write_rtx_csv(capture, folder / name)
        kind, entry = "dynamics", {"axis": form.axis, "file": name, "channel": f"reading_{form.unit}"}
        label = f"Dynamics of {form.axis} from {first.name}"
    applies = tolerance_of(form.kind, form.axis)
    if applies is not None and getattr(form, applies[1]) is not None:
        entry["tolerances"] = {applies[0]: getattr(form, applies[1])}
    base = f"{kind}-{entry.get('axis') or entry.get('plane') or 'file'}"
    test_id, n = base, 2
    while test_id in taken:
        test_id, n = f"{base}-{n}", n + 1
    return {"id": test_id, "kind": kind, "axis": entry.get("axis"), "source": "file", "label": label, "entry": entry}
