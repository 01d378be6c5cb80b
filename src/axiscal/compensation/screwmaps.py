"""Lead-screw error tables of open and PC-based controllers: TwinCAT CNC (``kw.ssfk``) and Mach4 screw mapping.

Beckhoff TwinCAT CNC (TF5200) axis compensation, leadscrew error compensation (SSFK): a
compensation value list per axis, ``kopf.*`` header and ``kw.ssfk.*`` body. P-COMP-00017
``kw.ssfk.unit`` = 1 gives lengths in 0.1 um; P-COMP-00018 ``kw.ssfk.interval`` is the spacing of
equidistant points (0: the points are listed as ``kw.ssfk.table[i].setpoint``); P-COMP-00019
``kw.ssfk.kw_startpos`` the first point; P-COMP-00020 ``kw.ssfk.kw_nr_max`` the number of points;
``kw.ssfk.bilateral`` = 1 one table per direction; P-COMP-00023/24 ``kw.ssfk.table[i].pos`` /
``.neg`` the compensation values, given as the absolute position error (actual - setpoint) that
the control removes, linearly interpolated between points. The manual's worked example: a point
programmed at 19866.7 um reached at 19856.5 um (+) and 19874.7 um (-) is entered as -102 and 80.

Mach4 screw mapping (MachMotion's "Mach 4 Screw Mapping", Machine Calibration plugin, Linear
Compensation): a map is entered as a Start Point (the most negative position mapped), a Length
(positive travel from it), a Number of Points (evenly spaced, both ends included) and the Error at
each point, "the difference between the expected position and the actual position", in machine
units; one map for both directions (builds after 2107) or one per direction (builds after 4780).
The map is typed into the plugin's dialog, not loaded from a file: axiscal prints the values to
enter.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

import numpy as np

from pathlib import Path

from axiscal.compensation.curve import ErrorCurve, error_curve
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_instance, check_integer, check_optional_number
from axiscal.units import INCH, MM, UM

__all__ = ["SCREWMAP_CONTROLLERS", "TWINCAT_UNIT", "Mach4ScrewMap", "TwincatTable", "mach4_screw_map", "screwmap_file",
           "twincat_table", "parse_twincat_table"]

#: controllers whose lead-screw table ``axiscal export screwmap`` writes
SCREWMAP_CONTROLLERS = ("twincat", "mach4")
#: machine units of a Mach4 profile, metres per unit
MACH4_UNITS = {"mm": MM, "in": INCH}

#: length unit of a metric TwinCAT compensation list (kw.ssfk.unit = 1), metres
TWINCAT_UNIT = 0.1 * UM
_SGN32 = 2**31 - 1


@dataclass(frozen=True)
class TwincatTable:
    """A TwinCAT CNC leadscrew error compensation list of one axis.

    Attributes
    ----------
    axis : str
        Logical axis name (``kopf.log_achs_name``).
    axis_number : int
        Logical axis number (``kopf.achs_nr``).
    setpoints : ndarray of int, shape (n,)
        Interpolation points, 0.1 um.
    pos, neg : ndarray of int, shape (n,)
        Position error (actual - setpoint) in the + and - direction, 0.1 um; ``neg`` equals ``pos``
        for a unilateral table.
    interval : int
        Spacing of equidistant points, 0.1 um; 0 when the points are listed.
    bilateral : bool
        One table per direction.
    resampled : bool
        True when the measured targets were resampled onto equidistant points.
    """

    axis: str
    axis_number: int
    setpoints: np.ndarray
    pos: np.ndarray
    neg: np.ndarray
    interval: int
    bilateral: bool
    resampled: bool = False

    @property
    def note(self) -> str | None:
        """A sentence saying the curve was resampled onto equidistant points, or None."""
        if not self.resampled:
            return None
        return (f"the mean deviations were resampled onto {self.setpoints.size} points"
                f" {self.interval * TWINCAT_UNIT / MM:g} mm apart (linear interpolation)")

    def correction(self, x, direction: str) -> np.ndarray:
        """What the control adds to a command at ``x`` (metres) moving in ``direction`` ("+" or "-"), metres."""
        if not isinstance(direction, str) or direction not in ("+", "-"):
            raise AxiscalError(f"unknown direction '{direction}'; use + or -")
        values = self.pos if direction == "+" or not self.bilateral else self.neg
        return -np.interp(check_array("x", x, unit="metres"), self.setpoints * TWINCAT_UNIT, values * TWINCAT_UNIT)

    def text(self) -> str:
        """The compensation value list (ASCII, ``#`` comments)."""
        lines = [
            "# leadscrew error compensation (SSFK), written by axiscal",
            f"kopf.achs_nr {self.axis_number}",
            f"kopf.log_achs_name {self.axis}",
            f"kw.ssfk.interval {self.interval}",
            f"kw.ssfk.kw_startpos {int(self.setpoints[0])}",
            f"kw.ssfk.kw_nr_max {self.setpoints.size}",
            "kw.ssfk.unit 1",
            f"kw.ssfk.bilateral {int(self.bilateral)}",
        ]
        if self.interval == 0:
            lines += [f"kw.ssfk.table[{i}].setpoint {int(v)}" for i, v in enumerate(self.setpoints)]
        lines += [f"kw.ssfk.table[{i}].pos {int(v)}" for i, v in enumerate(self.pos)]
        if self.bilateral:
            lines += [f"kw.ssfk.table[{i}].neg {int(v)}" for i, v in enumerate(self.neg)]
        return "\n".join(lines) + "\n"


def twincat_table(
    curve: ErrorCurve,
    *,
    axis: str = "X",
    axis_number: int = 1,
    interval_m: float | None = None,
    bilateral: bool = True,
    max_points: int | None = None,
) -> TwincatTable:
    """A TwinCAT CNC leadscrew error compensation list from the mean deviations of a positioning test.

    Parameters
    ----------
    curve : ErrorCurve
        Mean deviation per direction (:func:`axiscal.compensation.error_curve`), metres.
    axis : str, keyword-only
        Logical axis name.
    axis_number : int, keyword-only
        Logical axis number (>= 1).
    interval_m : float, optional, keyword-only
        Spacing of equidistant points, metres (a whole multiple of 0.1 um); the curve is
        resampled on it from the first target (linear interpolation, the end value held for a last
        point beyond the last target). None: the measured targets are listed (``interval`` 0).
    bilateral : bool, keyword-only
        One table per direction (default); False: one table of the bidirectional mean.
    max_points : int, optional, keyword-only
        The number of table entries the control reserves (P-COMP-00059); a longer table is refused.

    Returns
    -------
    TwincatTable

    Raises
    ------
    AxiscalError
        For a non-positive or non-finite interval, an axis number below 1, more points than
        ``max_points``, or values beyond SGN32.

    Examples
    --------
    >>> import numpy as np
    >>> curve = ErrorCurve(np.array([0.0, 0.01]), np.array([0.0, -10.2e-6]), np.array([0.0, 8e-6]))
    >>> twincat_table(curve).pos.tolist(), twincat_table(curve).neg.tolist()
    ([0, -102], [0, 80])
    """
    check_instance("curve", curve, ErrorCurve)
    check_instance("axis", axis, str, what="an axis name")
    check_instance("bilateral", bilateral, (bool, np.bool_))
    interval_m = check_optional_number("interval_m", interval_m)
    if max_points is not None:
        check_integer("max_points", max_points)
    if check_integer("axis_number", axis_number) < 1:
        raise AxiscalError(f"axis numbers start at 1, not {axis_number}")
    positions = np.asarray(curve.positions, dtype=float)
    if interval_m is None:
        nodes = positions
        interval = 0
    else:
        if not (math.isfinite(interval_m) and interval_m > 0):
            raise AxiscalError(f"the interval must be a positive length, not {interval_m / MM:g} mm")
        interval = round(interval_m / TWINCAT_UNIT)
        if interval < 1 or abs(interval * TWINCAT_UNIT - interval_m) > 1e-3 * TWINCAT_UNIT:
            raise AxiscalError(f"the interval {interval_m / MM:g} mm is not a whole number of 0.1 um")
        count = int(math.ceil((positions[-1] - positions[0]) / (interval * TWINCAT_UNIT) - 1e-9)) + 1
        nodes = positions[0] + interval * TWINCAT_UNIT * np.arange(count)
    if max_points is not None and nodes.size > max_points:
        raise AxiscalError(
            f"{nodes.size} points: the control reserves {max_points} (P-COMP-00059); give a larger interval"
        )
    up = curve.at(nodes, "+")
    down = curve.at(nodes, "-")
    if not bilateral:
        up = down = curve.at(nodes, "mean")
    setpoints = np.rint(nodes / TWINCAT_UNIT).astype(np.int64)
    pos = np.rint(up / TWINCAT_UNIT).astype(np.int64)
    neg = np.rint(down / TWINCAT_UNIT).astype(np.int64)
    if max(np.abs(setpoints).max(), np.abs(pos).max(), np.abs(neg).max()) > _SGN32:
        raise AxiscalError("a position or value is beyond the SGN32 range of the list (0.1 um units)")
    return TwincatTable(
        axis=axis, axis_number=axis_number, setpoints=setpoints, pos=pos, neg=neg, interval=interval,
        bilateral=bilateral,
        resampled=interval != 0 and (nodes.size != positions.size or not np.allclose(nodes, positions, rtol=0, atol=1e-9)),
    )


_LIST_ENTRY = re.compile(r"(kopf\.\w+|kw\.ssfk\.\w+|kw\.ssfk\.table\[(\d+)\]\.(setpoint|pos|neg))\s+(\S.*?)\s*")


def parse_twincat_table(text: str, *, source: str | None = None) -> TwincatTable:
    """A TwinCAT CNC leadscrew error compensation list read back from its text, as the control reads it.

    Lines ``key value``; ``#`` starts a comment line, blank lines are skipped. Equidistant points
    (``kw.ssfk.interval`` > 0) are laid out from ``kw.ssfk.kw_startpos``; otherwise every
    ``kw.ssfk.table[i].setpoint`` is listed. ``neg`` is read for a bilateral list and is ``pos``
    otherwise.

    Parameters
    ----------
    text : str
        The list.
    source : str, optional, keyword-only
        The file, named in errors.

    Returns
    -------
    TwincatTable

    Raises
    ------
    AxiscalError
        Naming the line: a line that is not a ``kopf.*`` or ``kw.ssfk.*`` entry, a value that is not a whole number, a
        table index at or past ``kw_nr_max``; a missing entry, a list in encoder increments
        (``kw.ssfk.unit`` 0), or points that do not increase.
    """
    check_instance("text", text, str)
    header: dict[str, str] = {}
    table: dict[str, dict[int, int]] = {"setpoint": {}, "pos": {}, "neg": {}}

    def fail(message: str, line: int | None = None) -> AxiscalError:
        return AxiscalError(message, path=source, line=line)

    for number, raw in enumerate(text.splitlines(), start=1):
        line = raw.strip()
        if not line or line.startswith("#"):
            continue
        found = _LIST_ENTRY.fullmatch(line)
        if found is None:
            raise fail(f"cannot read {line[:40]!r}: not a kopf.* or kw.ssfk.* entry", number)
        key, index, field, value = found.groups()
        if key.startswith("kopf."):
            header[key] = value
            continue
        try:
            whole = int(value)
        except ValueError:
            raise fail(f"{key} must be a whole number, not {value[:20]!r}", number) from None
        if index is None:
            header[key] = str(whole)
        else:
            table[field][int(index)] = whole
    for key in ("kopf.achs_nr", "kopf.log_achs_name", "kw.ssfk.interval", "kw.ssfk.kw_nr_max", "kw.ssfk.unit"):
        if key not in header:
            raise fail(f"the list has no {key}")
    if header["kw.ssfk.unit"] != "1":
        raise fail("the list is in encoder increments (kw.ssfk.unit 0): only metric lists (0.1 um) are read")
    count = int(header["kw.ssfk.kw_nr_max"])
    bilateral = header.get("kw.ssfk.bilateral", "0") == "1"
    interval = int(header["kw.ssfk.interval"])

    def column(field: str) -> np.ndarray:
        values = table[field]
        missing = [i for i in range(count) if i not in values]
        extra = [i for i in values if i >= count]
        if extra:
            raise fail(f"kw.ssfk.table[{extra[0]}].{field} is past kw.ssfk.kw_nr_max ({count})")
        if missing:
            raise fail(f"the list has no kw.ssfk.table[{missing[0]}].{field}")
        return np.array([values[i] for i in range(count)], dtype=np.int64)

    if interval > 0:
        if "kw.ssfk.kw_startpos" not in header:
            raise fail("the list has no kw.ssfk.kw_startpos")
        setpoints = int(header["kw.ssfk.kw_startpos"]) + interval * np.arange(count, dtype=np.int64)
    else:
        setpoints = column("setpoint")
        if np.any(np.diff(setpoints) <= 0):
            raise fail("the points kw.ssfk.table[i].setpoint do not increase")
    pos = column("pos")
    neg = column("neg") if bilateral else pos.copy()
    return TwincatTable(axis=header["kopf.log_achs_name"], axis_number=int(header["kopf.achs_nr"]), setpoints=setpoints,
                        pos=pos, neg=neg, interval=max(interval, 0), bilateral=bilateral)


@dataclass(frozen=True)
class Mach4ScrewMap:
    """The values of a Mach4 screw map of one axis, to enter in the Machine Calibration plugin.

    Attributes
    ----------
    axis : str
        Axis (motor) the map belongs to.
    unit : {"mm", "in"}
        Machine units of the profile; every value below is in them.
    start, length : float
        Start Point and Length, machine units.
    error_up, error_down : ndarray, shape (n,)
        Error at each point (expected - actual position) moving in the + and - direction,
        machine units; equal for a symmetric map.
    bidirectional : bool
        One map per direction (Mach4 builds after 4780) rather than one for both.
    decimals : int
        Decimals written.
    resampled : bool
        True when the measured targets were resampled onto the evenly spaced points.
    """

    axis: str
    unit: str
    start: float
    length: float
    error_up: np.ndarray
    error_down: np.ndarray
    bidirectional: bool
    decimals: int = 4
    resampled: bool = False

    @property
    def points(self) -> np.ndarray:
        """Position of each point, machine units, shape (n,)."""
        return np.linspace(self.start, self.start + self.length, self.error_up.size)

    @property
    def note(self) -> str | None:
        """A sentence saying the targets were resampled, or None."""
        if not self.resampled:
            return None
        return (f"the mean deviations were resampled onto {self.error_up.size} evenly spaced points"
                " (linear interpolation; Mach4 maps evenly spaced points)")

    def correction(self, x, direction: str) -> np.ndarray:
        """What the map adds to a command at ``x`` (metres) moving in ``direction`` ("+" or "-"), metres.

        Parameters
        ----------
        x : float or array_like, metres
        direction : {"+", "-"}

        Returns
        -------
        ndarray, shape of ``x``, metres
        """
        if not isinstance(direction, str) or direction not in ("+", "-"):
            raise AxiscalError(f"unknown direction '{direction}'; use + or -")
        values = self.error_up if direction == "+" else self.error_down
        scale = MACH4_UNITS[self.unit]
        return np.interp(check_array("x", x, unit="metres"), self.points * scale, values * scale)

    def text(self) -> str:
        """The values to type into the plugin, one point a line."""
        d, u = self.decimals, self.unit
        kind = "one map per direction" if self.bidirectional else "one map for both directions"
        lines = [
            f"Mach4 screw map, axis {self.axis} ({kind}); Configure > Plugins > Machine Calibration, Linear Compensation",
            f"Start Point       {self.start:.{d}f} {u}",
            f"Length            {self.length:.{d}f} {u}",
            f"Number of Points  {self.error_up.size}",
            f"{'Point':<7}{'Position':>14}" + (f"{'Error +':>14}{'Error -':>14}" if self.bidirectional else f"{'Error':>14}"),
        ]
        for k, (p, up, down) in enumerate(zip(self.points, self.error_up, self.error_down), start=1):
            row = f"{k:<7}{p:>14.{d}f}{up:>+14.{d}f}"
            lines.append(row + (f"{down:>+14.{d}f}" if self.bidirectional else ""))
        return "\n".join(lines) + "\n"


def mach4_screw_map(
    curve: ErrorCurve,
    *,
    axis: str = "X",
    points: int | None = None,
    bidirectional: bool = True,
    unit: str = "mm",
    decimals: int | None = None,
) -> Mach4ScrewMap:
    """The values of a Mach4 screw map from the mean deviations of a positioning test.

    Parameters
    ----------
    curve : ErrorCurve
        Mean deviation per direction (:func:`axiscal.compensation.error_curve`), metres; a linear axis.
    axis : str, keyword-only
        Axis name, for the heading.
    points : int, optional, keyword-only
        Number of evenly spaced points from the first target to the last (at least 2). Default:
        the number of targets (the targets themselves when they are evenly spaced).
    bidirectional : bool, keyword-only
        One map per direction (default; Mach4 builds after 4780); False: one map of the
        bidirectional mean.
    unit : {"mm", "in"}, keyword-only
        Machine units of the Mach4 profile.
    decimals : int, optional, keyword-only
        Decimals written (0..6; default 4 in mm, 5 in inches: 0.1 and 0.25 um).

    Returns
    -------
    Mach4ScrewMap
        Error = expected - actual position = minus the mean deviation, at each point.

    Raises
    ------
    AxiscalError
        For a rotary curve, fewer than 2 or more than 10^5 points, an unknown unit, or bad decimals.

    Examples
    --------
    >>> import numpy as np
    >>> curve = ErrorCurve(np.array([0.0, 0.1, 0.2]), np.array([0.0, 5e-6, 8e-6]), np.array([2e-6, 7e-6, 10e-6]))
    >>> m = mach4_screw_map(curve)
    >>> m.start, m.length, m.error_up.tolist(), m.error_down.tolist()
    (0.0, 200.0, [0.0, -0.005, -0.008], [-0.002, -0.007, -0.01])
    """
    check_instance("curve", curve, ErrorCurve)
    check_instance("axis", axis, str, what="an axis name")
    check_instance("bidirectional", bidirectional, (bool, np.bool_))
    if curve.period is not None:
        raise AxiscalError("a Mach4 screw map is written for a linear axis; this test is of a rotary axis")
    if not isinstance(unit, str) or unit not in MACH4_UNITS:
        raise AxiscalError(f"unknown unit {unit!r}; Mach4 profiles are in {' or '.join(MACH4_UNITS)}")
    if decimals is None:
        decimals = 4 if unit == "mm" else 5
    if not isinstance(decimals, int) or not 0 <= decimals <= 6:
        raise AxiscalError(f"decimals must be a whole number 0..6, not {decimals}")
    positions = np.asarray(curve.positions, dtype=float)
    count = positions.size if points is None else points
    if not isinstance(count, (int, np.integer)) or isinstance(count, bool) or not 2 <= count <= 100_000:
        raise AxiscalError(f"a screw map needs 2 to 10^5 points, not {count}")
    nodes = np.linspace(positions[0], positions[-1], int(count))
    scale = MACH4_UNITS[unit]
    up, down = curve.at(nodes, "+"), curve.at(nodes, "-")
    if not bidirectional:
        up = down = curve.at(nodes, "mean")
    def written(values):
        return np.round(-values / scale, decimals) + 0.0
    return Mach4ScrewMap(
        axis=axis, unit=unit, start=float(round(nodes[0] / scale, decimals)) + 0.0,
        length=float(round((nodes[-1] - nodes[0]) / scale, decimals)) + 0.0,
        error_up=written(up), error_down=written(down), bidirectional=bidirectional, decimals=decimals,
        resampled=nodes.size != positions.size or not np.allclose(nodes, positions, rtol=0, atol=1e-9),
    )


def screwmap_file(
    path: str | Path,
    *,
    controller: str,
    axis: str = "X",
    axis_number: int = 1,
    interval_m: float | None = None,
    points: int | None = None,
    bidirectional: bool = True,
    max_points: int | None = None,
    unit: str = "mm",
) -> TwincatTable | Mach4ScrewMap:
    """A controller's lead-screw table from a positioning run file (what ``axiscal export screwmap`` writes).

    Parameters
    ----------
    path : str or Path
        A positioning run (:func:`axiscal.positioning.read_positioning_run`).
    controller : {"twincat", "mach4"}, keyword-only
        TwinCAT CNC ``kw.ssfk`` list (:func:`twincat_table`) or Mach4 screw map (:func:`mach4_screw_map`).
    axis : str, keyword-only
        Axis name.
    axis_number : int, keyword-only
        TwinCAT: logical axis number.
    interval_m : float, optional, keyword-only
        TwinCAT: spacing of equidistant points, metres.
    points : int, optional, keyword-only
        Mach4: number of evenly spaced points.
    bidirectional : bool, keyword-only
        One table per direction (default) or one of the bidirectional mean.
    max_points : int, optional, keyword-only
        TwinCAT: table entries the control reserves (P-COMP-00059).
    unit : {"mm", "in"}, keyword-only
        Mach4: machine units of the profile.

    Returns
    -------
    TwincatTable or Mach4ScrewMap
        ``.text()`` is what to load or enter; ``.note`` says what to know first.

    Raises
    ------
    AxiscalError
        For a bad file (naming file and line), an unknown controller, an option the controller
        does not have, and the refusals of the table functions.
    """
    from axiscal.positioning import read_positioning_run, target_statistics

    if not isinstance(controller, str) or controller not in SCREWMAP_CONTROLLERS:
        raise AxiscalError(f"unknown controller {controller!r}; screw maps are written for {', '.join(SCREWMAP_CONTROLLERS)}")
    check_integer("axis_number", axis_number)
    if controller == "mach4" and (interval_m is not None or max_points is not None or axis_number != 1):
        raise AxiscalError("the interval, maximum points and axis number are TwinCAT settings; for Mach4 give the number of points")
    if controller == "twincat" and (points is not None or unit != "mm"):
        raise AxiscalError("the number of points and the unit are Mach4 settings; for TwinCAT give the interval")
    curve = error_curve(target_statistics(read_positioning_run(path).run))
    if controller == "twincat":
        return twincat_table(curve, axis=axis, axis_number=axis_number, interval_m=interval_m,
                             bilateral=bidirectional, max_points=max_points)
    return mach4_screw_map(curve, axis=axis, points=points, bidirectional=bidirectional, unit=unit)
