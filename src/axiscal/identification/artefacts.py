"""The measurement equation of each artefact: what it reads, as a function of the volumetric error at the machine points it uses.

Every artefact reads the machine at N points (axis positions and a tool point). With ``e_i`` the
volumetric error there (actual minus nominal, workpiece frame, :meth:`axiscal.model.Machine.volumetric_error`)
and ``x_i`` the nominal point the machine reports, the residuals are:

- ball plate (Kunzmann, Trapet and Waeldele 1990): ``x_i + e_i - (R (c_b - c̄) + t)`` per
  coordinate, ``c_b`` the certified centre of the ball probed, ``c̄`` the centroid of the balls
  measured, ``(R, t)`` the plate's pose (fitted): its turn about that centroid and where the
  centroid stands, so that nothing depends on the frame of the certificate;
- step gauge: ``n · (x_i - s) + n · e_i - (p + L_f)``, ``s, n`` the line, ``L_f`` the certified face
  position, ``p`` the gauge's place along the line (fitted);
- ballbar network: ``|x_i + e_i - c_k| - ℓ_i``, ``c_k`` the centre ball of setup k (fitted),
  ``ℓ_i`` the calibrated length plus the bar's reading;
- multilateration (Schwenke et al., CIRP Annals 54/1, 2005): ``|x_i + e_i - s_j| + d_j - ρ_i``,
  ``s_j`` the position of station j and ``d_j`` its dead path (both fitted);
- R-test (Weikert, CIRP Annals 53/1, 2004; ISO 10791-6): ``d_k · e_i + z_k - m_ik`` for sensor k
  of direction ``d_k`` (workpiece frame) and zero offset ``z_k`` (fitted).

Each residual depends on the error at one point, along one direction: the Jacobian of the
residuals is ``direction · ∂e/∂θ`` for the machine's terms and an analytic block for the
artefact's own unknowns (its pose, place, centres, stations, offsets).
"""

from __future__ import annotations

import dataclasses
from abc import ABC, abstractmethod
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
from scipy.optimize import least_squares
from scipy.spatial.transform import Rotation

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_instance, check_mapping
from axiscal.model.machine import Machine
from axiscal.units import MM

__all__ = [
    "MISFIT_M",
    "Artefact",
    "BallPlate",
    "StepGauge",
    "BallbarNetwork",
    "Multilateration",
    "RTest",
    "axis_positions",
    "r_test_positions",
    "ARTEFACT_KINDS",
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


#: the kind named in an artefact file -> its class
ARTEFACT_KINDS = {cls.kind: cls for cls in (BallPlate, StepGauge, BallbarNetwork, Multilateration, RTest)}
