"""The squareness sign conventions, stated once: ISO 230-1 terms and signs per plane, and the included-angle convention beside them.

ISO 230-1 names and signs of the squareness terms: EC0Y (XY plane), EB0Z (XZ), EA0Z (YZ).

Sign conventions (docs/squareness.md has the picture)
-------------------------------------------------------
* ``"included-angle"`` (the default): squareness = included angle between the positive directions
  of the two axes minus 90 degrees; positive when the axes open wider than a right angle (paper
  002 eqs 1 and 21; paper 004's values read the same way, see :mod:`axiscal.squareness.cmm`).
* ``"iso"``: the ISO 230-1 rotation of the second axis about the third axis by the right-hand rule:
  ``EC0Y = +s`` (XY), ``EB0Z = -s`` (XZ), ``EA0Z = +s`` (YZ), with ``s`` the included-angle value.
  The XZ sign flips because turning +Z about +Y moves it towards +X, closing the angle.
"""

from __future__ import annotations

from axiscal.conventions import PLANES
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_number

__all__ = [
    "PLANES",
    "CONVENTIONS",
    "iso_term",
    "squareness_name",
    "iso_from_included_angle",
    "included_angle_from_iso",
]


#: plane -> (first axis, second axis, ISO 230-1 term, sign of the ISO term against the included-angle value)
CONVENTIONS = ("included-angle", "iso")


def _plane(plane: str) -> tuple[str, str, str, int]:
    try:
        return PLANES[plane.upper()]
    except (KeyError, AttributeError):
        raise AxiscalError(f"unknown plane '{plane}'; use one of {', '.join(PLANES)}") from None


def iso_term(plane: str) -> str:
    """ISO 230-1 name of the squareness of ``plane``: XY -> EC0Y, XZ -> EB0Z, YZ -> EA0Z.

    Parameters
    ----------
    plane : {"XY", "XZ", "YZ"}
        The plane (any case).

    Returns
    -------
    str

    Raises
    ------
    AxiscalError
        An unknown plane.

    Examples
    --------
    >>> iso_term("xz")
    'EB0Z'
    """
    return _plane(plane)[2]


def squareness_name(plane: str, convention: str) -> str:
    """The name a squareness figure is shown under, saying its sign convention (docs/conventions.md).

    One figure, one sign: the verdict table, the report's section, the plot and the text name the
    judged squareness alike, so that its sign is read one way everywhere.

    Parameters
    ----------
    plane : {"XY", "XZ", "YZ"}
        The plane (any case).
    convention : {"included-angle", "iso"}
        ``"iso"``: the ISO 230-1 term (right-hand rule); ``"included-angle"``: the included angle
        of the positive axis directions minus 90 degrees.

    Returns
    -------
    str
        ``"EB0Z (ISO 230-1)"`` or ``"XZ included angle - 90 deg"``.

    Raises
    ------
    AxiscalError
        An unknown plane or convention.

    Examples
    --------
    >>> squareness_name("xz", "iso"), squareness_name("XY", "included-angle")
    ('EB0Z (ISO 230-1)', 'XY included angle - 90 deg')
    """
    first, second, term, _ = _plane(plane)
    if convention not in CONVENTIONS:
        raise AxiscalError(f"convention must be one of {', '.join(CONVENTIONS)}, not {convention!r}")
    return f"{term} (ISO 230-1)" if convention == "iso" else f"{first}{second} included angle - 90 deg"


def iso_from_included_angle(squareness_rad: float, *, plane: str) -> float:
    """ISO 230-1 squareness term from the included-angle value (included angle - 90 deg), rad.

    ``EC0Y = s_XY``, ``EB0Z = -s_XZ``, ``EA0Z = s_YZ``.

    Parameters
    ----------
    squareness_rad : float
        The value, radians.
    plane : {"XY", "XZ", "YZ"}, keyword-only

    Returns
    -------
    float
        Radians.

    Raises
    ------
    AxiscalError
        An unknown plane.

    Examples
    --------
    >>> iso_from_included_angle(1e-5, plane="XZ")
    -1e-05
    """
    return _plane(plane)[3] * check_number("squareness_rad", squareness_rad)


def included_angle_from_iso(iso_value_rad: float, *, plane: str) -> float:
    """Included angle minus 90 deg from the ISO 230-1 term of ``plane``, rad (the inverse).

    Parameters
    ----------
    iso_value_rad : float
        The value, radians.
    plane : {"XY", "XZ", "YZ"}, keyword-only

    Returns
    -------
    float
        Radians.

    Raises
    ------
    AxiscalError
        An unknown plane.

    Examples
    --------
    >>> included_angle_from_iso(1e-5, plane="XZ")
    -1e-05
    """
    return _plane(plane)[3] * check_number("iso_value_rad", iso_value_rad)
