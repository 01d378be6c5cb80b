"""Flatness files: the lines file (TOML) and the evaluation behind ``axiscal flatness``.

The lines of a Union Jack or a grid (ISO 230-1 flatness; ASME B89.3.7 for surface plates), each
given by its two ends in plan and either level or autocollimator readings (``angle_arcsec``,
``angle_urad`` or ``angle_um_per_m``, with the foot spacing) or a straightness profile (a CSV
file, or ``position_mm`` and ``deviation_um`` arrays). Every mistake is an AxiscalError naming the
file, the line of the file and the key. The format is in docs/flatness.md.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.flatness.moody import moody_union_jack
from axiscal.flatness.surface import EVALUATIONS, FlatnessLine, FlatnessSurface, line_from_angles, surface_from_lines
from axiscal.io.arguments import check_instance, check_path, render_checked
from axiscal.io.jsonio import write_sidecar
from axiscal.io.formats.base import read_format
from axiscal.io.formats.flatness import FlatnessFile
from axiscal.io.schema import confined_path
from axiscal.io.tabular import write_csv
from axiscal.io.templates import render_template
from axiscal.levels.files import ANGLE_COLUMNS
from axiscal.straightness.files import read_profile
from axiscal.units import MM, UM

__all__ = ["FlatnessLines", "read_flatness_lines", "FlatnessEvaluation", "evaluate_flatness"]

#: a line's foot spacing times its readings may differ from its length by this fraction before a warning
_FOOT_SLACK = 0.01


@dataclass(frozen=True)
class FlatnessLines:
    """The lines of a flatness file, read and checked.

    Attributes
    ----------
    lines : tuple of FlatnessLine
        The lines, SI.
    title : str
        The file's ``title`` (empty when not given).
    path : str
        The file.
    warnings : tuple of str
        What the reader noticed (a foot spacing that does not fit a line's length).
    """

    lines: tuple[FlatnessLine, ...]
    title: str
    path: str
    warnings: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        if not isinstance(self.lines, tuple) or not all(isinstance(line, FlatnessLine) for line in self.lines):
            raise AxiscalError("lines must be a tuple of FlatnessLine")
        check_path("path", self.path)


def _show(value: Any) -> str:
    text = repr(value)
    return text if len(text) <= 40 else text[:37] + "..."


def _unordered(position_mm: np.ndarray, where) -> tuple[int, str] | None:
    """The first station whose position repeats one before it or falls back, and the problem in words; None when they increase.

    ``where(k)`` says where station ``k`` stands (``station 3``, ``line 4``).
    """
    back = np.flatnonzero(np.diff(position_mm) <= 0)
    if back.size == 0:
        return None
    k = int(back[0]) + 1
    value = float(position_mm[k])
    first = np.flatnonzero(position_mm[:k] == value)
    if first.size:
        return k, f"position {value:g} mm is given twice ({where(int(first[0]))} and {where(k)})"
    return k, f"the positions must increase: {value:g} mm after {float(position_mm[k - 1]):g} mm ({where(k)})"


def read_flatness_lines(path: str | Path) -> FlatnessLines:
    """Read a flatness lines file (TOML): ``[[lines]]`` with their ends and readings or profiles.

    Parameters
    ----------
    path : str or Path
        The TOML file; profile files it names are read relative to its folder.

    Returns
    -------
    FlatnessLines

    Raises
    ------
    AxiscalError
        A missing or malformed file, an unknown key, a value of the wrong type, a line with no
        readings or with two kinds of readings, a level line without a foot spacing, a profile file
        that is missing, bad or outside the folder, a profile position given twice or falling back;
        naming the file, the line and the key (for a profile file, its line).

    Examples
    --------
    >>> import pathlib, tempfile
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "lines.toml"
    >>> _ = path.write_text('foot_mm = 100\\n[[lines]]\\nname = "a"\\nfrom_mm = [0, 0]\\nto_mm = [200, 0]\\n'
    ...                     'angle_urad = [10, -10]\\n')
    >>> (read_flatness_lines(path).lines[0].height_m / 1e-6).round(6).tolist()
    [0.0, 1.0, 0.0]
    """
    path = check_path("path", path)
    checked, where = read_format(FlatnessFile, path)  # read once, validated against the declared format
    if not checked.lines:
        raise AxiscalError("the file has no [[lines]]", path=path)
    default_foot = checked.foot_mm
    default_gravity = bool(checked.gravity)
    lines: list[FlatnessLine] = []
    warnings: list[str] = []
    for index, entry in enumerate(checked.lines):
        def fail(message: str, key: str | None = None, index: int = index) -> AxiscalError:
            return AxiscalError(message, path=path, line=where.of("lines", index, key))

        raw = {k: v for k, v in entry.given().items()}
        name = raw["name"]
        if any(line.name == name for line in lines):
            raise fail(f"two lines are named {name!r}", "name")
        start, end = np.array(raw["from_mm"], float) * MM, np.array(raw["to_mm"], float) * MM
        given = [k for k in (*ANGLE_COLUMNS, "profile", "deviation_um") if k in raw]
        if len(given) != 1:
            problem = "no readings" if not given else f"more than one kind of readings ({', '.join(given)})"
            raise fail(f"line {name!r} has {problem}: give one of {', '.join(ANGLE_COLUMNS)}, profile or deviation_um")
        kind = given[0]
        gravity = raw.get("gravity", default_gravity)
        try:
            if kind in ANGLE_COLUMNS:
                foot = raw.get("foot_mm", default_foot)
                if foot is None:
                    raise fail(f"line {name!r} is read as angles: give its foot_mm (or foot_mm at the top)", kind)
                if not foot > 0:
                    if "foot_mm" in raw:
                        raise fail(f"foot_mm must be positive, not {_show(foot)}", "foot_mm")
                    raise AxiscalError(f"foot_mm must be positive, not {_show(foot)}", path=path, line=where.of("", 0, "foot_mm"))
                angles = np.array(raw[kind], float) * ANGLE_COLUMNS[kind]
                line = line_from_angles(name, start, end, angles, foot_m=foot * MM, gravity=gravity)
                span = angles.size * foot * MM
                if abs(span - line.length_m) > _FOOT_SLACK * line.length_m:
                    warnings.append(f"line {name!r}: {angles.size} steps of {foot:g} mm make {span / MM:g} mm on a line"
                                    f" {line.length_m / MM:g} mm long; the rises are taken over {foot:g} mm")
            elif kind == "profile":
                profile = read_profile(confined_path(path.parent, raw["profile"]))
                bad = _unordered(profile.position_m / MM, lambda k: f"line {profile.lines[k]}")
                if bad is not None:
                    raise AxiscalError(f"line {name!r}: {bad[1]}", path=profile.path, line=profile.lines[bad[0]])
                line = FlatnessLine(name, start, end, profile.position_m, profile.deviation_m, gravity)
            else:
                if "position_mm" not in raw:
                    raise fail(f"line {name!r} gives deviation_um: give position_mm beside it", "deviation_um")
                if len(raw["position_mm"]) != len(raw["deviation_um"]):
                    raise fail(f"line {name!r}: {len(raw['position_mm'])} positions and {len(raw['deviation_um'])} deviations",
                               "deviation_um")
                bad = _unordered(np.array(raw["position_mm"], float), lambda k: f"station {k + 1}")
                if bad is not None:
                    raise fail(f"line {name!r}: position_mm: {bad[1]}", "position_mm")
                line = FlatnessLine(name, start, end, np.array(raw["position_mm"], float) * MM,
                                    np.array(raw["deviation_um"], float) * UM, gravity)
        except AxiscalError as exc:
            if exc.path is not None:
                raise
            raise fail(exc.message, kind) from None
        if "position_mm" in raw and kind != "deviation_um":
            raise fail(f"position_mm belongs with deviation_um, not with {kind}", "position_mm")
        lines.append(line)
    return FlatnessLines(tuple(lines), checked.title or "", str(path), tuple(warnings))


@dataclass(frozen=True)
class FlatnessEvaluation:
    """A flatness file evaluated: the lines as read and the surface joined from them.

    Attributes
    ----------
    source : FlatnessLines
        The file as read.
    surface : FlatnessSurface
        The surface, its closures and its flatness, SI.
    """

    source: FlatnessLines
    surface: FlatnessSurface

    def __post_init__(self) -> None:
        check_instance("source", self.source, FlatnessLines, what="FlatnessLines (read_flatness_lines)")
        check_instance("surface", self.surface, FlatnessSurface, what="a FlatnessSurface")

    def payload(self) -> dict[str, Any]:
        """The JSON object.

        Returns
        -------
        dict
            ``flatness_um`` (minimum zone), ``flatness_least_squares_um``, ``closure_max_um``,
            ``closures`` (``x_mm``, ``y_mm``, ``lines``, ``value_um`` each), ``evaluation``,
            ``lines``, ``points``, ``warnings``; Moody's evaluation adds ``flatness_moody_um``
            (the spread of his heights).
        """
        s = self.surface
        out: dict[str, Any] = {
            "flatness_um": s.zone.minimum_zone_m / UM,
            "flatness_least_squares_um": s.zone.least_squares_m / UM,
            "closure_max_um": s.closure_max_m / UM,
            "evaluation": s.evaluation,
            "lines": len(s.lines),
            "points": int(s.x_m.size),
            "closures": [{"x_mm": c.x_m / MM, "y_mm": c.y_m / MM, "lines": list(c.lines), "value_um": c.value_m / UM}
                         for c in s.closures],
            "warnings": list(self.source.warnings),
        }
        if s.evaluation == "moody":
            heights = np.concatenate(s.line_heights_m)
            out["flatness_moody_um"] = float(np.ptp(heights)) / UM
        return out

    def surface_columns(self) -> dict[str, np.ndarray]:
        """The surface as ``-o`` writes it: ``x_mm``, ``y_mm``, ``height_um`` (about the least-squares plane)."""
        return {"x_mm": self.surface.x_m / MM, "y_mm": self.surface.y_m / MM, "height_um": self.surface.z_m / UM}

    def report(self) -> str:
        """The readable summary."""
        payload = self.payload()
        worst = max(self.surface.closures, key=lambda c: abs(c.value_m), default=None)
        return render_checked(
            render_template, "flatness.txt.j2", title=self.source.title, worst=None if worst is None else {
                "x_mm": worst.x_m / MM, "y_mm": worst.y_m / MM, "lines": ", ".join(worst.lines), "value_um": worst.value_m / UM},
            **payload,
        ).rstrip("\n")


def evaluate_flatness(
    path: str | Path,
    *,
    evaluation: str = "least-squares",
    output: str | Path | None = None,
    plot_path: str | Path | None = None,
) -> FlatnessEvaluation:
    """Flatness of a surface from a lines file (what ``axiscal flatness`` does).

    Parameters
    ----------
    path : str or Path
        The lines file, read by :func:`read_flatness_lines`.
    evaluation : {"least-squares", "moody"}, keyword-only
        Join the lines by least squares (any layout; default) or by Moody's method (a Union Jack).
    output : str or Path, optional, keyword-only
        Write the surface's points (``x_mm, y_mm, height_um``) here, with a JSON sidecar.
    plot_path : str or Path, optional, keyword-only
        Write a contour map and a 3-D view of the surface.

    Returns
    -------
    FlatnessEvaluation

    Raises
    ------
    AxiscalError
        A bad file (see :func:`read_flatness_lines`), an unknown evaluation, lines that do not tie
        the surface together or do not make a Union Jack (Moody); naming the file.
    """
    if not isinstance(evaluation, str) or evaluation not in EVALUATIONS:
        raise AxiscalError(f"unknown evaluation {evaluation!r}; use one of {', '.join(EVALUATIONS)}")
    if output is not None:
        check_path("output", output)
    source = read_flatness_lines(path)
    try:
        surface = moody_union_jack(source.lines) if evaluation == "moody" else surface_from_lines(source.lines)
    except AxiscalError as exc:
        raise exc.located(path=path) from None
    result = FlatnessEvaluation(source, surface)
    if output is not None:
        payload = result.payload()
        write_csv(output, result.surface_columns(), fmt={"x_mm": "{:.3f}", "y_mm": "{:.3f}", "height_um": "{:.5f}"})
        write_sidecar(output, kind="flatness surface", sources=[path], evaluation=evaluation,
                      heights="about the least-squares plane",
                      flatness_um=payload["flatness_um"], flatness_least_squares_um=payload["flatness_least_squares_um"],
                      closure_max_um=payload["closure_max_um"])
    if plot_path is not None:
        from axiscal.flatness.plot import plot_flatness

        plot_flatness(plot_path, surface, title=source.title)
    return result
