"""Diagonal displacement test from the machine model (ISO 230-6; paper 000 eq 13).

A laser interferometer aligned along a face or body diagonal, zeroed at the start point, reads the
displacement of the tool point along the diagonal while all axes move together. The model predicts
that reading: the actual tool point at step i is ``A_i = nominal_i + e_i`` and the reading is
``(A_i - A_0) · u`` with ``u`` the nominal diagonal direction (``measure="projection"``, ISO 230-6),
or ``|A_i - A_0|`` (``measure="length"``, the form of paper 000 eq 13). They differ by the square
of the lateral error over twice the length: well below a nanometre for errors of micrometres.

Every error here is **actual minus nominal along the diagonal** (docs/conventions.md): the model's
error is ``predicted - nominal``; with interferometer readings P, the error before the model is
``E_BD = P - nominal`` and after it ``E_AD = P - predicted`` (what is left once the model's
prediction is the nominal). Paper 000 eq (13) writes both with the opposite sign
(``nominal - P``, ``predicted - P``).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_choice, check_instance
from axiscal.model.inputs import check_travel, parse_point, read_interferometer
from axiscal.model.machine import Machine, as_machine
from axiscal.model.output import SIGN_CONVENTION, TableResult, render_template
from axiscal.units import MM, UM

__all__ = ["MEASURES", "DEFAULT_STEPS", "MAX_DIAGONAL_STEPS", "DiagonalResult", "diagonal_positions", "diagonal_check", "diagonal_test"]

MEASURES = ("projection", "length")
#: intervals of a diagonal test when neither the caller nor the readings say
DEFAULT_STEPS = 10
#: most intervals of a diagonal test (a laser takes minutes per thousand points; more is a typing mistake)
MAX_DIAGONAL_STEPS = 1_000_000


@dataclass(frozen=True)
class DiagonalResult(TableResult):
    """A diagonal test predicted by the model, and compared with readings when given (SI units).

    Every error is actual minus nominal along the diagonal (module docstring).

    Attributes
    ----------
    positions_m : dict of str to ndarray, shape (N,)
        Axis positions of each step, in the machine's chain order.
    nominal_m : ndarray, shape (N,)
        Nominal displacement along the diagonal from the start point.
    predicted_m : ndarray, shape (N,)
        Displacement the model predicts an interferometer reads.
    model_error_m : ndarray, shape (N,)
        ``predicted - nominal``: the diagonal displacement error the model predicts.
    measured_m : ndarray or None
        Interferometer readings P.
    error_before_m : ndarray or None
        ``E_BD = P - nominal``: the measured error, without the model.
    error_after_m : ndarray or None
        ``E_AD = P - predicted``: the error left with the model.
    measure : {"projection", "length"}
        How the reading is formed from the actual points.
    name : str
        The machine's name (or chain), for reports.
    sources : tuple of str
        Files the test was computed from (machine, readings).
    """

    positions_m: dict[str, np.ndarray]
    nominal_m: np.ndarray
    predicted_m: np.ndarray
    model_error_m: np.ndarray
    measured_m: np.ndarray | None
    error_before_m: np.ndarray | None
    error_after_m: np.ndarray | None
    measure: str
    name: str = ""
    sources: tuple[str, ...] = field(default=())

    csv_format = "{:.6f}"
    csv_kind = "diagonal displacement test"

    @property
    def range_before_m(self) -> float:
        """Peak-to-valley of E_BD, metres (NaN without readings)."""
        return float(np.ptp(self.error_before_m)) if self.error_before_m is not None else float("nan")

    @property
    def range_after_m(self) -> float:
        """Peak-to-valley of E_AD, metres (NaN without readings)."""
        return float(np.ptp(self.error_after_m)) if self.error_after_m is not None else float("nan")

    @property
    def range_model_m(self) -> float:
        """Peak-to-valley of the model's error along the diagonal, metres."""
        return float(np.ptp(self.model_error_m))

    def columns(self) -> dict[str, np.ndarray]:
        """Per-point columns in display units (docs/formats.md).

        Returns
        -------
        dict of str to ndarray, shape (N,)
            ``<axis>_mm``, ``nominal_mm``, with readings ``measured_mm``, then ``model_error_um``
            and with readings ``E_BD_um``, ``E_AD_um``.
        """
        columns = {f"{k.lower()}_mm": q / MM for k, q in self.positions_m.items()}
        columns["nominal_mm"] = self.nominal_m / MM
        if self.measured_m is not None:
            columns["measured_mm"] = self.measured_m / MM
        columns["model_error_um"] = self.model_error_m / UM
        if self.error_before_m is not None and self.error_after_m is not None:
            columns["E_BD_um"] = self.error_before_m / UM
            columns["E_AD_um"] = self.error_after_m / UM
        return columns

    def sidecar_metadata(self) -> dict:
        """The summary without the points, for the sidecar.

        Returns
        -------
        dict
        """
        return {k: v for k, v in self.summary().items() if k != "points"}

    def summary(self) -> dict:
        """JSON-ready summary in display units (the output of ``axiscal diagonal --json``).

        Returns
        -------
        dict
            ``measure``, ``sign``, ``model_error_range_um``, with readings ``E_BD_range_um`` and
            ``E_AD_range_um``, and ``points`` (the columns, rounded to 6 decimals).
        """
        payload: dict = {"measure": self.measure, "sign": SIGN_CONVENTION, "model_error_range_um": self.range_model_m / UM}
        if self.measured_m is not None:
            payload["E_BD_range_um"] = self.range_before_m / UM
            payload["E_AD_range_um"] = self.range_after_m / UM
        payload["points"] = {k: np.round(v, 6) for k, v in self.columns().items()}
        return payload

    def text(self) -> str:
        """A few lines for a terminal: points, length and the P-V of each error.

        Returns
        -------
        str
            Rendered from the template ``model_diagonal.txt.j2``, ending in a newline.
        """
        return render_template(
            "model_diagonal.txt.j2",
            name=self.name,
            points=self.nominal_m.size,
            length_mm=float(self.nominal_m[-1] / MM),
            model_um=self.range_model_m / UM,
            before_um=None if self.measured_m is None else self.range_before_m / UM,
            after_um=None if self.measured_m is None else self.range_after_m / UM,
        )


def diagonal_positions(start_m: Mapping[str, float], end_m: Mapping[str, float], steps: int) -> dict[str, np.ndarray]:
    """Evenly spaced axis positions from a start to an end point, all axes moving together.

    Parameters
    ----------
    start_m, end_m : mapping of str to float
        Axis positions of the first and last point, metres; the same axes.
    steps : int
        Number of intervals.

    Returns
    -------
    dict of str to ndarray, shape (steps + 1,)
        Metres.

    Raises
    ------
    AxiscalError
        Different axes in start and end, a position that is not a finite number, or a number of
        steps that is not an integer from 1 to :data:`MAX_DIAGONAL_STEPS`.
    """
    if not isinstance(start_m, Mapping) or not isinstance(end_m, Mapping):
        raise AxiscalError("start and end must map axis letters to positions in metres")
    if set(start_m) != set(end_m):
        raise AxiscalError(f"start and end name different axes ({sorted(start_m)} vs {sorted(end_m)})")
    for point in (start_m, end_m):
        for letter, value in point.items():
            if isinstance(value, bool) or not isinstance(value, (int, float, np.number)) or not np.isfinite(value):
                raise AxiscalError(f"position of axis {letter} must be a finite number of metres, not {value!r}")
    if isinstance(steps, bool) or not isinstance(steps, (int, np.integer)) or not 1 <= steps <= MAX_DIAGONAL_STEPS:
        raise AxiscalError(f"a diagonal needs a whole number of steps from 1 to {MAX_DIAGONAL_STEPS}, not {steps!r}")
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

    Returns
    -------
    DiagonalResult
        Nominal and predicted displacements and, with readings, E_BD and E_AD (actual minus
        nominal along the diagonal).

    Raises
    ------
    AxiscalError
        An unknown measure, start and end naming different axes or not every axis of the chain,
        fewer than 1 step, a zero-length diagonal, or readings of the wrong length.

    Examples
    --------
    >>> result = diagonal_check(machine, {"X": 0.0, "Z": 0.0}, {"X": 0.19, "Z": 0.19}, 19)  # doctest: +SKIP
    >>> result.model_error_m  # predicted - nominal, metres  # doctest: +SKIP
    """
    check_instance("machine", machine, Machine)
    check_choice("measure", measure, MEASURES)
    if measured_m is not None:
        measured_m = check_array("measured_m", measured_m, ndim=1)
    positions = diagonal_positions(start_m, end_m, steps)
    missing = sorted(set(machine.letters) - set(positions))
    if missing:
        raise AxiscalError(f"the diagonal must give a start and end for axis {', '.join(missing)}")
    extra = sorted(set(positions) - set(machine.letters))
    if extra:
        raise AxiscalError(f"the diagonal names axis {', '.join(extra)}, which is not in chain '{machine.chain}'")
    positions = {k: positions[k] for k in machine.letters}
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
        before = measured_m - nominal
        after = measured_m - predicted
    return DiagonalResult(
        positions_m=positions,
        nominal_m=nominal,
        predicted_m=predicted,
        model_error_m=predicted - nominal,
        measured_m=measured_m,
        error_before_m=before,
        error_after_m=after,
        measure=measure,
        name=machine.name or machine.chain,
    )


def diagonal_test(
    machine: Machine | str | Path,
    start: Mapping[str, float] | str,
    end: Mapping[str, float] | str,
    *,
    steps: int | None = None,
    readings: np.ndarray | str | Path | None = None,
    measure: str = "projection",
) -> DiagonalResult:
    """The diagonal test of ``axiscal diagonal`` in one call: machine file, end points, readings file.

    Parameters
    ----------
    machine : Machine, str or Path
        The machine, or its description file (TOML, docs/formats.md).
    start, end : mapping of str to float, or str
        Axis positions of the first and last point: metres, or text in mm such as ``"X=0,Z=0"``.
    steps : int, optional
        Number of intervals (default: one fewer than the readings, else 10).
    readings : ndarray, str or Path, optional
        Interferometer readings zeroed at the start: metres, or a CSV ``nominal_mm, measured_mm``
        whose nominal column must match the diagonal's points.
    measure : {"projection", "length"}
        Reading as displacement along the diagonal (ISO 230-6) or as point distance (paper 000 eq 13).

    Returns
    -------
    DiagonalResult
        Errors actual minus nominal along the diagonal; ``sources`` names the files read.

    Raises
    ------
    AxiscalError
        A bad machine or readings file (naming file and line), bad end points, an end point
        outside an error table, or any reason of :func:`diagonal_check`.

    Examples
    --------
    >>> result = diagonal_test("machine.toml", "X=0,Z=0", "X=190,Z=190", readings="laser.csv")  # doctest: +SKIP
    >>> result.range_after_m  # doctest: +SKIP
    """
    check_choice("measure", measure, MEASURES)
    model = as_machine(machine)
    start_m = parse_point(start, "start") if isinstance(start, str) else start
    end_m = parse_point(end, "end") if isinstance(end, str) else end
    diagonal_positions(start_m, end_m, 1)  # the end points: mappings of finite numbers, same axes
    sources = [str(machine)] if isinstance(machine, (str, Path)) else []
    measured = None
    if readings is not None and not isinstance(readings, (str, Path)):
        measured = check_array("readings", readings, ndim=1, min_len=2)
    if steps is None:
        if isinstance(readings, (str, Path)):
            steps = read_interferometer(readings).size - 1
        else:
            steps = measured.size - 1 if measured is not None else DEFAULT_STEPS
    check_travel(model, {k: np.array([start_m[k], end_m[k]]) for k in start_m if k in end_m}, path=None)
    result = diagonal_check(model, start_m, end_m, steps, measure=measure)
    if isinstance(readings, (str, Path)):
        measured = read_interferometer(readings, result.nominal_m)
        sources.append(str(readings))
    if measured is not None:
        result = diagonal_check(model, start_m, end_m, steps, measured_m=measured, measure=measure)
    return replace(result, sources=tuple(sources))
