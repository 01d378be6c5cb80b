"""The outputs of an identification: the machine folder, ``identify.json``, ``identify.html`` and its figures.

The result objects call these (:meth:`axiscal.identification.Identification.write`, ``.report()``);
they take the result and never import the solver. The output folder is built beside its
destination and swapped into place whole (:func:`axiscal.io.folders.atomic_folder`): a run killed
at any moment leaves the earlier output as it was, never error tables of two runs side by side.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from axiscal.conventions import AXIS_INDEX, ROTARY_LETTERS, component_names
from axiscal.io.arguments import check_path
from axiscal.io.atomic import write_text
from axiscal.io.folders import atomic_folder
from axiscal.io.jsonio import write_json, write_sidecar
from axiscal.io.tabular import write_csv
from axiscal.io.templates import render_template
from axiscal.model.machine import Machine
from axiscal.units import ANGLE_UNITS, MM, UM

__all__ = ["write_machine_folder", "write_identification", "report_html"]

_URAD = ANGLE_UNITS["urad"]
_DEG = ANGLE_UNITS["deg"]


def _number(value: float) -> str:
    return f"{value:.6f}"


def write_machine_folder(machine: Machine, folder: str | Path, *, comment: str = "") -> Path:
    """Write ``machine`` as a machine folder: ``machine.toml`` and one error table CSV per axis.

    Parameters
    ----------
    machine : Machine
        The machine.
    folder : str or Path
        Created if missing; ``machine.toml`` and ``<axis>_errors.csv`` are replaced.
    comment : str, keyword-only
        A first comment line of ``machine.toml``.

    Returns
    -------
    Path
        The ``machine.toml`` written.
    """
    folder = check_path("folder", folder)
    folder.mkdir(parents=True, exist_ok=True)
    lines = [f"# {comment}"] if comment else []
    lines += [f'name = "{machine.name}"', f'chain = "{machine.chain}"',
              "tool_mm = [" + ", ".join(_number(v / MM) for v in machine.tool_m) + "]",
              "workpiece_mm = [" + ", ".join(_number(v / MM) for v in machine.workpiece_m) + "]",
              f'squareness_placement = "{machine.squareness_placement}"']
    for letter in machine.letters:
        table = machine.table(letter)
        rotary = letter in ROTARY_LETTERS
        unit, factor = ("deg", _DEG) if rotary else ("mm", MM)
        columns = {f"position_{unit}": table.position_m / factor}
        for row, name in enumerate(component_names(letter)):
            columns[f"{name}_um" if row < 3 else f"{name}_urad"] = table.values[row] / (UM if row < 3 else _URAD)
        positions = table.position_m
        if table.periodic and positions[-1] - positions[0] > 2 * np.pi * (1 - 1e-12) and np.allclose(table.values[:, -1], table.values[:, 0]):
            columns = {k: v[:-1] for k, v in columns.items()}
        csv = folder / f"{letter.lower()}_errors.csv"
        write_csv(csv, columns, fmt="{:.6f}")
        write_sidecar(csv, kind="error table", axis=letter, interpolation=table.interpolation, method=comment or "machine")
        origin = machine.axes[letter].origin_m
        lines += ["", f"[axes.{letter}]", f'errors = "{csv.name}"',
                  "origin_mm = [" + ", ".join(_number(v / MM) for v in origin) + "]",
                  f'interpolation = "{table.interpolation}"', f"hold_ends = {'true' if table.hold_ends else 'false'}"]
        if rotary:
            lines.append(f"periodic = {'true' if table.periodic else 'false'}")
    if machine.squareness_rad:
        lines += ["", "[squareness]"] + [f"{k}_urad = {_number(v / _URAD)}" for k, v in machine.squareness_rad.items()]
    if machine.location:
        lines += ["", "[location]"] + [
            f"{k}_um = {_number(v / UM)}" if k[1] in AXIS_INDEX else f"{k}_urad = {_number(v / _URAD)}" for k, v in machine.location.items()
        ]
    return write_text(folder / "machine.toml", "\n".join(lines) + "\n")


#: order of the axes on the page
_AXIS_ORDER = "XYZABC"


def _inline_svg(fig) -> str:
    """The ``<svg>`` element of a drawn figure, for placing in the page (the figure stays open)."""
    import re
    import tempfile

    from axiscal.io.figures import save_figure

    with tempfile.TemporaryDirectory(prefix="axiscal-identify-") as folder:
        path = save_figure(fig, Path(folder) / "plot.svg", close=False)
        text = path.read_text(encoding="utf-8")
    text = text[text.find("<svg"):]
    return re.sub(r"\s*<metadata>.*?</metadata>", "", text, count=1, flags=re.S)


def _figures(result, png_folder: Path | None = None) -> tuple[list, list, dict]:
    """Each figure of the page drawn once: its inline SVG and, given a folder, its PNG there.

    Returns the (artefact, svg) and (axis, svg) pairs in the page's order and the PNG files by key.
    """
    from axiscal.identification.plot import motions_figure, residuals_figure
    from axiscal.io.figures import pyplot, save_figure

    figures = [("residuals", name, residuals_figure, f"residuals_{_slug(name)}.png") for name in result.residuals]
    letters = sorted(result.spans, key=lambda a: (_AXIS_ORDER.find(a) % 99, a))
    figures += [("motions", letter, motions_figure, f"motions_{letter.lower()}.png") for letter in letters]
    pages: dict[str, list] = {"residuals": [], "motions": []}
    files = {}
    for kind, name, draw, png in figures:
        fig = draw(result, name)
        try:
            if png_folder is not None:
                files[f"{kind}_{name}"] = save_figure(fig, png_folder / png, close=False)
            pages[kind].append((name, _inline_svg(fig)))
        finally:
            pyplot().close(fig)
    return pages["residuals"], pages["motions"], files


def _display(parameter: dict) -> dict:
    """A parameter as the page shows it: an artefact's position (``plate:x``) in mm, lengths in µm, angles in µrad."""
    name, unit, value, u = parameter["name"], parameter["unit"], parameter["value"], parameter["u"]
    if unit == "um" and name.rpartition(":")[2] in ("x", "y", "z", "tx", "ty", "tz") and not parameter["machine"]:
        return {**parameter, "value": value / 1000.0, "u": None if u is None else u / 1000.0, "unit": "mm", "digits": 4}
    return {**parameter, "unit": {"um": "µm", "urad": "µrad"}.get(unit, unit), "digits": 3}


def report_html(result, *, generated: str | None = None) -> str:
    """``identify.html`` of an identification, rendered from its Jinja2 template: one self-contained page.

    Parameters
    ----------
    result : Identification
        What :func:`axiscal.identify` returned.
    generated : str, keyword-only
        When the page was made (default: today, UTC).

    Returns
    -------
    str
        The HTML page, its plots inline as SVG (no file beside it is needed), the machine's name and
        the date, the axes in X, Y, Z order, positions in mm, the coverage factor stated once.
    """
    artefacts, axes, _ = _figures(result)
    return _page(result, artefacts, axes, generated)


def _page(result, artefacts: list, axes: list, generated: str | None) -> str:
    """identify.html from its template, the figures' SVGs given."""
    import datetime as _dt

    summary = result.summary()
    return render_template(
        "identification/identify.html.j2",
        summary=summary,
        machine=result.machine.name or "machine",
        generated=generated or _dt.datetime.now(_dt.timezone.utc).date().isoformat(),
        parameters=[_display(p) for p in summary["parameters"]],
        artefacts=artefacts,
        axes=axes,
    )


def write_identification(result, folder: str | Path) -> dict:
    """Write an identification: the machine folder, ``identify.json``, ``identify.html`` and its figures.

    Parameters
    ----------
    result : Identification
        What :func:`axiscal.identify` returned.
    folder : str or Path
        The output folder: made beside and put in place whole once everything is written (an
        existing folder must be empty or an earlier identification's, holding identify.json; it is
        replaced as a whole).

    Returns
    -------
    dict of str to Path
        ``machine``, ``json``, ``html`` and each figure.

    Raises
    ------
    AxiscalError
        For a folder that holds something else or cannot be written; it is then as it was.
    """
    # identify.html is self-contained (its plots inline); the PNGs stay for other documents
    folder = check_path("folder", folder)

    def fill(staging: Path) -> dict:
        files = {"machine": write_machine_folder(result.machine, staging,
                                                 comment=f"identified by axiscal identify ({result.model})")}
        files["json"] = write_json(staging / "identify.json", result.summary())
        artefacts, axes, pngs = _figures(result, staging)  # each figure drawn once, for its PNG and the page
        files.update(pngs)
        files["html"] = write_text(staging / "identify.html", _page(result, artefacts, axes, None))
        return {key: folder / Path(path).relative_to(staging) for key, path in files.items()}

    return atomic_folder(folder, fill, marker="identify.json")


def _slug(name: str) -> str:
    return "".join(c if c.isalnum() or c in "-_" else "_" for c in name)
