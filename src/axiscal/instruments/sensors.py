"""The 6-DOF sensor head of one linear axis and its equations (paper 000, section 2, eqs 1-3).

Each axis carries the paper's measuring system:

- a linear scale: its read head gives the carriage position, so scale reading minus the
  commanded (nominal) position is the positioning error at the read head (the Abbe point);
- a PSD lit by a laser fixed on the base: the spot shift *is* the straightness error at the PSD
  (the Bryan point), eq (1): ``delta = Delta``;
- a quadrant detector behind a lens of focal length ``f1``: a tilt of the beam moves the focused
  spot by ``f1 * angle``, eq (2): ``angle = Delta / f1`` (pitch and yaw);
- an autocollimator looking at a plane mirror along the rail: the reflected beam turns by twice
  the roll, eq (3): ``roll = Delta / (2 f2)``.

:class:`SensorHead` holds the geometry and channel names read from ``[axes.<L>.sensors]`` of a
machine TOML file (docs/formats.md, section "Sensor geometry"). Points are in the carriage frame
of the axis, relative to the point whose errors the HTM model uses (the carriage origin, the
paper's functional points FP1 and FP2); the Abbe-Bryan transfer (paper 000 eqs 4-5) moves the
measured translations from the read head and the PSD to that point.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from axiscal.conventions import AXIS_INDEX, component_names
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_count, check_number
from axiscal.units import MM, UM

__all__ = [
    "straightness_from_psd",
    "angle_from_quadrant",
    "roll_from_autocollimation",
    "quadrant_shift",
    "autocollimation_shift",
    "SignedComponent",
    "parse_signed_component",
    "SensorHead",
    "DEFAULT_ROTATIONS",
    "sensor_head_from_dict",
]

def straightness_from_psd(shift_m: np.ndarray) -> np.ndarray:
    """Paper 000 eq (1): the straightness error is the PSD spot shift.

    Parameters
    ----------
    shift_m : array_like
        Spot shift on the PSD, metres.

    Returns
    -------
    ndarray
        Straightness error, metres (the same numbers).

    Examples
    --------
    >>> float(straightness_from_psd(2e-6))
    2e-06
    """
    return check_array("shift_m", shift_m)


def angle_from_quadrant(shift_m: np.ndarray, focal_m: float) -> np.ndarray:
    """Paper 000 eq (2): pitch or yaw from the spot shift behind a lens, ``Delta / f``.

    Parameters
    ----------
    shift_m : array_like
        Spot shift on the quadrant detector, metres.
    focal_m : float
        Focal length f1 of the lens, metres.

    Returns
    -------
    ndarray
        Angle, radians.

    Examples
    --------
    >>> round(float(angle_from_quadrant(1e-6, 0.1)), 12)
    1e-05
    """
    return check_array("shift_m", shift_m) / check_number("focal_m", focal_m, positive=True)


def roll_from_autocollimation(shift_m: np.ndarray, focal_m: float) -> np.ndarray:
    """Paper 000 eq (3): roll from the autocollimated spot off a plane mirror, ``Delta / (2 f)``.

    Parameters
    ----------
    shift_m : array_like
        Spot shift, metres.
    focal_m : float
        Focal length f2 of the autocollimator, metres.

    Returns
    -------
    ndarray
        Roll, radians.

    Examples
    --------
    >>> round(float(roll_from_autocollimation(2e-6, 0.1)), 12)
    1e-05
    """
    return check_array("shift_m", shift_m) / (2.0 * check_number("focal_m", focal_m, positive=True))


def quadrant_shift(angle_rad: np.ndarray, focal_m: float) -> np.ndarray:
    """Inverse of eq (2): the spot shift a beam tilt of ``angle_rad`` gives.

    Parameters
    ----------
    angle_rad : array_like
        Tilt, radians.
    focal_m : float
        Focal length f1, metres.

    Returns
    -------
    ndarray
        Spot shift, metres.
    """
    return check_array("angle_rad", angle_rad) * check_number("focal_m", focal_m, positive=True)


def autocollimation_shift(roll_rad: np.ndarray, focal_m: float) -> np.ndarray:
    """Inverse of eq (3): the spot shift a roll of ``roll_rad`` gives.

    Parameters
    ----------
    roll_rad : array_like
        Roll, radians.
    focal_m : float
        Focal length f2, metres.

    Returns
    -------
    ndarray
        Spot shift, metres.
    """
    return check_array("roll_rad", roll_rad) * (2.0 * check_number("focal_m", focal_m, positive=True))


@dataclass(frozen=True)
class SignedComponent:
    """An error component and the sign with which a detector sees it.

    Parameters
    ----------
    index : int
        0..5 in the order of :func:`axiscal.conventions.component_names`.
    sign : float
        +1 or -1.
    """

    index: int
    sign: float

    def __post_init__(self) -> None:
        check_count("index", self.index, minimum=0, maximum=5)
        if self.sign not in (1.0, -1.0) or isinstance(self.sign, bool):
            raise AxiscalError(f"sign must be +1 or -1, not {self.sign!r}")


def parse_signed_component(text: str, letter: str, *, what: str) -> SignedComponent:
    """Parse ``"ECX"`` or ``"-EBX"`` for axis ``letter`` into (component index, sign).

    Parameters
    ----------
    text : str
        Component name, optionally with a sign.
    letter : str
        Axis letter.
    what : str, keyword-only
        Where the value came from, for the error message.

    Returns
    -------
    SignedComponent

    Raises
    ------
    AxiscalError
        If ``text`` names no component of the axis.

    Examples
    --------
    >>> parse_signed_component("-EBX", "X", what="qd_v")
    SignedComponent(index=4, sign=-1.0)
    """
    if letter not in AXIS_INDEX:
        raise AxiscalError(f"letter must be an axis letter {', '.join(AXIS_INDEX)}, not {letter!r}")
    names = component_names(letter)
    value = str(text).strip().upper()
    sign = 1.0
    if value[:1] in "+-":
        sign = -1.0 if value[0] == "-" else 1.0
        value = value[1:]
    if value not in names:
        raise AxiscalError(f"{what} = '{text}': expected one of {', '.join(names)}, optionally with a sign ('-{names[4]}')")
    return SignedComponent(names.index(value), sign)


@dataclass(frozen=True)
class SensorHead:
    """Geometry and channels of the 6-DOF measuring system on one axis (SI units).

    Parameters
    ----------
    letter : str
        Axis letter.
    prefix : str
        Start of every channel name of this axis (default: the letter in lower case).
    scale_point_m, psd_point_m : tuple of 3 floats
        Read head of the scale (Abbe point) and PSD spot (Bryan point) in the carriage frame,
        relative to the point the axis' errors refer to, metres.
    qd_focal_m, roll_focal_m : float
        Focal lengths f1 (eq 2) and f2 (eq 3), metres.
    qd_u, qd_v, roll : SignedComponent
        Which rotation the quadrant detector's u and v shifts and the roll detector measure.
    psd_range_m, qd_range_m, roll_range_m : float
        Half-range of the detectors' spot shifts (readings beyond are faults), metres.
    scale_margin_m : float
        How far outside the axis travel the scale and command channels may read, metres.
    """

    letter: str
    prefix: str
    scale_point_m: tuple[float, float, float]
    psd_point_m: tuple[float, float, float]
    qd_focal_m: float
    roll_focal_m: float
    qd_u: SignedComponent
    qd_v: SignedComponent
    roll: SignedComponent
    psd_range_m: float = 100e-6
    qd_range_m: float = 500e-6
    roll_range_m: float = 500e-6
    scale_margin_m: float = 5e-3

    def __post_init__(self) -> None:
        if self.letter not in AXIS_INDEX:
            raise AxiscalError(f"letter must be an axis letter {', '.join(AXIS_INDEX)}, not {self.letter!r}")
        for name in ("scale_point_m", "psd_point_m"):
            point = check_array(name, getattr(self, name), ndim=1)
            if point.shape != (3,):
                raise AxiscalError(f"{name} must be 3 numbers of metres, not shape {point.shape}")
            object.__setattr__(self, name, tuple(float(v) for v in point))
        for name in ("qd_focal_m", "roll_focal_m", "psd_range_m", "qd_range_m", "roll_range_m", "scale_margin_m"):
            object.__setattr__(self, name, check_number(name, getattr(self, name), positive=True))
        for name in ("qd_u", "qd_v", "roll"):
            if not isinstance(getattr(self, name), SignedComponent):
                raise AxiscalError(f"{name} must be a SignedComponent, not {getattr(self, name)!r}")

    @property
    def index(self) -> int:
        return AXIS_INDEX[self.letter]

    @property
    def cross_directions(self) -> tuple[str, str]:
        """The two straightness directions (lower case), e.g. ``("y", "z")`` for X."""
        return tuple(d for d in "xyz" if d != self.letter.lower())  # type: ignore[return-value]

    @property
    def channels(self) -> dict[str, str]:
        """Channel name by role: cmd, scale, psd_<d1>, psd_<d2>, qd_u, qd_v, roll."""
        p = self.prefix
        d1, d2 = self.cross_directions
        return {
            "cmd": f"{p}_cmd_mm",
            "scale": f"{p}_scale_mm",
            f"psd_{d1}": f"{p}_psd_{d1}_um",
            f"psd_{d2}": f"{p}_psd_{d2}_um",
            "qd_u": f"{p}_qd_u_um",
            "qd_v": f"{p}_qd_v_um",
            "roll": f"{p}_roll_um",
        }

    def offsets_m(self) -> np.ndarray:
        """Rows ``P - M_i`` for the x, y, z translation (scale for the axis direction, PSD across), (3, 3) m."""
        offsets = np.tile(-np.asarray(self.psd_point_m, dtype=float), (3, 1))
        offsets[self.index] = -np.asarray(self.scale_point_m, dtype=float)
        return offsets


_SENSOR_KEYS = {
    "prefix",
    "scale_point_mm",
    "psd_point_mm",
    "qd_focal_mm",
    "roll_focal_mm",
    "qd_u",
    "qd_v",
    "roll",
    "psd_range_um",
    "qd_range_um",
    "roll_range_um",
    "scale_margin_mm",
    "calibration",
}

#: default meaning of the detector axes: the beam runs along the axis; u is the first cross
#: direction, v the second; a tilt about v moves the spot along u and the other way round
DEFAULT_ROTATIONS = {"X": ("ECX", "-EBX", "EAX"), "Y": ("-ECY", "EAY", "EBY"), "Z": ("EBZ", "-EAZ", "ECZ")}


def _positive(section: Mapping, key: str, default: float, where: str) -> float:
    value = section.get(key, default)
    if not isinstance(value, (int, float)) or isinstance(value, bool) or not np.isfinite(value) or value <= 0:
        raise AxiscalError(f"{where} {key} must be a positive number")
    return float(value)


def _point(section: Mapping, key: str, where: str) -> tuple[float, float, float]:
    value = section.get(key, [0.0, 0.0, 0.0])
    if not (isinstance(value, list) and len(value) == 3 and all(isinstance(v, (int, float)) for v in value)):
        raise AxiscalError(f"{where} {key} must be a list of 3 numbers in mm, e.g. [0.0, -30.0, 20.0]")
    return tuple(float(v) * MM for v in value)  # type: ignore[return-value]


def sensor_head_from_dict(letter: str, section: Mapping) -> SensorHead:
    """Build a :class:`SensorHead` from the ``[axes.<L>.sensors]`` table (docs/formats.md).

    Parameters
    ----------
    letter : str
        Axis letter.
    section : mapping
        The TOML table: points and focal lengths in mm, ranges in um.

    Returns
    -------
    SensorHead
        The geometry in SI.

    Raises
    ------
    AxiscalError
        For an unknown key, a bad value or rotations that are not three different ones.
    """
    if letter not in AXIS_INDEX:
        raise AxiscalError(f"letter must be an axis letter {', '.join(AXIS_INDEX)}, not {letter!r}")
    where = f"[axes.{letter}.sensors]"
    if not isinstance(section, Mapping):
        raise AxiscalError(f"{where} must be a table")
    unknown = sorted(set(section) - _SENSOR_KEYS)
    if unknown:
        raise AxiscalError(f"{where}: unknown key {', '.join(unknown)}; known keys: {', '.join(sorted(_SENSOR_KEYS))}")
    prefix = str(section.get("prefix", letter.lower()))
    if not prefix.replace("_", "").isalnum():
        raise AxiscalError(f"{where} prefix '{prefix}' must be letters, digits and '_'")
    defaults = DEFAULT_ROTATIONS[letter]
    rotations = [
        parse_signed_component(section.get(key, default), letter, what=f"{where} {key}")
        for key, default in zip(("qd_u", "qd_v", "roll"), defaults)
    ]
    for rotation, key in zip(rotations, ("qd_u", "qd_v", "roll")):
        if rotation.index < 3:
            raise AxiscalError(f"{where} {key} must name a rotation (EA, EB or EC), not a translation")
    if len({r.index for r in rotations}) != 3:
        raise AxiscalError(f"{where} qd_u, qd_v and roll must measure three different rotations")
    return SensorHead(
        letter=letter,
        prefix=prefix,
        scale_point_m=_point(section, "scale_point_mm", where),
        psd_point_m=_point(section, "psd_point_mm", where),
        qd_focal_m=_positive(section, "qd_focal_mm", 100.0, where) * MM,
        roll_focal_m=_positive(section, "roll_focal_mm", 100.0, where) * MM,
        qd_u=rotations[0],
        qd_v=rotations[1],
        roll=rotations[2],
        psd_range_m=_positive(section, "psd_range_um", 100.0, where) * UM,
        qd_range_m=_positive(section, "qd_range_um", 500.0, where) * UM,
        roll_range_m=_positive(section, "roll_range_um", 500.0, where) * UM,
        scale_margin_m=_positive(section, "scale_margin_mm", 5.0, where) * MM,
    )
