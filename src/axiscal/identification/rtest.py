"""The R-test (Weikert, CIRP Annals 53/1, 2004; ISO 10791-6): three displacement sensors on a ball carried by the rotary axes.

``d_k · e_i + z_k - m_ik`` for sensor k of direction ``d_k`` (workpiece frame) and zero offset ``z_k`` (fitted).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.model.machine import Machine

from axiscal.identification.equation import Artefact, _misfit, r_test_positions

__all__ = [
    "RTest",
]


@dataclass(frozen=True)
class RTest(Artefact):
    """An R-test: displacement sensors on the table read a ball on the tool while the axes move together.

    Parameters
    ----------
    name, tool_m
        See :class:`Artefact` (``tool_m``: the ball's centre).
    axis_positions_m : dict of str to ndarray, shape (N,)
        Every axis of the chain at each reading: metres, radians for rotary axes.
    directions : ndarray, shape (K, 3)
        Unit sensing direction of each sensor in the workpiece (table) frame.
    readings_m : ndarray, shape (N, K)
        Sensor readings, metres (each sensor's zero unknown).
    ball_table_m : ndarray, shape (3,) or None
        Where the ball nominally stays on the table (workpiece frame), metres: with it, linear
        axes missing from ``axis_positions_m`` follow from the nominal kinematics.
    """

    axis_positions_m: dict = field(default_factory=dict)
    directions: np.ndarray = field(default_factory=lambda: np.eye(3))
    readings_m: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))
    ball_table_m: np.ndarray | None = None

    kind = "r_test"

    @property
    def count(self) -> int:
        return self.readings_m.size

    @property
    def unknowns(self) -> tuple[str, ...]:
        return tuple(f"{self.name}:zero_{k + 1}" for k in range(self.directions.shape[0]))

    def positions(self, machine: Machine) -> dict[str, np.ndarray]:
        missing = [k for k in machine.letters if k not in self.axis_positions_m]
        if missing and self.ball_table_m is not None and not set(missing) & set(machine.rotary):
            tooled = dataclasses.replace(machine, tool_m=tuple(float(v) for v in self.tool_m))
            solved = r_test_positions(tooled, {k: self.axis_positions_m[k] for k in machine.rotary}, self.ball_table_m)
            return {k: self.axis_positions_m.get(k, solved[k]) for k in machine.letters}
        if missing:
            raise AxiscalError(f"{self.name}: no positions of axis {', '.join(missing)} of chain '{machine.chain}'", path=self.data_path or None)
        return {k: self.axis_positions_m[k] for k in machine.letters}

    def start(self, nominal_m, error_m):
        along = error_m @ self.directions.T - self.readings_m
        zero = -np.median(along, axis=0)
        spread = (along + zero).ravel()
        _misfit(self, spread, np.repeat(np.arange(len(self.readings_m)), self.directions.shape[0]), "sensor reading")
        return zero

    def residuals(self, nominal_m, error_m, p):
        return (error_m @ self.directions.T + p - self.readings_m).ravel()

    def partials(self, nominal_m, error_m, p):
        n, k = self.readings_m.shape
        return np.repeat(np.arange(n), k), np.tile(self.directions, (n, 1)), np.tile(np.eye(k), (n, 1))
