"""Compensation files read back as each controller reads them: the correction it adds to a command.

A virtual controller (and every round-trip test of the table writers) reads the written text
alone, nothing of the object that wrote it, and rebuilds the correction the control applies:

- LinuxCNC ``COMP_FILE``: ``nominal forward reverse`` triplets (:func:`parse_linuxcnc`); type 0
  holds the positions reached (trim = nominal - value), type 1 the corrections; interpolated
  linearly, the end trims held beyond the table (LinuxCNC's motion module, ``usrmotintf.cc``).
- FANUC parameter tape: point N sits at reference + (N - 3620) * 3624; its value is the change of
  the correction over the section N-1 .. N, in units of 3623 x the detection unit; the correction
  is 0 at the reference (3627 for - travel with a bidirectional table, parameters 3626/3627).
- SINUMERIK MSEC (``$AA_ENC_COMP`` INI): a positive value moves the axis negative: the correction
  is ``-value`` interpolated over ``MIN + i STEP``.
- HEIDENHAIN ``.COM``: the control subtracts the error column (plus ``BACKLASH`` in -).

The correction is in metres and is added to the commanded position; what is left at a position
is ``deviation(x + correction) + correction``.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

import numpy as np

from axiscal.compensation.curve import _check_direction
from axiscal.compensation.linuxcnc import parse_linuxcnc
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_choice, check_instance, check_number
from axiscal.units import MM

__all__ = ["CONTROLLERS", "ControllerCompensation", "parse_fanuc_tape", "parse_siemens", "read_compensation"]

CONTROLLERS = ("linuxcnc", "fanuc", "siemens", "heidenhain")


@dataclass(frozen=True)
class ControllerCompensation:
    """The correction a controller adds to commanded positions, rebuilt from its compensation file.

    Attributes
    ----------
    controller : str
        The controller whose file it is.
    nodes_m : ndarray, shape (k,), metres
        Positions of the table's points.
    plus_m, minus_m : ndarray, shape (k,), metres
        Correction at each point for travel in + and in - (the same array for a one-curve table).
    """

    controller: str
    nodes_m: np.ndarray
    plus_m: np.ndarray
    minus_m: np.ndarray

    def __post_init__(self) -> None:
        check_choice("controller", self.controller, CONTROLLERS)
        nodes = check_array("nodes_m", self.nodes_m, ndim=1, min_len=1, unit="metres")
        for name in ("plus_m", "minus_m"):
            values = check_array(name, getattr(self, name), ndim=1, unit="metres")
            if values.shape != nodes.shape:
                raise AxiscalError(f"{name} must hold one correction per node ({nodes.size}), not {values.size}")
        if np.any(np.diff(nodes) <= 0):
            raise AxiscalError("nodes_m must strictly increase")

    def correction(self, x, direction: str) -> np.ndarray:
        """Correction added to commanded positions ``x`` moving in ``direction``, metres.

        Parameters
        ----------
        x : float or array_like, metres
        direction : {"+", "-"}

        Returns
        -------
        ndarray, shape of ``x``, metres
            Linear between points, the end values held beyond them.
        """
        _check_direction(direction)
        values = self.plus_m if direction in ("+", "mean") else self.minus_m
        return np.interp(check_array("x", x, unit="metres"), self.nodes_m, values)


def parse_fanuc_tape(text: str) -> tuple[dict[int, int], dict[int, int]]:
    """The parameters (``N<number>A<axis>P<value>``) and data (``N1<point>P<value>``) of a FANUC tape.

    Parameters
    ----------
    text : str
        The tape, between ``%`` lines.

    Returns
    -------
    params, data : dict of int to int
        Parameter number to value; compensation point number to value.

    Raises
    ------
    AxiscalError
        For a tape not framed by ``%`` or a line that is neither form (naming the line).
    """
    check_instance("text", text, str, what="the text of a FANUC parameter tape")
    lines = text.splitlines()
    if len(lines) < 2 or lines[0] != "%" or lines[-1] != "%":
        raise AxiscalError("a FANUC tape starts and ends with a '%' line", line=1)
    params: dict[int, int] = {}
    data: dict[int, int] = {}
    for number, line in enumerate(lines[1:-1], start=2):
        m = re.fullmatch(r"N(\d{5})A\d+P(-?\d+)", line)
        if m:
            params[int(m.group(1))] = int(m.group(2))
            continue
        m = re.fullmatch(r"N1(\d{4})P(-?\d+)", line)
        if not m:
            raise AxiscalError(f"'{line}' is neither N<parameter>A<axis>P<value> nor N1<point>P<value>", line=number)
        data[int(m.group(1))] = int(m.group(2))
    return params, data


def parse_siemens(text: str) -> tuple[list[float], dict[str, float]]:
    """The values and the STEP/MIN/MAX/IS_MODULO settings of a SINUMERIK MSEC INI file.

    Parameters
    ----------
    text : str

    Returns
    -------
    values : list of float
        ``$AA_ENC_COMP[0,i,AXIS]`` in order of i (mm or deg).
    params : dict of str to float

    Raises
    ------
    AxiscalError
        For a file without the INI frame, values out of order, or a line of another form.
    """
    check_instance("text", text, str, what="the text of a SINUMERIK compensation file")
    lines = text.splitlines()
    if len(lines) < 3 or lines[0] != "%_N_AX_EEC_INI" or lines[1] != "CHANDATA(1)" or lines[-1] != "M17":
        raise AxiscalError("a SINUMERIK MSEC file starts '%_N_AX_EEC_INI', 'CHANDATA(1)' and ends 'M17'", line=1)
    values: list[float] = []
    params: dict[str, float] = {}
    for number, line in enumerate(lines[2:-1], start=3):
        m = re.fullmatch(r"\$AA_ENC_COMP\[0,(\d+),\w+\]=(-?\d+(?:\.\d+)?)", line)
        if m:
            if int(m.group(1)) != len(values):
                raise AxiscalError(f"compensation value {m.group(1)} is out of order", line=number)
            values.append(float(m.group(2)))
            continue
        m = re.fullmatch(r"\$AA_ENC_COMP_(STEP|MIN|MAX|IS_MODULO)\[0,\w+\]=(-?[\d.]+)", line)
        if not m:
            raise AxiscalError(f"'{line}' is not a compensation value or setting", line=number)
        params[m.group(1)] = float(m.group(2))
    return values, params


def _linuxcnc(text: str, comp_type: int, unit_m: float) -> ControllerCompensation:
    rows = parse_linuxcnc(text)
    nominal = rows[:, 0]
    trims = [nominal - rows[:, c] if comp_type == 0 else rows[:, c] for c in (1, 2)]
    return ControllerCompensation("linuxcnc", nominal * unit_m, trims[0] * unit_m, trims[1] * unit_m)


def _fanuc(text: str, reference_position_m: float, detection_unit_m: float, increment_m: float) -> ControllerCompensation:
    params, data = parse_fanuc_tape(text)
    missing = [p for p in (3620, 3621, 3622, 3623, 3624) if p not in params]
    if missing:
        raise AxiscalError(f"the tape lacks parameter(s) {', '.join(map(str, missing))}")
    ref, first, last = params[3620], params[3621], params[3622]
    unit = params[3623] * detection_unit_m
    numbers = np.arange(first - 1, last + 1)
    nodes = reference_position_m + (numbers - ref) * params[3624] * increment_m

    def absolute(point_value, at_reference: int) -> np.ndarray:
        try:
            steps = np.array([point_value(n) for n in numbers[1:]], dtype=float)
        except KeyError as exc:
            raise AxiscalError(f"the tape has no value for compensation point {exc.args[0]}") from None
        cumulative = np.concatenate([[0.0], np.cumsum(steps)])
        return (cumulative - cumulative[ref - (first - 1)] + at_reference) * unit

    plus = absolute(lambda n: data[n], 0)
    minus = absolute(lambda n: data[params[3626] + n - first], params.get(3627, 0)) if 3626 in params else plus
    return ControllerCompensation("fanuc", nodes, plus, minus)


def _siemens(text: str, unit_m: float) -> ControllerCompensation:
    values, params = parse_siemens(text)
    if "STEP" not in params or "MIN" not in params:
        raise AxiscalError("the file lacks $AA_ENC_COMP_STEP or $AA_ENC_COMP_MIN")
    nodes = params["MIN"] + params["STEP"] * np.arange(len(values))
    correction = -np.asarray(values) * unit_m
    return ControllerCompensation("siemens", nodes * unit_m, correction, correction)


def _heidenhain(text: str, unit_m: float) -> ControllerCompensation:
    lines = text.splitlines()
    if len(lines) < 3 or not lines[0].startswith("BEGIN") or lines[-1] != "[END]":
        raise AxiscalError("a HEIDENHAIN .COM table starts 'BEGIN ...' and ends '[END]'", line=1)
    header = lines[1].split()
    try:
        rows = np.array([[float(cell) for cell in line.split()] for line in lines[2:-1]])
    except ValueError:
        raise AxiscalError("a row of the table is not numbers") from None
    if rows.ndim != 2 or rows.shape[1] != len(header):
        raise AxiscalError(f"rows must have the {len(header)} columns the header names")
    position, error = rows[:, 1], rows[:, 2]
    extra = rows[:, header.index("BACKLASH")] if "BACKLASH" in header else np.zeros_like(error)
    return ControllerCompensation("heidenhain", position * unit_m, -error * unit_m, -(error + extra) * unit_m)


def read_compensation(
    text: str,
    controller: str,
    *,
    comp_type: int = 1,
    unit_m: float = MM,
    reference_position_m: float = 0.0,
    detection_unit_m: float = 1e-6,
    increment_m: float = 1e-6,
) -> ControllerCompensation:
    """The correction a controller applies, read from its compensation file's text.

    Parameters
    ----------
    text : str
        The file's content.
    controller : {"linuxcnc", "fanuc", "siemens", "heidenhain"}
    comp_type : {0, 1}, keyword-only
        linuxcnc: ``COMP_FILE_TYPE`` of the INI (default 1, corrections).
    unit_m : float, metres, keyword-only
        linuxcnc, siemens, heidenhain: the machine unit of the file (default 1 mm).
    reference_position_m : float, metres, keyword-only
        fanuc: machine position of the reference position (the tape does not hold it).
    detection_unit_m, increment_m : float, metres, keyword-only
        fanuc: the detection unit (3623 multiplies it) and the increment system (3624 counts it),
        default 1 um each.

    Returns
    -------
    ControllerCompensation

    Raises
    ------
    AxiscalError
        For an unknown controller, or a file the controller would refuse or misread.

    Examples
    --------
    >>> c = read_compensation("0 0 0\\n100 -0.002 -0.004\\n", "linuxcnc")
    >>> round(float(c.correction(0.05, "-")) * 1e6, 3)
    -2.0
    """
    check_instance("text", text, str, what="the text of a compensation file")
    check_choice("controller", controller, CONTROLLERS)
    unit_m = check_number("unit_m", unit_m, positive=True, unit="m")
    if controller == "linuxcnc":
        if comp_type not in (0, 1) or isinstance(comp_type, bool):
            raise AxiscalError(f"comp_type must be 0 or 1, not {comp_type!r}")
        return _linuxcnc(text, comp_type, unit_m)
    if controller == "fanuc":
        return _fanuc(text, check_number("reference_position_m", reference_position_m, unit="m"),
                      check_number("detection_unit_m", detection_unit_m, positive=True, unit="m"),
                      check_number("increment_m", increment_m, positive=True, unit="m"))
    if controller == "siemens":
        return _siemens(text, unit_m)
    return _heidenhain(text, unit_m)
