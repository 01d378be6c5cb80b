"""A physically modelled 2-axis XZ module with its 6-DOF sensors: the default data source (paper 000).

The module is the one of paper 000: chain ``FXZ`` (X on the frame carries Z, Z carries the tool),
190 mm strokes, squareness EB0Z = -42.4 arcsec (section 5), the functional point 40 mm off the Z
carriage (``y2`` of eq 9) and Z's carriage 50 mm above X's (``z0`` of eq 7). Its true error
motions are smooth curves of the sizes lead-screw modules show (positioning tens of um,
straightness a few um, angles tens of urad); a mass on the Z slide tilts both carriages more
(the 2 kg experiment of section 5). The amplitudes are chosen so that the diagonal error before
the model is of the size the paper reports; they are not the paper's (it publishes no curves).

Each sensor has a true gain and offset that calibration must find, and reading noise; the roll
detector's plane mirror has a form error that the mirror map must find. The module emits raw
frames (the channels of :class:`axiscal.measurement.pipeline.MeasurementSystem`) along a path, the truth
that goes with them, the data of its calibration runs, and the readings of a laser
interferometer on the XZ diagonal (the diagonal experiment run on it is
:mod:`axiscal.measurement.experiment`).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from axiscal.conventions import component_names
from axiscal.errors import AxiscalError
from axiscal.instruments.abbe import transfer_point
from axiscal.io.arguments import check_array, check_count, check_mapping, check_number, check_same_length
from axiscal.instruments.calibration import (
    Calibration,
    fit_mirror,
    fit_sensitivity,
    transfer_reference,
)
from axiscal.instruments.sensors import (
    SensorHead,
    SignedComponent,
    autocollimation_shift,
    quadrant_shift,
    roll_from_autocollimation,
)
from axiscal.measurement.pipeline import (
    MeasurementSystem,
    spatial_error,
)
from axiscal.model.machine import Axis, Machine
from axiscal.model.tables import ErrorTable
from axiscal.units import ARCSEC, MM, UM, URAD

#: SI per unit of the rows of the error curves: tx, ty, tz in um, ea, eb, ec in urad
_ERROR_UNITS = np.array([UM, UM, UM, URAD, URAD, URAD])[:, None]

__all__ = [
    "STROKE_M",
    "SQUARENESS_EB0Z_RAD",
    "TOOL_M",
    "Z_ORIGIN_M",
    "PATHS",
    "INTERFEROMETER_BEAM_M",
    "QD_FOCAL_M",
    "ROLL_FOCAL_M",
    "NOISE",
    "REFERENCE_NOISE",
    "Truth",
    "VirtualModule",
]

STROKE_M = 0.19
SQUARENESS_EB0Z_RAD = -42.4 * ARCSEC
TOOL_M = (0.0, -0.040, 0.0)
Z_ORIGIN_M = (0.0, 0.0, 0.050)
#: the motions the module can make (:meth:`VirtualModule.positions`); the commands that drive it offer these
PATHS = ("diagonal", "raster", "back-and-forth")

#: (amplitude, cycles over the stroke, phase) of the smooth error curves, um or urad
_CURVES = {
    "X": {
        "EXX": (-0.175, [(2.0, 1.5, 0.3), (0.6, 4.0, 1.0)]),
        "EYX": (0.0, [(2.5, 0.5, 0.0), (0.5, 2.0, 1.0)]),
        "EZX": (0.0, [(-3.0, 0.5, 0.0), (0.4, 1.5, 0.7)]),
        "EAX": (0.0, [(14.0, 0.5, 0.3), (3.0, 2.0, 0.0)]),
        "EBX": (0.12, [(22.0, 0.5, 0.0), (5.0, 1.5, 1.2)]),
        "ECX": (0.0, [(-18.0, 0.5, 0.6), (4.0, 2.5, 0.0)]),
    },
    "Z": {
        "EXZ": (0.0, [(3.5, 0.5, 0.0), (0.5, 2.0, 0.3)]),
        "EYZ": (0.0, [(-1.8, 0.5, 0.2), (0.3, 1.5, 0.0)]),
        "EZZ": (-0.12, [(1.5, 2.5, 1.0), (0.5, 5.0, 0.0)]),
        "EAZ": (0.0, [(16.0, 0.5, 0.0), (4.0, 1.5, 0.5)]),
        "EBZ": (0.0, [(-20.0, 0.5, 0.4), (3.0, 2.0, 0.0)]),
        "ECZ": (0.0, [(10.0, 0.5, 1.0), (2.0, 3.0, 0.0)]),
    },
}
#: change of the angular errors per kg on the Z slide, urad/kg: (constant, slope over the stroke)
_LOAD = {"EBX": (12.0, 23.0), "EAX": (3.0, 2.0), "EAZ": (-4.0, -3.0), "EBZ": (5.0, 6.0)}

#: the sensor heads of the module (mm): read heads beside and below the carriages, PSDs above
_GEOMETRY = {
    "X": {"scale_point": (0.0, -25.0, -30.0), "psd_point": (0.0, 20.0, 15.0)},
    "Z": {"scale_point": (20.0, -25.0, 0.0), "psd_point": (-15.0, 20.0, 0.0)},
}
#: where the interferometer's beam meets the carriage, relative to the scale's read head (m)
INTERFEROMETER_BEAM_M = np.array([0.0, 0.045, 0.020])
QD_FOCAL_M = 0.100
ROLL_FOCAL_M = 0.080

#: reading noise (rms) of each kind of channel, in the channel's unit (mm for scales, um for spots)
NOISE = {"cmd": 0.0, "scale": 0.1e-3, "psd": 0.2, "qd": 0.05, "roll": 0.08}
#: reference instruments: inductive probe (um), autocollimator (rad), level (rad), interferometer (m)
REFERENCE_NOISE = {"probe": 0.02, "autocollimator": 0.05 * ARCSEC, "level": 0.2 * ARCSEC, "interferometer": 5e-9}


def _curve(q_m: np.ndarray, slope: float, terms: list[tuple[float, float, float]]) -> np.ndarray:
    """slope * q_mm + sum a sin(2 pi c s + p) - its value at 0 (um or urad), with s = q / stroke."""
    s = q_m / STROKE_M
    value = slope * (q_m / MM)
    for a, c, p in terms:
        value = value + a * (np.sin(2 * np.pi * c * s + p) - np.sin(p))
    return value


def _moved(errors: np.ndarray, point_m) -> np.ndarray:
    """Translation (3, N) of the carriage point ``point_m`` from the errors (6, N) at its origin (Abbe-Bryan)."""
    return transfer_point(errors[:3].T, errors[3:].T, np.asarray(point_m, dtype=float)).T


@dataclass(frozen=True)
class Truth:
    """Gain and offset a raw channel really has: ``true value = gain * raw + offset``.

    Attributes
    ----------
    gain : float
        True sensitivity.
    offset : float
        True offset, the channel's unit.
    noise : float
        Reading noise (rms), the channel's unit.
    """

    gain: float
    offset: float
    noise: float

    def __post_init__(self) -> None:
        if check_number("gain", self.gain, unit="") == 0.0:
            raise AxiscalError("gain must not be zero")
        check_number("offset", self.offset, unit="")
        check_number("noise", self.noise, nonnegative=True, unit="")


class VirtualModule:
    """Physically modelled 2-axis XZ module of paper 000 (190 mm strokes), the default source.

    Parameters
    ----------
    seed : int
        Seed of the sensors' true gains and offsets and of all noise (default 0).
    load_kg : float
        Mass on the Z slide, kg (default 0; the paper's second experiment uses 2).
    noise : bool
        Add reading noise to sensors and reference instruments (default True).
    speed_mm_s : float
        Axis speed along the paths, mm/s (default 50).
    """

    def __init__(self, *, seed: int = 0, load_kg: float = 0.0, noise: bool = True, speed_mm_s: float = 50.0):
        seed = check_count("seed", seed, minimum=0)
        load_kg = check_number("load_kg", load_kg, nonnegative=True)
        if not isinstance(noise, (bool, np.bool_)):
            raise AxiscalError(f"noise must be True or False, not {noise!r}")
        speed_mm_s = check_number("speed_mm_s", speed_mm_s, positive=True, unit="millimetres per second")
        self.seed = seed
        self.load_kg = float(load_kg)
        self.noise = bool(noise)
        self.speed_m_s = speed_mm_s * MM
        self._rng = np.random.default_rng([seed, 1])
        heads = {}
        for letter in ("X", "Z"):
            names = component_names(letter)
            u, v, roll = {"X": (("ECX", 1), ("EBX", -1), ("EAX", 1)), "Z": (("EBZ", 1), ("EAZ", -1), ("ECZ", 1))}[letter]
            heads[letter] = SensorHead(
                letter=letter,
                prefix=letter.lower(),
                scale_point_m=tuple(c * MM for c in _GEOMETRY[letter]["scale_point"]),
                psd_point_m=tuple(c * MM for c in _GEOMETRY[letter]["psd_point"]),
                qd_focal_m=QD_FOCAL_M,
                roll_focal_m=ROLL_FOCAL_M,
                qd_u=SignedComponent(names.index(u[0]), float(u[1])),
                qd_v=SignedComponent(names.index(v[0]), float(v[1])),
                roll=SignedComponent(names.index(roll[0]), float(roll[1])),
            )
        self.heads = heads
        self._curve_arrays = {}
        for letter in ("X", "Z"):
            names = component_names(letter)
            curves = [_CURVES[letter][n] for n in names]
            self._curve_arrays[letter] = (
                np.array([c[0] for c in curves]),
                np.array([[a for a, _, _ in c[1]] for c in curves]),
                np.array([[f for _, f, _ in c[1]] for c in curves]),
                np.array([[p for _, _, p in c[1]] for c in curves]),
                np.array([_LOAD.get(n, (0.0, 0.0))[0] for n in names]),
                np.array([_LOAD.get(n, (0.0, 0.0))[1] for n in names]),
            )
        grid = np.linspace(0.0, STROKE_M, 39)
        self.machine = Machine(
            chain="FXZ",
            axes={
                k: Axis(
                    k,
                    ErrorTable(k, grid, self.true_errors(k, grid), interpolation="cubic"),
                    Z_ORIGIN_M if k == "Z" else (0.0, 0.0, 0.0),
                )
                for k in ("X", "Z")
            },
            squareness_rad={"EB0Z": SQUARENESS_EB0Z_RAD},
            tool_m=TOOL_M,
            name="virtual XZ module (paper 000)",
        )
        truth_rng = np.random.default_rng([seed, 0])
        self.sensor_truth: dict[str, Truth] = {}
        for letter, head in heads.items():
            for role, name in head.channels.items():
                kind = role.split("_")[0]
                if kind == "cmd":
                    self.sensor_truth[name] = Truth(1.0, 0.0, 0.0)
                elif kind == "scale":
                    gain = 1.0 + truth_rng.uniform(-40e-6, 40e-6)
                    self.sensor_truth[name] = Truth(gain, truth_rng.uniform(-5e-3, 5e-3), NOISE[kind])
                else:
                    gain = 1.0 + truth_rng.uniform(-0.05, 0.05)
                    self.sensor_truth[name] = Truth(gain, truth_rng.uniform(-20.0, 20.0), NOISE[kind])
        #: plane-mirror form error seen by each roll detector: (amplitude urad, cycles, phase)
        self.mirror_terms = {
            k: [(truth_rng.uniform(3.0, 6.0), 0.7, truth_rng.uniform(0, np.pi)), (1.5, 1.6, truth_rng.uniform(0, np.pi))]
            for k in ("X", "Z")
        }

    def _letter(self, letter: str) -> str:
        if not isinstance(letter, str) or letter not in self.heads:
            raise AxiscalError(f"letter must be an axis of the module ({', '.join(self.heads)}), not {letter!r}")
        return letter

    def _positions(self, positions_m: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
        """``"X"`` and ``"Z"`` commanded positions as finite 1-D arrays of one length, within the strokes."""
        check_mapping("positions_m", positions_m, ("X", "Z"), what="a mapping of 'X' and 'Z' to positions in metres")
        out = {k: check_array(f"positions_m['{k}']", positions_m[k], ndim=1, min_len=1) for k in ("X", "Z")}
        check_same_length(**{f"positions_m['{k}']": v for k, v in out.items()})
        return out

    def true_errors(self, letter: str, q_m: np.ndarray) -> np.ndarray:
        """The six error motions of axis ``letter`` at positions ``q_m`` (with the load).

        Parameters
        ----------
        letter : str
            ``"X"`` or ``"Z"``.
        q_m : array_like, shape (N,)
            Positions, m.

        Returns
        -------
        ndarray, shape (6, N)
            Rows tx, ty, tz (m) and ea, eb, ec (rad).
        """
        q = check_array("q_m", q_m).reshape(-1)
        slope, amplitude, cycles, phase, constant, ramp = self._curve_arrays[self._letter(letter)]
        s = q / STROKE_M
        waves = amplitude[:, :, None] * (np.sin(2 * np.pi * cycles[:, :, None] * s + phase[:, :, None]) - np.sin(phase)[:, :, None])
        value = slope[:, None] * (q / MM) + waves.sum(axis=1)
        if self.load_kg:
            value += self.load_kg * (constant[:, None] + ramp[:, None] * s)
        return value * _ERROR_UNITS

    def mirror_error(self, letter: str, q_m: np.ndarray) -> np.ndarray:
        """The apparent roll the plane mirror's form adds.

        Parameters
        ----------
        letter : str
            Axis letter.
        q_m : array_like
            Positions, m.

        Returns
        -------
        ndarray
            Apparent roll, rad.
        """
        return _curve(check_array("q_m", q_m), 0.0, self.mirror_terms[self._letter(letter)]) * URAD

    def positions(self, t_s: np.ndarray, *, path: str = "diagonal") -> dict[str, np.ndarray]:
        """Commanded positions of X and Z at times ``t_s`` along a periodic path.

        Parameters
        ----------
        t_s : array_like, shape (N,)
            Times, s.
        path : str, keyword-only
            One of :data:`PATHS`.

        Returns
        -------
        dict of str to ndarray, shape (N,)
            ``"X"`` and ``"Z"`` positions, m.

        Raises
        ------
        AxiscalError
            For an unknown path.

        ``"diagonal"``: both axes 0 -> 190 mm -> 0 together; ``"back-and-forth"``: X 0 -> 190 ->
        0 mm with Z at mid-stroke; ``"raster"``: X sweeps back and forth while Z steps 10 mm per
        sweep, up through the square and back down.
        """
        t = check_array("t_s", t_s)
        if not isinstance(path, str) or path not in PATHS:
            raise AxiscalError(f"unknown path {path!r}; use one of {', '.join(PATHS)}")
        sweep = STROKE_M / self.speed_m_s
        phase = np.mod(t / sweep, 2.0)
        triangle = STROKE_M * np.where(phase < 1.0, phase, 2.0 - phase)
        if path == "diagonal":
            return {"X": triangle, "Z": triangle.copy()}
        if path == "back-and-forth":
            return {"X": triangle, "Z": np.full(t.shape, STROKE_M / 2)}
        if path == "raster":
            lines = 20
            sweep_index = np.floor(np.mod(t / sweep, 2 * lines)).astype(int)
            level = np.where(sweep_index < lines, sweep_index, 2 * lines - 1 - sweep_index)
            return {"X": triangle, "Z": level * (STROKE_M / (lines - 1))}
        raise AxiscalError(f"unknown path '{path}'; use one of {', '.join(PATHS)}")

    def _noise(self, kind: str, shape: tuple[int, ...], rng: np.random.Generator) -> np.ndarray:
        scale = NOISE.get(kind, REFERENCE_NOISE.get(kind, 0.0))
        if not self.noise or scale == 0.0:
            return np.zeros(shape)
        return rng.normal(0.0, scale, shape)

    def sensor_values(self, letter: str, q_m: np.ndarray, errors: np.ndarray) -> dict[str, np.ndarray]:
        """What each channel of axis ``letter`` should read (true physical value, channel unit)."""
        head = self.heads[self._letter(letter)]
        q_m = check_array("q_m", q_m, ndim=1)
        errors = check_array("errors", errors, ndim=2)
        if errors.shape != (6, q_m.size):
            raise AxiscalError(f"errors must have shape (6, {q_m.size}), rows tx, ty, tz, ea, eb, ec; not {errors.shape}")
        at_scale = _moved(errors, head.scale_point_m)
        at_psd = _moved(errors, head.psd_point_m)
        names = head.channels
        out = {names["cmd"]: q_m / MM, names["scale"]: (q_m + at_scale[head.index]) / MM}
        for d in head.cross_directions:
            out[names[f"psd_{d}"]] = at_psd["xyz".index(d)] / UM
        out[names["qd_u"]] = head.qd_u.sign * quadrant_shift(errors[head.qd_u.index], head.qd_focal_m) / UM
        out[names["qd_v"]] = head.qd_v.sign * quadrant_shift(errors[head.qd_v.index], head.qd_focal_m) / UM
        roll = errors[head.roll.index] + self.mirror_error(letter, q_m)
        out[names["roll"]] = head.roll.sign * autocollimation_shift(roll, head.roll_focal_m) / UM
        return out

    def raw(self, values: dict[str, np.ndarray], rng: np.random.Generator) -> dict[str, np.ndarray]:
        """Raw readings from true values: ``(value - offset) / gain`` plus reading noise."""
        check_mapping("values", values, what="a mapping of channel names to true values")
        if not isinstance(rng, np.random.Generator):
            raise AxiscalError(f"rng must be a numpy.random.Generator, not {type(rng).__name__}")
        unknown = sorted(set(values) - set(self.sensor_truth))
        if unknown:
            raise AxiscalError(f"values: unknown channel '{unknown[0]}'; channels are {', '.join(self.sensor_truth)}")
        out = {}
        for name, value in values.items():
            value = check_array(f"values['{name}']", value)
            truth = self.sensor_truth[name]
            noise = rng.normal(0.0, truth.noise, value.shape) if self.noise and truth.noise else 0.0
            out[name] = (value - truth.offset) / truth.gain + noise
        return out

    def frames(self, t_s: np.ndarray, *, path: str = "diagonal") -> tuple[dict[str, np.ndarray], dict[str, np.ndarray]]:
        """Raw frames and their truth at times ``t_s`` along ``path`` (see :meth:`positions`).

        Parameters
        ----------
        t_s : array_like, shape (N,)
            Times, s.
        path : str, keyword-only
            One of :data:`PATHS`.

        Returns
        -------
        frames : dict of str to ndarray, shape (N,)
            ``"t_s"`` and every channel of :meth:`measurement_system`, raw.
        truth : dict of str to ndarray, shape (N,)
            SI, named as :meth:`MeasurementSystem.process` names its results: ``"t_s"``; per
            axis the six true errors (``"EXX_m"`` .. ``"ECZ_rad"``); the true scale positions
            ``"x_m"``, ``"z_m"`` and commands ``"x_cmd_m"``, ``"z_cmd_m"``; the true spatial
            error ``"ex_m"``, ``"ey_m"``, ``"ez_m"``, ``"e_m"`` and functional point ``"px_m"``,
            ``"py_m"``, ``"pz_m"``.
        """
        t = np.atleast_1d(check_array("t_s", t_s))
        q = self.positions(t, path=path)
        return self.frames_at(q, t_s=t)

    def frames_at(self, positions_m: dict[str, np.ndarray], *, t_s: np.ndarray | None = None):
        """Raw frames and truth (as :meth:`frames`) at given commanded positions.

        Parameters
        ----------
        positions_m : dict of str to ndarray, shape (N,)
            ``"X"`` and ``"Z"`` commanded positions, m.
        t_s : ndarray, shape (N,), keyword-only
            Time stamps, s (default zeros).

        Returns
        -------
        frames, truth : dict of str to ndarray
            As :meth:`frames`.
        """
        positions_m = self._positions(positions_m)
        n = positions_m["X"].size
        t = np.zeros(n) if t_s is None else check_array("t_s", t_s, ndim=1)
        check_same_length(positions_m=positions_m["X"], t_s=t)
        frames: dict[str, np.ndarray] = {"t_s": t}
        truth: dict[str, np.ndarray] = {"t_s": t}
        errors = {}
        for letter in ("X", "Z"):
            q = positions_m[letter]
            e = self.true_errors(letter, q)
            errors[letter] = e
            values = self.sensor_values(letter, q, e)
            frames.update(self.raw(values, self._rng))
            names = component_names(letter)
            for row, name in enumerate(names):
                truth[f"{name}_{'m' if row < 3 else 'rad'}"] = e[row]
            truth[f"{letter.lower()}_m"] = values[self.heads[letter].channels["scale"]] * MM
            truth[f"{letter.lower()}_cmd_m"] = q
        error = spatial_error(self.machine, positions_m, errors)
        actual = self.machine.nominal_point(positions_m) + error
        for k, axis in enumerate("xyz"):
            truth[f"e{axis}_m"] = error[:, k]
        truth["e_m"] = np.linalg.norm(error, axis=1)
        for k, axis in enumerate("xyz"):
            truth[f"p{axis}_m"] = actual[:, k]
        return frames, truth

    def true_point(self, positions_m: dict[str, np.ndarray]) -> np.ndarray:
        """Where the functional point really is at the commanded positions.

        Parameters
        ----------
        positions_m : dict of str to ndarray, shape (N,)
            Commanded positions, m.

        Returns
        -------
        ndarray, shape (N, 3)
            The functional point, m.
        """
        positions_m = self._positions(positions_m)
        errors = {k: self.true_errors(k, positions_m[k]) for k in ("X", "Z")}
        return self.machine.nominal_point(positions_m) + spatial_error(self.machine, positions_m, errors)

    def laser_diagonal(self, positions_m: dict[str, np.ndarray]) -> np.ndarray:
        """Readings of a laser interferometer along the diagonal through the given stops (m).

        The beam is aligned with the nominal line from the first stop to the last, the reflector
        sits on the functional point, and the reading is zeroed at the first stop: the functional
        point's true displacement along the beam, plus the interferometer's noise.

        Parameters
        ----------
        positions_m : dict of str to ndarray, shape (n,)
            Commanded positions of X and Z at the stops, m.

        Returns
        -------
        ndarray, shape (n,)
            Readings, m (0 at the first stop).
        """
        positions_m = self._positions(positions_m)
        nominal = self.machine.nominal_point(positions_m)
        direction = nominal[-1] - nominal[0]
        if not np.linalg.norm(direction) > 0.0:
            raise AxiscalError("positions_m: the first and the last stop must differ (they set the beam's direction)")
        direction = direction / np.linalg.norm(direction)
        actual = self.true_point(positions_m)
        reading = (actual - actual[0]) @ direction
        if self.noise:
            reading = reading + self._rng.normal(0.0, REFERENCE_NOISE["interferometer"], reading.shape)
        reading[0] = 0.0
        return reading

    def calibration_runs(self) -> dict[str, dict[str, np.ndarray]]:
        """Simulated calibration data of every channel (section 4.1 of paper 000).

        One data set per PSD and angle channel (``"raw"`` and ``"reference"``, both in the
        channel's unit: PSDs displaced against an inductive probe over +-90 um, detectors tilted
        against an autocollimator over +-100 arcsec); per scale ``"raw"``, ``"position_m"``,
        ``"interferometer_m"`` (beam off the read head), the autocollimator's ``"eps_rad"`` (n, 3)
        and ``"offset_m"`` (read head minus beam), so the reading can be moved to the read head
        first (section 4.2); per axis ``"<L>_mirror"``: ``"position_m"``, ``"raw"`` readings of the
        roll detector and ``"level_rad"`` along the travel (eq 11).
        """
        rng = np.random.default_rng([self.seed, 2])
        runs: dict[str, dict[str, np.ndarray]] = {}
        steps = np.linspace(-1.0, 1.0, 21)
        for letter, head in self.heads.items():
            names = head.channels
            for d in head.cross_directions:
                shift = steps * 90.0
                reference = shift + self._noise("probe", shift.shape, rng)
                runs[names[f"psd_{d}"]] = {"raw": self.raw({names[f"psd_{d}"]: shift}, rng)[names[f"psd_{d}"]], "reference": reference}
            for role, focal, factor in (("qd_u", head.qd_focal_m, 1.0), ("qd_v", head.qd_focal_m, 1.0), ("roll", head.roll_focal_m, 2.0)):
                angle = steps * 100.0 * ARCSEC
                shift = angle * focal * factor / UM
                measured = angle + self._noise("autocollimator", angle.shape, rng)
                runs[names[role]] = {"raw": self.raw({names[role]: shift}, rng)[names[role]], "reference": measured * focal * factor / UM}
            q = np.linspace(0.0, STROKE_M, 39)
            e = self.true_errors(letter, q)
            values = self.sensor_values(letter, q, e)
            beam = np.asarray(head.scale_point_m) + INTERFEROMETER_BEAM_M
            eps_true = e[3:].T
            at_beam = transfer_point(e[:3].T, eps_true, beam)
            runs[names["scale"]] = {
                "raw": self.raw({names["scale"]: values[names["scale"]]}, rng)[names["scale"]],
                "position_m": q,
                "interferometer_m": q + at_beam[:, head.index] + self._noise("interferometer", q.shape, rng),
                "eps_rad": eps_true + self._noise("autocollimator", eps_true.shape, rng),
                "offset_m": -INTERFEROMETER_BEAM_M,
            }
            roll = e[head.roll.index]
            runs[f"{letter}_mirror"] = {
                "position_m": q,
                "raw": self.raw({names["roll"]: values[names["roll"]]}, rng)[names["roll"]],
                "level_rad": roll + self._noise("level", roll.shape, rng),
            }
        return runs

    @cached_property
    def calibration(self) -> Calibration:
        """The calibration the module's simulated calibration runs give (fits, not the truth)."""
        runs = self.calibration_runs()
        channels = {}
        for head in self.heads.values():
            for role, name in head.channels.items():
                run = runs.get(name)
                if role == "scale":
                    at_head = transfer_reference(run["interferometer_m"], run["eps_rad"], run["offset_m"], head.index)
                    channels[name] = fit_sensitivity(name, run["raw"], at_head / MM)
                elif run is not None:
                    channels[name] = fit_sensitivity(name, run["raw"], run["reference"])
        mirrors = {}
        for letter, head in self.heads.items():
            run = runs[f"{letter}_mirror"]
            shift_m = channels[head.channels["roll"]].apply(run["raw"]) * UM
            module_roll = head.roll.sign * roll_from_autocollimation(shift_m, head.roll_focal_m)
            mirrors[letter] = fit_mirror(letter, run["position_m"], module_roll, run["level_rad"])
        return Calibration(channels, mirrors)

    def measurement_system(self) -> MeasurementSystem:
        """The module's measurement system, calibrated by its simulated calibration runs.

        Returns
        -------
        MeasurementSystem
        """
        return MeasurementSystem(self.machine, self.heads, self.calibration)
