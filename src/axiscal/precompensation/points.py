"""Pre-compensated commands: where to command the axes so that the tool lands on the programmed point.

A programmed point q (the axis positions a program asks for) puts the tool, in the machine model
of docs/conventions.md, at ``actual_point(q) = nominal_point(q) + volumetric_error(q)``. The
pre-compensated command c solves ``actual_point(c) = nominal_point(q)``: the model's inverse
(:meth:`axiscal.model.machine.Machine.command_for`, fixed-point iteration on the nominal
kinematics) for chains of linear axes. With rotary axes standing still at their programmed angles
(a trunnion in 3+2 work), the same equation is solved for the linear axes by Newton steps on the
model's own nominal and actual points, with the nominal kinematics' derivative, which is exact
because the nominal point is affine in the linear axes while the rotary axes stand still.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass, replace

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_instance, check_number
from axiscal.model.machine import Machine, as_machine
from axiscal.units import MM

__all__ = ["PrecompensatedPoints", "precompensate_points", "machine_with_tool", "solve_commands"]

_LINEAR = ("X", "Y", "Z")
_POINT = re.compile(r"point (\d+): (.*)", re.DOTALL)
#: largest miss of a solved command along each axis, metres
SOLVE_TOLERANCE_M = 1e-11
_ITERATIONS = 50


class CommandError(AxiscalError):
    """A command the model cannot give for one point (``index``: 0-based)."""

    def __init__(self, message: str, index: int):
        super().__init__(message)
        self.index = index


@dataclass(frozen=True)
class PrecompensatedPoints:
    """Programmed points and the commands that put the tool on them (SI).

    Attributes
    ----------
    programmed_m : ndarray, shape (N, 3)
        The programmed X, Y, Z axis positions, metres.
    command_m : ndarray, shape (N, 3)
        The pre-compensated commands, metres; a column of an axis the machine does not have is
        the programmed one.
    correction_m : ndarray, shape (N, 3)
        ``command_m - programmed_m``, metres.
    residual_m : ndarray, shape (N,)
        Distance from the tool at the command to the nominal point, as the model predicts it, metres.
    """

    programmed_m: np.ndarray
    command_m: np.ndarray
    correction_m: np.ndarray
    residual_m: np.ndarray


def machine_with_tool(machine: Machine | str, tool_m: tuple[float, float, float] | None) -> Machine:
    """The machine (or its description file), with its functional point moved to ``tool_m`` when given."""
    model = as_machine(machine)
    if tool_m is None:
        return model
    tool = check_array("tool_m", tool_m, ndim=1, min_len=3, last=3)
    return replace(model, tool_m=tuple(float(v) for v in tool))


def solve_commands(machine: Machine, programmed: Mapping[str, np.ndarray]) -> dict[str, np.ndarray]:
    """Commands of the machine's linear axes that put the tool on the nominal points of ``programmed``.

    Parameters
    ----------
    machine : Machine
    programmed : Mapping[str, ndarray, shape (N,)]
        Every axis of the machine's chain: metres, radians for rotary axes (which stand still).

    Returns
    -------
    dict of str to ndarray, shape (N,)
        The linear axes' commands, metres.

    Raises
    ------
    CommandError
        Naming the first point whose command the model cannot give (outside an error table, no
        convergence), with its index.
    """
    target = machine.nominal_point(programmed)
    linear = [k for k in machine.letters if k not in machine.rotary]
    if not machine.rotary:
        try:
            return machine.command_for(target, tolerance_m=SOLVE_TOLERANCE_M, max_iterations=_ITERATIONS)
        except AxiscalError as error:
            found = _POINT.fullmatch(error.message)
            if found is None:
                raise
            raise CommandError(found.group(2), int(found.group(1)) - 1) from None
    command = {k: np.array(programmed[k], dtype=float) for k in machine.letters}
    jacobian = np.empty((len(target), 3, len(linear)))
    for j, letter in enumerate(linear):
        step = dict(command)
        step[letter] = command[letter] + 1.0
        jacobian[:, :, j] = machine.nominal_point(step) - target
    for _ in range(_ITERATIONS):
        for letter in linear:
            table = machine.table(letter)
            k = table.first_outside(command[letter])
            if k is not None:
                raise CommandError(f"needs {letter} = {command[letter][k] / MM:.6g} mm, outside the error table of axis"
                                   f" {letter} ({table.start_m / MM:.6g} to {table.end_m / MM:.6g} mm)", k)
        miss = machine.actual_point(command) - target
        if not np.any(np.abs(miss) > SOLVE_TOLERANCE_M):
            break
        if len(linear) == 3:
            delta = np.linalg.solve(jacobian, miss[:, :, None])[:, :, 0]
        else:
            delta = np.einsum("nij,nj->ni", np.linalg.pinv(jacobian), miss)
        for j, letter in enumerate(linear):
            command[letter] = command[letter] - delta[:, j]
    else:
        worst = int(np.argmax(np.abs(miss).max(axis=1)))
        raise CommandError("inverse kinematics did not converge", worst)
    return {k: command[k] for k in linear}


def precompensate_points(
    machine: Machine | str,
    points_m: np.ndarray,
    *,
    rotary_rad: Mapping[str, float] | None = None,
    tool_m: tuple[float, float, float] | None = None,
) -> PrecompensatedPoints:
    """Pre-compensated commands for programmed points: the tool lands on each nominal point.

    Parameters
    ----------
    machine : Machine or str
        The machine model, or its description file (TOML, docs/formats.md).
    points_m : ndarray, shape (N, 3)
        Programmed X, Y, Z axis positions, metres (the columns of axes the machine does not have
        are passed through).
    rotary_rad : Mapping[str, float], optional, keyword-only
        The angle each rotary axis of the machine stands at, radians (default 0).
    tool_m : sequence of 3 floats, optional, keyword-only
        The functional point in the frame of the last tool-side carriage, metres (default: the
        machine file's ``tool_mm``).

    Returns
    -------
    PrecompensatedPoints

    Raises
    ------
    AxiscalError
        For points that are not finite or not of shape (N, 3), a rotary angle of an axis the machine
        does not have, or a point whose command the model cannot give (named, 1-based).

    Examples
    --------
    >>> result = precompensate_points("examples/xfyz_machine/machine.toml", [[0.3, 0.2, 0.1]])  # doctest: +SKIP
    >>> result.correction_m  # (1, 3), metres  # doctest: +SKIP
    """
    model = machine_with_tool(machine, tool_m)
    points = check_array("points_m", points_m, ndim=2, min_len=1, last=3)
    angles = {} if rotary_rad is None else dict(rotary_rad)
    for letter, value in angles.items():
        check_instance("rotary_rad key", letter, str)
        if letter not in model.rotary:
            raise AxiscalError(f"rotary_rad names {letter!r}, not a rotary axis of chain '{model.chain}'")
        angles[letter] = check_number(f"rotary_rad[{letter!r}]", value)
    n = points.shape[0]
    programmed = {k: points[:, _LINEAR.index(k)] for k in model.letters if k in _LINEAR}
    programmed |= {k: np.full(n, angles.get(k, 0.0)) for k in model.rotary}
    try:
        solved = solve_commands(model, programmed)
    except CommandError as error:
        raise AxiscalError(f"point {error.index + 1}: {error.message}") from None
    command = points.copy()
    for letter, values in solved.items():
        command[:, _LINEAR.index(letter)] = values
    full = dict(programmed) | solved
    residual = np.linalg.norm(model.actual_point(full) - model.nominal_point(programmed), axis=1)
    return PrecompensatedPoints(points, command, command - points, residual)
