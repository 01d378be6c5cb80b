"""Ray-vector tracing through prisms made of plane faces, and the pentaprism of a squareness set-up.

Paper 002 (Liang et al., "Analysis for squareness measurement error of machine tool introduced by
steering prism"), section 3: vector refraction (eq 3), the reflection matrix (eq 4), the
pentaprism's faces (eq 2) and its ideal beam path (eqs 5-7), rotations of the prism (eqs 8-9) and
the angle between incident and exit beams (eqs 10-11), whose quadratic law for a rotation about Z
is eq (12).

Conventions
-----------
* Directions are unit 3-vectors; positions are metres. Every batch function takes arrays of shape
  ``(n, 3)`` (a single ``(3,)`` vector is treated as ``n = 1``) and returns batched arrays.
* A face is a plane given by a unit normal and a point on it. The sign of a face's normal does not
  matter: reflection uses ``I - 2 N N^T`` (eq 4) and refraction turns the normal against the ray
  before applying eq (3), which assumes ``x . N < 0``.
* A prism is one glass body in an ambient medium; the ray meets its faces in the order listed
  (sequential tracing, planes unbounded). Each refracting face toggles the ray between the ambient
  medium and the glass.
* Rotations are active: ``rotation_xyz(a, b, c) = S_X(a) S_Y(b) S_Z(c)`` (eq 8) turns the prism's
  normals as ``N' = S N`` (eq 9) while the beam stays put.

For the ideal pentaprism the whole prism acts on any incident direction as one rotation by 90
degrees about the normal of its principal section (the two mirrors give the rotation; the exit face
is the entrance face turned by the same rotation, so the two refractions undo each other). Hence
the angle between incident and exit beams is ``arccos(cos(b)^2 sin(c)^2)`` for the rotation
``S_X(a) S_Y(b) S_Z(c)``: exactly 90 degrees for rotations about X and Y, ``90 deg - c^2`` to
leading order for a rotation ``c`` about Z, whatever the glass index. The tests check the tracer
against this closed form.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Literal

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_broadcast, check_instance, check_number

__all__ = [
    "BK7_INDEX",
    "PENTAPRISM_INCIDENT",
    "rotation_x",
    "rotation_y",
    "rotation_z",
    "rotation_xyz",
    "reflection_matrix",
    "reflect",
    "refract",
    "Face",
    "Prism",
    "RayTrace",
    "trace",
    "angle_between",
    "pentaprism",
    "mirror_angle_error_for_deviation",
    "pentaprism_deviation",
    "PentaprismSensitivity",
    "pentaprism_sensitivity",
]

#: Refractive index of N-BK7 at 587.6 nm, the default glass of the pentaprism.
BK7_INDEX = 1.5168

#: what a face does to a ray (a type alias, not part of the public names)
FaceKind = Literal["refract", "reflect"]

#: Incident beam of paper 002, eq (5): travelling along -X into the prism.
PENTAPRISM_INCIDENT = np.array([-1.0, 0.0, 0.0])


def _unit(vectors: np.ndarray, what: str) -> np.ndarray:
    vectors = check_array(what, vectors, last=3, finite=False)
    norms = np.linalg.norm(vectors, axis=-1, keepdims=True)
    if np.any(~np.isfinite(norms)) or np.any(norms == 0.0):
        raise AxiscalError(f"{what} must be finite non-zero vectors")
    return vectors / norms


def _batch(vectors: np.ndarray | Sequence[float], what: str) -> np.ndarray:
    array = check_array(what, vectors)
    if array.ndim == 1:
        array = array[np.newaxis, :]
    if array.ndim != 2 or array.shape[1] != 3:
        raise AxiscalError(f"{what} must have shape (3,) or (n, 3), got {array.shape}")
    return array


def _glass_index(index: float, name: str = "index") -> float:
    try:
        value = check_number(name, index, low=1.0)
    except AxiscalError:
        raise AxiscalError(f"{name}: a refractive index must be a finite number of at least 1 (glass in air), got {index!r}") from None
    return value


def _cos_sin(angle_rad: float | np.ndarray) -> tuple[np.ndarray, ...]:
    """cos, sin, ones and zeros of the angle(s), the entries of a rotation matrix."""
    a = check_array("angle_rad", angle_rad)
    return np.cos(a), np.sin(a), np.ones_like(a), np.zeros_like(a)


def rotation_x(angle_rad: float | np.ndarray) -> np.ndarray:
    """S_X(alpha) of paper 002 eq (8): rotation about X.

    Parameters
    ----------
    angle_rad : float or ndarray
        Rotation angle, radians.

    Returns
    -------
    ndarray, shape ``angle.shape + (3, 3)``
        The rotation matrix (matrices).
    """
    c, s, one, zero = _cos_sin(angle_rad)
    return np.stack([np.stack([one, zero, zero], -1), np.stack([zero, c, -s], -1), np.stack([zero, s, c], -1)], -2)


def rotation_y(angle_rad: float | np.ndarray) -> np.ndarray:
    """S_Y(beta) of paper 002 eq (8): rotation about Y.

    Parameters
    ----------
    angle_rad : float or ndarray
        Rotation angle, radians.

    Returns
    -------
    ndarray, shape ``angle.shape + (3, 3)``
        The rotation matrix (matrices).
    """
    c, s, one, zero = _cos_sin(angle_rad)
    return np.stack([np.stack([c, zero, s], -1), np.stack([zero, one, zero], -1), np.stack([-s, zero, c], -1)], -2)


def rotation_z(angle_rad: float | np.ndarray) -> np.ndarray:
    """S_Z(gamma) of paper 002 eq (8): rotation about Z.

    Parameters
    ----------
    angle_rad : float or ndarray
        Rotation angle, radians.

    Returns
    -------
    ndarray, shape ``angle.shape + (3, 3)``
        The rotation matrix (matrices).
    """
    c, s, one, zero = _cos_sin(angle_rad)
    return np.stack([np.stack([c, -s, zero], -1), np.stack([s, c, zero], -1), np.stack([zero, zero, one], -1)], -2)


def rotation_xyz(rx_rad: float | np.ndarray, ry_rad: float | np.ndarray, rz_rad: float | np.ndarray) -> np.ndarray:
    """``S_X(rx) S_Y(ry) S_Z(rz)``, the prism rotation of paper 002 eq (9).

    Parameters
    ----------
    rx_rad, ry_rad, rz_rad : float or ndarray
        Rotations about X, Y and Z, radians (broadcast against each other).

    Returns
    -------
    ndarray, shape ``broadcast + (3, 3)``
        The rotation matrix (matrices).
    """
    rx, ry, rz = check_broadcast(**{n: check_array(n, a) for n, a in (("rx_rad", rx_rad), ("ry_rad", ry_rad), ("rz_rad", rz_rad))})
    return rotation_x(rx) @ rotation_y(ry) @ rotation_z(rz)


def reflection_matrix(normal: np.ndarray | Sequence[float]) -> np.ndarray:
    """Reflection matrix ``B = I - 2 N N^T`` of a mirror with unit normal ``N`` (paper 002 eq 4).

    Parameters
    ----------
    normal : array_like, shape (..., 3)
        Mirror normals (normalised here; either sign).

    Returns
    -------
    ndarray, shape (..., 3, 3)
    """
    n = _unit(normal, "normal (mirror normals)")
    return np.eye(3) - 2.0 * n[..., :, np.newaxis] * n[..., np.newaxis, :]


def reflect(directions: np.ndarray, normal: np.ndarray) -> np.ndarray:
    """Reflected unit directions, ``B d`` with ``B`` of eq (4).

    Parameters
    ----------
    directions : ndarray, shape (n, 3)
        Unit directions of the incident rays.
    normal : ndarray, shape (3,) or (n, 3)
        Mirror normal(s).

    Returns
    -------
    ndarray, shape (n, 3)
        Reflected directions.
    """
    directions = check_array("directions", directions, last=3)
    n = _unit(normal, "normal (mirror normals)")
    directions, n = check_broadcast(directions=directions, normal=n)
    return directions - 2.0 * np.sum(directions * n, axis=-1, keepdims=True) * n


def refract(directions: np.ndarray, normal: np.ndarray, index_ratio: float) -> np.ndarray:
    """Refracted unit directions by the vector law of refraction (paper 002 eq 3).

    ``x' = mu [x - N (x.N)] - N sqrt(1 - mu^2 + mu^2 (x.N)^2)`` with ``mu = n1 / n2`` and ``N``
    turned against the ray (``x . N < 0``), as eq (3) assumes.

    Parameters
    ----------
    directions : ndarray, shape (n, 3)
        Unit directions of the incident rays.
    normal : ndarray, shape (3,) or (n, 3)
        Face normal (either sign).
    index_ratio : float
        ``n1 / n2``, index of the medium the ray leaves over that of the medium it enters.

    Returns
    -------
    ndarray, shape (n, 3)
        Refracted unit directions.

    Raises
    ------
    AxiscalError
        If a ray is totally internally reflected (the square root's argument is negative).
    """
    directions = check_array("directions", directions, last=3)
    index_ratio = check_number("index_ratio", index_ratio, positive=True)
    directions, n = check_broadcast(directions=directions, normal=_unit(normal, "normal (face normals)"))
    cos_in = np.sum(directions * n, axis=-1, keepdims=True)
    n = np.where(cos_in > 0.0, -n, n)
    cos_in = -np.abs(cos_in)
    tangential = directions - n * cos_in
    # 1 - mu^2 + mu^2 (x.N)^2 written as 1 - mu^2 |x - N (x.N)|^2: the same for a unit x, without
    # the cancellation of two terms of size mu^2 (digits lost near normal incidence or for large mu)
    radicand = 1.0 - index_ratio**2 * np.sum(tangential * tangential, axis=-1, keepdims=True)
    if np.any(radicand < 0.0):
        raise AxiscalError("total internal reflection at a refracting face: no refracted ray")
    return index_ratio * tangential - n * np.sqrt(radicand)


@dataclass(frozen=True)
class Face:
    """A plane face of a prism.

    Attributes
    ----------
    normal : ndarray, shape (3,)
        Unit normal (either sign).
    point_m : ndarray, shape (3,), metres
        A point on the face.
    kind : {"refract", "reflect"}
        What the face does to the ray.
    """

    normal: np.ndarray
    point_m: np.ndarray
    kind: FaceKind

    def __post_init__(self) -> None:
        if self.kind not in ("refract", "reflect"):
            raise AxiscalError(f"face kind must be 'refract' or 'reflect', not {self.kind!r}")
        normal = _unit(check_array("normal (a face normal)", self.normal, ndim=1, last=3), "normal (a face normal)")
        point = check_array("point_m (a face point)", self.point_m, ndim=1, last=3)
        object.__setattr__(self, "normal", normal)
        object.__setattr__(self, "point_m", point)


@dataclass(frozen=True)
class Prism:
    """One glass body bounded by plane faces, met by the ray in the order listed.

    Attributes
    ----------
    faces : tuple of Face
        The faces in the order the ray meets them.
    index : float
        Refractive index of the glass (at least 1).
    pivot_m : ndarray, shape (3,), metres
        The point the prism turns about in :meth:`rotated` (its centre, say).
    """

    faces: tuple[Face, ...]
    index: float
    pivot_m: np.ndarray = field(default_factory=lambda: np.zeros(3))

    def __post_init__(self) -> None:
        _glass_index(self.index)
        if isinstance(self.faces, (str, bytes)) or not hasattr(self.faces, "__iter__") or not self.faces:
            raise AxiscalError("a prism needs at least one face")
        if not all(isinstance(f, Face) for f in self.faces):
            raise AxiscalError("faces must be Face objects")
        object.__setattr__(self, "faces", tuple(self.faces))
        object.__setattr__(self, "index", float(self.index))
        object.__setattr__(self, "pivot_m", check_array("pivot_m", self.pivot_m, ndim=1, last=3))

    def rotated(self, rotation: np.ndarray) -> Prism:
        """The prism turned by the 3x3 rotation matrix ``rotation`` about :attr:`pivot_m` (eq 9)."""
        r = check_array("rotation", rotation)
        if r.shape != (3, 3):
            raise AxiscalError(f"rotation must be a 3x3 matrix, not shape {r.shape}")
        c = self.pivot_m
        faces = tuple(Face(r @ f.normal, r @ (f.point_m - c) + c, f.kind) for f in self.faces)
        return Prism(faces, self.index, c)

    def translated(self, offset_m: np.ndarray | Sequence[float]) -> Prism:
        """The prism moved by ``offset_m`` (shape (3,), metres)."""
        t = check_array("offset_m", offset_m, ndim=1, last=3)
        return Prism(tuple(Face(f.normal, f.point_m + t, f.kind) for f in self.faces), self.index, self.pivot_m + t)


@dataclass(frozen=True)
class RayTrace:
    """The path of a batch of rays through a prism.

    Attributes
    ----------
    points_m : ndarray, shape (n, k + 1, 3), metres
        Start point of each ray, then its intersection with each of the ``k`` faces.
    directions : ndarray, shape (n, k + 1, 3)
        Unit direction before the first face, then after each face.
    """

    points_m: np.ndarray
    directions: np.ndarray

    @property
    def exit_direction(self) -> np.ndarray:
        """Unit direction after the last face, shape (n, 3)."""
        return self.directions[:, -1, :]

    @property
    def exit_point_m(self) -> np.ndarray:
        """Where each ray leaves the last face, shape (n, 3), metres."""
        return self.points_m[:, -1, :]


def trace(
    prism: Prism,
    origins_m: np.ndarray | Sequence[float],
    directions: np.ndarray | Sequence[float],
    *,
    ambient_index: float = 1.0,
) -> RayTrace:
    """Trace rays through the faces of ``prism`` in order.

    Parameters
    ----------
    prism : Prism
    origins_m : array_like, shape (3,) or (n, 3), metres
        Start points of the rays (outside the prism, before its first face).
    directions : array_like, shape (3,) or (n, 3)
        Directions of the rays (normalised here).
    ambient_index : float, keyword-only
        Refractive index of the medium around the prism (1 for air, the default).

    Returns
    -------
    RayTrace

    Raises
    ------
    AxiscalError
        If a ray runs parallel to a face or would have to go backwards to reach it (it misses the
        prism as set up), or is totally internally reflected at a refracting face.
    """
    check_instance("prism", prism, Prism, what="a Prism")
    ambient_index = _glass_index(ambient_index, "ambient_index")
    points = _batch(origins_m, "origins_m (ray origins)")
    dirs = _unit(_batch(directions, "directions (ray directions)"), "directions (ray directions)")
    points, dirs = check_broadcast(origins_m=points, directions=dirs)
    points, dirs = points.copy(), dirs.copy()
    path_points, path_dirs = [points], [dirs]
    inside = False
    for number, face in enumerate(prism.faces, start=1):
        along = dirs @ face.normal
        reach = (face.point_m - points) @ face.normal
        with np.errstate(divide="ignore", invalid="ignore"):
            distance = reach / along
        if np.any(np.abs(along) < 1e-12) or np.any(distance < -1e-12):
            raise AxiscalError(f"a ray misses face {number} of the prism (parallel to it or behind it)")
        points = points + distance[:, np.newaxis] * dirs
        if face.kind == "reflect":
            dirs = reflect(dirs, face.normal)
        else:
            n_from, n_to = (prism.index, ambient_index) if inside else (ambient_index, prism.index)
            dirs = refract(dirs, face.normal, n_from / n_to)
            inside = not inside
        path_points.append(points)
        path_dirs.append(dirs)
    return RayTrace(np.stack(path_points, axis=1), np.stack(path_dirs, axis=1))


def angle_between(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Angle between direction vectors (last axis), in rad, by ``atan2(|a x b|, a . b)`` (eqs 7, 11).

    ``atan2`` keeps full precision near 0 and 90 degrees, where ``arccos`` of eq (11) loses digits.

    Parameters
    ----------
    a, b : ndarray, shape (..., 3)
        Direction vectors (any length).

    Returns
    -------
    ndarray, shape (...)
        Angles, radians.

    Examples
    --------
    >>> round(float(angle_between([1.0, 0.0, 0.0], [0.0, 2.0, 0.0])), 12)
    1.570796326795
    """
    a = _unit(a, "a (a direction)")
    b = _unit(b, "b (a direction)")
    a, b = check_broadcast(a=a, b=b)
    return np.arctan2(np.linalg.norm(np.cross(a, b), axis=-1), np.sum(a * b, axis=-1))


def pentaprism(*, index: float = BK7_INDEX, size_m: float = 0.02, mirror_angle_error_rad: float = 0.0) -> Prism:
    """The pentaprism of paper 002 (face normals of eq 2), principal section in the XZ plane.

    The entrance face M1 (normal +X) is the plane ``x = a`` and the exit face M4 (normal +Z) the
    plane ``z = 0``, both ``a = size_m`` wide; the mirrors M2 and M3 meet them at 112.5 degrees.
    A beam travelling along -X at height ``z = h`` (0 < h < a) leaves along -Z at ``x = a - h``.
    The pivot for rotations is the centre of the entrance and exit faces' square, ``(a/2, 0, a/2)``.

    Parameters
    ----------
    index : float, keyword-only
        Refractive index of the glass; default N-BK7 (1.5168).
    size_m : float, keyword-only
        Width ``a`` of the entrance and exit faces, metres.
    mirror_angle_error_rad : float, keyword-only
        Error ``e`` of the 45 degree angle between the two mirrors (M3 turned about Y, about its
        centre, so that the mirrors include ``45 deg + e``). In the principal section the beam is turned by ``90 deg + 2 e`` inside
        the glass and leaves the exit face at ``arcsin(n sin 2e)``: the prism deviates the beam by
        ``90 deg + arcsin(n sin 2e)``. See :func:`mirror_angle_error_for_deviation`.

    Returns
    -------
    Prism
        Its four faces, glass index and pivot.

    Raises
    ------
    AxiscalError
        If ``index`` is below 1 or ``size_m`` is not positive.
    """
    a = check_number("size_m (the prism size)", size_m, positive=True, unit="metres")
    index = _glass_index(index)
    mirror_angle_error_rad = check_number("mirror_angle_error_rad", mirror_angle_error_rad)
    c8, s8 = np.cos(np.pi / 8.0), np.sin(np.pi / 8.0)
    t = a / c8  # length of each mirror face
    n1 = np.array([1.0, 0.0, 0.0])
    n2 = np.array([c8, 0.0, s8])
    n3 = np.array([-s8, 0.0, -c8])
    n4 = np.array([0.0, 0.0, 1.0])
    p1 = np.array([a, 0.0, a / 2.0])
    p2 = np.array([-t * s8, 0.0, t * c8]) / 2.0
    p3 = np.array([a - t * c8 / 2.0, 0.0, a + t * s8 / 2.0])
    p4 = np.array([a / 2.0, 0.0, 0.0])
    if mirror_angle_error_rad:
        n3 = rotation_y(-mirror_angle_error_rad) @ n3
    faces = (Face(n1, p1, "refract"), Face(n2, p2, "reflect"), Face(n3, p3, "reflect"), Face(n4, p4, "refract"))
    return Prism(faces, float(index), np.array([a / 2.0, 0.0, a / 2.0]))


def mirror_angle_error_for_deviation(deviation_error_rad: float, *, index: float = BK7_INDEX) -> float:
    """Mirror angle error ``e`` that makes the pentaprism deviate the beam by ``90 deg + d`` (eq 13).

    Inverts ``d = arcsin(n sin 2e)`` (see :func:`pentaprism`): ``e = arcsin(sin(d) / n) / 2``.

    Parameters
    ----------
    deviation_error_rad : float
        Wanted deviation error ``d``, radians.
    index : float, keyword-only
        Glass index.

    Returns
    -------
    float
        Mirror angle error ``e``, radians.

    Raises
    ------
    AxiscalError
        If ``index`` is below 1.
    """
    index = _glass_index(index)
    deviation_error_rad = check_number("deviation_error_rad", deviation_error_rad)
    return float(np.arcsin(np.sin(deviation_error_rad) / index) / 2.0)


def pentaprism_deviation(
    rx_rad: float | np.ndarray,
    ry_rad: float | np.ndarray,
    rz_rad: float | np.ndarray,
    *,
    index: float = BK7_INDEX,
    deviation_error_rad: float = 0.0,
    translation_m: Sequence[float] | np.ndarray = (0.0, 0.0, 0.0),
) -> float | np.ndarray:
    """Angle between the incident and the exit beam of a turned pentaprism (paper 002 eqs 9-11).

    The prism of :func:`pentaprism` is turned by ``S_X(rx) S_Y(ry) S_Z(rz)`` (eq 9) about its
    centre and moved by ``translation_m``; the beam ``[-1, 0, 0]`` (eq 5) is traced through it.

    Parameters
    ----------
    rx_rad, ry_rad, rz_rad : float or ndarray, radians
        Rotations about X, Y, Z; they broadcast against each other.
    index : float, keyword-only
        Refractive index of the glass (default 1.5168, N-BK7).
    deviation_error_rad : float, keyword-only
        Build error ``d`` of the prism: unturned, it deviates the beam by ``90 deg + d`` (eq 13).
        Realised as the mirror angle error of :func:`mirror_angle_error_for_deviation`.
    translation_m : array_like, shape (3,), metres, keyword-only
        Shift of the prism; it moves the exit beam but does not turn it.

    Returns
    -------
    float or ndarray, radians
        ``omega'`` of eq (11), shape of the broadcast angles (a float for scalar angles). For the
        ideal prism: exactly pi/2 for rotations about X and Y; ``pi/2 - rz^2`` to leading order for
        a rotation about Z (eq 12), whatever the index.

    Raises
    ------
    AxiscalError
        If ``index`` is below 1, or the prism is turned so far that the beam misses a face or is
        totally internally reflected.
    """
    index = _glass_index(index)
    deviation_error_rad = check_number("deviation_error_rad", deviation_error_rad)
    rotation = rotation_xyz(rx_rad, ry_rad, rz_rad)
    shape = rotation.shape[:-2]
    rotation = rotation.reshape(-1, 3, 3)
    error = mirror_angle_error_for_deviation(deviation_error_rad, index=index) if deviation_error_rad else 0.0
    size = 0.02
    prism = pentaprism(index=index, size_m=size, mirror_angle_error_rad=error)
    offset = check_array("translation_m", translation_m, ndim=1, last=3)
    # Trace in the prism's own frame: turning the prism by R about its pivot c is the same as
    # turning the beam by R^T about c (and undoing the shift), then turning the exit beam back.
    origin = np.array([2.0 * size, 0.0, size / 2.0])
    inverse = np.swapaxes(rotation, -1, -2)
    origins = np.einsum("nij,j->ni", inverse, origin - prism.pivot_m - offset) + prism.pivot_m
    directions = np.einsum("nij,j->ni", inverse, PENTAPRISM_INCIDENT)
    exit_directions = np.einsum("nij,nj->ni", rotation, trace(prism, origins, directions).exit_direction)
    omega = angle_between(PENTAPRISM_INCIDENT, exit_directions).reshape(shape)
    return float(omega) if omega.ndim == 0 else omega


@dataclass(frozen=True)
class PentaprismSensitivity:
    """Change of the pentaprism's deviation with its set-up (paper 002 Fig. 5).

    Attributes
    ----------
    rotation_rad : ndarray, shape (m,)
        Rotation angles swept about each axis in turn.
    change_rad : ndarray, shape (3, m)
        Deviation minus 90 degrees for rotations about X, Y, Z (rows).
    translation_m : ndarray, shape (p,)
        Shifts swept along each axis in turn.
    translation_change_rad : ndarray, shape (3, p)
        Deviation minus 90 degrees for shifts along X, Y, Z (rows): zero.
    quadratic_coefficient : float
        Least-squares ``c`` of ``change_Z = -c rz^2`` (rad per rad^2); 1 for the ideal prism, i.e.
        ``4.848e-6`` arcsec per arcsec^2 as paper 002 eq (12) prints it.
    index : float
        Glass index used.
    """

    rotation_rad: np.ndarray
    change_rad: np.ndarray
    translation_m: np.ndarray
    translation_change_rad: np.ndarray
    quadratic_coefficient: float
    index: float


def pentaprism_sensitivity(
    rotation_rad: np.ndarray | Sequence[float],
    translation_m: np.ndarray | Sequence[float] = (-1e-3, 0.0, 1e-3),
    *,
    index: float = BK7_INDEX,
) -> PentaprismSensitivity:
    """Sweep the pentaprism's rotation about X, Y, Z and its shift along X, Y, Z (Fig. 5).

    Parameters
    ----------
    rotation_rad : array_like, shape (m,), radians
        Rotation angles (each axis in turn, the others zero).
    translation_m : array_like, shape (p,), metres
        Shifts (each axis in turn).
    index : float, keyword-only
        Glass index.

    Returns
    -------
    PentaprismSensitivity
        Deviation changes per rotation axis and per shift axis (rad) and the quadratic
        coefficient of the change with rotation about Z.
    """
    angles = check_array("rotation_rad", rotation_rad, ndim=1, min_len=1)
    shifts = check_array("translation_m", translation_m, ndim=1, min_len=1)
    if not np.any(angles):
        raise AxiscalError("rotation_rad must hold a non-zero angle (the quadratic coefficient needs one)")
    zero = np.zeros_like(angles)
    change = np.stack(
        [
            pentaprism_deviation(angles, zero, zero, index=index),
            pentaprism_deviation(zero, angles, zero, index=index),
            pentaprism_deviation(zero, zero, angles, index=index),
        ]
    ) - np.pi / 2.0
    moved = np.empty((3, shifts.size))
    for axis in range(3):
        for k, shift in enumerate(shifts):
            offset = np.zeros(3)
            offset[axis] = shift
            moved[axis, k] = pentaprism_deviation(0.0, 0.0, 0.0, index=index, translation_m=offset) - np.pi / 2.0
    squares = angles**2
    denominator = float(np.sum(squares**2))
    coefficient = float(-np.sum(change[2] * squares) / denominator) if denominator > 0.0 else float("nan")
    return PentaprismSensitivity(angles, change, shifts, moved, coefficient, float(index))
