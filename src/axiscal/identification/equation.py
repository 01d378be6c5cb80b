"""What every artefact's measurement equation shares: the :class:`Artefact` it fills in, the misfit check, and the axis positions that reach its points.

The artefacts themselves (:mod:`axiscal.identification.artefacts` lists their equations) fill in
where they are read, their own unknowns, their residuals and the residuals' partial derivatives.
"""

from __future__ import annotations

import dataclasses
from abc import ABC, abstractmethod
from dataclasses import dataclass

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_instance, check_mapping
from axiscal.model.machine import Machine
from axiscal.units import MM

__all__ = [
    "MISFIT_M",
    "Artefact",
    "axis_positions",
    "r_test_positions",
]


#: a reading further than this from what the artefact's nominal geometry predicts is a mistake, not an error motion
MISFIT_M = 1e-4


def axis_positions(machine: Machine, points_m: np.ndarray, tool_m: np.ndarray) -> dict[str, np.ndarray]:
    """Axis positions at which a chain of linear axes reports ``points_m`` for tool point ``tool_m``.

    Parameters
    ----------
    machine : Machine
        A chain of linear axes.
    points_m : ndarray, shape (N, 3)
        Reported points, workpiece frame, metres.
    tool_m : ndarray, shape (3,)
        The tool point (stylus tip, reflector, ball) in the last tool-side carriage, metres.

    Returns
    -------
    dict of str to ndarray, shape (N,)
        Metres.

    Raises
    ------
    AxiscalError
        A chain with rotary axes (their positions must be given).
    """
    if machine.rotary:
        raise AxiscalError(f"chain '{machine.chain}' has rotary axes: an artefact on it gives every axis position")
    tooled = dataclasses.replace(machine, tool_m=tuple(float(v) for v in tool_m))
    offset = tooled.nominal_point({k: np.zeros(1) for k in machine.letters})[0]
    out = {}
    for letter in machine.letters:
        sign = 1.0 if letter in machine.tool_side else -1.0
        index = "XYZ".index(letter)
        out[letter] = sign * (points_m[:, index] - offset[index])
    return out


def r_test_positions(machine: Machine, rotary_m: dict, ball_workpiece_m: np.ndarray) -> dict:
    """Linear axis positions that keep the ball at ``ball_workpiece_m`` (workpiece frame) while the rotary axes turn.

    Parameters
    ----------
    machine : Machine
        A chain with rotary axes; its tool point is the ball.
    rotary_m : dict of str to ndarray, shape (N,)
        Angles of every rotary axis, radians.
    ball_workpiece_m : ndarray, shape (3,)
        Where the ball sits relative to the workpiece point, in the workpiece frame, metres.

    Returns
    -------
    dict of str to ndarray, shape (N,)
        Every axis of the chain: the angles given and the linear positions (metres) from the
        nominal kinematics (affine in the linear axes for fixed angles).
    """
    check_instance("machine", machine, Machine)
    if not machine.rotary:
        raise AxiscalError(f"chain '{machine.chain}' has no rotary axis to turn")
    check_mapping("rotary_m", rotary_m, machine.rotary, what="a mapping of every rotary axis of the chain to its angles")
    ball_workpiece_m = check_array("ball_workpiece_m", ball_workpiece_m, ndim=1, last=3)
    n = len(check_array(f"rotary_m[{machine.rotary[0]!r}]", rotary_m[machine.rotary[0]], ndim=1, unit=""))
    linear = [k for k in machine.letters if k not in machine.rotary]
    base = {k: np.asarray(rotary_m[k], dtype=float) for k in machine.rotary} | {k: np.zeros(n) for k in linear}
    p0 = machine.nominal_point(base)
    columns = []
    for letter in linear:
        moved = dict(base)
        moved[letter] = np.ones(n)
        columns.append(machine.nominal_point(moved) - p0)
    matrix = np.stack(columns, axis=2)  # (N, 3, L)
    out = dict(base)
    target = np.asarray(ball_workpiece_m, dtype=float) - p0
    q = np.stack([np.linalg.lstsq(matrix[i], target[i], rcond=None)[0] for i in range(n)])
    for k, letter in enumerate(linear):
        out[letter] = q[:, k]
    return out


def _skew(v: np.ndarray) -> np.ndarray:
    """[v]x for each row of v (N, 3) -> (N, 3, 3)."""
    out = np.zeros(v.shape[:-1] + (3, 3))
    out[..., 0, 1], out[..., 0, 2] = -v[..., 2], v[..., 1]
    out[..., 1, 0], out[..., 1, 2] = v[..., 2], -v[..., 0]
    out[..., 2, 0], out[..., 2, 1] = -v[..., 1], v[..., 0]
    return out


def _misfit(artefact: "Artefact", residual: np.ndarray, rows: np.ndarray, what: str) -> None:
    """Refuse the worst reading if its residual exceeds :data:`MISFIT_M`, naming its line (a fit spreads
    one wrong reading over the others; the worst is the one to look at)."""
    worst = int(np.argmax(np.abs(residual))) if residual.size else 0
    if residual.size and abs(residual[worst]) > MISFIT_M:
        k = int(rows[worst])
        line = int(artefact.lines[k]) if len(artefact.lines) > k else None
        raise AxiscalError(
            f"{artefact.name}: {what} {abs(residual[worst]) / MM:.4g} mm off (more than {MISFIT_M / MM:g} mm)",
            path=artefact.data_path or None,
            line=line,
        )


@dataclass(frozen=True)
class Artefact(ABC):
    """What every artefact holds: a name, the tool point, and where its readings came from.

    Parameters
    ----------
    name : str
        Its name in reports and in the names of its own unknowns.
    tool_m : ndarray, shape (3,)
        The probed point on the tool (stylus tip, ball, reflector) in the last tool-side carriage, m.
    data_path : str
        The data file, for messages (empty when made in Python).
    lines : tuple of int
        The line of each reading in that file (empty when made in Python).
    """

    name: str
    tool_m: np.ndarray
    data_path: str = ""
    lines: tuple[int, ...] = ()

    kind = ""

    @abstractmethod
    def positions(self, machine: Machine) -> dict[str, np.ndarray]:
        """Axis positions (N,) of the points the artefact reads."""

    def reported(self, machine: Machine, positions: dict[str, np.ndarray]) -> np.ndarray:
        """The nominal points (N, 3) the machine reports at the readings, workpiece frame, metres.

        For an artefact measured in machine coordinates these are the coordinates in its file (on a
        machine of fewer than three linear axes, the coordinates along the missing ones too).
        """
        points = getattr(self, "points_m", None)
        if points is not None:
            return points
        tooled = dataclasses.replace(machine, tool_m=tuple(float(v) for v in self.tool_m))
        return tooled.nominal_point(positions)

    @property
    @abstractmethod
    def unknowns(self) -> tuple[str, ...]:
        """Names of the artefact's own unknowns (its pose, place, centres ...)."""

    @abstractmethod
    def start(self, nominal_m: np.ndarray, error_m: np.ndarray) -> np.ndarray:
        """The artefact's unknowns fitted with the machine as it starts; refuses readings that do not fit."""

    @abstractmethod
    def residuals(self, nominal_m: np.ndarray, error_m: np.ndarray, p: np.ndarray) -> np.ndarray:
        """The residuals (M,), metres."""

    @abstractmethod
    def partials(self, nominal_m: np.ndarray, error_m: np.ndarray, p: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(point (M,), direction (M, 3), d residual / d p (M, len(unknowns)))."""

    def systematic(self) -> tuple[np.ndarray, np.ndarray]:
        """Calibration errors of the artefact: (S (M, K), u (K,)); residuals move by S δ, δ of standard uncertainty u."""
        return np.zeros((self.count, 0)), np.zeros(0)

    @property
    @abstractmethod
    def count(self) -> int:
        """Number of residuals M."""
