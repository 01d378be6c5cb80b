"""Controller compensation tables from the mean positioning deviations of an ISO 230-2 test.

Writes the pitch (lead-screw) error tables of four controls: the LinuxCNC joint ``COMP_FILE``
(types 0 and 1), FANUC pitch error compensation (parameters 3620-3627 and the incremental
compensation data), SIEMENS SINUMERIK measuring-system error compensation (``$AA_ENC_COMP``) and
HEIDENHAIN nonlinear axis error compensation (``*.COM``). Each table knows how its control
applies it (:meth:`correction`: interpolate between the points, add to the command), so the
tests check the table by applying it to the measured errors. See docs/compensation.md for the
formats, the sources and the sign conventions.

Sign convention of this module: a control *correction* ``c(x)`` is what the control adds to the
commanded position ``x`` before it moves the axis; the error left after compensation is
``e(x) + c(x)`` with ``e = actual - target`` (the ISO 230-2 deviation). A perfect table has
``c = -e``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.positioning import TargetStatistics
from axiscal.units import MM

LINUXCNC_MAX_ENTRIES = 256
HEIDENHAIN_MAX_ENTRIES = 256
DIRECTIONS = ("+", "-")


@dataclass(frozen=True)
class ErrorCurve:
    """Mean positional deviation per approach direction against nominal position (metres).

    Between the measured positions the error is taken as piecewise linear; beyond the end
    positions it is held at the end values.

    Attributes
    ----------
    positions : ndarray, shape (m,), metres, strictly increasing
    up, down : ndarray, shape (m,), metres
        Mean deviation (actual - target) approaching in the + and - direction.
    """

    positions: np.ndarray
    up: np.ndarray
    down: np.ndarray

    @property
    def mean(self) -> np.ndarray:
        """Bidirectional mean deviation, shape (m,), metres."""
        return 0.5 * (self.up + self.down)

    def at(self, x, direction: str) -> np.ndarray:
        """Deviation at positions ``x`` (metres) for direction "+", "-" or "mean"."""
        values = {"+": self.up, "-": self.down, "mean": self.mean}.get(direction)
        if values is None:
            raise AxiscalError(f"unknown direction '{direction}'; use +, - or mean")
        return np.interp(np.asarray(x, dtype=float), self.positions, values)


def error_curve(stats: TargetStatistics) -> ErrorCurve:
    """The mean deviations of a positioning test as an :class:`ErrorCurve`."""
    return ErrorCurve(np.asarray(stats.targets), np.asarray(stats.mean_up), np.asarray(stats.mean_down))


def _check_direction(direction: str) -> None:
    if direction not in DIRECTIONS:
        raise AxiscalError(f"unknown direction '{direction}'; use + or -")


def _grid(start: float, end: float, step: float) -> np.ndarray:
    if not (math.isfinite(step) and step > 0):
        raise AxiscalError(f"the table interval must be positive, got {step / MM:g} mm")
    count = int(math.ceil((end - start) / step - 1e-9)) + 1
    return start + step * np.arange(count)


# ---------------------------------------------------------------------------------- LinuxCNC


@dataclass(frozen=True)
class LinuxcncTable:
    """A LinuxCNC joint compensation file (``[JOINT_n] COMP_FILE``, ``COMP_FILE_TYPE``).

    One line per entry, ``nominal forward reverse`` in machine units, nothing else: LinuxCNC
    reads triplets with ``sscanf("%lf %lf %lf")`` and stops at the first line that is not
    three numbers. Nominals strictly increase; at most 256 entries.

    ``comp_type`` 0: ``forward``/``reverse`` are the positions actually reached at ``nominal``
    when travelling forward (+) / in reverse (-); LinuxCNC uses ``nominal - forward`` as the
    correction. ``comp_type`` 1: they are the corrections themselves (trims), added to the
    commanded position. Between entries LinuxCNC interpolates linearly; beyond the first and
    last entry it holds their values.

    Attributes
    ----------
    nominal, forward, reverse : ndarray, shape (k,), machine units as written to the file
    comp_type : int
    unit_m : float
        Metres per machine unit (1e-3 for a metric machine).
    decimals : int
        Decimals written; the resolution is 10**-decimals machine units.
    """

    nominal: np.ndarray
    forward: np.ndarray
    reverse: np.ndarray
    comp_type: int
    unit_m: float = MM
    decimals: int = 6

    @property
    def resolution(self) -> float:
        """Smallest step of a written value, metres."""
        return 10.0 ** (-self.decimals) * self.unit_m

    @property
    def nodes(self) -> np.ndarray:
        return self.nominal * self.unit_m

    def text(self) -> str:
        d = self.decimals
        return "".join(f"{n:.{d}f} {f:.{d}f} {r:.{d}f}\n" for n, f, r in zip(self.nominal, self.forward, self.reverse))

    def correction(self, x, direction: str) -> np.ndarray:
        """The correction LinuxCNC adds to commanded positions ``x`` (metres) moving in ``direction``."""
        _check_direction(direction)
        values = self.forward if direction == "+" else self.reverse
        trims = self.nominal - values if self.comp_type == 0 else values
        x_units = np.asarray(x, dtype=float) / self.unit_m
        return np.interp(x_units, self.nominal, trims) * self.unit_m


def linuxcnc_table(curve: ErrorCurve, *, comp_type: int = 1, unit_m: float = MM, decimals: int = 6) -> LinuxcncTable:
    """LinuxCNC compensation file at the measured targets.

    Parameters
    ----------
    curve : ErrorCurve
        Mean deviations per direction.
    comp_type : {0, 1}, keyword-only
        ``COMP_FILE_TYPE`` (default 1): 0 writes the positions reached (``nominal + e``), 1 writes
        the corrections (``-e``).
    unit_m : float, keyword-only
        Metres per machine unit (default 1e-3: a metric machine).
    decimals : int, keyword-only
        Decimals written (default 6: 1 nm on a metric machine).
    """
    if comp_type not in (0, 1):
        raise AxiscalError(f"LinuxCNC COMP_FILE_TYPE is 0 or 1, got {comp_type}")
    if curve.positions.size > LINUXCNC_MAX_ENTRIES:
        raise AxiscalError(
            f"{curve.positions.size} targets: a LinuxCNC compensation file holds at most {LINUXCNC_MAX_ENTRIES} entries"
        )
    nominal = np.round(curve.positions / unit_m, decimals)
    if np.any(np.diff(nominal) <= 0):
        raise AxiscalError(f"targets closer than {10.0 ** -decimals:g} machine units: nominals would not increase")
    if comp_type == 1:
        forward, reverse = -curve.up / unit_m, -curve.down / unit_m
    else:
        forward, reverse = nominal + curve.up / unit_m, nominal + curve.down / unit_m
    return LinuxcncTable(nominal, np.round(forward, decimals) + 0.0, np.round(reverse, decimals) + 0.0, comp_type, unit_m, decimals)


def parse_linuxcnc(text: str) -> np.ndarray:
    """Read a compensation file as LinuxCNC does: triplets until the first line that is not one.

    Returns an array of shape (k, 3). Raises if any line after that point would be ignored, if the
    nominals do not strictly increase or if there are more than 256 entries (LinuxCNC rejects
    those with "compensation values must increase" / "too many compensation entries").
    """
    lines = text.splitlines()
    rows = []
    for line in lines:
        cells = line.split()
        try:
            values = [float(c) for c in cells[:3]]
        except ValueError:
            break
        if len(values) < 3:
            break
        rows.append(values)
    if len(rows) != len(lines):
        raise AxiscalError(f"LinuxCNC would stop reading at line {len(rows) + 1}: not three numbers", line=len(rows) + 1)
    table = np.array(rows, dtype=float).reshape(-1, 3)
    if table.shape[0] > LINUXCNC_MAX_ENTRIES:
        raise AxiscalError(f"{table.shape[0]} entries: LinuxCNC accepts at most {LINUXCNC_MAX_ENTRIES}")
    if np.any(np.diff(table[:, 0]) <= 0):
        raise AxiscalError("nominal positions must strictly increase")
    return table


# ---------------------------------------------------------------------------------- FANUC


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
    points : ndarray of int, shape (k,)
        Compensation point numbers 3621 .. 3622 (for a rotary axis 3621 is the reference point,
        which repeats the value of 3622; ``points`` then starts one after it).
    values : ndarray of int, shape (k,)
        Incremental values for travel in the + direction (or both directions when not bidirectional).
    values_down : ndarray of int, shape (k,) or None
        Incremental values for travel in the - direction (bidirectional table), points
        ``down_first .. down_first + k - 1``.
    reference_value_down : int
        Parameter 3627 (bidirectional), in compensation units.
    reference_deviation_m : float
        The deviation at the reference position, which the table leaves uncorrected (of the +
        direction for a bidirectional table, which assumes the reference is approached in +; of
        the bidirectional mean otherwise), metres.
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
    input_increment_m: float = 1e-6
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
        """
        _check_direction(direction)
        if direction == "-" and self.values_down is not None:
            absolute = self._absolute(self.values_down, self.reference_value_down)
        else:
            absolute = self._absolute(self.values, 0)
        return np.interp(np.asarray(x, dtype=float), self.nodes, absolute * self.resolution)

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


def fanuc_table(
    curve: ErrorCurve,
    *,
    interval_m: float,
    reference_position_m: float = 0.0,
    reference_point: int | None = None,
    magnification: int = 1,
    detection_unit_m: float = 1e-6,
    bidirectional: bool = False,
    rotary: bool = False,
    travel_per_revolution: float | None = None,
    value_limit: int = 127,
    max_point: int = 1023,
    input_increment_m: float = 1e-6,
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
    input_increment_m, axis_number : keyword-only
        Unit of parameter 3624 (1 um, IS-B) and the axis number written on the tape.
    """
    if not 1 <= magnification <= 100:
        raise AxiscalError(f"FANUC pitch error magnification (parameter 3623) is 1..100, got {magnification}")
    if not (math.isfinite(interval_m) and interval_m > 0):
        raise AxiscalError(f"the compensation interval must be positive, got {interval_m / MM:g} mm")
    if abs(interval_m / input_increment_m - round(interval_m / input_increment_m)) > 1e-6:
        raise AxiscalError(f"the interval {interval_m / MM:g} mm is not a whole number of input increments")
    unit = magnification * detection_unit_m
    lo, hi = float(curve.positions[0]), float(curve.positions[-1])
    if rotary:
        if travel_per_revolution is None or travel_per_revolution <= 0:
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
        absolute = np.round(-(e - e_ref) / unit).astype(int)
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


# ---------------------------------------------------------------------------------- SIEMENS


@dataclass(frozen=True)
class SiemensTable:
    """SINUMERIK measuring-system (lead-screw) error compensation, ``%_N_AX_EEC_INI``.

    ``$AA_ENC_COMP[e, i, AXIS]`` holds the compensation value of point i (mm) for encoder e,
    from ``$AA_ENC_COMP_MIN`` in steps of ``$AA_ENC_COMP_STEP`` up to ``$AA_ENC_COMP_MAX``.
    The control changes the axis actual value by the compensation value: a positive value
    moves the axis in the negative direction. So the value is the deviation itself
    (``+e``) and the correction applied to the command is its negative. Linear interpolation
    between points, end values held beyond MIN and MAX. One curve for both directions.
    """

    axis: str
    start_m: float
    step_m: float
    values_mm: np.ndarray
    encoder: int = 0
    decimals: int = 4

    @property
    def resolution(self) -> float:
        return 10.0 ** (-self.decimals) * MM

    @property
    def nodes(self) -> np.ndarray:
        return self.start_m + self.step_m * np.arange(self.values_mm.size)

    @property
    def end_m(self) -> float:
        return float(self.nodes[-1])

    def correction(self, x, direction: str) -> np.ndarray:
        _check_direction(direction)
        return -np.interp(np.asarray(x, dtype=float), self.nodes, self.values_mm * MM)

    def text(self) -> str:
        e, a, d = self.encoder, self.axis, self.decimals
        lines = ["%_N_AX_EEC_INI", "CHANDATA(1)"]
        lines += [f"$AA_ENC_COMP[{e},{i},{a}]={v:.{d}f}" for i, v in enumerate(self.values_mm)]
        lines += [
            f"$AA_ENC_COMP_STEP[{e},{a}]={self.step_m / MM:.4f}",
            f"$AA_ENC_COMP_MIN[{e},{a}]={self.start_m / MM:.4f}",
            f"$AA_ENC_COMP_MAX[{e},{a}]={self.end_m / MM:.4f}",
            f"$AA_ENC_COMP_IS_MODULO[{e},{a}]=0",
            "M17",
        ]
        return "\n".join(lines) + "\n"


def siemens_table(
    curve: ErrorCurve,
    *,
    step_m: float,
    axis: str = "X1",
    direction: str = "mean",
    zero_at_m: float | None = None,
    encoder: int = 0,
    decimals: int = 4,
    max_points: int = 1000,
) -> SiemensTable:
    """SINUMERIK ``$AA_ENC_COMP`` table on an even grid from the first measured target.

    Parameters
    ----------
    curve : ErrorCurve
    step_m : float, keyword-only
        ``$AA_ENC_COMP_STEP``, metres.
    axis : str, keyword-only
        Machine axis name (default "X1").
    direction : {"mean", "+", "-"}, keyword-only
        Which mean deviation the one curve holds (default the bidirectional mean; the reversal
        is then left to backlash compensation, MD32450).
    zero_at_m : float, optional, keyword-only
        Shift the curve so its value is zero here (Siemens recommends zero at the reference
        point, so that switching the compensation on makes no jump).
    encoder : int, keyword-only
        Encoder index (0 = first measuring system).
    decimals : int, keyword-only
        Decimals of mm written (default 4: 0.1 um).
    max_points : int, keyword-only
        MD38000 $MA_MM_ENC_COMP_MAX_POINTS of the control (default 1000).
    """
    if not axis or not axis.replace("_", "").isalnum():
        raise AxiscalError(f"'{axis}' is not a machine axis name")
    nodes = _grid(float(curve.positions[0]), float(curve.positions[-1]), step_m)
    if nodes.size > max_points:
        raise AxiscalError(f"{nodes.size} compensation points exceed MD38000 = {max_points}: use a larger step")
    e = curve.at(nodes, direction)
    if zero_at_m is not None:
        e = e - curve.at(zero_at_m, direction)
    return SiemensTable(axis, float(nodes[0]), step_m, np.round(e / MM, decimals) + 0.0, encoder, decimals)


# ---------------------------------------------------------------------------------- HEIDENHAIN


@dataclass(frozen=True)
class HeidenhainTable:
    """HEIDENHAIN nonlinear axis error compensation table (``<axis>.COM``).

    Rows ``NR AXISPOS <axis> BACKLASH`` between ``BEGIN <axis>.COM MM`` and ``[END]``, at most
    256 rows, AXISPOS (mm, machine datum) increasing. The axis column holds the error measured
    in the + direction (actual - nominal, mm: positive when the axis travels too far, as in
    HEIDENHAIN's linear axis error parameter); the BACKLASH column the additional error when
    traversing in the - direction (``mean_down - mean_up`` = -B_i). The control subtracts the
    error, interpolating linearly between rows. Without BACKLASH the axis column holds the
    bidirectional mean.
    """

    axis: str
    positions_mm: np.ndarray
    error_mm: np.ndarray
    backlash_mm: np.ndarray | None
    decimals: int = 4

    @property
    def resolution(self) -> float:
        return 10.0 ** (-self.decimals) * MM

    @property
    def nodes(self) -> np.ndarray:
        return self.positions_mm * MM

    def correction(self, x, direction: str) -> np.ndarray:
        _check_direction(direction)
        error = self.error_mm
        if direction == "-" and self.backlash_mm is not None:
            error = error + self.backlash_mm
        return -np.interp(np.asarray(x, dtype=float), self.nodes, error * MM)

    def text(self) -> str:
        d = self.decimals
        header = f"{'NR':<6}{'AXISPOS':>14}{self.axis:>14}" + (f"{'BACKLASH':>14}" if self.backlash_mm is not None else "")
        lines = [f"BEGIN {self.axis}.COM MM", header]
        for k, (p, e) in enumerate(zip(self.positions_mm, self.error_mm)):
            row = f"{k:<6}{p:>+14.{d}f}{e:>+14.{d}f}"
            if self.backlash_mm is not None:
                row += f"{self.backlash_mm[k]:>+14.{d}f}"
            lines.append(row)
        lines.append("[END]")
        return "\n".join(lines) + "\n"


def heidenhain_table(curve: ErrorCurve, *, axis: str = "X", backlash: bool = True, decimals: int = 4) -> HeidenhainTable:
    """HEIDENHAIN ``.COM`` table at the measured targets (see :class:`HeidenhainTable`)."""
    if not axis.isalpha():
        raise AxiscalError(f"'{axis}' is not an axis name")
    if curve.positions.size > HEIDENHAIN_MAX_ENTRIES:
        raise AxiscalError(f"{curve.positions.size} targets: a .COM table holds at most {HEIDENHAIN_MAX_ENTRIES} rows")
    positions = np.round(curve.positions / MM, decimals)
    if backlash:
        error = np.round(curve.up / MM, decimals) + 0.0
        extra = np.round((curve.down - curve.up) / MM, decimals) + 0.0
    else:
        error, extra = np.round(curve.mean / MM, decimals) + 0.0, None
    return HeidenhainTable(axis.upper(), positions, error, extra, decimals)


def residuals(table, curve: ErrorCurve, x, direction: str, *, offset: float = 0.0) -> np.ndarray:
    """Error left at ``x`` (metres) after ``table`` is applied: ``e(x) - offset + c(x)``.

    ``direction`` is "+", "-" or "mean"; for "mean" the table's + correction is used (tables
    with one curve apply it in both directions). ``offset`` is the part of the error a table
    leaves to the reference position by construction: FANUC tables are zero at the reference
    position, so there it is the deviation at the reference position (of the + direction for a
    bidirectional table, which assumes the reference is approached in +), see
    :attr:`FanucTable.reference_deviation_m`.
    """
    return curve.at(x, direction) - offset + table.correction(x, "+" if direction == "mean" else direction)
