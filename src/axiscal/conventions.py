"""Names and orders fixed once for the whole project (ISO 230-1 error names).

Every linear axis has six error motions named ``E`` + error direction + moving axis (``EXX`` the
positioning error of X, ``EYX`` and ``EZX`` its straightness, ``EAX`` its roll, ``EBX`` and
``ECX`` its pitch and yaw). Everywhere in the code the six come in the order translations x, y,
z, then rotations about x, y, z. Squareness errors between axes carry ISO 230-1's short names
(``EC0Y``, ``EB0Z``, ``EA0Z``). Signs and the error matrix are set out in docs/conventions.md.
"""

from __future__ import annotations

from axiscal.errors import AxiscalError

__all__ = ["LETTERS", "AXIS_INDEX", "COMPONENT_KINDS", "SQUARENESS_TERMS", "component_names"]

#: the linear axes
LETTERS = ("X", "Y", "Z")
#: index of each linear axis in a position or error vector
AXIS_INDEX = {"X": 0, "Y": 1, "Z": 2}
#: order of the six components everywhere in the code: translations x, y, z, then rotations a, b, c
COMPONENT_KINDS = ("tx", "ty", "tz", "ea", "eb", "ec")
#: squareness terms of a linear machine: rotation of the second axis about Z, Y, X
SQUARENESS_TERMS = ("EC0Y", "EB0Z", "EA0Z")


def component_names(letter: str) -> tuple[str, ...]:
    """ISO 230-1 names of the six error motions of axis ``letter``, in the order tx, ty, tz, a, b, c.

    Parameters
    ----------
    letter : str
        ``"X"``, ``"Y"`` or ``"Z"``.

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
    """
    if letter not in LETTERS:
        raise AxiscalError(f"unknown linear axis '{letter}'; axes are X, Y, Z")
    return tuple(f"E{d}{letter}" for d in ("X", "Y", "Z", "A", "B", "C"))
