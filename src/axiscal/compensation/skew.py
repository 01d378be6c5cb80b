"""Skew (squareness) correction lines for 3D-printer and small-machine firmware: Klipper, Marlin, RepRapFirmware.

Each firmware shears the commanded position before it reaches the motors; the factor it wants is
the tangent of the squareness, with its own sign and its own way of being entered:

* Klipper (``klippy/extras/skew_correction.py``): ``SET_SKEW XY=AC,BD,AD`` takes the diagonals AC,
  BD and the side AD of a square drawn by the machine; ``calc_skew_factor`` turns them into
  ``xy_factor`` and ``calc_skew`` commands ``x - y * xy_factor - z * (xz_factor - xy_factor * yz_factor)``,
  ``y - z * yz_factor``.
* Marlin (``Marlin/src/gcode/calibrate/M852.cpp``, ``Planner::skew`` in ``planner.h``): ``M852 I J K``
  sets the same three factors with the same shear as Klipper's (Klipper's module is a port of it);
  ``XY_SKEW_FACTOR`` is the Configuration.h define.
* RepRapFirmware (``M556``, ``Move::AxisTransform``): ``M556 S<length> X<dev> Y<dev> Z<dev>`` sets
  ``tanXY = X/S``, ``tanYZ = Y/S``, ``tanXZ = Z/S`` and commands ``x + tanXY y + tanXZ z``,
  ``y + tanYZ z``.

Here a squareness ``s`` is the included angle between the positive directions of the two axes minus
90 degrees (``axiscal squareness``'s default convention): a machine with ``s > 0`` places the point
commanded at ``(x, y)`` at ``(x - y sin s, y cos s)``; the correction commands ``x + y tan s``. So
Klipper's and Marlin's factor is ``-tan s`` and RepRapFirmware's tangent is ``+tan s``.
"""

from __future__ import annotations

import math
import os
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_choice, check_number, check_path, is_real
from axiscal.io.jsonio import read_json
from axiscal.units import MM

__all__ = [
    "FIRMWARES",
    "SKEW_PLANES",
    "SKEW_CONVENTIONS",
    "MAX_SKEW_RAD",
    "SkewCorrection",
    "skew_correction",
    "klipper_lengths",
    "squareness_from_results",
]

FIRMWARES = ("klipper", "marlin", "rrf")
SKEW_PLANES = ("XY", "XZ", "YZ")
SKEW_CONVENTIONS = ("included-angle", "iso")
#: sign of the ISO 230-1 term (EC0Y, EB0Z, EA0Z) against the included-angle value (docs/squareness.md)
_ISO_SIGN = {"XY": 1, "XZ": -1, "YZ": 1}
#: Firmware skew correction is a small shear; beyond this the frame needs squaring by hand, rad.
MAX_SKEW_RAD = math.radians(5.0)
_MARLIN_LETTER = {"XY": "I", "XZ": "J", "YZ": "K"}
_RRF_LETTER = {"XY": "X", "YZ": "Y", "XZ": "Z"}


@dataclass(frozen=True)
class SkewCorrection:
    """The lines that set a firmware's skew correction.

    Attributes
    ----------
    firmware : str
        ``"klipper"``, ``"marlin"`` or ``"rrf"``.
    squareness_rad : dict of str to float
        Squareness per plane given (``"XY"``, ``"XZ"``, ``"YZ"``), included angle minus 90 deg, rad.
    factors : dict of str to float
        The firmware's own factor per plane: Klipper's and Marlin's ``xy/xz/yz`` skew factor
        (``-tan s``), RepRapFirmware's ``tanXY/tanXZ/tanYZ`` (``+tan s``).
    lines : tuple of str
        The G-code line(s) to send.
    notes : tuple of str
        What the firmware needs besides (configuration sections, defines, how to keep the setting).
    square_m : float
        Side of the square the lengths refer to (Klipper, RepRapFirmware), metres.
    """

    firmware: str
    squareness_rad: dict[str, float]
    factors: dict[str, float]
    lines: tuple[str, ...]
    notes: tuple[str, ...]
    square_m: float

    def text(self) -> str:
        """The notes as ``;`` comment lines, then the lines (G-code, one per line)."""
        return "".join(f"; {note}\n" for note in self.notes) + "".join(f"{line}\n" for line in self.lines)


def klipper_lengths(squareness_rad: float, square_m: float) -> tuple[float, float, float]:
    """Diagonals AC, BD and side AD of the square of side ``square_m`` a skewed machine draws, metres.

    The corners, as Klipper's and Marlin's documentation draw them: A at the plane's origin, D along
    the first axis, B along the second, C opposite A. With the included angle at A equal to
    ``90 deg + s``, ``AC = L sqrt(2 - 2 sin s)``, ``BD = L sqrt(2 + 2 sin s)``, ``AD = L``.

    Parameters
    ----------
    squareness_rad : float
        ``s``, included angle minus 90 deg, rad.
    square_m : float
        ``L``, metres.

    Returns
    -------
    tuple of float
        ``(AC, BD, AD)``, metres.

    Examples
    --------
    >>> [round(v * 1000, 6) for v in klipper_lengths(0.0, 0.1)]
    [141.421356, 141.421356, 100.0]
    """
    squareness_rad = check_number("squareness_rad", squareness_rad)
    square_m = check_number("square_m", square_m, positive=True)
    s = math.sin(squareness_rad)
    return square_m * math.sqrt(2.0 - 2.0 * s), square_m * math.sqrt(2.0 + 2.0 * s), square_m


def _check(planes: Mapping[str, float], square_m: float) -> None:
    if not planes:
        raise AxiscalError("no squareness given: give at least one of XY, XZ, YZ")
    for plane, value in planes.items():
        if plane not in SKEW_PLANES:
            raise AxiscalError(f"unknown plane '{plane}'; use one of {', '.join(SKEW_PLANES)}")
        if not math.isfinite(value):
            raise AxiscalError(f"the {plane} squareness must be a finite number")
        if abs(value) > MAX_SKEW_RAD:
            raise AxiscalError(
                f"the {plane} squareness {math.degrees(value):+.3f} deg is beyond {math.degrees(MAX_SKEW_RAD):g} deg:"
                " square the frame mechanically first (firmware skew correction is a small shear)"
            )
    if not math.isfinite(square_m) or square_m <= 0:
        raise AxiscalError(f"the square size must be a positive length, not {square_m / MM:g} mm")


def skew_correction(
    firmware: str,
    *,
    xy_rad: float | None = None,
    xz_rad: float | None = None,
    yz_rad: float | None = None,
    square_m: float = 0.1,
    convention: str = "included-angle",
) -> SkewCorrection:
    """The skew correction lines of a firmware for measured squareness.

    Parameters
    ----------
    firmware : str
        ``"klipper"``, ``"marlin"`` or ``"rrf"`` (RepRapFirmware).
    xy_rad, xz_rad, yz_rad : float, optional, keyword-only
        Squareness of each plane measured, rad, in ``convention``; planes not given are left as the
        firmware has them.
    square_m : float, keyword-only
        Side of the square the Klipper lengths and the RepRapFirmware deviations refer to, metres
        (default 0.1 m).
    convention : str, keyword-only
        ``"included-angle"`` (default): included angle between the positive axis directions minus
        90 deg, as ``axiscal squareness`` gives by default. ``"iso"``: the ISO 230-1 terms EC0Y
        (XY), EB0Z (XZ), EA0Z (YZ), right-hand-rule signs (EB0Z = -(included angle - 90 deg)).

    Returns
    -------
    SkewCorrection

    Raises
    ------
    AxiscalError
        For an unknown firmware or convention, no plane given, a non-finite value, a squareness
        beyond :data:`MAX_SKEW_RAD`, or a non-positive square size.

    Examples
    --------
    >>> from axiscal.units import ARCSEC
    >>> skew_correction("marlin", xy_rad=100 * ARCSEC).lines
    ('M852 I-0.00048481',)
    >>> skew_correction("rrf", xy_rad=100 * ARCSEC).lines
    ('M556 S100 X0.048481',)
    """
    check_choice("firmware", firmware, FIRMWARES)
    check_choice("convention", convention, SKEW_CONVENTIONS)
    for name, value in (("xy_rad", xy_rad), ("xz_rad", xz_rad), ("yz_rad", yz_rad)):
        if value is not None and not is_real(value):
            check_number(name, value)
    if not is_real(square_m):
        check_number("square_m", square_m, positive=True)
    given = {p: v for p, v in (("XY", xy_rad), ("XZ", xz_rad), ("YZ", yz_rad)) if v is not None}
    planes = {p: (v * _ISO_SIGN[p] if convention == "iso" else float(v)) for p, v in given.items()}
    _check(planes, square_m)
    square_mm = square_m / MM
    if firmware == "klipper":
        factors = {p.lower(): -math.tan(s) for p, s in planes.items()}
        parts = []
        for plane, s in planes.items():
            ac, bd, ad = (v / MM for v in klipper_lengths(s, square_m))
            parts.append(f"{plane}={ac:.6f},{bd:.6f},{ad:.6f}")
        lines = ("SET_SKEW " + " ".join(parts),)
        notes = (
            "Klipper: needs a [skew_correction] section in printer.cfg;"
            " SKEW_PROFILE SAVE=<name> then SAVE_CONFIG keeps the setting, SKEW_PROFILE LOAD=<name> restores it",
            f"AC,BD,AD: what a {square_mm:g} mm square printed without correction measures (Klipper calc_skew_factor turns them into the factor)",
        )
    elif firmware == "marlin":
        factors = {p.lower(): -math.tan(s) for p, s in planes.items()}
        lines = ("M852 " + " ".join(f"{_MARLIN_LETTER[p]}{factors[p.lower()]:.8f}" for p in planes),)
        notes = (
            "Marlin: needs SKEW_CORRECTION in Configuration.h"
            + ("" if set(planes) == {"XY"} else " and SKEW_CORRECTION_FOR_Z for J (XZ) and K (YZ)")
            + "; M500 stores the factors in EEPROM",
            *(f"or in Configuration.h: #define {p}_SKEW_FACTOR {factors[p.lower()]:.8f}" for p in planes),
        )
    else:
        factors = {p.lower(): math.tan(s) for p, s in planes.items()}
        deviations = " ".join(
            f"{_RRF_LETTER[p]}{factors[p.lower()] * square_mm:.6f}" for p in ("XY", "YZ", "XZ") if p in planes
        )
        lines = (f"M556 S{square_mm:g} {deviations}",)
        notes = (
            f"RepRapFirmware: M556 deviations over S = {square_mm:g} mm (tangent = deviation / S);"
            " put the line in config.g to keep it",
        )
    return SkewCorrection(
        firmware=firmware, squareness_rad=planes, factors=factors, lines=lines, notes=notes, square_m=square_m
    )


def squareness_from_results(paths: Sequence[str | Path]) -> dict[str, float]:
    """Squareness per plane from the JSON output of ``axiscal squareness --json``, one file per plane.

    Parameters
    ----------
    paths : sequence of str or Path
        The result files.

    Returns
    -------
    dict of str to float
        Plane (``"XY"``, ``"XZ"``, ``"YZ"``) to included angle minus 90 deg, rad (taken from
        ``included_angle_deg``, whatever convention the file was written in).

    Raises
    ------
    AxiscalError
        Naming the file: not a squareness result (no ``plane`` or ``included_angle_deg``), an
        unknown plane, or the same plane in two files.
    """
    if isinstance(paths, (str, os.PathLike)) or not isinstance(paths, Iterable):
        raise AxiscalError(f"paths must be a list of result files, not {paths!r}")
    paths = [check_path("paths", path) for path in paths]
    planes: dict[str, float] = {}
    for path in paths:
        body = read_json(path)
        if not isinstance(body, dict) or "plane" not in body or "included_angle_deg" not in body:
            raise AxiscalError(
                "not a squareness result: expected the JSON of 'axiscal squareness --json' (plane, included_angle_deg)",
                path=path,
            )
        plane = str(body["plane"]).upper()
        if plane not in SKEW_PLANES:
            raise AxiscalError(f"unknown plane '{body['plane']}'", path=path)
        if plane in planes:
            raise AxiscalError(f"a second {plane} result; give one file per plane", path=path)
        try:
            angle = float(body["included_angle_deg"])
        except (TypeError, ValueError):
            raise AxiscalError(f"included_angle_deg is {body['included_angle_deg']!r}, not a number", path=path) from None
        planes[plane] = math.radians(angle - 90.0)
    return planes
