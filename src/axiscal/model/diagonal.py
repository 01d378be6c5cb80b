"""Diagonal displacement test from the machine model (ISO 230-6; paper 000 eq 13).

A laser interferometer aligned along a face or body diagonal, zeroed at the start point, reads the
displacement of the tool point along the diagonal while all axes move together. The model predicts
that reading: the actual tool point at step i is ``A_i = nominal_i + e_i`` and the reading is
``(A_i - A_0) · u`` with ``u`` the nominal diagonal direction (``measure="projection"``, ISO 230-6),
or ``|A_i - A_0|`` (``measure="length"``, the form of paper 000 eq 13). They differ by the square
of the lateral error over twice the length: well below a nanometre for errors of micrometres.

Paper 000 eq (13) compares the interferometer reading P with the nominal diagonal length
(``E_BD``, error before the model) and with the model's prediction (``E_AD``, after the model).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.model.machine import Machine

__all__ = ["MEASURES", "DiagonalResult", "diagonal_positions", "diagonal_check"]

MEASURES = ("projection", "length")


@dataclass(frozen=True)
class DiagonalResult:
    """A diagonal test predicted by the model, and compared with readings when given (SI units).

    Attributes
    ----------
    positions_m : dict of str to ndarray, shape (N,)
        Axis positions of each step.
    nominal_m : ndarray, shape (N,)
        Nominal displacement along the diagonal from the start point.
    predicted_m : ndarray, shape (N,)
        Displacement the model predicts an interferometer reads.
    model_error_m : ndarray, shape (N,)
        ``predicted - nominal``: the diagonal displacement error the model predicts.
    measured_m : ndarray or None
        Interferometer readings P.
    error_before_m, error_after_m : ndarray or None
        Paper 000 eq (13): ``E_BD = nominal - P`` and ``E_AD = predicted - P``.
    """

    positions_m: dict[str, np.ndarray]
    nominal_m: np.ndarray
    predicted_m: np.ndarray
    model_error_m: np.ndarray
    measured_m: np.ndarray | None
    error_before_m: np.ndarray | None
    error_after_m: np.ndarray | None
    measure: str

    @property
    def range_before_m(self) -> float:
        """Peak-to-valley of E_BD (NaN without readings)."""
        return float(np.ptp(self.error_before_m)) if self.error_before_m is not None else float("nan")

    @property
    def range_after_m(self) -> float:
        """Peak-to-valley of E_AD (NaN without readings)."""
        return float(np.ptp(self.error_after_m)) if self.error_after_m is not None else float("nan")


def diagonal_positions(start_m: Mapping[str, float], end_m: Mapping[str, float], steps: int) -> dict[str, np.ndarray]:
    """``steps + 1`` evenly spaced axis positions from ``start_m`` to ``end_m`` (all axes move together)."""
    if set(start_m) != set(end_m):
        raise AxiscalError(f"start and end name different axes ({sorted(start_m)} vs {sorted(end_m)})")
    if steps < 1:
        raise AxiscalError("a diagonal needs at least 1 step")
    fraction = np.linspace(0.0, 1.0, steps + 1)
    return {k: start_m[k] + (end_m[k] - start_m[k]) * fraction for k in start_m}


def diagonal_check(
    machine: Machine,
    start_m: Mapping[str, float],
    end_m: Mapping[str, float],
    steps: int,
    *,
    measured_m: np.ndarray | None = None,
    measure: str = "projection",
) -> DiagonalResult:
    """Predict (and compare with readings) a diagonal displacement test.

    Parameters
    ----------
    machine : Machine
    start_m, end_m : mapping of str to float
        Axis positions of the first and last point, metres; every axis of the chain.
    steps : int
        Number of intervals; the test has ``steps + 1`` points.
    measured_m : ndarray, shape (steps + 1,), optional
        Interferometer readings (zeroed at the start), metres.
    measure : {"projection", "length"}
        How the reading is formed from the actual points (module docstring).
    """
    if measure not in MEASURES:
        raise AxiscalError(f"unknown measure '{measure}'; use one of {', '.join(MEASURES)}")
    positions = diagonal_positions(start_m, end_m, steps)
    missing = sorted(set(machine.letters) - set(positions))
    if missing:
        raise AxiscalError(f"the diagonal must give a start and end for axis {', '.join(missing)}")
    nominal_points = machine.nominal_point(positions)
    actual_points = nominal_points + machine.volumetric_error(positions)
    span = nominal_points[-1] - nominal_points[0]
    length = float(np.linalg.norm(span))
    if length == 0.0:
        raise AxiscalError("the diagonal's start and end are the same point")
    direction = span / length
    nominal = (nominal_points - nominal_points[0]) @ direction
    moved = actual_points - actual_points[0]
    predicted = moved @ direction if measure == "projection" else np.linalg.norm(moved, axis=1)
    before = after = None
    if measured_m is not None:
        measured_m = np.asarray(measured_m, dtype=float)
        if measured_m.shape != nominal.shape:
            raise AxiscalError(f"{measured_m.size} interferometer readings for a diagonal of {nominal.size} points")
        before = nominal - measured_m
        after = predicted - measured_m
    return DiagonalResult(
        positions_m=positions,
        nominal_m=nominal,
        predicted_m=predicted,
        model_error_m=predicted - nominal,
        measured_m=measured_m,
        error_before_m=before,
        error_after_m=after,
        measure=measure,
    )
