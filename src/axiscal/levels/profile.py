"""Straightness profile and angular error motion from electronic level readings.

ISO 230-1 (straightness and angular error motions measured with precision levels): a level of
foot spacing ``l`` reads the slope of the chord between its feet, ``rise / l``. Stepping the level
along the axis by one foot spacing each time (the classic method), the heights of the stations
are the running sum of the rises, ``z_(k+1) = z_k + l * theta_k``; with any other steps each
reading is taken as the slope at the middle of the level and integrated by the trapezoid rule.
A second level on a fixed part of the machine (the differential set-up) reads the tilt of the
whole machine, which is subtracted reading by reading.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_choice, check_number, check_same_length

__all__ = ["INTEGRATIONS", "LevelProfile", "level_profile"]

#: how the readings are integrated: stations one foot apart, or slopes at the levels' middles
INTEGRATIONS = ("foot-chain", "midpoint")
#: the largest position or foot spacing taken, metres
_LIMIT_M = 1e9
#: the largest slope taken, rad (a level reads a few mrad at most)
_LIMIT_RAD = 1.0


@dataclass(frozen=True)
class LevelProfile:
    """A straightness profile integrated from level readings, SI.

    Attributes
    ----------
    position_m : ndarray, shape (m,)
        Positions of the profile's points along the axis, metres: the stations (rear feet and the
        last front foot, ``m = n + 1``) for the foot chain, the levels' middles (``m = n``) otherwise.
    deviation_m : ndarray, shape (m,)
        Heights of those points, metres, the first at zero.
    reading_position_m : ndarray, shape (n,)
        Where the rear foot stood at each reading, metres.
    angle_rad : ndarray, shape (n,)
        The readings less the reference level's, radians (the slope, rise over foot): the angular
        error motion along the axis (pitch with the level along it, roll with the level across it).
    foot_m : float
        The foot spacing, metres.
    integration : str
        ``"foot-chain"`` (every step one foot spacing) or ``"midpoint"``.
    """

    position_m: np.ndarray
    deviation_m: np.ndarray
    reading_position_m: np.ndarray
    angle_rad: np.ndarray
    foot_m: float
    integration: str

    def __post_init__(self) -> None:
        for name in ("position_m", "deviation_m", "reading_position_m", "angle_rad"):
            object.__setattr__(self, name, check_array(name, getattr(self, name), ndim=1, min_len=1))
        check_same_length(position_m=self.position_m, deviation_m=self.deviation_m)
        check_same_length(reading_position_m=self.reading_position_m, angle_rad=self.angle_rad)
        object.__setattr__(self, "foot_m", check_number("foot_m", self.foot_m, positive=True))
        check_choice("integration", self.integration, INTEGRATIONS)

    @property
    def angular_error_rad(self) -> float:
        """The angular error motion: the range (max - min) of the corrected readings, radians."""
        return float(np.ptp(self.angle_rad))


def level_profile(
    position_m: np.ndarray,
    angle_rad: np.ndarray,
    *,
    foot_m: float,
    reference_rad: np.ndarray | None = None,
) -> LevelProfile:
    """Integrate level readings into a straightness profile.

    Parameters
    ----------
    position_m : array_like, shape (n,)
        Where the level's rear foot stood at each reading, metres, strictly increasing.
    angle_rad : array_like, shape (n,)
        The readings as slopes (rise of the front foot over the rear one, divided by the foot
        spacing), radians; positive when the front foot is higher.
    foot_m : float, keyword-only
        The level's foot spacing, metres.
    reference_rad : array_like, shape (n,), optional, keyword-only
        The readings of a second level on a fixed part of the machine, radians, subtracted
        reading by reading (the differential set-up).

    Returns
    -------
    LevelProfile
        The profile (foot chain when every step is one foot spacing, to 1e-6 of it; midpoint
        integration otherwise) and the corrected angles.

    Raises
    ------
    AxiscalError
        Fewer than 2 readings, arrays of different lengths, values that are not finite or beyond
        any physical size, positions that do not increase, a foot spacing that is not positive.

    Examples
    --------
    >>> from axiscal.units import MM, URAD
    >>> p = level_profile([0, 100 * MM, 200 * MM], [10 * URAD, 0.0, -10 * URAD], foot_m=100 * MM)
    >>> (p.deviation_m / 1e-6).round(6).tolist()
    [0.0, 1.0, 1.0, 0.0]
    """
    foot_m = check_number("foot_m", foot_m, positive=True, high=_LIMIT_M)
    position = check_array("position_m", position_m, ndim=1, min_len=2, limit=_LIMIT_M)
    angle = check_array("angle_rad", angle_rad, ndim=1, limit=_LIMIT_RAD)
    check_same_length(position_m=position, angle_rad=angle)
    if reference_rad is not None:
        reference = check_array("reference_rad", reference_rad, ndim=1, limit=_LIMIT_RAD)
        check_same_length(position_m=position, reference_rad=reference)
        angle = angle - reference
    steps = np.diff(position)
    if np.any(steps <= 0.0):
        k = int(np.flatnonzero(steps <= 0.0)[0]) + 1
        raise AxiscalError(f"position_m must increase: reading {k} is at {position[k]:g} m after {position[k - 1]:g} m")
    if np.all(np.abs(steps - foot_m) <= 1e-6 * foot_m):
        stations = np.append(position, position[-1] + foot_m)
        heights = np.concatenate(([0.0], np.cumsum(foot_m * angle)))
        return LevelProfile(stations, heights, position, angle, foot_m, "foot-chain")
    middles = position + 0.5 * foot_m
    heights = np.concatenate(([0.0], np.cumsum(0.5 * (angle[1:] + angle[:-1]) * steps)))
    return LevelProfile(middles, heights, position, angle, foot_m, "midpoint")
