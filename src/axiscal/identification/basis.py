"""Error functions of an axis for identification: Legendre polynomials or linear splines in the normalised position.

An error motion ``f(q)`` of an axis over its travel ``[a, b]`` is written in the normalised position
``u = 2 (q - a) / (b - a) - 1`` (``u`` from -1 to 1) as a sum of basis functions with unknown
coefficients, the polynomial error functions of the ball-plate analyses (Kunzmann, Trapet and
Waeldele, CIRP Annals 39/1, 1990; MSLNZ ls_cmm_error_map):

- ``poly:N``: ``φ_k(u) = P_k(u) - P_k(-1)``, ``k = 1 .. N``, ``P_k`` the Legendre polynomial of degree k;
- ``spline:K``: a linear spline on K equal intervals (K + 1 knots): ``φ_j`` is the hat function of
  knot j (``j = 1 .. K``), so the coefficients are the error's values at the knots.

Terms that no artefact can tell from the artefact's pose (a rigid-body motion) are left out
explicitly, not fitted and left to chance:

- every error motion is zero at the start of the travel (no constant term: a constant translation
  of any axis is a translation of the whole workspace, a constant rotation a rotation plus a
  squareness and an Abbe offset);
- a straightness error motion has no linear term: its slope is a rigid rotation or a squareness,
  which the squareness terms ``EC0Y, EB0Z, EA0Z`` carry. For ``poly:N`` this drops ``k = 1``
  (the other ``P_k`` are orthogonal to every line, so the reference line is the least-squares
  line); for ``spline:K`` the last knot is zero too (the reference line joins the end points).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.polynomial import legendre

from axiscal.errors import AxiscalError

__all__ = ["MODEL_KINDS", "MAX_MODEL_ORDER", "ErrorModel", "parse_model"]

#: the families of error functions
MODEL_KINDS = ("poly", "spline")
#: highest polynomial degree or number of spline intervals accepted
MAX_MODEL_ORDER = 40


@dataclass(frozen=True)
class ErrorModel:
    """A family of error functions: ``poly`` of degree ``order`` or ``spline`` of ``order`` intervals.

    Parameters
    ----------
    kind : {"poly", "spline"}
        Legendre polynomials or a linear spline.
    order : int
        Polynomial degree N (1 to 40) or number of spline intervals K (1 to 40).

    Examples
    --------
    >>> model = parse_model("poly:3")
    >>> model.labels(straightness=False), model.labels(straightness=True)
    ((1, 2, 3), (2, 3))
    """

    kind: str
    order: int

    def __post_init__(self) -> None:
        if self.kind not in MODEL_KINDS:
            raise AxiscalError(f"unknown error model '{self.kind}'; use poly:N or spline:K")
        if isinstance(self.order, bool) or not isinstance(self.order, (int, np.integer)) or not 1 <= self.order <= MAX_MODEL_ORDER:
            raise AxiscalError(f"the order of an error model is a whole number from 1 to {MAX_MODEL_ORDER}, not {self.order!r}")

    @property
    def text(self) -> str:
        """The model as written on the command line (``"poly:3"``)."""
        return f"{self.kind}:{self.order}"

    def labels(self, *, straightness: bool) -> tuple[int, ...]:
        """The basis functions used for one error motion: degrees (poly) or knots (spline).

        Parameters
        ----------
        straightness : bool, keyword-only
            A straightness motion (no linear term).

        Returns
        -------
        tuple of int
            May be empty (``poly:1`` or ``spline:1`` for a straightness motion).
        """
        if self.kind == "poly":
            return tuple(range(2 if straightness else 1, self.order + 1))
        return tuple(range(1, self.order if straightness else self.order + 1))

    def evaluate(self, label: int, u: np.ndarray) -> np.ndarray:
        """Basis function ``label`` at normalised positions ``u`` (-1 at the start of the travel, 1 at its end).

        Parameters
        ----------
        label : int
            A degree (poly) or a knot (spline) of :meth:`labels`.
        u : ndarray, shape (N,)
            Normalised positions.

        Returns
        -------
        ndarray, shape (N,)
            Dimensionless; zero at ``u = -1``.
        """
        if self.kind == "poly":
            c = np.zeros(label + 1)
            c[label] = 1.0
            return legendre.legval(u, c) - legendre.legval(-1.0, c)
        knots = np.linspace(-1.0, 1.0, self.order + 1)
        values = np.zeros(self.order + 1)
        values[label] = 1.0
        return np.interp(u, knots, values)

    def table_positions(self, start: float, end: float) -> np.ndarray:
        """Positions at which an identified error function is written as a table.

        Parameters
        ----------
        start, end : float
            The travel, metres or radians.

        Returns
        -------
        ndarray
            The knots of a spline (its table is then exact with linear interpolation); 101 points
            for a polynomial (cubic interpolation of them is within 1e-6 of the polynomial's range).
        """
        count = self.order + 1 if self.kind == "spline" else 101
        return np.linspace(start, end, count)


def parse_model(text: str | ErrorModel) -> ErrorModel:
    """Read ``"poly:N"`` or ``"spline:K"``.

    Parameters
    ----------
    text : str or ErrorModel
        The model as written on the command line, or a model (returned as it is).

    Returns
    -------
    ErrorModel

    Raises
    ------
    AxiscalError
        Any other text, or an order outside 1 to 40.
    """
    if isinstance(text, ErrorModel):
        return text
    if not isinstance(text, str):
        raise AxiscalError(f"an error model is a text such as 'poly:3' or 'spline:8', not {text!r:.40}")
    kind, sep, order = text.strip().partition(":")
    if not sep or kind not in MODEL_KINDS or not order.strip().isdigit():
        raise AxiscalError(f"error model '{text}': use poly:N (Legendre polynomials of degree N) or spline:K (K intervals)")
    return ErrorModel(kind, int(order))
