"""A ballbar test evaluated in one call: ISO 230-4 figures, diagnostics, the JSON object and the text report.

The JSON keys (figures in um, ``squareness_urad``, ``scale_mismatch_ppm``, ``servo_mismatch_ms``)
are the interface of ``axiscal ballbar --json``; docs/ballbar.md describes each. The squareness
is also given as ISO 230-1's term for the plane (docs/conventions.md): EC0Y for X and Y,
EB0Z for X and Z (opposite sign), EA0Z for Y and Z.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.circular.diagnostics import BallbarDiagnostics, diagnose
from axiscal.circular.evaluation import (
    MM_PER_MIN,
    BallbarTrace,
    CircularFigures,
    iso230_4,
    plane_axes,
    radial_deviations,
)
from axiscal.circular.reader import read_ballbar
from axiscal.conventions import SQUARENESS_TERMS
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_count, check_instance, check_number, is_real
from axiscal.units import ANGLE_UNITS, LENGTH_UNITS, MM, UM

__all__ = [
    "PPM",
    "MS",
    "STANDARD",
    "BallbarResult",
    "iso_squareness",
    "evaluate_ballbar",
    "evaluate_ballbar_file",
    "ballbar_payload",
    "circle_deviations",
    "trace_payload",
    "TRACE_POINTS",
    "format_number",
    "render_report",
]

#: one part per million (1 um per m)
PPM = UM / LENGTH_UNITS["m"]
#: seconds in a millisecond
MS = 1e-3
#: the standard the figures follow
STANDARD = "ISO 230-4:2005"
#: ISO 230-1 squareness term of each pair of axes, and its sign against (included angle - 90 deg)
_ISO_TERMS = {
    frozenset("XY"): (SQUARENESS_TERMS[0], 1.0),
    frozenset("XZ"): (SQUARENESS_TERMS[1], -1.0),
    frozenset("YZ"): (SQUARENESS_TERMS[2], 1.0),
}
_URAD = ANGLE_UNITS["urad"]


def iso_squareness(plane: str, squareness: float) -> tuple[str, float]:
    """ISO 230-1's squareness term for the plane's axes, and its value (radians).

    Parameters
    ----------
    plane : str
        Two axes, e.g. ``"XY"`` or ``"ZX"``.
    squareness : float, radians
        Included angle between the positive axes minus 90 degrees.

    Returns
    -------
    tuple of (str, float)
        ``("EC0Y", q)`` for X and Y, ``("EB0Z", -q)`` for X and Z, ``("EA0Z", q)`` for Y and Z.

    Examples
    --------
    >>> iso_squareness("ZX", 5e-6)
    ('EB0Z', -5e-06)
    """
    term, sign = _ISO_TERMS[frozenset("".join(plane_axes(plane)))]
    return term, sign * check_number("squareness", squareness, unit="radians")


@dataclass(frozen=True)
class BallbarResult:
    """A circular test evaluated: the trace, its ISO 230-4 figures and the diagnostics (SI units).

    Attributes
    ----------
    trace : BallbarTrace
    figures : CircularFigures
    diagnostics : BallbarDiagnostics
    feed : float or None, m/s
        The feed of the test, when given.
    """

    trace: BallbarTrace
    figures: CircularFigures
    diagnostics: BallbarDiagnostics
    feed: float | None = None

    def __post_init__(self) -> None:
        for name, kind in (("trace", BallbarTrace), ("figures", CircularFigures), ("diagnostics", BallbarDiagnostics)):
            if not isinstance(getattr(self, name), kind):
                raise AxiscalError(f"{name} must be a {kind.__name__}, not {type(getattr(self, name)).__name__}")
        if self.feed is not None:
            check_number("feed", self.feed, positive=True, unit="metres per second")


def evaluate_ballbar(trace: BallbarTrace, *, feed: float | None = None) -> BallbarResult:
    """ISO 230-4 figures and diagnostics of a trace.

    Parameters
    ----------
    trace : BallbarTrace
    feed : float, optional, m/s
        Feed of the test; with both directions it gives the servo mismatch.

    Returns
    -------
    BallbarResult

    Raises
    ------
    AxiscalError
        If the feed is not a positive speed.
    """
    check_instance("trace", trace, BallbarTrace, what="a BallbarTrace")
    return BallbarResult(trace=trace, figures=iso230_4(trace), diagnostics=diagnose(trace, feed=feed), feed=feed)


def evaluate_ballbar_file(path: str | Path, *, radius: float, plane: str = "XY", feed: float | None = None) -> BallbarResult:
    """Read a trace file (see :func:`axiscal.circular.reader.read_ballbar`) and evaluate it.

    Parameters
    ----------
    path : str or Path
        CSV with ``angle_deg, direction, radius_deviation_um``.
    radius : float, metres, keyword-only
        Nominal radius.
    plane : str, keyword-only
        First and second axis.
    feed : float, optional, m/s

    Returns
    -------
    BallbarResult

    Raises
    ------
    AxiscalError
        On a bad file (naming it and the line), radius, plane or feed.
    """
    return evaluate_ballbar(read_ballbar(path, radius=radius, plane=plane), feed=feed)


def _um(value: float) -> float | None:
    return value / UM if math.isfinite(value) else None


def _result(result: BallbarResult) -> BallbarResult:
    check_instance("result", result, BallbarResult, what="a BallbarResult (evaluate_ballbar)")
    return result


def ballbar_payload(result: BallbarResult) -> dict[str, Any]:
    """The JSON object of ``axiscal ballbar --json`` (lengths in um, angles in urad, scale in ppm, time in ms).

    Parameters
    ----------
    result : BallbarResult

    Returns
    -------
    dict
        Plain values; a figure that cannot be given (H or G_cw of a single direction, the servo
        mismatch without feed) is None.
    """
    _result(result)
    t, f, d = result.trace, result.figures, result.diagnostics
    term, iso_value = iso_squareness(t.plane, d.squareness)
    return {
        "standard": STANDARD,
        "plane": t.plane,
        "axes": list(t.axes),
        "radius_mm": t.radius / MM,
        "feed_mm_min": None if result.feed is None else result.feed / MM_PER_MIN,
        "directions": list(t.present),
        "points": {direction: int(t.rows(direction).size) for direction in t.present},
        "G_ccw_um": _um(f.G.get("ccw", math.nan)),
        "G_cw_um": _um(f.G.get("cw", math.nan)),
        "H_um": _um(f.H),
        "F_max_um": _um(f.F_max),
        "F_min_um": _um(f.F_min),
        "centre_x_um": _um(f.centre[0]),
        "centre_y_um": _um(f.centre[1]),
        "radius_offset_um": _um(f.radius_offset),
        "squareness_urad": d.squareness / _URAD,
        "squareness_iso_term": term,
        "squareness_iso_urad": iso_value / _URAD,
        "scale_mismatch_ppm": d.scale_mismatch / PPM,
        "backlash_um": {k: _um(v) for k, v in d.backlash.items()},
        "reversal_spike_um": {k: {dr: _um(v) for dr, v in per.items()} for k, per in d.reversal_spike.items()},
        "cyclic_error_um": {k: _um(v) for k, v in d.cyclic_error.items()},
        "cyclic_pitch_mm": {k: (v / MM if math.isfinite(v) else None) for k, v in d.cyclic_pitch.items()},
        "servo_mismatch_ms": d.servo_mismatch / MS if math.isfinite(d.servo_mismatch) else None,
        "residual_rms_um": _um(d.residual_rms),
        "warnings": list(d.warnings),
    }


#: most points per direction :func:`trace_payload` keeps (one each degree of a full circle)
TRACE_POINTS = 360


def circle_deviations(result: BallbarResult) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """Each direction's path as its distance from the least-squares circle: what the polar plot draws.

    The distance of each point from the least-squares centre of all points
    (:func:`~axiscal.circular.evaluation.radial_deviations`) minus the least-squares radius.

    Parameters
    ----------
    result : BallbarResult

    Returns
    -------
    dict of str to (ndarray, ndarray)
        Direction (``"ccw"``, ``"cw"``, those measured) -> angles (radians in [0, 2 pi), sorted)
        and deviations (metres), each shape (n,).
    """
    _result(result)
    trace, figures = result.trace, result.figures
    out = {}
    for d in trace.present:
        a, dev = trace.path(d)
        out[d] = (a, radial_deviations(a, dev, trace.radius, figures.centre) - figures.radius_offset)
    return out


def trace_payload(result: BallbarResult, *, max_points: int = TRACE_POINTS) -> dict[str, dict[str, list[float]]]:
    """The paths of :func:`circle_deviations` as a JSON object, thinned for a results file.

    Every k-th point of a direction is kept, k the smallest step leaving at most ``max_points``
    (a 3600-point trace keeps every tenth point: one each degree).

    Parameters
    ----------
    result : BallbarResult
    max_points : int, keyword-only
        Most points kept per direction (default :data:`TRACE_POINTS`).

    Returns
    -------
    dict
        Direction -> ``{"angle_deg": [...], "deviation_um": [...]}`` (4 decimals).

    Raises
    ------
    AxiscalError
        For a ``result`` that is not a BallbarResult or a ``max_points`` below 2.
    """
    max_points = check_count("max_points", max_points, minimum=2)
    out = {}
    for d, (a, r) in circle_deviations(result).items():
        step = max(1, -(-a.size // max_points))
        out[d] = {"angle_deg": np.round(np.degrees(a[::step]), 4).tolist(),
                  "deviation_um": np.round(r[::step] / UM, 4).tolist()}
    return out


def format_number(value: float | None, fmt: str = "{:+.2f}") -> str:
    """A value of :func:`ballbar_payload` for a report: formatted, or ``n/a`` as wide as the format makes a number.

    Parameters
    ----------
    value : float or None
    fmt : str
        A :meth:`str.format` pattern for one number.

    Returns
    -------
    str

    Examples
    --------
    >>> format_number(None, "{:6.2f}"), format_number(1.5, "{:6.2f}")
    ('   n/a', '  1.50')
    """
    if not isinstance(fmt, str):
        raise AxiscalError(f"fmt must be a format string such as '{{:+.2f}}', not {fmt!r}")
    if value is not None and not is_real(value):
        raise AxiscalError(f"value must be a number or None, not {value!r}")
    try:
        return "n/a".rjust(len(fmt.format(0.0))) if value is None else fmt.format(value)
    except (ValueError, IndexError, KeyError) as exc:
        raise AxiscalError(f"fmt {fmt!r} is not a format for one number: {exc}") from None


def render_report(result: BallbarResult) -> str:
    """The readable report of ``axiscal ballbar`` (from the package's ``templates/ballbar.txt.j2``).

    Parameters
    ----------
    result : BallbarResult

    Returns
    -------
    str
        Several lines, no trailing newline.
    """
    from importlib.resources import files

    import jinja2

    _result(result)
    text = (files("axiscal") / "templates" / "ballbar.txt.j2").read_text(encoding="utf-8")
    env = jinja2.Environment(undefined=jinja2.StrictUndefined, keep_trailing_newline=False, trim_blocks=True, lstrip_blocks=True)
    env.filters["num"] = format_number
    return env.from_string(text).render(p=ballbar_payload(result), source=result.trace.source).rstrip("\n")
