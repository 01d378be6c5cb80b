"""The maximum permissible error of a CMM length test as its maker states it (ISO 10360-2:2009, 5.1).

A length measurement error E0 (and E150, with the 150 mm ram offset) is stated in one of three forms:
``±(A + L/K)``, ``±min(A + L/K, B)`` or ``±B``, with A and B in micrometres, the length L in
millimetres and K a dimensionless number, so that ``L/K`` reads in micrometres: ``1.5 + L/333`` is
3.0 um at L = 500 mm. In SI the slope is ``1 / (1000 K)`` metres per metre.

A limit of a CMM test (A and B of an MPE, R0,MPL, a probing MPE, the test uncertainty) is at most
:data:`LIMIT_M` (10 mm, 10000 um), and K is from 1 to a million (L/K from 1 um per mm down): a
larger value is a typing or unit mistake that would turn every verdict into a pass.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_number
from axiscal.units import MM, UM

__all__ = ["LIMIT_M", "K_RANGE", "Mpe"]

#: the largest limit (A, B, R0,MPL, a probing MPE) or test uncertainty a CMM test takes, metres
LIMIT_M = 10e-3
#: the range of K (L in mm over K reads in um): 1 um per mm at most
K_RANGE = (1.0, 1e6)


@dataclass(frozen=True)
class Mpe:
    """A stated maximum permissible error ``±min(A + L/K, B)`` (K and B optional).

    Parameters
    ----------
    a_m : float
        A, metres (> 0, at most :data:`LIMIT_M`). Alone (no K, no B) it is the constant form ``±A``.
    k : float or None
        K, dimensionless (:data:`K_RANGE`): the length term is L/K with L in mm read as um.
    b_m : float or None
        B, the cap, metres (> 0, not below A, at most :data:`LIMIT_M`).

    Raises
    ------
    AxiscalError
        A non-positive or non-finite A, K or B, one beyond its range, or B below A.

    Examples
    --------
    >>> mpe = Mpe(1.5e-6, k=333.0, b_m=4e-6)
    >>> [round(float(v) * 1e6, 4) for v in mpe.at([0.0, 0.5, 1.0])]
    [1.5, 3.0015, 4.0]
    >>> mpe.statement()
    '±min(1.5 + L/333, 4) um, L in mm'
    """

    a_m: float
    k: float | None = None
    b_m: float | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "a_m", check_number("a_m", self.a_m, positive=True, high=LIMIT_M))
        if self.k is not None:
            object.__setattr__(self, "k", check_number("k", self.k, unit="", low=K_RANGE[0], high=K_RANGE[1]))
        if self.b_m is not None:
            b = check_number("b_m", self.b_m, positive=True, high=LIMIT_M)
            if b < self.a_m:
                raise AxiscalError(f"b_m (the cap B, {b / UM:g} um) must not be below a_m (A, {self.a_m / UM:g} um)")
            object.__setattr__(self, "b_m", b)

    def at(self, length_m: Any) -> np.ndarray:
        """The MPE at measured lengths.

        Parameters
        ----------
        length_m : array_like
            Lengths, metres (their magnitude is used).

        Returns
        -------
        ndarray
            MPE, metres, the shape of ``length_m``.
        """
        length = np.abs(check_array("length_m", length_m))
        return self._at(length)

    def _at(self, length: np.ndarray) -> np.ndarray:
        value = np.full(np.shape(length), self.a_m, dtype=float)
        if self.k is not None:
            value = value + length / MM / self.k * UM
        if self.b_m is not None:
            value = np.minimum(value, self.b_m)
        return value

    def statement(self) -> str:
        """The MPE as a data sheet writes it, e.g. ``±(1.5 + L/333) um, L in mm``."""
        a = f"{self.a_m / UM:g}"
        if self.k is None:
            return f"±{min(self.a_m, self.b_m or self.a_m) / UM:g} um"
        term = f"{a} + L/{self.k:g}"
        if self.b_m is None:
            return f"±({term}) um, L in mm"
        return f"±min({term}, {self.b_m / UM:g}) um, L in mm"

    def payload(self) -> dict[str, Any]:
        """``a_um``, ``k``, ``b_um`` (None where not stated) and ``statement``."""
        return {"a_um": self.a_m / UM, "k": self.k, "b_um": None if self.b_m is None else self.b_m / UM,
                "statement": self.statement()}
