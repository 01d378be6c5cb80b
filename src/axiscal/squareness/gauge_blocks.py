"""The gauge block check of a CMM's squareness compensation (paper 004, section 4.2).

A 6-point least-squares plane on one measuring face of a gauge block gives its axis (the plane's
normal); the point-to-point length between one point on each face, projected on that axis, is the
measured length. The blocks of paper 004 are simulated on a CMM with the given squareness errors,
read before and after eq (6) (:mod:`axiscal.squareness.cmm_squareness`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_number
from axiscal.squareness.cmm_squareness import CmmSquareness, _points, _squareness, compensate, readings_for
from axiscal.straightness.report import render_report
from axiscal.units import MM, UM

__all__ = [
    "PAPER_004_IMPROVEMENT_UM",
    "PAPER_004_GAUGE_BLOCKS_MM",
    "Plane",
    "least_squares_plane",
    "gauge_block_length",
    "GaugeBlockCheck",
    "simulate_gauge_block",
    "GaugeBlockStudy",
    "gauge_block_study",
]


#: paper 004, Table 2 as its text gives it: error reductions of the two gauge blocks by compensation, um
PAPER_004_IMPROVEMENT_UM = {"X": 11.0, "Y": 5.0}
#: paper 004, section 4.2: the gauge blocks checked, along X and along Y, mm
PAPER_004_GAUGE_BLOCKS_MM = {"X": 0.992, "Y": 1.000}


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
    >>> from axiscal.squareness.cmm_squareness import PAPER_004_SQUARENESS_ARCMIN
    >>> from axiscal.units import ARCMIN
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
