"""Calibrated artefacts measured in machine coordinates: the ball plate (Kunzmann, Trapet and Waeldele 1990) and the step gauge.

Ball plate: ``x_i + e_i - (R (c_b - c̄) + t)`` per coordinate, ``(R, t)`` the plate's pose (fitted).
Step gauge: ``n · (x_i - s) + n · e_i - (p + L_f)``, ``p`` the gauge's place along its line (fitted).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
from scipy.spatial.transform import Rotation

from axiscal.errors import AxiscalError
from axiscal.model.machine import Machine

from axiscal.identification.equation import Artefact, _misfit, _skew, axis_positions

__all__ = [
    "BallPlate",
    "StepGauge",
]


@dataclass(frozen=True)
class BallPlate(Artefact):
    """A ball plate in one position: certified centres in the plate's frame, measured centres in machine coordinates.

    Parameters
    ----------
    name, tool_m
        See :class:`Artefact` (``tool_m``: the stylus tip).
    centres_m : ndarray, shape (B, 3)
        Certified ball centres in the plate's frame, metres.
    centre_u_m : ndarray, shape (B,)
        Their standard uncertainty (each coordinate), metres.
    ball : ndarray of int, shape (N,)
        Index into ``centres_m`` of each measured centre (repeats allowed).
    measured_m : ndarray, shape (N, 3)
        Measured centres as the machine reports them (workpiece frame), metres.
    rotation : ndarray, shape (3, 3) or None
        The plate's nominal orientation (columns: its x, y, z axes in machine axes); None: fitted.
    origin_m : ndarray, shape (3,) or None
        The plate's nominal origin in machine axes; None: fitted.
    """

    centres_m: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))
    centre_u_m: np.ndarray = field(default_factory=lambda: np.zeros(0))
    ball: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=int))
    measured_m: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))
    rotation: np.ndarray | None = None
    origin_m: np.ndarray | None = None
    balls: tuple[str, ...] = ()

    kind = "ball_plate"

    @property
    def points_m(self) -> np.ndarray:
        """The reported points of the readings (N, 3), metres."""
        return self.measured_m

    @property
    def count(self) -> int:
        return 3 * len(self.ball)

    @property
    def unknowns(self) -> tuple[str, ...]:
        return tuple(f"{self.name}:{k}" for k in ("rx", "ry", "rz", "tx", "ty", "tz"))

    def positions(self, machine: Machine) -> dict[str, np.ndarray]:
        return axis_positions(machine, self.measured_m, self.tool_m)

    @cached_property
    def reference_rotation(self) -> np.ndarray:
        """The plate's orientation (3, 3) fitted to the measured centres as reported (Kabsch); the
        pose's rotation unknowns turn the plate from there."""
        plate = self.centres_m[self.ball]
        if np.linalg.matrix_rank(plate - plate.mean(axis=0), tol=1e-6) < 2:
            raise AxiscalError(f"{self.name}: the pose of a plate needs at least 3 balls not on one line")
        rotation, _ = Rotation.align_vectors(self.measured_m - self.measured_m.mean(axis=0), plate - plate.mean(axis=0))
        return rotation.as_matrix()

    @cached_property
    def centred_m(self) -> np.ndarray:
        """The certified centres of the balls measured (N, 3) about their centroid, metres: the pose
        turns the plate about that centroid and moves it by ``t``, so that the pose's unknowns, and
        so the machine identified, do not depend on where the certificate puts its origin or how
        it turns its axes."""
        plate = self.centres_m[self.ball]
        return plate - plate.mean(axis=0)

    def start(self, nominal_m: np.ndarray, error_m: np.ndarray) -> np.ndarray:
        actual = nominal_m + error_m
        plate = self.centres_m[self.ball]
        rows = np.arange(len(self.ball))
        if self.rotation is not None:
            placed = plate @ self.rotation.T + self.origin_m
            _misfit(self, np.linalg.norm(actual - placed, axis=1), rows, "ball measured where the stated pose does not put it:")
        rotation, _ = Rotation.align_vectors(actual - actual.mean(axis=0), self.centred_m)
        turn = rotation.as_matrix() @ self.reference_rotation.T
        turned = self.centred_m @ rotation.as_matrix().T
        origin = actual.mean(axis=0)  # where the centroid of the balls measured stands
        _misfit(self, np.linalg.norm(actual - turned - origin, axis=1), rows, "ball does not fit the plate (wrong ball name?):")
        return np.concatenate([Rotation.from_matrix(turn).as_rotvec(), origin])

    def _placed(self, p: np.ndarray) -> np.ndarray:
        rotation = Rotation.from_rotvec(p[:3]).as_matrix() @ self.reference_rotation
        return self.centred_m @ rotation.T + p[3:], rotation

    def residuals(self, nominal_m, error_m, p):
        placed, _ = self._placed(p)
        return (nominal_m + error_m - placed).ravel()

    def partials(self, nominal_m, error_m, p):
        n = len(self.ball)
        placed, _ = self._placed(p)
        d_pose = np.concatenate([_skew(placed - p[3:]), np.broadcast_to(-np.eye(3), (n, 3, 3))], axis=2)
        return np.repeat(np.arange(n), 3), np.tile(np.eye(3), (n, 1)), d_pose.reshape(3 * n, 6)

    def systematic(self):
        n, b = len(self.ball), len(self.centres_m)
        s = np.zeros((n, 3, b, 3))
        s[np.arange(n), :, self.ball, :] = -self.reference_rotation
        # a centre also moves the centroid the plate turns about, by its share of the balls measured
        share = np.bincount(self.ball, minlength=b) / n
        s += share[None, None, :, None] * self.reference_rotation[None, :, None, :]
        return s.reshape(3 * n, 3 * b), np.repeat(self.centre_u_m, 3)


@dataclass(frozen=True)
class StepGauge(Artefact):
    """A step gauge along a line: certified face positions, measured faces in machine coordinates.

    Parameters
    ----------
    name, tool_m
        See :class:`Artefact`.
    start_m : ndarray, shape (3,)
        A point of the line in machine axes, metres.
    direction : ndarray, shape (3,)
        Unit vector of the line in machine axes.
    faces_m : ndarray, shape (F,)
        Certified face positions along the gauge, metres.
    face_u_m : ndarray, shape (F,)
        Their standard uncertainty, metres.
    face : ndarray of int, shape (N,)
        Index into ``faces_m`` of each measured face.
    measured_m : ndarray, shape (N, 3)
        Measured face points as the machine reports them, metres.
    """

    start_m: np.ndarray = field(default_factory=lambda: np.zeros(3))
    direction: np.ndarray = field(default_factory=lambda: np.array([1.0, 0.0, 0.0]))
    faces_m: np.ndarray = field(default_factory=lambda: np.zeros(0))
    face_u_m: np.ndarray = field(default_factory=lambda: np.zeros(0))
    face: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=int))
    measured_m: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))
    face_names: tuple[str, ...] = ()

    kind = "step_gauge"

    @property
    def points_m(self) -> np.ndarray:
        """The reported points of the readings (N, 3), metres."""
        return self.measured_m

    @property
    def count(self) -> int:
        return len(self.face)

    @property
    def unknowns(self) -> tuple[str, ...]:
        return (f"{self.name}:place",)

    def positions(self, machine: Machine) -> dict[str, np.ndarray]:
        return axis_positions(machine, self.measured_m, self.tool_m)

    def _along(self, nominal_m, error_m):
        return (nominal_m + error_m - self.start_m) @ self.direction - self.faces_m[self.face]

    def start(self, nominal_m, error_m):
        along = self._along(nominal_m, error_m)
        place = float(np.median(along))
        _misfit(self, along - place, np.arange(len(self.face)), "face measured")
        return np.array([place])

    def residuals(self, nominal_m, error_m, p):
        return self._along(nominal_m, error_m) - p[0]

    def partials(self, nominal_m, error_m, p):
        n = len(self.face)
        return np.arange(n), np.tile(self.direction, (n, 1)), -np.ones((n, 1))

    def systematic(self):
        s = np.zeros((len(self.face), len(self.faces_m)))
        s[np.arange(len(self.face)), self.face] = -1.0
        return s, self.face_u_m
