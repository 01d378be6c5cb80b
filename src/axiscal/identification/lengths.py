"""Artefacts that read lengths: the ballbar network and multilateration (Schwenke et al., CIRP Annals 54/1, 2005).

Ballbar network: ``|x_i + e_i - c_k| - ℓ_i``, ``c_k`` the centre ball of setup k (fitted).
Multilateration: ``|x_i + e_i - s_j| + d_j - ρ_i``, station ``s_j`` and dead path ``d_j`` (fitted).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import least_squares

from axiscal.errors import AxiscalError
from axiscal.model.machine import Machine

from axiscal.identification.equation import MISFIT_M, Artefact, _misfit, axis_positions

__all__ = [
    "BallbarNetwork",
    "Multilateration",
]


@dataclass(frozen=True)
class BallbarNetwork(Artefact):
    """Ballbar lengths from centre balls (one per setup, fitted) to tool positions.

    Parameters
    ----------
    name, tool_m
        See :class:`Artefact` (``tool_m``: the tool ball's centre).
    setup : ndarray of int, shape (N,)
        The setup (centre ball) of each reading, 0 .. S-1.
    centres_m : ndarray, shape (S, 3)
        Nominal centre of each setup's centre ball in machine axes, metres (fitted from there).
    ends_m : ndarray, shape (N, 3)
        Nominal tool-ball centre of each reading as the machine reports it, metres.
    lengths_m : ndarray, shape (N,)
        Measured lengths: the calibrated length plus the bar's reading, metres.
    length_u_m : float
        Standard uncertainty of the calibrated length, metres.
    """

    setup: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=int))
    centres_m: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))
    ends_m: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))
    lengths_m: np.ndarray = field(default_factory=lambda: np.zeros(0))
    length_u_m: float = 0.0
    setups: tuple[str, ...] = ()

    kind = "ballbar_network"

    @property
    def points_m(self) -> np.ndarray:
        """The reported points of the readings (N, 3), metres."""
        return self.ends_m

    @property
    def count(self) -> int:
        return len(self.setup)

    @property
    def unknowns(self) -> tuple[str, ...]:
        names = self.setups or tuple(str(k + 1) for k in range(len(self.centres_m)))
        return tuple(f"{self.name}:centre_{s}:{c}" for s in names for c in "xyz")

    def positions(self, machine: Machine) -> dict[str, np.ndarray]:
        return axis_positions(machine, self.ends_m, self.tool_m)

    def _vector(self, nominal_m, error_m, p):
        return nominal_m + error_m - p.reshape(-1, 3)[self.setup]

    def start(self, nominal_m, error_m):
        p = self.centres_m.ravel().copy()
        _misfit(self, self.residuals(nominal_m, error_m, p), np.arange(self.count), "length measured")
        return p

    def residuals(self, nominal_m, error_m, p):
        return np.linalg.norm(self._vector(nominal_m, error_m, p), axis=1) - self.lengths_m

    def partials(self, nominal_m, error_m, p):
        v = self._vector(nominal_m, error_m, p)
        n = v / np.linalg.norm(v, axis=1)[:, None]
        d = np.zeros((self.count, len(p)))
        for c in range(3):
            d[np.arange(self.count), 3 * self.setup + c] = -n[:, c]
        return np.arange(self.count), n, d

    def systematic(self):
        return -np.ones((self.count, 1)), np.array([self.length_u_m])


@dataclass(frozen=True)
class Multilateration(Artefact):
    """Ranges from a tracking interferometer at several stations to a reflector on the tool.

    Parameters
    ----------
    name, tool_m
        See :class:`Artefact` (``tool_m``: the reflector's centre).
    station : ndarray of int, shape (N,)
        The station of each range, 0 .. S-1.
    targets_m : ndarray, shape (N, 3)
        Nominal reflector positions as the machine reports them, metres.
    ranges_m : ndarray, shape (N,)
        Measured ranges, metres (each station's dead path unknown).
    stations_m : ndarray, shape (S, 3) or None
        Stations' approximate positions; None: found from the ranges (at least 5 targets per
        station, not all in one plane).
    """

    station: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=int))
    targets_m: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))
    ranges_m: np.ndarray = field(default_factory=lambda: np.zeros(0))
    stations_m: np.ndarray | None = None
    stations: tuple[str, ...] = ()

    kind = "multilateration"

    @property
    def points_m(self) -> np.ndarray:
        """The reported points of the readings (N, 3), metres."""
        return self.targets_m

    @property
    def count(self) -> int:
        return len(self.station)

    @property
    def size(self) -> int:
        return int(self.station.max()) + 1 if self.count else 0

    @property
    def unknowns(self) -> tuple[str, ...]:
        names = self.stations or tuple(str(k + 1) for k in range(self.size))
        return tuple(f"{self.name}:station_{s}:{c}" for s in names for c in ("x", "y", "z", "dead_path"))

    def positions(self, machine: Machine) -> dict[str, np.ndarray]:
        return axis_positions(machine, self.targets_m, self.tool_m)

    def start(self, nominal_m, error_m):
        actual = nominal_m + error_m
        p = np.zeros(4 * self.size)
        for s in range(self.size):
            rows = np.flatnonzero(self.station == s)
            x, rho = actual[rows], self.ranges_m[rows]
            if self.stations_m is not None:
                position = self.stations_m[s]
                dead = float(np.mean(rho - np.linalg.norm(x - position, axis=1)))
            else:
                # rho² - |x|² = -2 x·s + 2 rho d + (|s|² - d²): linear in s, d and |s|² - d²
                design = np.column_stack([-2.0 * x, 2.0 * rho, np.ones(len(rows))])
                if len(rows) < 5 or np.linalg.matrix_rank(design / np.abs(design).max(axis=0), tol=1e-9) < 5:
                    raise AxiscalError(
                        f"{self.name}: station {self.unknowns[4 * s].split(':')[1][8:]} needs at least 5 targets not all in "
                        "one plane to be found (or give its approximate position)",
                        path=self.data_path or None,
                    )
                solution = np.linalg.lstsq(design, rho**2 - np.einsum("ij,ij->i", x, x), rcond=None)[0]
                # then the ranges themselves, robustly: one wrong range must stand out, not spread
                refined = least_squares(
                    lambda v: np.linalg.norm(x - v[:3], axis=1) + v[3] - rho, solution[:4], loss="soft_l1", f_scale=MISFIT_M / 10
                ).x
                position, dead = refined[:3], float(refined[3])
            p[4 * s : 4 * s + 3], p[4 * s + 3] = position, dead
        _misfit(self, self.residuals(nominal_m, error_m, p), np.arange(self.count), "range does not fit its station:")
        return p

    def residuals(self, nominal_m, error_m, p):
        q = p.reshape(-1, 4)
        return np.linalg.norm(nominal_m + error_m - q[self.station, :3], axis=1) + q[self.station, 3] - self.ranges_m

    def partials(self, nominal_m, error_m, p):
        q = p.reshape(-1, 4)
        v = nominal_m + error_m - q[self.station, :3]
        n = v / np.linalg.norm(v, axis=1)[:, None]
        d = np.zeros((self.count, len(p)))
        rows = np.arange(self.count)
        for c in range(3):
            d[rows, 4 * self.station + c] = -n[:, c]
        d[rows, 4 * self.station + 3] = 1.0
        return rows, n, d
