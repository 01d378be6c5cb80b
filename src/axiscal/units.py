"""Unit suffixes used in file columns and CLI flags, and their factors to SI.

Columns and flags carry their unit in the name (``EXX_um``, ``EAX_arcsec``); inside the code every
value is SI (metres, radians). This module is the only place that knows the factors.
"""

from __future__ import annotations

import math

from axiscal.errors import AxiscalError

__all__ = [
    "LENGTH_UNITS",
    "ANGLE_UNITS",
    "ARCSEC",
    "ARCMIN",
    "URAD",
    "NM",
    "PPM",
    "UM",
    "MM",
    "INCH",
    "DEG",
    "split_unit",
    "length_factor",
    "angle_factor",
]

#: metres per unit, for translations
LENGTH_UNITS: dict[str, float] = {"nm": 1e-9, "um": 1e-6, "mm": 1e-3, "m": 1.0}
#: radians per unit, for rotations
ANGLE_UNITS: dict[str, float] = {
    "urad": 1e-6,
    "mrad": 1e-3,
    "rad": 1.0,
    "arcsec": math.pi / (180.0 * 3600.0),
    "arcmin": math.pi / (180.0 * 60.0),
    "deg": math.pi / 180.0,
}

ARCSEC = ANGLE_UNITS["arcsec"]
ARCMIN = ANGLE_UNITS["arcmin"]
URAD = ANGLE_UNITS["urad"]
#: parts per million, for ratios (n - 1, expansion)
PPM = 1e-6
NM = LENGTH_UNITS["nm"]
UM = LENGTH_UNITS["um"]
MM = LENGTH_UNITS["mm"]
#: metres per inch (exactly 25.4 mm, the international inch of 1959)
INCH = 25.4 * MM
#: radians per degree
DEG = ANGLE_UNITS["deg"]


def split_unit(name: str) -> tuple[str, str]:
    """Split ``"EXX_um"`` into ``("EXX", "um")``; raise if there is no ``_unit`` suffix."""
    stem, sep, unit = name.rpartition("_")
    if not sep or not stem:
        raise AxiscalError(f"'{name}' has no unit suffix (e.g. '{name}_um')")
    return stem, unit


def length_factor(unit: str, *, allowed: tuple[str, ...] = ("nm", "um", "mm"), what: str = "") -> float:
    """Metres per ``unit``; ``allowed`` restricts the suffixes accepted."""
    if unit not in allowed:
        raise AxiscalError(f"unknown length unit '{unit}'{' for ' + what if what else ''}; use one of {', '.join(allowed)}")
    return LENGTH_UNITS[unit]


def angle_factor(unit: str, *, allowed: tuple[str, ...] = ("urad", "mrad", "arcsec"), what: str = "") -> float:
    """Radians per ``unit``; ``allowed`` restricts the suffixes accepted."""
    if unit not in allowed:
        raise AxiscalError(f"unknown angle unit '{unit}'{' for ' + what if what else ''}; use one of {', '.join(allowed)}")
    return ANGLE_UNITS[unit]
