"""Squareness of a three-axis CMM: measured from PSD runs, and compensated by paper 004's eq (6).

Paper 004 (Li et al., micro/nano CMM): a laser turned 90 degrees by a pentaprism is the reference
for the second axis; a PSD on that axis follows the beam and the fitted line of its readings gives
the squareness, less the prism's deviation alpha_p (section 3.3). The compensation model of eq (6):

    x' = x - y a_xy - z a_xz,    y' = y - z a_yz,    z' = z,

with (x, y, z) the CMM's scale readings and (x', y', z') the corrected coordinates. The gauge block check that
verifies it is :mod:`axiscal.squareness.gauge_blocks`.

Signs. Paper 004's text only says an error angle above 0 is positive; the sign comes from its
section 4.1 and eq (6): moving Y to y gives a position error ``-y a_xy`` along X (Z to z:
``-z a_xz`` along X, ``-z a_yz`` along Y), so a positive value leans the second axis towards the
negative first axis and opens the included angle beyond 90 degrees. That is the included-angle
convention of :mod:`axiscal.squareness.signs`: ``a_xy, a_xz, a_yz`` are the included angles of X-Y, X-Z,
Y-Z minus 90 degrees. As ISO 230-1 terms: ``EC0Y = a_xy``, ``EB0Z = -a_xz``, ``EA0Z = a_yz``.
Eq (6) keeps X fixed (and Y in the XY plane); an HTM chain (:class:`axiscal.model.machine.Machine`,
``squareness_placement="relative"``) has the same included angles in every chain, but may turn the
whole point set by a small rigid rotation when the axis nearest the frame is not X.
A PSD run's reading is the position of the beam on the detector along the positive first axis of
the plane (X for XY and XZ, Y for YZ); a second axis leaning towards the negative first axis
carries the detector away from the beam, so the reading grows with travel and the slope is the
squareness.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_instance, check_number
from axiscal.squareness.signs import iso_from_included_angle
from axiscal.straightness.reference import reference_line
from axiscal.units import ARCMIN

__all__ = [
    "PAPER_004_SQUARENESS_ARCMIN",
    "MAX_CMM_SQUARENESS_ARCMIN",
    "CmmSquareness",
    "compensate",
    "readings_for",
    "psd_squareness",
    "squareness_from_psd_runs",
]


#: paper 004, section 4.1: the measured a_xy, a_xz, a_yz, arc minutes (included-angle signs)
PAPER_004_SQUARENESS_ARCMIN = (8.05, 27.1, -16.6)
#: Largest CMM squareness :meth:`CmmSquareness.checked` accepts, arc minutes: eq (6) is a small-angle model.
MAX_CMM_SQUARENESS_ARCMIN = 60.0


@dataclass(frozen=True)
class CmmSquareness:
    """The three squareness errors of paper 004, included-angle convention, radians.

    Attributes
    ----------
    xy_rad, xz_rad, yz_rad : float
        ``a_xy``, ``a_xz``, ``a_yz``: included angle of the two axes minus 90 degrees.
    """

    xy_rad: float
    xz_rad: float
    yz_rad: float

    def __post_init__(self) -> None:
        for name in ("xy_rad", "xz_rad", "yz_rad"):  # squareness values must be finite numbers
            object.__setattr__(self, name, check_number(name, getattr(self, name)))

    @classmethod
    def from_iso(cls, terms: Mapping[str, float]) -> CmmSquareness:
        """From ISO 230-1 terms ``EC0Y``, ``EB0Z``, ``EA0Z`` (radians; a missing term is 0)."""
        if not isinstance(terms, Mapping):
            raise AxiscalError(f"terms must map EC0Y, EB0Z, EA0Z to radians, not {terms!r}")
        unknown = sorted(set(terms) - {"EC0Y", "EB0Z", "EA0Z"})
        if unknown:
            raise AxiscalError(f"unknown squareness term {', '.join(unknown)}; use EC0Y, EB0Z, EA0Z")
        ec0y, eb0z, ea0z = (check_number(term, terms.get(term, 0.0), unit="radians") for term in ("EC0Y", "EB0Z", "EA0Z"))
        return cls(xy_rad=ec0y, xz_rad=-eb0z, yz_rad=ea0z)

    @classmethod
    def checked(cls, xy_rad: float, xz_rad: float, yz_rad: float) -> CmmSquareness:
        """The three values, refused when eq (6), a small-angle model, does not hold for them.

        Parameters
        ----------
        xy_rad, xz_rad, yz_rad : float
            ``a_xy``, ``a_xz``, ``a_yz``, radians (included-angle convention).

        Returns
        -------
        CmmSquareness

        Raises
        ------
        AxiscalError
            A value that is not finite or beyond :data:`MAX_CMM_SQUARENESS_ARCMIN`.

        Examples
        --------
        >>> CmmSquareness.checked(0.0, 1e-3, 0.0).xz_rad
        0.001
        """
        values = cls(xy_rad, xz_rad, yz_rad)
        if any(abs(v) > MAX_CMM_SQUARENESS_ARCMIN * ARCMIN for v in (xy_rad, xz_rad, yz_rad)):
            shown = ",".join(f"{v / ARCMIN:g}" for v in (xy_rad, xz_rad, yz_rad))
            raise AxiscalError(
                f"values must be within +-{MAX_CMM_SQUARENESS_ARCMIN:g} arc minutes "
                f"(eq 6 is a small-angle model; check the unit), got '{shown}'"
            )
        return values

    def iso(self) -> dict[str, float]:
        """The same as ISO 230-1 terms, radians: ``EC0Y = a_xy, EB0Z = -a_xz, EA0Z = a_yz``."""
        return {
            "EC0Y": iso_from_included_angle(self.xy_rad, plane="XY"),
            "EB0Z": iso_from_included_angle(self.xz_rad, plane="XZ"),
            "EA0Z": iso_from_included_angle(self.yz_rad, plane="YZ"),
        }

    def matrix(self) -> np.ndarray:
        """Matrix ``C`` of eq (6), ``corrected = C @ reading``; shape (3, 3)."""
        return np.array([[1.0, -self.xy_rad, -self.xz_rad], [0.0, 1.0, -self.yz_rad], [0.0, 0.0, 1.0]])


def _points(points_m: np.ndarray | Sequence[Sequence[float]]) -> np.ndarray:
    points = check_array("points_m", points_m, finite=False)
    if points.ndim == 1:
        points = points[np.newaxis, :]
    if points.ndim != 2 or points.shape[1] != 3:
        raise AxiscalError(f"points (points_m) must have shape (n, 3), got {points.shape}")
    if not np.all(np.isfinite(points)):
        raise AxiscalError("points (points_m) must be finite numbers")
    return points


def _squareness(value: CmmSquareness, name: str = "squareness") -> CmmSquareness:
    check_instance(name, value, CmmSquareness, what="a CmmSquareness")
    return value


def compensate(points_m: np.ndarray, squareness: CmmSquareness) -> np.ndarray:
    """Corrected coordinates from CMM readings by eq (6) of paper 004.

    Parameters
    ----------
    points_m : array_like, shape (n, 3), metres
        Readings (x, y, z).
    squareness : CmmSquareness

    Returns
    -------
    ndarray, shape (n, 3), metres
        ``(x - y a_xy - z a_xz, y - z a_yz, z)``.

    Raises
    ------
    AxiscalError
        Points not of shape (n, 3) or not finite.

    Examples
    --------
    >>> c = CmmSquareness(1e-4, 0.0, 0.0)
    >>> compensate([[0.0, 0.1, 0.0]], c).round(9).tolist()
    [[-1e-05, 0.1, 0.0]]
    """
    return _points(points_m) @ _squareness(squareness).matrix().T


def readings_for(points_m: np.ndarray, squareness: CmmSquareness) -> np.ndarray:
    """The inverse of :func:`compensate`: the readings at which eq (6) gives ``points_m``.

    Exact inverse of the triangular map: ``z = z'``, ``y = y' + z a_yz``,
    ``x = x' + y a_xy + z a_xz`` (with the ``y`` just found). Shapes as in :func:`compensate`.

    Parameters
    ----------
    points_m : array_like, shape (n, 3), metres
        True coordinates.
    squareness : CmmSquareness

    Returns
    -------
    ndarray, shape (n, 3), metres
        The readings.

    Raises
    ------
    AxiscalError
        Points not of shape (n, 3) or not finite.
    """
    p = _points(points_m)
    squareness = _squareness(squareness)
    z = p[:, 2]
    y = p[:, 1] + z * squareness.yz_rad
    x = p[:, 0] + y * squareness.xy_rad + z * squareness.xz_rad
    return np.column_stack([x, y, z])


def psd_squareness(
    position_m: np.ndarray,
    reading_m: np.ndarray,
    *,
    prism_deviation_rad: float = 0.0,
    reference: str = "least-squares",
) -> float:
    """Squareness of one plane from a PSD run (paper 004 section 3.3), radians.

    Parameters
    ----------
    position_m : array_like, shape (n,), metres
        Positions of the moving (second) axis.
    reading_m : array_like, shape (n,), metres
        PSD readings: the beam's position on the detector along the positive first axis.
    prism_deviation_rad : float, keyword-only
        ``alpha_p``, the prism's deviation (see :func:`axiscal.squareness.evaluation.prism_reversal`).
    reference : {"least-squares", "end-points"}, keyword-only
        Line through the readings: least squares (default) or the line through the first and
        last reading, which paper 004's section 2.1 describes.

    Returns
    -------
    float
        ``atan(slope) - alpha_p``: included angle minus 90 degrees.

    Raises
    ------
    AxiscalError
        Fewer than 2 points, all at one position, or an unknown reference.
    """
    prism_deviation_rad = check_number("prism_deviation_rad", prism_deviation_rad)
    size = np.size(position_m) if not isinstance(position_m, (str, bytes)) and position_m is not None else 0
    if size < 2:
        raise AxiscalError(f"a PSD run has {size} point(s); a line needs at least 2 (position_m)")
    try:
        line = reference_line(position_m, reading_m, reference=reference)
    except AxiscalError as exc:
        raise AxiscalError(exc.message.replace("deviation_m", "reading_m")) from None
    return math.atan(line.slope) - prism_deviation_rad


def squareness_from_psd_runs(
    runs: Mapping[str, tuple[np.ndarray, np.ndarray]],
    *,
    prism_deviation_rad: float = 0.0,
    reference: str = "least-squares",
) -> CmmSquareness:
    """The three squareness errors from three PSD runs keyed ``"XY"``, ``"XZ"``, ``"YZ"``.

    Each value is ``(position_m, reading_m)`` as in :func:`psd_squareness`.

    Parameters
    ----------
    runs : mapping of str to (ndarray, ndarray)
        ``"XY"``, ``"XZ"``, ``"YZ"`` to ``(position_m, reading_m)``, metres.
    prism_deviation_rad, reference : keyword-only
        As in :func:`psd_squareness`.

    Returns
    -------
    CmmSquareness

    Raises
    ------
    AxiscalError
        A plane missing or unknown, or a run :func:`psd_squareness` refuses.
    """
    if not isinstance(runs, Mapping):
        raise AxiscalError(f"runs must map XY, XZ and YZ to (position_m, reading_m), not {type(runs).__name__}")
    missing = sorted({"XY", "XZ", "YZ"} - set(runs))
    extra = sorted(set(runs) - {"XY", "XZ", "YZ"})
    if missing or extra:
        raise AxiscalError(f"need PSD runs for XY, XZ and YZ exactly (missing {missing or 'none'}, unknown {extra or 'none'})")
    values = {}
    for plane in ("XY", "XZ", "YZ"):
        run = runs[plane]
        if isinstance(run, (str, bytes)) or not hasattr(run, "__len__") or len(run) != 2:
            raise AxiscalError(f"runs['{plane}'] must be (position_m, reading_m), not {run!r}"[:200])
        values[plane] = psd_squareness(*run, prism_deviation_rad=prism_deviation_rad, reference=reference)
    return CmmSquareness(values["XY"], values["XZ"], values["YZ"])
