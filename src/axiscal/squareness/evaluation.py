"""Squareness of two axes from two straightness runs, and the pentaprism's own deviation.

Paper 002 (Liang et al.): squareness = included angle of the two axes' fitted lines minus 90
degrees (eq 1), minus the prism's deviation from 90 degrees (eq 13, eq 21); the prism's deviation
by autocollimator and wedge (eq 22). Paper 004 (Li et al.): the prism's deviation by reversal
(eqs 2-5; eqs 4-5 are missing from the text and follow from 2-3) and the angular resolution of a
PSD set-up, r = a / L (eq 1). ISO 230-1 names and signs of the squareness terms: EC0Y (XY plane),
EB0Z (XZ), EA0Z (YZ).

The sign conventions (``"included-angle"``, the default, and ``"iso"``) are stated once in
:mod:`axiscal.squareness.signs`; the prism's deviation by reversal and by wedge and the PSD's
resolution are :mod:`axiscal.squareness.prism`. Their names are importable from here too.

Runs
----
The first run moves the first axis of the plane and records the deviation along the second axis;
the second run moves the second axis and records the deviation along the first. Both are in the
machine's right-handed frame. A fitted line ``deviation = k position + b`` gives the direction
``(1, k1)`` of the first axis and ``(k2, 1)`` of the second (components along first, second axis),
so the included angle is ``theta = 90 deg - atan(k1) - atan(k2)``.

The prism deviation ``D`` is that of eq (13): the prism turns the beam by ``90 deg + D`` between the
incident beam and the exit beam. With the beam arriving against the first axis as in paper 002
(incident ``[-1, 0, 0]``) and leaving along the positive second axis, the exit beam, the second
axis' reference, makes ``90 deg - D`` with the positive first axis, so the second run sees the
axis ``D`` too far open and eq (21) subtracts it. If only one of the two beams is reversed (the
beam arrives along the positive first axis, or leaves along the negative second axis, e.g. turned
down to -Z), the reference makes ``90 deg + D`` and ``-D`` must be given instead.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.conventions import PLANES
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_instance, check_number, check_path
from axiscal.straightness.files import Profile, read_profile
from axiscal.straightness.reference import ReferenceLine, reference_line
from axiscal.straightness.report import render_report
from axiscal.squareness.prism import ReversalResult, prism_deviation_from_wedge, prism_reversal, psd_angular_resolution
from axiscal.squareness.signs import (
    CONVENTIONS,
    _plane,
    included_angle_from_iso,
    iso_from_included_angle,
    iso_term,
    squareness_name,
)
from axiscal.units import ARCSEC, UM

__all__ = [
    "PLANES",
    "CONVENTIONS",
    "iso_term",
    "squareness_name",
    "iso_from_included_angle",
    "included_angle_from_iso",
    "SquarenessResult",
    "squareness_from_slopes",
    "squareness",
    "ReversalResult",
    "prism_reversal",
    "prism_deviation_from_wedge",
    "psd_angular_resolution",
    "SQUARENESS_REFERENCES",
    "SquarenessEvaluation",
    "squareness_from_files",
]

#: Beyond this the two "axes" are not two crossing axes (lines parallel or nearly so), rad.
_MAX_SQUARENESS = math.pi / 4.0
#: A pentaprism off 90 degrees by this much or more is not a pentaprism (a unit slip, most likely), rad.
_MAX_PRISM_DEVIATION = math.pi / 180.0


@dataclass(frozen=True)
class SquarenessResult:
    """Squareness of two axes in one plane.

    Attributes
    ----------
    plane : str
        ``"XY"``, ``"XZ"`` or ``"YZ"``.
    convention : str
        Convention of :attr:`squareness_rad`: ``"iso"`` or ``"included-angle"``.
    squareness_rad : float
        The squareness in that convention, prism deviation removed (eq 21), radians.
    included_angle_rad : float
        Included angle between the positive axis directions, prism deviation removed, radians.
    measured_included_angle_rad : float
        Included angle of the two fitted lines as measured (theta of eq 1), radians.
    prism_deviation_rad : float
        ``D`` of eq (13) that was removed, radians.
    iso_term : str
        ``EC0Y``, ``EB0Z`` or ``EA0Z``.
    iso_value_rad : float
        The squareness as that ISO 230-1 term (right-hand-rule sign), radians.
    slope_first, slope_second : float
        Slopes (m/m) of the two runs' fitted lines, each in its own run: deviation along the other
        axis per unit of travel.
    first_line, second_line : ReferenceLine or None
        The fitted lines when the result came from data (None from slopes alone).
    """

    plane: str
    convention: str
    squareness_rad: float
    included_angle_rad: float
    measured_included_angle_rad: float
    prism_deviation_rad: float
    iso_term: str
    iso_value_rad: float
    slope_first: float
    slope_second: float
    first_line: ReferenceLine | None = None
    second_line: ReferenceLine | None = None

    @property
    def name(self) -> str:
        """What :attr:`squareness_rad` is shown as: :func:`squareness_name` of its plane and convention."""
        return squareness_name(self.plane, self.convention)


def squareness_from_slopes(
    slope_first: float,
    slope_second: float,
    *,
    plane: str = "XY",
    prism_deviation_rad: float = 0.0,
    convention: str = "included-angle",
) -> SquarenessResult:
    """Squareness from the slopes of the two runs' fitted lines (paper 002 eqs 1 and 21).

    Parameters
    ----------
    slope_first : float
        Slope of the first run: deviation along the second axis per travel of the first (m/m).
    slope_second : float
        Slope of the second run: deviation along the first axis per travel of the second (m/m).
        A line given in the common frame as ``second = k' first + b`` (paper 002's k') has
        ``slope_second = 1 / k'``.
    plane : {"XY", "XZ", "YZ"}, keyword-only
    prism_deviation_rad : float, keyword-only
        ``D`` of eq (13), radians (0 when no prism turned the beam); its sign as in the module
        docstring (beam arriving against the first axis, leaving along the second).
    convention : {"included-angle", "iso"}, keyword-only
        Sign convention of ``squareness_rad``: ``"included-angle"`` (default, eq 21: included
        angle - 90 deg - D) or ``"iso"`` (the ISO 230-1 term's sign); both values are in the result.

    Raises
    ------
    AxiscalError
        Unknown plane or convention, non-finite slopes, a prism deviation of 1 degree or more, or
        lines that are (nearly) parallel: an included angle more than 45 degrees off a right angle
        is not the squareness of two axes.

    Returns
    -------
    SquarenessResult
        Without fitted lines.

    Examples
    --------
    >>> from axiscal.units import ARCSEC
    >>> result = squareness_from_slopes(-0.00044783, 1 / 3001.62173825, prism_deviation_rad=2.7 * ARCSEC)
    >>> round(result.squareness_rad / ARCSEC, 2)
    20.95
    """
    first, second, term, _ = _plane(plane)
    if not isinstance(convention, str) or convention not in CONVENTIONS:
        raise AxiscalError(f"unknown sign convention {convention!r}; use one of {', '.join(CONVENTIONS)}")
    slope_first = check_number("slope_first", slope_first, unit="")
    slope_second = check_number("slope_second", slope_second, unit="")
    prism_deviation_rad = check_number("prism_deviation_rad", prism_deviation_rad, unit="radians")
    if abs(prism_deviation_rad) >= _MAX_PRISM_DEVIATION:
        raise AxiscalError(
            f"a prism deviation of {prism_deviation_rad / ARCSEC:.6g} arcsec is 1 degree or more off 90 degrees: "
            "not a pentaprism (check the unit: arc seconds)"
        )
    measured = math.pi / 2.0 - math.atan(slope_first) - math.atan(slope_second)
    if abs(measured - math.pi / 2.0) >= _MAX_SQUARENESS:
        raise AxiscalError(
            f"the two fitted lines are (nearly) parallel: included angle {math.degrees(measured):.3f} deg; "
            f"the first run must move {first} (deviation along {second}), the second move {second} (deviation along {first})"
        )
    included = measured - prism_deviation_rad
    value = included - math.pi / 2.0
    iso_value = iso_from_included_angle(value, plane=plane)
    return SquarenessResult(
        plane=plane.upper(),
        convention=convention,
        squareness_rad=iso_value if convention == "iso" else value,
        included_angle_rad=included,
        measured_included_angle_rad=measured,
        prism_deviation_rad=float(prism_deviation_rad),
        iso_term=term,
        iso_value_rad=iso_value,
        slope_first=float(slope_first),
        slope_second=float(slope_second),
    )


def squareness(
    first_position_m: np.ndarray,
    first_deviation_m: np.ndarray,
    second_position_m: np.ndarray,
    second_deviation_m: np.ndarray,
    *,
    plane: str = "XY",
    prism_deviation_rad: float = 0.0,
    reference: str = "least-squares",
    convention: str = "included-angle",
) -> SquarenessResult:
    """Squareness from two straightness runs (paper 002 eqs 1, 15 and 21).

    Parameters
    ----------
    first_position_m, first_deviation_m : array_like, shape (n,), metres
        First run: positions of the first axis, deviations along the second axis.
    second_position_m, second_deviation_m : array_like, shape (m,), metres
        Second run: positions of the second axis, deviations along the first axis.
    plane, prism_deviation_rad, convention
        As in :func:`squareness_from_slopes`.
    reference : {"least-squares", "end-points", "minimum-zone"}, keyword-only
        Reference line fitted to each run (default least squares, eq 15).

    Raises
    ------
    AxiscalError
        A run with fewer than 2 points (or all at one position), or the cases of
        :func:`squareness_from_slopes`.

    Returns
    -------
    SquarenessResult
        With both fitted lines.
    """
    lines = []
    for label, position, deviation in (
        ("first", first_position_m, first_deviation_m),
        ("second", second_position_m, second_deviation_m),
    ):
        size = np.size(position) if not isinstance(position, (str, bytes)) and position is not None else 0
        if size < 2:
            raise AxiscalError(f"the {label} run has {size} point(s); a line needs at least 2 ({label}_position_m)")
        try:
            lines.append(reference_line(position, deviation, reference=reference))
        except AxiscalError as exc:
            message = exc.message.replace("position_m", f"{label}_position_m").replace("deviation_m", f"{label}_deviation_m")
            raise AxiscalError(f"{label} run: {message}") from None
    result = squareness_from_slopes(
        lines[0].slope, lines[1].slope, plane=plane, prism_deviation_rad=prism_deviation_rad, convention=convention
    )
    return replace(result, first_line=lines[0], second_line=lines[1])


#: reference lines :func:`squareness_from_files` fits to a run
SQUARENESS_REFERENCES = ("least-squares", "end-points")


@dataclass(frozen=True)
class SquarenessEvaluation:
    """Squareness from two run files, with the runs it came from.

    Attributes
    ----------
    result : SquarenessResult
        The squareness, SI.
    first, second : Profile
        The two runs as read, metres.
    """

    result: SquarenessResult
    first: Profile
    second: Profile

    def __post_init__(self) -> None:
        check_instance("result", self.result, SquarenessResult, what="a SquarenessResult")
        for name in ("first", "second"):
            check_instance(name, getattr(self, name), Profile, what="a Profile (read_profile)")

    def payload(self) -> dict[str, Any]:
        """The JSON object: angles in arcsec and degrees, slopes, straightness of each run in um."""
        result = self.result
        first, second = result.first_line, result.second_line
        return {
            "plane": result.plane,
            "convention": result.convention,
            "squareness_arcsec": result.squareness_rad / ARCSEC,
            "included_angle_deg": math.degrees(result.included_angle_rad),
            "measured_included_angle_deg": math.degrees(result.measured_included_angle_rad),
            "prism_deviation_arcsec": result.prism_deviation_rad / ARCSEC,
            "iso_term": result.iso_term,
            "iso_value_arcsec": result.iso_value_rad / ARCSEC,
            "slope_first": result.slope_first,
            "slope_second": result.slope_second,
            "reference": None if first is None else first.reference,
            "straightness_first_um": None if first is None else first.straightness_m / UM,
            "straightness_second_um": None if second is None else second.straightness_m / UM,
        }

    def report(self) -> str:
        """The readable summary: slopes, included angles, the prism's deviation, both conventions."""
        result = self.result
        first_axis, second_axis = PLANES[result.plane][:2]
        return render_report(
            "squareness.txt.j2",
            first_axis=first_axis,
            second_axis=second_axis,
            first_path=self.first.path,
            second_path=self.second.path,
            slope_first=result.slope_first,
            slope_first_arcsec=math.atan(result.slope_first) / ARCSEC,
            slope_second=result.slope_second,
            slope_second_arcsec=math.atan(result.slope_second) / ARCSEC,
            measured_included_angle_deg=math.degrees(result.measured_included_angle_rad),
            prism_deviation_arcsec=result.prism_deviation_rad / ARCSEC,
            included_angle_deg=math.degrees(result.included_angle_rad),
            convention_name="ISO 230-1 sign" if result.convention == "iso" else "included angle - 90 deg",
            squareness_arcsec=result.squareness_rad / ARCSEC,
            iso_term=result.iso_term,
            iso_value_arcsec=result.iso_value_rad / ARCSEC,
        )


def squareness_from_files(
    first_path: str | Path,
    second_path: str | Path,
    *,
    plane: str = "XY",
    prism_deviation_rad: float = 0.0,
    reference: str = "least-squares",
    convention: str = "included-angle",
) -> SquarenessEvaluation:
    """Squareness of two axes from two straightness run files (paper 002 eqs 1, 15 and 21).

    Parameters
    ----------
    first_path : str or Path
        Run of the plane's first axis (deviation along the second axis), read by
        :func:`axiscal.straightness.files.read_profile`.
    second_path : str or Path
        Run of the plane's second axis (deviation along the first axis).
    plane, prism_deviation_rad, convention : keyword-only
        As in :func:`squareness_from_slopes`.
    reference : {"least-squares", "end-points"}, keyword-only
        Line fitted to each run (default least squares, eq 15).

    Returns
    -------
    SquarenessEvaluation

    Raises
    ------
    AxiscalError
        A bad file (naming it and the line), an unknown reference, or the cases of
        :func:`squareness_from_slopes`.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> _ = (folder / "x.csv").write_text("position_mm,deviation_um\\n0,0\\n100,1\\n")
    >>> _ = (folder / "y.csv").write_text("position_mm,deviation_um\\n0,0\\n100,0\\n")
    >>> run = squareness_from_files(folder / "x.csv", folder / "y.csv")
    >>> round(run.payload()["squareness_arcsec"], 3)
    -2.063
    """
    if not isinstance(reference, str) or reference not in SQUARENESS_REFERENCES:
        raise AxiscalError(f"the reference line of a squareness run must be least-squares or end-points, not {reference!r}")
    first, second = read_profile(check_path("first_path", first_path)), read_profile(check_path("second_path", second_path))
    result = squareness(
        first.position_m,
        first.deviation_m,
        second.position_m,
        second.deviation_m,
        plane=plane,
        prism_deviation_rad=prism_deviation_rad,
        reference=reference,
        convention=convention,
    )
    return SquarenessEvaluation(result, first, second)
