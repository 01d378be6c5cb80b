"""Calibration of the sensor channels against reference instruments (paper 000, section 4.1, eqs 11-12).

Three pieces, each a fit on simulated or recorded data with a stated residual band:

- **sensitivity and offset** of a channel (PSD against an inductive probe, quadrant detector
  against an autocollimator, scale against a laser interferometer): the reference value ``r``
  against the raw reading ``u`` by least squares, ``r = gain * u + offset``; the residuals say how
  well the set-up reached (paper 000: within +-1 um and +-1 arcsec);
- the **plane mirror** of the roll detector: its form error is mapped against a level, eq (11)
  ``eps_error(i) = eps'_x(i) - eps_level(i)``, fitted by a Legendre polynomial whose order is
  chosen by leave-one-out cross-validation, and subtracted in use, eq (12)
  ``eps_x = eps'_x - eps_error(q)``;
- the **reference instrument's own offsets**: a probe or interferometer beam does not touch the
  point the sensor measures, so its reading is moved there first (section 4.2, the Abbe-Bryan
  transfer ``delta_M = delta_R + eps x (M - R)``) by :func:`transfer_reference`.

A :class:`Calibration` gathers the results per channel and per axis and is saved to and read from
a JSON file (format in docs/measurement.md); the measurement system applies it on load.
"""

from __future__ import annotations

import json
import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from numpy.polynomial import legendre

from axiscal.errors import AxiscalError
from axiscal.instruments.abbe import transfer_point
from axiscal.io.arguments import check_array, check_count, check_instance, check_number, check_path
from axiscal.io.atomic import write_text
from axiscal.io.jsonio import json_line
from axiscal.io.tabular import read_text
from axiscal.units import MM, URAD

__all__ = [
    "FORMAT",
    "VERSION",
    "ChannelCalibration",
    "fit_sensitivity",
    "transfer_reference",
    "MirrorCorrection",
    "fit_mirror",
    "Calibration",
    "save_calibration",
    "calibration_from_dict",
    "load_calibration",
]

FORMAT = "axiscal-sensor-calibration"
VERSION = 1


@dataclass(frozen=True)
class ChannelCalibration:
    """Gain and offset of one raw channel: ``value = gain * raw + offset`` in the channel's unit.

    Parameters
    ----------
    channel : str
        Raw channel name.
    gain : float
        Sensitivity, channel unit per raw unit (1 for an uncalibrated channel).
    offset : float
        Offset, the channel's unit (mm for scales, um for spot shifts).
    residual_max, residual_rms : float
        The fit's largest and rms residual, the channel's unit.
    points : int
        Number of calibration points.
    """

    channel: str
    gain: float
    offset: float
    residual_max: float = 0.0
    residual_rms: float = 0.0
    points: int = 0

    def __post_init__(self) -> None:
        if not isinstance(self.channel, str) or not self.channel:
            raise AxiscalError(f"channel must be a channel name, not {self.channel!r}")
        gain = check_number("gain", self.gain)
        if gain == 0.0:
            raise AxiscalError(f"channel {self.channel}: gain must not be zero")
        object.__setattr__(self, "gain", gain)
        object.__setattr__(self, "offset", check_number("offset", self.offset))
        for name in ("residual_max", "residual_rms"):
            object.__setattr__(self, name, check_number(name, getattr(self, name), nonnegative=True))
        object.__setattr__(self, "points", check_count("points", self.points, minimum=0))

    def apply(self, raw: np.ndarray) -> np.ndarray:
        """Calibrated values ``gain * raw + offset`` of raw readings (the channel's unit); NaN stays NaN
        (a missing reading)."""
        return check_array("raw", raw, finite=False) * self.gain + self.offset


def fit_sensitivity(channel: str, raw: np.ndarray, reference: np.ndarray) -> ChannelCalibration:
    """Least-squares ``reference = gain * raw + offset`` for one channel.

    Parameters
    ----------
    channel : str
        Name of the raw channel.
    raw : ndarray, shape (n,)
        Raw readings, the channel's unit.
    reference : ndarray, shape (n,)
        What the reference instrument says the channel should read, the same unit (already moved
        to the sensor's measuring point with :func:`transfer_reference` where the two differ).

    Returns
    -------
    ChannelCalibration
        Gain, offset and the residual band (max |residual| and rms), channel unit.
    """
    u = check_array("raw", raw, finite=False)
    r = check_array("reference", reference, finite=False)
    if u.ndim != 1 or u.shape != r.shape:
        raise AxiscalError(f"channel {channel}: raw and reference must be 1-D arrays of the same length")
    if u.size < 3:
        raise AxiscalError(f"channel {channel}: at least 3 calibration points are needed, got {u.size}")
    if not (np.all(np.isfinite(u)) and np.all(np.isfinite(r))):
        raise AxiscalError(f"channel {channel}: calibration data hold non-finite values")
    if np.ptp(u) <= 0:
        raise AxiscalError(f"channel {channel}: the raw readings do not vary, so no sensitivity can be fitted")
    design = np.column_stack([u, np.ones_like(u)])
    (gain, offset), *_ = np.linalg.lstsq(design, r, rcond=None)
    residual = r - (gain * u + offset)
    return ChannelCalibration(
        channel=channel,
        gain=float(gain),
        offset=float(offset),
        residual_max=float(np.max(np.abs(residual))),
        residual_rms=float(np.sqrt(np.mean(residual**2))),
        points=int(u.size),
    )


def transfer_reference(reference_m: np.ndarray, eps_rad: np.ndarray, offset_m: np.ndarray, component: int) -> np.ndarray:
    """Move a reference instrument's translation reading from its point R to the sensor's point M.

    Section 4.2 of paper 000: the interferometer beam is off the scale's read head, the probe off
    the PSD spot; the carriage's rotations turn that offset into a difference, so the reading is
    transferred before the comparison: ``delta_M = delta_R + (eps x (M - R))[component]``.

    Parameters
    ----------
    reference_m : ndarray, shape (n,)
        The reference reading of translation ``component``, metres.
    eps_rad : ndarray, shape (n, 3)
        Rotations EA, EB, EC of the carriage at each point (from a reference angle instrument or
        the calibrated angle channels), radians.
    offset_m : array_like, shape (3,)
        ``M - R``: the sensor's measuring point minus the reference's, in the carriage frame, m.
    component : int
        0, 1 or 2 for the x, y or z translation.

    Returns
    -------
    ndarray, shape (n,)
        The reading moved to M, metres (:func:`axiscal.instruments.abbe.transfer_point`).

    Raises
    ------
    AxiscalError
        For shapes other than the above or a component outside 0..2.
    """
    eps = check_array("eps_rad", eps_rad)
    offset = check_array("offset_m", offset_m)
    if eps.ndim != 2 or eps.shape[1] != 3 or offset.shape != (3,):
        raise AxiscalError("eps_rad must have shape (n, 3) and offset_m shape (3,)")
    component = check_count("component", component, minimum=0, maximum=2)
    reference = check_array("reference_m", reference_m)
    if reference.ndim > 1 or reference.ndim == 1 and reference.shape[0] != eps.shape[0]:
        raise AxiscalError(f"reference_m must have one value per row of eps_rad ({eps.shape[0]}), not shape {reference.shape}")
    delta = np.zeros(eps.shape)
    delta[:, component] = reference
    return transfer_point(delta, eps, offset)[:, component]


@dataclass(frozen=True)
class MirrorCorrection:
    """The plane mirror's form error as seen by the roll detector, against position (eq 11 fitted).

    Parameters
    ----------
    letter : str
        Axis letter.
    start_m, end_m : float
        The mapped range of positions, metres.
    coefficients_rad : tuple of float
        Legendre coefficients over the position normalised to [-1, 1] on ``start_m..end_m``,
        radians; :meth:`evaluate` returns the apparent roll the mirror adds.
    residual_max_rad, residual_rms_rad : float
        Residuals of the fit, radians.
    cv_rms_rad : tuple of float
        Leave-one-out rms error of every order tried, radians.
    points : int
        Points of the map.
    """

    letter: str
    start_m: float
    end_m: float
    coefficients_rad: tuple[float, ...]
    residual_max_rad: float = 0.0
    residual_rms_rad: float = 0.0
    cv_rms_rad: tuple[float, ...] = ()
    points: int = 0

    def __post_init__(self) -> None:
        start = check_number("start_m", self.start_m)
        end = check_number("end_m", self.end_m)
        if end <= start:
            raise AxiscalError(f"axis {self.letter}: end_m must be greater than start_m")
        coefficients = check_array("coefficients_rad", self.coefficients_rad, ndim=1, min_len=1)
        object.__setattr__(self, "start_m", start)
        object.__setattr__(self, "end_m", end)
        object.__setattr__(self, "coefficients_rad", tuple(float(c) for c in coefficients))

    @property
    def order(self) -> int:
        return len(self.coefficients_rad) - 1

    def evaluate(self, q_m: np.ndarray) -> np.ndarray:
        """Form error eps_error at positions ``q_m`` (shape (N,), finite), radians; positions are clipped to the map."""
        return self._evaluate(check_array("q_m", q_m))

    def _evaluate(self, q: np.ndarray) -> np.ndarray:
        """:meth:`evaluate` on a checked float array (the measurement pipeline's path)."""
        scale = 2.0 / (self.end_m - self.start_m)
        s = np.clip((q - self.start_m) * scale - 1.0, -1.0, 1.0)
        return legendre.legval(s, np.asarray(self.coefficients_rad))

    def inside(self, q_m: np.ndarray) -> np.ndarray:
        """Whether each position lies within the mapped range."""
        return (q_m >= self.start_m) & (q_m <= self.end_m)


def _loo_rms(design: np.ndarray, y: np.ndarray) -> float:
    """Leave-one-out rms prediction error of a linear least-squares fit, from the hat matrix."""
    q, _ = np.linalg.qr(design)
    hat = np.sum(q * q, axis=1)
    coef, *_ = np.linalg.lstsq(design, y, rcond=None)
    residual = y - design @ coef
    if np.any(hat >= 1.0 - 1e-9):
        return math.inf
    return float(np.sqrt(np.mean((residual / (1.0 - hat)) ** 2)))


def fit_mirror(
    letter: str,
    position_m: np.ndarray,
    module_roll_rad: np.ndarray,
    level_roll_rad: np.ndarray,
    *,
    max_order: int = 12,
) -> MirrorCorrection:
    """Map the plane mirror's form error against a level and fit it (paper 000 eqs 11-12).

    The points ``eps_error(i) = eps'_x(i) - eps_level(i)`` (eq 11) are fitted by Legendre
    polynomials of order 0..``max_order`` (at most n - 2); the order with the smallest
    leave-one-out cross-validation rms error is kept, so the order is chosen by the data.

    Parameters
    ----------
    letter : str
        Axis letter.
    position_m : ndarray, shape (n,)
        Positions of the map, metres (any order, at least 4 distinct).
    module_roll_rad : ndarray, shape (n,)
        Roll read by the module (after the detector's sensitivity calibration), radians.
    level_roll_rad : ndarray, shape (n,)
        Roll read by the level at the same positions, radians.
    max_order : int
        Highest polynomial order tried (default 12).

    Returns
    -------
    MirrorCorrection
        The fitted form error, its residuals and the cross-validation rms for every order tried.
    """
    q = check_array("position_m", position_m, finite=False)
    module = check_array("module_roll_rad", module_roll_rad, finite=False)
    level = check_array("level_roll_rad", level_roll_rad, finite=False)
    max_order = check_count("max_order", max_order, minimum=0)
    if q.ndim != 1 or q.shape != module.shape or q.shape != level.shape:
        raise AxiscalError(f"axis {letter}: positions, module and level readings must be 1-D of the same length")
    eps_error = module - level
    if q.ndim != 1 or q.shape != eps_error.shape:
        raise AxiscalError(f"axis {letter}: positions, module and level readings must be 1-D of the same length")
    if not (np.all(np.isfinite(q)) and np.all(np.isfinite(eps_error))):
        raise AxiscalError(f"axis {letter}: mirror map holds non-finite values")
    if np.unique(q).size < 4:
        raise AxiscalError(f"axis {letter}: the mirror map needs at least 4 distinct positions, got {np.unique(q).size}")
    start, end = float(q.min()), float(q.max())
    s = (q - start) * (2.0 / (end - start)) - 1.0
    top = min(max_order, np.unique(q).size - 2)
    scores = []
    for order in range(top + 1):
        scores.append(_loo_rms(legendre.legvander(s, order), eps_error))
    best = int(np.argmin(scores))
    coefficients = legendre.legfit(s, eps_error, best)
    residual = eps_error - legendre.legval(s, coefficients)
    return MirrorCorrection(
        letter=letter,
        start_m=start,
        end_m=end,
        coefficients_rad=tuple(float(c) for c in coefficients),
        residual_max_rad=float(np.max(np.abs(residual))),
        residual_rms_rad=float(np.sqrt(np.mean(residual**2))),
        cv_rms_rad=tuple(float(v) for v in scores),
        points=int(q.size),
    )


@dataclass(frozen=True)
class Calibration:
    """All calibration results of a measuring system: per channel and per axis mirror.

    Parameters
    ----------
    channels : mapping of str to ChannelCalibration
        By channel name.
    mirrors : mapping of str to MirrorCorrection
        By axis letter.
    """

    channels: Mapping[str, ChannelCalibration] = field(default_factory=dict)
    mirrors: Mapping[str, MirrorCorrection] = field(default_factory=dict)

    def __post_init__(self) -> None:
        for name, kind in (("channels", ChannelCalibration), ("mirrors", MirrorCorrection)):
            entries = getattr(self, name)
            if not isinstance(entries, Mapping) or not all(isinstance(v, kind) for v in entries.values()):
                raise AxiscalError(f"{name} must map names to {kind.__name__} objects, not {entries!r}"[:200])

    def channel(self, name: str) -> ChannelCalibration:
        """The calibration of one channel.

        Parameters
        ----------
        name : str
            Raw channel name.

        Returns
        -------
        ChannelCalibration
            Identity (gain 1, offset 0) when the channel was never calibrated.
        """
        return self.channels.get(name, ChannelCalibration(name, 1.0, 0.0))

    def merged(self, other: "Calibration") -> "Calibration":
        """This calibration with every entry of ``other`` added or replacing the old one.

        Parameters
        ----------
        other : Calibration
            The newer entries.

        Returns
        -------
        Calibration
        """
        return Calibration({**self.channels, **other.channels}, {**self.mirrors, **other.mirrors})

    def to_dict(self) -> dict:
        """The JSON form of the calibration file (positions in mm, mirror values in urad)."""
        return {
            "format": FORMAT,
            "version": VERSION,
            "channels": {
                name: {
                    "gain": c.gain,
                    "offset": c.offset,
                    "residual_max": c.residual_max,
                    "residual_rms": c.residual_rms,
                    "points": c.points,
                }
                for name, c in sorted(self.channels.items())
            },
            "mirrors": {
                letter: {
                    "start_mm": m.start_m / MM,
                    "end_mm": m.end_m / MM,
                    "legendre_urad": [c / URAD for c in m.coefficients_rad],
                    "residual_max_urad": m.residual_max_rad / URAD,
                    "residual_rms_urad": m.residual_rms_rad / URAD,
                    "cv_rms_urad": [v / URAD if math.isfinite(v) else None for v in m.cv_rms_rad],
                    "points": m.points,
                }
                for letter, m in sorted(self.mirrors.items())
            },
        }


def save_calibration(calibration: Calibration, path: str | Path) -> None:
    """Write a calibration as JSON, atomically (docs/measurement.md, "Calibration file").

    Parameters
    ----------
    calibration : Calibration
        What to save.
    path : str or Path
        The JSON file (replaced whole, never left half written).

    Returns
    -------
    None

    Raises
    ------
    AxiscalError
        If the file cannot be written (naming it).
    """
    check_instance("calibration", calibration, Calibration, what="a Calibration")
    write_text(check_path("path", path), json.dumps(calibration.to_dict(), indent=2) + "\n")


def _number(entry: Mapping, key: str, fail, *, default: float | None = None) -> float:
    value = entry.get(key, default)
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise fail(f"'{key}' must be a finite number", key)
    return float(value)


def _whole(value: float) -> int | float:
    """A count read from JSON: an int when it is whole, else left for the record's check to refuse."""
    return int(value) if value == int(value) else value


def calibration_from_dict(data: Mapping, *, locate: Callable[..., int | None] | None = None) -> Calibration:
    """Build a :class:`Calibration` from the parsed JSON (see :func:`save_calibration`).

    Parameters
    ----------
    data : mapping
        The parsed calibration file.
    locate : callable, optional, keyword-only
        ``locate(*keys)`` -> the line of that key path in the file (:func:`axiscal.io.json_line`),
        so that an error names its line.

    Returns
    -------
    Calibration

    Raises
    ------
    AxiscalError
        If it is not a calibration file of this version, or an entry is not a finite number.
    """
    def error(message: str, *keys: str) -> AxiscalError:
        return AxiscalError(message, line=None if locate is None else (locate(*keys) or 1))

    if not isinstance(data, Mapping) or data.get("format") != FORMAT:
        raise error(f"not a sensor calibration file (expected \"format\": \"{FORMAT}\")", "format")
    if data.get("version") != VERSION:
        raise error(f"calibration file version {data.get('version')!r} is not supported (expected {VERSION})", "version")
    sections = {}
    for section in ("channels", "mirrors"):
        sections[section] = data.get(section, {})
        if not isinstance(sections[section], Mapping):
            raise error(f"'{section}' must be an object", section)
    channels: dict[str, ChannelCalibration] = {}
    for name, entry in sections["channels"].items():
        where = f"channel '{name}'"

        def fail(message: str, key: str | None = None, where=where, name=name) -> AxiscalError:
            return error(f"{where}: {message}", "channels", name, *([key] if key else []))

        if not isinstance(entry, Mapping):
            raise fail("expected an object with gain and offset")
        gain = _number(entry, "gain", fail)
        if gain == 0.0:
            raise fail("gain must not be zero", "gain")
        values = {key: _number(entry, key, fail, default=default) for key, default in
                  (("offset", None), ("residual_max", 0.0), ("residual_rms", 0.0), ("points", 0))}
        values["points"] = _whole(values["points"])
        try:
            channels[name] = ChannelCalibration(channel=name, gain=gain, **values)
        except AxiscalError as exc:  # the entry's own checks (a negative residual, points not whole)
            raise fail(exc.message) from None
    mirrors: dict[str, MirrorCorrection] = {}
    for letter, entry in sections["mirrors"].items():
        where = f"mirror of axis '{letter}'"

        def fail(message: str, key: str | None = None, where=where, letter=letter) -> AxiscalError:
            return error(f"{where}: {message}", "mirrors", letter, *([key] if key else []))

        if letter not in ("X", "Y", "Z") or not isinstance(entry, Mapping):
            raise fail("expected an axis letter X, Y or Z with an object")
        start, end = _number(entry, "start_mm", fail) * MM, _number(entry, "end_mm", fail) * MM
        if not end > start:
            raise fail("end_mm must be greater than start_mm", "end_mm")
        coefficients = entry.get("legendre_urad")
        if not (isinstance(coefficients, list) and coefficients
                and all(isinstance(c, (int, float)) and not isinstance(c, bool) and math.isfinite(c) for c in coefficients)):
            raise fail("'legendre_urad' must be a non-empty list of finite numbers", "legendre_urad")
        cv_values = entry.get("cv_rms_urad", [])
        if not (isinstance(cv_values, list)
                and all(v is None or (isinstance(v, (int, float)) and not isinstance(v, bool)) for v in cv_values)):
            raise fail("'cv_rms_urad' must be a list of numbers (null: not resolved)", "cv_rms_urad")
        cv = [math.inf if v is None else float(v) * URAD for v in cv_values]
        try:
            mirrors[letter] = MirrorCorrection(
                letter=letter,
                start_m=start,
                end_m=end,
                coefficients_rad=tuple(float(c) * URAD for c in coefficients),
                residual_max_rad=_number(entry, "residual_max_urad", fail, default=0.0) * URAD,
                residual_rms_rad=_number(entry, "residual_rms_urad", fail, default=0.0) * URAD,
                cv_rms_rad=tuple(cv),
                points=_whole(_number(entry, "points", fail, default=0)),
            )
        except AxiscalError as exc:  # the entry's own checks
            raise fail(exc.message) from None
    return Calibration(channels, mirrors)


def load_calibration(path: str | Path) -> Calibration:
    """Read a calibration JSON file.

    Parameters
    ----------
    path : str or Path
        The file (docs/measurement.md, "Calibration file").

    Returns
    -------
    Calibration

    Raises
    ------
    AxiscalError
        If the file is missing, not JSON or not a calibration (naming the file and line).
    """
    path = check_path("path", path)
    text = read_text(path)
    try:
        data = json.loads(text)
    except json.JSONDecodeError as exc:
        raise AxiscalError(f"malformed JSON: {exc.msg}", path=path, line=exc.lineno) from None
    try:
        return calibration_from_dict(data, locate=lambda *keys: json_line(text, *keys))
    except AxiscalError as exc:
        raise exc.located(path=path) from None
