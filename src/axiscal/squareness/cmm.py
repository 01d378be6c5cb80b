"""Squareness of a three-axis CMM from PSD runs, its compensation, and the gauge block check.

Paper 004 (Li et al., micro/nano CMM): a laser turned 90 degrees by a pentaprism is the reference
for the second axis; a PSD on that axis follows the beam and the fitted line of its readings gives
the squareness, less the prism's deviation alpha_p (section 3.3). The compensation model of eq (6):

    x' = x - y a_xy - z a_xz,    y' = y - z a_yz,    z' = z,

with (x, y, z) the CMM's scale readings and (x', y', z') the corrected coordinates. Verification
(section 4.2): a 6-point least-squares plane on one measuring face of a gauge block gives its axis
(the plane's normal); the point-to-point length between one point on each face, projected on that
axis, is the measured length.

Signs. Paper 004's text only says an error angle above 0 is positive; the sign comes from its
section 4.1 and eq (6): moving Y to y gives a position error ``-y a_xy`` along X (Z to z:
``-z a_xz`` along X, ``-z a_yz`` along Y), so a positive value leans the second axis towards the
negative first axis and opens the included angle beyond 90 degrees. That is the included-angle
convention of :mod:`axiscal.squareness.evaluation`: ``a_xy, a_xz, a_yz`` are the included angles of X-Y, X-Z,
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
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_instance, check_number, check_path
from axiscal.io.atomic import write_text
from axiscal.io.jsonio import write_sidecar
from axiscal.io.tabular import read_csv, write_csv
from axiscal.squareness.evaluation import iso_from_included_angle
from axiscal.straightness.reference import reference_line
from axiscal.straightness.report import render_report
from axiscal.units import ARCMIN, MM, UM

__all__ = [
    "PAPER_004_IMPROVEMENT_UM",
    "PAPER_004_SQUARENESS_ARCMIN",
    "PAPER_004_GAUGE_BLOCKS_MM",
    "MAX_CMM_SQUARENESS_ARCMIN",
    "CmmSquareness",
    "compensate",
    "readings_for",
    "psd_squareness",
    "squareness_from_psd_runs",
    "Plane",
    "least_squares_plane",
    "gauge_block_length",
    "GaugeBlockCheck",
    "simulate_gauge_block",
    "CmmCompensation",
    "compensate_file",
    "GaugeBlockStudy",
    "gauge_block_study",
]

#: paper 004, Table 2 as its text gives it: error reductions of the two gauge blocks by compensation, um
PAPER_004_IMPROVEMENT_UM = {"X": 11.0, "Y": 5.0}
#: paper 004, section 4.1: the measured a_xy, a_xz, a_yz, arc minutes (included-angle signs)
PAPER_004_SQUARENESS_ARCMIN = (8.05, 27.1, -16.6)
#: paper 004, section 4.2: the gauge blocks checked, along X and along Y, mm
PAPER_004_GAUGE_BLOCKS_MM = {"X": 0.992, "Y": 1.000}
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


@dataclass(frozen=True)
class Plane:
    """A least-squares plane through measured points.

    Attributes
    ----------
    normal : ndarray, shape (3,)
        Unit normal of the plane.
    centroid_m : ndarray, shape (3,)
        Centroid of the points, metres (the plane passes through it).
    rms_m : float
        RMS perpendicular distance of the points from the plane, metres.
    """

    normal: np.ndarray
    centroid_m: np.ndarray
    rms_m: float


def least_squares_plane(points_m: np.ndarray) -> Plane:
    """The plane minimising the squared perpendicular distances (smallest singular vector).

    Parameters
    ----------
    points_m : array_like, shape (n, 3), metres
        At least 3 points, not all on one line.

    Returns
    -------
    Plane
        Normal oriented with a non-negative largest component (the sign of a plane's normal is
        otherwise arbitrary).

    Raises
    ------
    AxiscalError
        Fewer than 3 points, or points on one line (or one point): no plane is defined.
    """
    points = _points(points_m)
    if len(points) < 3:
        raise AxiscalError(f"{len(points)} point(s): a plane needs at least 3")
    centroid = points.mean(axis=0)
    _, singular, vt = np.linalg.svd(points - centroid)
    scale = max(float(singular[0]), 1e-300)
    if singular[1] <= 1e-9 * scale:
        raise AxiscalError("the points lie on one line: no plane is defined (probe points spread over the face)")
    normal = vt[2]
    if normal[np.argmax(np.abs(normal))] < 0:
        normal = -normal
    return Plane(normal, centroid, float(singular[2] / math.sqrt(len(points))))


def gauge_block_length(face_points_m: np.ndarray, first_point_m: np.ndarray, second_point_m: np.ndarray) -> float:
    """Gauge block length by paper 004 section 4.2, metres.

    The least-squares plane of ``face_points_m`` (6 points in a rectangle on one measuring face)
    gives the block's axis; the vector from ``first_point_m`` (on one measuring face) to
    ``second_point_m`` (on the other) projected on that axis is the length (absolute value).

    Parameters
    ----------
    face_points_m : array_like, shape (n, 3), metres
        Points on one measuring face, n >= 3.
    first_point_m, second_point_m : array_like, shape (3,), metres
        One point on each measuring face.

    Returns
    -------
    float
        The length, metres.

    Raises
    ------
    AxiscalError
        Face points that define no plane, or points not finite.
    """
    axis = least_squares_plane(face_points_m).normal
    first = _points(first_point_m)[0]
    second = _points(second_point_m)[0]
    return float(abs((second - first) @ axis))


@dataclass(frozen=True)
class GaugeBlockCheck:
    """A simulated gauge block measurement on a CMM with squareness errors, before and after eq (6).

    Attributes
    ----------
    nominal_m : float
        The block's length.
    axis : ndarray, shape (3,)
        Unit axis of the block in the CMM's frame.
    aligned_before_m, aligned_after_m : float
        Measured minus nominal length by the paper's procedure (6-point plane, projection), before
        and after compensation, metres.
    unaligned_before_m, unaligned_after_m : float
        The same when the point-to-point vector is projected on the machine axis nearest to the
        block's axis instead of the measured plane's normal (no alignment), metres. Meant for
        blocks along a machine axis; for an oblique block it holds the cosine error as well.
    """

    nominal_m: float
    axis: np.ndarray
    aligned_before_m: float
    aligned_after_m: float
    unaligned_before_m: float
    unaligned_after_m: float

    @property
    def aligned_improvement_m(self) -> float:
        """How much the paper's procedure's error falls with compensation: ``|before| - |after|``, m."""
        return abs(self.aligned_before_m) - abs(self.aligned_after_m)

    @property
    def unaligned_improvement_m(self) -> float:
        """``|before| - |after|`` for the unaligned point-to-point length, m."""
        return abs(self.unaligned_before_m) - abs(self.unaligned_after_m)


def _face_basis(axis: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    helper = np.eye(3)[int(np.argmin(np.abs(axis)))]
    u = np.cross(axis, helper)
    u /= np.linalg.norm(u)
    return u, np.cross(axis, u)


def simulate_gauge_block(
    squareness: CmmSquareness,
    nominal_m: float,
    axis: Sequence[float] | np.ndarray,
    *,
    centre_m: Sequence[float] | np.ndarray = (0.0, 0.0, 0.0),
    probe_rectangle_m: tuple[float, float] = (20e-3, 6e-3),
    end_offset_m: Sequence[float] | np.ndarray = (0.0, 0.0, 0.0),
    compensation: CmmSquareness | None = None,
) -> GaugeBlockCheck:
    """Simulate paper 004's gauge block check on a CMM whose axes are out of square.

    The CMM reads :func:`readings_for` the true contact points (its scales read as if the axes
    were square). The block's first measuring face passes through ``centre_m`` with normal
    ``axis``; six probe points sit on a 3 x 2 grid spanning ``probe_rectangle_m`` on that face; one
    end point is probed at ``centre_m`` and the other on the opposite face, moved across the axis
    by ``end_offset_m`` (its component along the axis is dropped).

    Parameters
    ----------
    squareness : CmmSquareness
        The CMM's actual squareness errors.
    nominal_m : float
        Block length, metres.
    axis : array_like, shape (3,)
        Direction of the block's axis in the CMM frame (normalised here).
    centre_m, probe_rectangle_m, end_offset_m : keyword-only, metres
        Where the block is and how it is probed.
    compensation : CmmSquareness, keyword-only
        Squareness used by eq (6) for the "after" figures (default: the CMM's own, a perfect
        calibration).

    Returns
    -------
    GaugeBlockCheck

    Raises
    ------
    AxiscalError
        A block length that is not positive, or an axis that is zero or not finite.
    """
    squareness = _squareness(squareness)
    if compensation is not None:
        _squareness(compensation, "compensation")
    nominal_m = check_number("nominal_m (the block length)", nominal_m, positive=True, unit="metres")
    n = check_array("axis", axis, ndim=1, last=3, finite=False)
    if not np.all(np.isfinite(n)) or np.linalg.norm(n) == 0.0:
        raise AxiscalError("the block axis must be a finite non-zero vector")
    n = n / np.linalg.norm(n)
    centre = check_array("centre_m", centre_m, ndim=1, last=3)
    offset = check_array("end_offset_m", end_offset_m, ndim=1, last=3)
    offset = offset - (offset @ n) * n
    u, v = _face_basis(n)
    rectangle = check_array("probe_rectangle_m", probe_rectangle_m, ndim=1, last=2)
    if np.any(rectangle <= 0.0):
        raise AxiscalError(f"probe_rectangle_m must be a positive width and height in metres, not {rectangle.tolist()}")
    width, height = rectangle
    grid = [(a, b) for b in (-0.5, 0.5) for a in (-0.5, 0.0, 0.5)]
    face = np.array([centre + a * width * u + b * height * v for a, b in grid])
    first = centre
    second = centre + nominal_m * n + offset
    correction = squareness if compensation is None else compensation
    nominal_axis = np.eye(3)[int(np.argmax(np.abs(n)))]

    def measure(points: np.ndarray) -> tuple[float, float]:
        aligned = gauge_block_length(points[:6], points[6], points[7]) - nominal_m
        unaligned = abs(float((points[7] - points[6]) @ nominal_axis)) - nominal_m
        return aligned, unaligned

    read = readings_for(np.vstack([face, first, second]), squareness)
    before = measure(read)
    after = measure(compensate(read, correction))
    return GaugeBlockCheck(
        nominal_m=float(nominal_m),
        axis=n,
        aligned_before_m=before[0],
        aligned_after_m=after[0],
        unaligned_before_m=before[1],
        unaligned_after_m=after[1],
    )


# ---------------------------------------------------------------------------------------------
# file-level calls of ``axiscal cmm``


@dataclass(frozen=True)
class CmmCompensation:
    """Points of a file moved by eq (6) of paper 004 (or its inverse).

    Attributes
    ----------
    points_m : ndarray, shape (n, 3)
        The points as read, metres.
    moved_m : ndarray, shape (n, 3)
        Corrected coordinates (or, inverse, the readings the CMM shows), metres.
    csv_text : str
        The CSV: the input's columns as they were, then ``x_corrected_mm, y_corrected_mm,
        z_corrected_mm`` (inverse: ``*_reading_mm``).
    metadata : dict
        What the sidecar holds besides kind and sources: the model, a_xy, a_xz, a_yz in arcmin.
    """

    points_m: np.ndarray
    moved_m: np.ndarray
    csv_text: str
    metadata: dict[str, Any]


def compensate_file(
    points_path: str | Path,
    squareness: CmmSquareness,
    *,
    inverse: bool = False,
    output: str | Path | None = None,
) -> CmmCompensation:
    """Correct the CMM readings of a file by eq (6) of paper 004, or go the other way.

    Parameters
    ----------
    points_path : str or Path
        CSV with ``x_mm, y_mm, z_mm`` (other columns are carried through).
    squareness : CmmSquareness
        a_xy, a_xz, a_yz, radians.
    inverse : bool, keyword-only
        From true coordinates to the readings the CMM shows (:func:`readings_for`).
    output : str or Path, optional, keyword-only
        Write the CSV here, with its JSON sidecar.

    Returns
    -------
    CmmCompensation

    Raises
    ------
    AxiscalError
        Missing file or column, or a cell that is not a finite number (naming file and line).
    """
    squareness = _squareness(squareness)
    if not isinstance(inverse, (bool, np.bool_)):
        raise AxiscalError(f"inverse must be True or False, not {inverse!r}")
    table = read_csv(check_path("points_path", points_path))
    table.require("x_mm", "y_mm", "z_mm")
    points = np.column_stack([table.numeric(name) for name in ("x_mm", "y_mm", "z_mm")]) * MM
    moved = readings_for(points, squareness) if inverse else compensate(points, squareness)
    suffix = "reading" if inverse else "corrected"
    columns: dict[str, Any] = {name: table.text(name) for name in table.header}
    for k, axis in enumerate("xyz"):
        columns[f"{axis}_{suffix}_mm"] = moved[:, k] / MM
    text = write_csv(None, columns, fmt="{:.6f}")
    metadata: dict[str, Any] = {
        "model": f"paper 004 eq (6){' inverse' if inverse else ''}",
        "squareness_arcmin": {
            "a_xy": squareness.xy_rad / ARCMIN,
            "a_xz": squareness.xz_rad / ARCMIN,
            "a_yz": squareness.yz_rad / ARCMIN,
        },
        "iso_terms_arcmin": {term: value / ARCMIN for term, value in squareness.iso().items()},
    }
    if output is not None:
        write_text(output, text)
        write_sidecar(output, kind="cmm compensation", sources=[points_path], **metadata)
    return CmmCompensation(points, moved, text, metadata)


@dataclass(frozen=True)
class GaugeBlockStudy:
    """Paper 004's gauge block check simulated before and after compensation.

    Attributes
    ----------
    end_offset_m : float
        Sideways distance between the two probed end points, metres.
    blocks : dict of str to GaugeBlockCheck
        ``"X"`` and ``"Y"``: the blocks of :data:`PAPER_004_GAUGE_BLOCKS_MM`.
    """

    end_offset_m: float
    blocks: dict[str, GaugeBlockCheck]

    def payload(self) -> dict[str, Any]:
        """The JSON object: errors in um per block, with paper 004's published improvement."""
        body = {
            axis: {
                "nominal_mm": check.nominal_m / MM,
                "aligned_before_um": check.aligned_before_m / UM,
                "aligned_after_um": check.aligned_after_m / UM,
                "aligned_improvement_um": check.aligned_improvement_m / UM,
                "unaligned_before_um": check.unaligned_before_m / UM,
                "unaligned_after_um": check.unaligned_after_m / UM,
                "unaligned_improvement_um": check.unaligned_improvement_m / UM,
                "paper_004_improvement_um": PAPER_004_IMPROVEMENT_UM[axis],
            }
            for axis, check in self.blocks.items()
        }
        return {"end_offset_mm": self.end_offset_m / MM, "blocks": body}

    def report(self) -> str:
        """The readable table of the check."""
        payload = self.payload()
        return render_report("squareness_gauge_blocks.txt.j2", end_offset_mm=payload["end_offset_mm"], blocks=payload["blocks"])


def gauge_block_study(squareness: CmmSquareness, *, end_offset_m: float = 1.0 * MM) -> GaugeBlockStudy:
    """Simulate paper 004's gauge block check (0.992 mm along X, 1.000 mm along Y) before and after eq (6).

    Parameters
    ----------
    squareness : CmmSquareness
        The CMM's squareness errors (paper 004's: ``PAPER_004_SQUARENESS_ARCMIN``).
    end_offset_m : float, keyword-only
        Sideways distance, in each of the two across directions, between the two probed end
        points, metres (default 1 mm).

    Returns
    -------
    GaugeBlockStudy

    Raises
    ------
    AxiscalError
        An offset that is not a finite number.

    Examples
    --------
    >>> values = CmmSquareness(*(v * ARCMIN for v in PAPER_004_SQUARENESS_ARCMIN))
    >>> round(gauge_block_study(values).payload()["blocks"]["X"]["unaligned_improvement_um"], 1)
    10.2
    """
    squareness = _squareness(squareness)
    end_offset_m = check_number("end_offset_m (the end offset)", end_offset_m, unit="metres")
    d = end_offset_m
    blocks = {
        "X": simulate_gauge_block(squareness, PAPER_004_GAUGE_BLOCKS_MM["X"] * MM, (1, 0, 0), end_offset_m=(0, d, d)),
        "Y": simulate_gauge_block(squareness, PAPER_004_GAUGE_BLOCKS_MM["Y"] * MM, (0, 1, 0), end_offset_m=(d, 0, -d)),
    }
    return GaugeBlockStudy(float(end_offset_m), blocks)
