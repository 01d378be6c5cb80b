"""The machine of a visit: its ``machine.toml`` taken from the data folder or the example, or made from a short form.

A visit measures one machine, described as the library describes every machine
(:func:`axiscal.model.machine.load_machine`, docs/formats.md): its chain and one error table per
axis, whose first and last positions are the axis's travel. :func:`machine_choices` lists the
descriptions the New visit form offers: the example three-axis machine tool shipped with axiscal
(``examples/xfyz_machine``; what ``sim`` runs when the visit names no other), and every
``machine.toml`` of the data folder (a machine kept there, or one of an earlier visit).
:func:`copy_machine` puts the chosen description and its error tables into the visit's folder;
:func:`write_new_machine` writes a nominal one (error tables of zeros over each axis's travel) from
the short form: the name, the chain and the travels. :func:`machine_axes` says what each axis is
(linear in mm, rotary in degrees) and its travel.
"""

from __future__ import annotations

import re
import shutil
import tomllib
from importlib import resources
from pathlib import Path
from typing import Any

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_path
from axiscal.io.atomic import write_text

__all__ = ["MACHINE_FILE", "example_machine", "machine_axes", "machine_choices", "copy_machine", "write_new_machine",
           "parse_travels"]

#: the name of the visit's machine description in its folder
MACHINE_FILE = "machine.toml"
#: the choice that names the example machine (the one ``sim`` runs by default)
EXAMPLE = "example"
_ROTARY = "ABC"
_LINEAR = "XYZ"


def example_machine() -> Path:
    """The example three-axis machine tool (``examples/xfyz_machine``), as shipped in the package.

    Parameters
    ----------
    (none)

    Returns
    -------
    Path
        Its ``machine.toml``.
    """
    return Path(str(resources.files("axiscal") / "data" / "xfyz_machine" / MACHINE_FILE))


def machine_axes(path: str | Path) -> dict[str, Any]:
    """A machine description's name, chain and axes, each with its kind and travel.

    Parameters
    ----------
    path : str or Path
        A ``machine.toml``.

    Returns
    -------
    dict
        ``name``, ``chain`` and ``axes``: a list of ``{"axis", "rotary", "unit", "start", "end"}``
        in the chain's order (travel in mm, or in degrees for a rotary axis).

    Raises
    ------
    AxiscalError
        For a description the library does not read (naming the file and the line).
    """
    import math

    from axiscal.model.machine import load_machine
    from axiscal.units import MM

    path = check_path("path", path)
    machine = load_machine(path)
    axes = []
    for letter in machine.letters:
        start, end = machine.travel_m(letter)
        rotary = letter in machine.rotary
        scale = 180.0 / math.pi if rotary else 1.0 / MM
        axes.append({"axis": letter, "rotary": rotary, "unit": "deg" if rotary else "mm",
                     "start": round(float(start) * scale, 6), "end": round(float(end) * scale, 6)})
    text = tomllib.loads(path.read_text(encoding="utf-8"))
    return {"name": str(text.get("name") or path.parent.name), "chain": str(text.get("chain", "")), "axes": axes}


def machine_choices(data: Path) -> list[dict[str, Any]]:
    """The machine descriptions the New visit form offers: the example, then those of the data folder.

    Parameters
    ----------
    data : Path
        The data folder; its ``machine.toml`` files (up to three folders down) are listed, each
        with the folder it lies in (an earlier visit's with its machine, serial and date, as its
        campaign.toml states them); one the library does not read is listed with the reason.

    Returns
    -------
    list of dict
        ``choice`` (``"example"`` or the path relative to the data folder), ``label``, and the
        fields of :func:`machine_axes` (or ``problem``).
    """
    data = check_path("data", data).resolve()
    out = [{"choice": EXAMPLE, "label": "example: 3-axis machine tool XFYZ (X 0-800, Y 0-500, Z 0-400 mm)"}
           | machine_axes(example_machine())]
    found = sorted(p for depth in ("*", "*/*", "*/*/*") for p in data.glob(f"{depth}/{MACHINE_FILE}"))
    for path in found:
        relative = path.relative_to(data).as_posix()
        try:
            described = machine_axes(path)
        except AxiscalError as exc:
            out.append({"choice": relative, "label": relative, "problem": str(exc), "axes": []})
            continue
        out.append({"choice": relative, "label": _visit_label(path) or f"{described['name']} ({relative})"} | described)
    return out


def _visit_label(path: Path) -> str:
    """``earlier visit: VMC 1 (S1), 2026-11-26, XFYZ`` for the machine of a visit's folder, else empty."""
    campaign = path.parent / "campaign.toml"
    if not campaign.is_file():
        return ""
    try:
        text = tomllib.loads(campaign.read_text(encoding="utf-8"))
        machine, when = text["machine"], text["campaign"]["date"]
        chain = tomllib.loads(path.read_text(encoding="utf-8")).get("chain", "")
    except (OSError, ValueError, KeyError, TypeError):
        return ""
    serial = f" ({machine['serial']})" if machine.get("serial") else ""
    return f"earlier visit: {machine.get('name', '')}{serial}, {when}, {chain}"


def copy_machine(source: Path, folder: Path) -> dict[str, Any]:
    """Copy a machine description and the error tables it names into a visit's folder as ``machine.toml``.

    Parameters
    ----------
    source : Path
        The description chosen (checked by :func:`machine_axes` first).
    folder : Path
        The visit's folder.

    Returns
    -------
    dict
        What :func:`machine_axes` says of the copy.

    Raises
    ------
    AxiscalError
        For a description the library does not read.
    """
    source, folder = check_path("source", source), check_path("folder", folder)
    machine_axes(source)
    folder.mkdir(parents=True, exist_ok=True)
    text = tomllib.loads(source.read_text(encoding="utf-8"))
    for axis in (text.get("axes") or {}).values():
        name = axis.get("errors") if isinstance(axis, dict) else None
        if isinstance(name, str) and (source.parent / name).is_file():
            target = folder / name
            target.parent.mkdir(parents=True, exist_ok=True)
            if (source.parent / name).resolve() != target.resolve():
                shutil.copyfile(source.parent / name, target)
    if source.resolve() != (folder / MACHINE_FILE).resolve():
        write_text(folder / MACHINE_FILE, source.read_text(encoding="utf-8"))
    return machine_axes(folder / MACHINE_FILE)


def parse_travels(text: Any) -> dict[str, tuple[float, float]]:
    """The travels of the short form: ``X=0:600, Y=0:400, C=0:360`` (mm, degrees for A, B, C).

    Parameters
    ----------
    text : str

    Returns
    -------
    dict of str to (float, float)
        Axis letter -> (start, end), in the order written.

    Raises
    ------
    AxiscalError
        For a part that is not ``LETTER=START:END``, a letter given twice, an end not beyond its start.
    """
    if not isinstance(text, str) or not text.strip():
        raise AxiscalError("name each axis with its travel: X=0:600, Y=0:400, Z=0:300 (mm; degrees for A, B, C)")
    out: dict[str, tuple[float, float]] = {}
    for part in text.replace(";", ",").split(","):
        match = re.fullmatch(r"\s*([XYZABCxyzabc])\s*=\s*(-?[\d.]+)\s*:\s*(-?[\d.]+)\s*", part)
        if match is None:
            raise AxiscalError(f"'{part.strip()}': write each axis as LETTER=START:END, such as X=0:600")
        letter = match.group(1).upper()
        try:
            start, end = float(match.group(2)), float(match.group(3))
        except ValueError:
            raise AxiscalError(f"'{part.strip()}': the travel's ends must be numbers") from None
        if letter in out:
            raise AxiscalError(f"axis {letter} is given twice")
        if not end > start:
            raise AxiscalError(f"axis {letter}: the end of its travel must lie beyond its start")
        if abs(start) > 1e5 or abs(end) > 1e5:
            raise AxiscalError(f"axis {letter}: a travel within 100 000 mm (or degrees)")
        out[letter] = (start, end)
    return out


def write_new_machine(folder: Path, name: Any, chain: Any, travels: Any) -> dict[str, Any]:
    """Write a nominal machine description from the short form into a visit's folder.

    Each axis gets an error table of zeros over its travel (11 rows): the machine as designed,
    whose errors the visit measures.

    Parameters
    ----------
    folder : Path
        The visit's folder.
    name : str
        The machine's name.
    chain : str
        Workpiece-side axes, ``F``, tool-side axes (``XFYZ``, ``CAFXYZ``).
    travels : str
        As :func:`parse_travels` reads it; one travel for each axis of the chain.

    Returns
    -------
    dict
        What :func:`machine_axes` says of it.

    Raises
    ------
    AxiscalError
        For a chain without ``F`` or with a letter that is not an axis, a travel missing or given
        for an axis not in the chain, or a description the library then refuses.
    """
    folder = check_path("folder", folder)
    if not isinstance(name, str) or not name.strip():
        raise AxiscalError("name the machine")
    if not isinstance(chain, str) or not re.fullmatch(r"[XYZABC]*F[XYZABC]*", chain.strip().upper()):
        raise AxiscalError(f"chain {chain!r}: the workpiece-side axes, F (the frame), the tool-side axes, such as XFYZ")
    chain = chain.strip().upper()
    letters = chain.replace("F", "")
    if len(set(letters)) != len(letters) or not letters:
        raise AxiscalError(f"chain {chain!r}: each axis once, and at least one")
    travels = parse_travels(travels)
    missing = [k for k in letters if k not in travels]
    extra = [k for k in travels if k not in letters]
    if missing or extra:
        raise AxiscalError("give one travel for each axis of the chain"
                           + (f": {', '.join(missing)} missing" if missing else "")
                           + (f": {', '.join(extra)} not in the chain" if extra else ""))
    folder.mkdir(parents=True, exist_ok=True)
    lines = ["# A machine described in the axiscal workbench: nominal (error tables of zeros over each travel).",
             f"name = {_quoted(name.strip())}", f'chain = "{chain}"', ""]
    for letter in letters:
        start, end = travels[letter]
        rotary = letter in _ROTARY
        unit, angle = ("deg", "urad") if rotary else ("mm", "urad")
        columns = [f"position_{unit}"] + [f"E{c}{letter}_um" for c in "XYZ"] + [f"E{c}{letter}_{angle}" for c in "ABC"]
        rows = [",".join(columns)]
        for k in range(11):
            rows.append(",".join([f"{start + (end - start) * k / 10:.6g}"] + ["0"] * 6))
        table = f"{letter.lower()}_errors.csv"
        write_text(folder / table, "\n".join(rows) + "\n")
        lines += [f"[axes.{letter}]", f'errors = "{table}"'] + (["periodic = false"] if rotary else []) + [""]
    write_text(folder / MACHINE_FILE, "\n".join(lines))
    return machine_axes(folder / MACHINE_FILE)


def _quoted(text: str) -> str:
    import json

    return json.dumps(text, ensure_ascii=False)
