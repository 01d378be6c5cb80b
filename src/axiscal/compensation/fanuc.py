"""FANUC compensation table: pitch error compensation, parameters 3620-3627 and the incremental data.

After the parameter manual of Series 0i (B-63980EN): compensation point N at reference position +
(N - 3620) x 3624, each value the change of the correction over the section ending at point N, in
units of 3623 x the detection unit.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from axiscal.compensation.curve import ErrorCurve, _check_direction
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_count, check_instance, check_integer, check_number, check_optional_number
from axiscal.units import DEG, MM, UM

#: the largest axis number a FANUC parameter tape carries (Series 30i: 32 axes)
MAX_AXIS_NUMBER = 32

__all__ = ["MAX_AXIS_NUMBER", "FanucTable", "fanuc_table"]


@dataclass(frozen=True)
class FanucTable:
    """FANUC pitch error compensation of one axis: parameters and incremental data.

    Compensation point ``N`` sits at ``reference_position + (N - reference_point) * interval``;
    its value is the *change* of the correction over the interval that ends there (the section
    between points N-1 and N), in units of ``magnification * detection_unit``. The correction is
    zero at the reference position (it is cumulated from there), so a deviation the axis has at
    the reference position itself is not something the table can correct.

    Parameters written: 3620 reference point number, 3621 / 3622 the farthest points on the - / +
    side, 3623 magnification, 3624 interval (in input increments), and for bidirectional tables
    (3605#0 = 1) 3626 the first point of the table for travel in the - direction and 3627 the
    correction at the reference position when it is approached in the - direction.

    Attributes
    ----------
    reference_point : int
        Parameter 3620, the compensation point number of the reference position.
    reference_position_m : float, metres
        Machine position of the reference position.
    interval_m : float, metres
        Interval between compensation points (3624).
    magnification : int
        Parameter 3623.
    detection_unit_m : float, metres
        Detection unit of the axis; one compensation unit is ``magnification * detection_unit_m``.
    points : ndarray of int, shape (k,)
        Compensation point numbers 3621 .. 3622 (for a rotary axis 3621 is the reference point,
        which repeats the value of 3622; ``points`` then starts one after it).
    values : ndarray of int, shape (k,)
        Incremental values for travel in the + direction (or both directions when not bidirectional).
    values_down : ndarray of int, shape (k,) or None
        Incremental values for travel in the - direction (bidirectional table), points
        ``down_first .. down_first + k - 1``.
    down_first : int or None
        Parameter 3626, the first point of the - direction table (bidirectional), else None.
    reference_value_down : int
        Parameter 3627 (bidirectional), in compensation units.
    rotary : bool
        A rotary axis (one revolution from the reference point).
    input_increment_m : float, metres
        Unit of parameter 3624.
    axis_number : int
        Axis number written on the tape.
    reference_deviation_m : float
        The deviation at the reference position, which the table leaves uncorrected (of the +
        direction for a bidirectional table, which assumes the reference is approached in +; of
        the bidirectional mean otherwise), metres.

    Examples
    --------
    >>> from axiscal.compensation.curve import error_curve
    >>> from axiscal.positioning import paper003_table4_run, target_statistics
    >>> curve = error_curve(target_statistics(paper003_table4_run()))
    >>> table = fanuc_table(curve, interval_m=0.01)
    >>> table.points.tolist(), table.values.tolist()
    ([1, 2], [0, -1])
    """

    reference_point: int
    reference_position_m: float
    interval_m: float
    magnification: int
    detection_unit_m: float
    points: np.ndarray
    values: np.ndarray
    values_down: np.ndarray | None = None
    down_first: int | None = None
    reference_value_down: int = 0
    rotary: bool = False
    input_increment_m: float = UM
    axis_number: int = 1
    reference_deviation_m: float = 0.0

    @property
    def resolution(self) -> float:
        """One compensation unit, metres."""
        return self.magnification * self.detection_unit_m

    @property
    def nodes(self) -> np.ndarray:
        """Positions of the compensation points, metres, shape (k + 1,) including the start of the first section."""
        first = self.points[0] - 1
        return self.reference_position_m + (np.arange(first, self.points[-1] + 1) - self.reference_point) * self.interval_m

    def _absolute(self, values: np.ndarray, at_reference: int) -> np.ndarray:
        """Cumulated correction at every node (compensation units), zero (or 3627) at the reference."""
        first = self.points[0] - 1
        cumulative = np.concatenate([[0], np.cumsum(values)])
        k_ref = self.reference_point - first
        return cumulative - cumulative[k_ref] + at_reference

    def correction(self, x, direction: str) -> np.ndarray:
        """The correction at commanded positions ``x`` (metres), interpolated linearly between points.

        Exact at the compensation points. A control without interpolated pitch error compensation
        outputs each section's increment as a step at the compensation point, so between points it
        may differ from this by up to one increment (see docs/compensation.md).

        Parameters
        ----------
        x : float or array_like, metres
            Commanded positions.
        direction : {"+", "-"}
            Direction of travel (the - table of a bidirectional table for "-").

        Returns
        -------
        ndarray, shape of ``x``, metres
        """
        _check_direction(direction)
        if direction == "-" and self.values_down is not None:
            absolute = self._absolute(self.values_down, self.reference_value_down)
        else:
            absolute = self._absolute(self.values, 0)
        return np.interp(check_array("x", x, unit="metres"), self.nodes, absolute * self.resolution)

    def text(self) -> str:
        """The parameters and data as a FANUC parameter tape (``N<number>A<axis>P<value>`` / ``N<10000 + point>P<value>``)."""
        a = self.axis_number
        lines = [
            "%",
            f"N03620A{a}P{self.reference_point}",
            f"N03621A{a}P{self.reference_point if self.rotary else int(self.points[0])}",
            f"N03622A{a}P{int(self.points[-1])}",
            f"N03623A{a}P{self.magnification}",
            f"N03624A{a}P{round(self.interval_m / self.input_increment_m)}",
        ]
        if self.values_down is not None:
            lines += [f"N03626A{a}P{self.down_first}", f"N03627A{a}P{self.reference_value_down}"]
        data = dict(zip(self.points.tolist(), self.values.tolist()))
        if self.rotary:
            data[self.reference_point] = int(self.values[-1])
        if self.values_down is not None:
            data.update(zip(range(self.down_first, self.down_first + self.values_down.size), self.values_down.tolist()))
        lines += [f"N{10000 + p}P{v}" for p, v in sorted(data.items())]
        lines.append("%")
        return "\n".join(lines) + "\n"


# largest interval, unit or position a FANUC table takes, metres (or radians): beyond it a value
# has no physical meaning and the arithmetic would overflow
_LARGEST_M = 1e3


def fanuc_table(
    curve: ErrorCurve,
    *,
    interval_m: float,
    reference_position_m: float = 0.0,
    reference_point: int | None = None,
    magnification: int = 1,
    detection_unit_m: float = UM,
    bidirectional: bool = False,
    rotary: bool = False,
    travel_per_revolution: float | None = None,
    value_limit: int = 127,
    max_point: int = 1023,
    input_increment_m: float = UM,
    axis_number: int = 1,
) -> FanucTable:
    """FANUC pitch error compensation from the mean deviations.

    Parameters
    ----------
    curve : ErrorCurve
        Mean deviations per direction (positions in metres; radians for a rotary axis).
    interval_m : float, keyword-only
        Interval between compensation points (parameter 3624), metres (radians for rotary).
    reference_position_m : float, keyword-only
        Machine position of the reference position (default 0).
    reference_point : int, optional, keyword-only
        Compensation point number of the reference position (3620). Default: the smallest
        number that puts the farthest - point at 1.
    magnification : int, keyword-only
        Parameter 3623, 1..100: one compensation unit is ``magnification * detection_unit_m``.
    detection_unit_m : float, keyword-only
        Detection unit of the axis (default 1 um).
    bidirectional : bool, keyword-only
        Write a second table for travel in the - direction (3605#0 = 1, 3626, 3627). Without it
        the table holds the bidirectional mean deviation (the reversal is left to backlash
        compensation), and the reference position is assumed to be returned to in the +
        direction.
    rotary : bool, keyword-only
        Rotary axis: the table spans one revolution from the reference point, the values of
        points ``reference + 1 .. 3622`` sum to zero and point 3620 repeats the value of 3622.
    travel_per_revolution : float, keyword-only
        Needed with ``rotary``: one revolution in the unit of the positions (2 pi for radians).
    value_limit : int, keyword-only
        Largest magnitude of one incremental value (127 on Series 0i/16i).
    max_point : int, keyword-only
        Highest compensation point number the control has (1023 on Series 0i/16i).
    input_increment_m : float, keyword-only
        Unit of parameter 3624, metres (1 um, IS-B).
    axis_number : int, keyword-only
        The axis number written on the tape (default 1).

    Returns
    -------
    FanucTable
        Parameters and incremental values; ``reference_deviation_m`` is the deviation at the
        reference position that the table leaves to the reference position setting.

    Raises
    ------
    AxiscalError
        For a magnification outside 1..100, an interval that is not positive or not a whole
        number of input increments, a reference position outside the measured travel, points
        beyond 0..``max_point``, an increment larger than ``value_limit``, or a rotary axis
        without whole sections per revolution.

    Examples
    --------
    >>> from axiscal.compensation.curve import error_curve
    >>> from axiscal.positioning import paper003_table4_run, target_statistics
    >>> curve = error_curve(target_statistics(paper003_table4_run()))
    >>> print(fanuc_table(curve, interval_m=0.01).text(), end="")
    %
    N03620A1P0
    N03621A1P1
    N03622A1P2
    N03623A1P1
    N03624A1P10000
    N10001P0
    N10002P-1
    %
    """
    check_instance("curve", curve, ErrorCurve)
    for name, value in (("interval_m", interval_m), ("reference_position_m", reference_position_m),
                        ("detection_unit_m", detection_unit_m), ("input_increment_m", input_increment_m)):
        check_number(name, value, low=-_LARGEST_M, high=_LARGEST_M)
    check_optional_number("travel_per_revolution", travel_per_revolution, unit="", high=_LARGEST_M)
    for name, value in (("magnification", magnification), ("value_limit", value_limit), ("max_point", max_point),
                        ("axis_number", axis_number)):
        check_integer(name, value)
    if reference_point is not None:
        check_count("reference_point", reference_point, minimum=0)
    check_instance("bidirectional", bidirectional, (bool, np.bool_))
    check_instance("rotary", rotary, (bool, np.bool_))
    if not 1 <= magnification <= 100:
        raise AxiscalError(f"FANUC pitch error magnification (parameter 3623) is 1..100, got {magnification}")
    # messages in the units of the axis: mm and um, or degrees for a rotary axis
    big, big_unit, small, small_unit = (DEG, "deg", DEG, "deg") if rotary else (MM, "mm", UM, "um")
    if not (math.isfinite(input_increment_m) and input_increment_m > 0):
        raise AxiscalError(f"the input increment must be positive, got {input_increment_m / small:g} {small_unit}")
    if not (math.isfinite(interval_m) and interval_m > 0):
        raise AxiscalError(f"the compensation interval must be positive, got {interval_m / big:g} {big_unit}")
    if abs(interval_m / input_increment_m - round(interval_m / input_increment_m)) > 1e-6:
        raise AxiscalError(f"the interval {interval_m / big:g} {big_unit} is not a whole number of input increments")
    if not (math.isfinite(detection_unit_m) and detection_unit_m > 0):
        raise AxiscalError(f"the detection unit must be positive, got {detection_unit_m / small:g} {small_unit}")
    if not 1 <= axis_number <= MAX_AXIS_NUMBER:
        raise AxiscalError(f"the axis number on the parameter tape is 1..{MAX_AXIS_NUMBER}, got {axis_number}")
    if not math.isfinite(reference_position_m):
        raise AxiscalError("the reference position must be a finite number")
    unit = magnification * detection_unit_m
    lo, hi = float(curve.positions[0]), float(curve.positions[-1])
    span = travel_per_revolution if rotary and travel_per_revolution is not None else hi - lo
    if span > interval_m * (max_point + 1):
        raise AxiscalError(
            f"the interval {interval_m / big:g} {big_unit} gives more compensation points than 0..{max_point} hold; use a larger one"
        )
    if rotary:
        if travel_per_revolution is None or not (math.isfinite(travel_per_revolution) and travel_per_revolution > 0):
            raise AxiscalError("a rotary axis needs the travel per revolution (parameter 3625)")
        sections = travel_per_revolution / interval_m
        if abs(sections - round(sections)) > 1e-9:
            raise AxiscalError("for a rotary axis the interval must divide one revolution into whole sections")
        n_minus, n_plus = 0, int(round(sections))
    else:
        if not lo - 1e-12 <= reference_position_m <= hi + 1e-12:
            raise AxiscalError(
                f"the reference position {reference_position_m / MM:g} mm lies outside the measured travel"
                f" {lo / MM:g} .. {hi / MM:g} mm"
            )
        n_minus = int(math.ceil((reference_position_m - lo) / interval_m - 1e-9))
        n_plus = int(math.ceil((hi - reference_position_m) / interval_m - 1e-9))
    if reference_point is None:
        reference_point = n_minus
    # point N holds the section ending at node N; the first section starts n_minus intervals
    # below the reference (for a rotary axis: at the reference, which then repeats the last value)
    first = reference_point - n_minus + 1
    last = reference_point + n_plus
    if first < 0 or last > max_point:
        raise AxiscalError(f"compensation points {first}..{last} do not fit in 0..{max_point}; choose another reference point")

    node_numbers = np.arange(first - 1, last + 1)
    nodes = reference_position_m + (node_numbers - reference_point) * interval_m

    def deviation(direction: str) -> np.ndarray:
        if rotary:
            # one revolution, closed: a target at start + 360 deg is the start again and is dropped
            x0 = curve.positions[0]
            keep = curve.positions < x0 + travel_per_revolution * (1 - 1e-9)
            phase = np.mod(nodes - x0, travel_per_revolution) + x0
            closed_x = np.append(curve.positions[keep], x0 + travel_per_revolution)
            e = curve.at(curve.positions[keep], direction)
            return np.interp(phase, closed_x, np.append(e, e[0]))
        return curve.at(nodes, direction)

    k_ref = reference_point - (first - 1)

    def increments(e: np.ndarray, e_ref: float) -> tuple[np.ndarray, int]:
        with np.errstate(over="ignore"):  # a unit far too small: refused just below
            scaled = np.round(-(e - e_ref) / unit)
        if not np.abs(scaled).max(initial=0.0) <= 2.0**53:
            raise AxiscalError(
                f"a compensation value of {np.abs(scaled).max():.3g} units: the detection unit or magnification is far too small"
            )
        absolute = scaled.astype(int)
        return np.diff(absolute), int(absolute[k_ref])

    if bidirectional:
        e_up, e_down = deviation("+"), deviation("-")
        e_ref = float(e_up[k_ref])
        values, _ = increments(e_up, e_ref)
        values_down, ref_down = increments(e_down, e_ref)
    else:
        e_mean = deviation("mean")
        e_ref = float(e_mean[k_ref])
        values, _ = increments(e_mean, e_ref)
        values_down, ref_down = None, 0
    for name, v in (("+", values), ("-", values_down)):
        if v is not None and np.abs(v).max(initial=0) > value_limit:
            raise AxiscalError(
                f"an incremental value of {int(np.abs(v).max())} units ({name} direction) exceeds +-{value_limit}:"
                f" use a larger magnification or a smaller interval"
            )
    down_first = None
    if bidirectional:
        down_first = last + 1
        if down_first + values.size - 1 > max_point:
            raise AxiscalError(f"the - direction table does not fit below point {max_point}")
    return FanucTable(
        reference_point=reference_point,
        reference_position_m=reference_position_m,
        interval_m=interval_m,
        magnification=magnification,
        detection_unit_m=detection_unit_m,
        points=np.arange(first, last + 1),
        values=values,
        values_down=values_down,
        down_first=down_first,
        reference_value_down=ref_down,
        rotary=rotary,
        input_increment_m=input_increment_m,
        axis_number=axis_number,
        reference_deviation_m=e_ref,
    )
