"""An axis of a machine and the chain notation: workpiece-side axes, ``F`` (the frame), tool-side axes (ISO 10791, ISO 230-1).

``"XFYZ"``: the table moves X, the column carries Y and Z. Where each squareness term sits in the
chain is stated here once (docs/conventions.md); :class:`~axiscal.model.chain.Machine` builds on it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from axiscal.conventions import ROTARY_LETTERS
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_choice, check_instance
from axiscal.io.formats.machine import SQUARENESS_PLACEMENTS as _FORMAT_PLACEMENTS
from axiscal.model.kinematics import AXIS_INDEX
from axiscal.model.tables import ErrorTable, _floats

__all__ = [
    "SQUARENESS_PLACEMENTS",
    "Axis",
    "parse_chain",
]

#: squareness term -> (axis whose guideway it turns, reference axis, index of the rotation vector component)
_SQUARENESS_PLACE = {"EC0Y": ("Y", "X", 2), "EB0Z": ("Z", "X", 1), "EA0Z": ("Z", "Y", 0)}
#: where a squareness term sits in the chain; the first is the default (docs/conventions.md)
SQUARENESS_PLACEMENTS = _FORMAT_PLACEMENTS


@dataclass(frozen=True)
class Axis:
    """One linear axis of a machine: its letter, error table and carriage origin.

    Parameters
    ----------
    letter : str
        X, Y or Z.
    table : ErrorTable, optional
        Its six error motions; None (default) for an ideal axis.
    origin_m : tuple of 3 floats
        Origin of the carriage frame at position 0 in its parent's frame, metres.
    """

    letter: str
    table: ErrorTable | None = None
    origin_m: tuple[float, float, float] = (0.0, 0.0, 0.0)

    def __post_init__(self) -> None:
        check_choice("letter", self.letter, ("X", "Y", "Z", *ROTARY_LETTERS))
        if self.table is not None:
            check_instance("table", self.table, ErrorTable)
            if self.table.letter != self.letter:
                raise AxiscalError(f"table is the error table of axis {self.table.letter}, not of axis {self.letter}")
        origin = _floats(self.origin_m, f"axis {self.letter}: origin_m")
        if origin.shape != (3,) or not np.all(np.isfinite(origin)):
            raise AxiscalError(f"axis {self.letter}: origin_m must be 3 finite numbers of metres, not {self.origin_m!r:.60}")


def parse_chain(chain: str) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """Split a kinematic chain into its workpiece-side and tool-side axes (ISO 10791 notation).

    Parameters
    ----------
    chain : str
        Workpiece-side axes, ``F`` (the frame), tool-side axes, e.g. ``"XFYZ"`` or ``"CAFXYZ"`` (a
        trunnion); up to 3 linear axes X, Y, Z and up to 3 rotary axes A, B, C, each at most once,
        at least one axis (case and surrounding blanks are ignored).

    Returns
    -------
    workpiece_side, tool_side : tuple of str
        Each branch ordered from the frame outward.

    Raises
    ------
    AxiscalError
        Not a string, no or several ``F``, a letter that is not an axis, an axis named twice,
        or no axis.

    Examples
    --------
    >>> parse_chain("YXFZ")
    (('X', 'Y'), ('Z',))
    """
    if not isinstance(chain, str):
        raise AxiscalError(f"a chain is a string such as 'XFYZ', not {chain!r}")
    chain = chain.strip().upper()
    if chain.count("F") != 1:
        raise AxiscalError(f"chain '{chain}' must contain exactly one 'F' (the frame), e.g. 'XFYZ'")
    left, right = chain.split("F")
    letters = left + right
    for letter in letters:
        if letter not in AXIS_INDEX and letter not in ROTARY_LETTERS:
            raise AxiscalError(f"chain '{chain}': '{letter}' is not a linear axis (X, Y, Z) or a rotary axis (A, B, C)")
    if len(set(letters)) != len(letters):
        raise AxiscalError(f"chain '{chain}' names an axis twice")
    if not letters:
        raise AxiscalError(f"chain '{chain}' must have at least one axis")
    return tuple(reversed(left)), tuple(right)
