"""Names and orders fixed once for the whole project (ISO 230-1 error names).

Every linear axis has six error motions named ``E`` + error direction + moving axis (``EXX`` the
positioning error of X, ``EYX`` and ``EZX`` its straightness, ``EAX`` its roll, ``EBX`` and
``ECX`` its pitch and yaw). Everywhere in the code the six come in the order translations x, y,
z, then rotations about x, y, z. Squareness errors between axes carry ISO 230-1's short names
(``EC0Y``, ``EB0Z``, ``EA0Z``). Signs and the error matrix are set out in docs/conventions.md.

Rotary axes A, B, C turn about X, Y, Z, positive by the right-hand rule (ISO 841). Their six error
motions follow the same pattern (``EXC, EYC`` radial, ``EZC`` axial, ``EAC, EBC`` tilt, ``ECC``
angular positioning for C), and the location errors of their average line follow ISO 230-7
(``EX0C, EY0C`` position, ``EA0C, EB0C`` orientation for C).
"""

from __future__ import annotations

from axiscal.errors import AxiscalError

__all__ = [
    "LETTERS",
    "AXIS_INDEX",
    "ROTARY_LETTERS",
    "ROTARY_INDEX",
    "COMPONENT_KINDS",
    "SQUARENESS_TERMS",
    "PLANES",
    "component_names",
    "location_names",
]

#: the linear axes
LETTERS = ("X", "Y", "Z")
#: index of each linear axis in a position or error vector
AXIS_INDEX = {"X": 0, "Y": 1, "Z": 2}
#: the rotary axes, turning about X, Y, Z (ISO 841)
ROTARY_LETTERS = ("A", "B", "C")
#: index of the linear axis each rotary axis turns about
ROTARY_INDEX = {"A": 0, "B": 1, "C": 2}
#: order of the six components everywhere in the code: translations x, y, z, then rotations a, b, c
COMPONENT_KINDS = ("tx", "ty", "tz", "ea", "eb", "ec")
#: squareness terms of a linear machine: rotation of the second axis about Z, Y, X
SQUARENESS_TERMS = ("EC0Y", "EB0Z", "EA0Z")
#: plane -> (first axis, second axis, its ISO 230-1 squareness term, sign of that term against
#: the included angle minus 90 degrees; docs/conventions.md)
PLANES: dict[str, tuple[str, str, str, int]] = {
    "XY": ("X", "Y", "EC0Y", 1),
    "XZ": ("X", "Z", "EB0Z", -1),
    "YZ": ("Y", "Z", "EA0Z", 1),
}


def component_names(letter: str) -> tuple[str, ...]:
    """ISO 230-1 names of the six error motions of axis ``letter``, in the order tx, ty, tz, a, b, c.

    Parameters
    ----------
    letter : str
        ``"X"``, ``"Y"``, ``"Z"`` or a rotary axis ``"A"``, ``"B"``, ``"C"``.

    Returns
    -------
    tuple of str
        Six names.

    Raises
    ------
    AxiscalError
        For any other letter.

    Examples
    --------
    >>> component_names("X")
    ('EXX', 'EYX', 'EZX', 'EAX', 'EBX', 'ECX')
    >>> component_names("C")
    ('EXC', 'EYC', 'EZC', 'EAC', 'EBC', 'ECC')
    """
    if letter not in LETTERS + ROTARY_LETTERS:
        raise AxiscalError(f"unknown axis '{letter!r}'; axes are X, Y, Z, A, B, C")
    return tuple(f"E{d}{letter}" for d in ("X", "Y", "Z", "A", "B", "C"))


def location_names(letter: str) -> tuple[str, ...]:
    """ISO 230-7 names of the four location errors of rotary axis ``letter``'s average line.

    Parameters
    ----------
    letter : str
        ``"A"``, ``"B"`` or ``"C"``.

    Returns
    -------
    tuple of str
        The two position errors (along the two linear axes normal to the rotary axis), then the
        two orientation errors (about those axes).

    Raises
    ------
    AxiscalError
        For any other letter.

    Examples
    --------
    >>> location_names("C")
    ('EX0C', 'EY0C', 'EA0C', 'EB0C')
    """
    if letter not in ROTARY_LETTERS:
        raise AxiscalError(f"unknown rotary axis '{letter!r}'; rotary axes are A, B, C")
    normal = [k for k in LETTERS if LETTERS.index(k) != ROTARY_INDEX[letter]]
    turned = [ROTARY_LETTERS[LETTERS.index(k)] for k in normal]
    return tuple(f"E{k}0{letter}" for k in normal) + tuple(f"E{k}0{letter}" for k in turned)
