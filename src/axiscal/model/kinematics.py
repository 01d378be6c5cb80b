"""Homogeneous-transformation (HTM) chain of a machine with linear and rotary axes (paper 000, eqs 6-10; ISO 230-7).

Each axis k contributes ``A_k(q) = M_k · Trans(o_k) · Trans(q · u_k) · E_k(q)``:

- ``E_k(q)``: the error matrix of paper 000 eq (6), rotation part ``[[1, -ec, eb], [ec, 1, -ea],
  [-eb, ea, 1]]`` (that is ``I + [eps]x`` with ``eps = (ea, eb, ec)``) and translation
  ``(tx, ty, tz)``, all read from the axis' error table at q;
- ``Trans(q · u_k)``: the nominal motion along the axis letter;
- ``Trans(o_k)``: the origin of the carriage frame at q = 0 in its parent's frame;
- ``M_k``: the squareness of the axis' guideway, ``I + [s]x`` in the same first-order form as
  paper 000 eq (8). :class:`axiscal.model.machine.Machine` fills ``s`` so that each measured
  squareness term is the included angle between its two axes: ``s = (0, 0, EC0Y)`` for Y,
  ``s = (EA0Z, EB0Z, 0)`` for Z, identity for X, except where the turned axis carries its
  reference axis (then the reference axis gets the opposite rotation; docs/conventions.md).

The tool branch (axes right of F, from the frame outward) gives ``T_tool = Π A_k · Trans(tool)``,
the workpiece branch (axes left of F, read from F outward) ``T_wp = Π A_k · Trans(workpiece)``.
The volumetric error is the origin of ``T_wp⁻¹ · T_tool`` minus the same with every error zero,
expressed in the workpiece frame.

:func:`volumetric_error` evaluates this without forming matrices: it carries the tool point
through the chain as three coordinates, which is exact (no linearisation: the inverse of
``I + [eps]x`` is applied in closed form). Up to 65536 points it does so as NumPy arrays; from
there on, point by point in one compiled pass on threads (:mod:`axiscal.model.chain_kernel`,
numba), so that a process that only asks for small maps never loads the compiler.
:func:`reference_volumetric_error` is the plain per-point product of 4x4 matrices, kept for tests
and benchmarks.

A rotary axis R (A, B, C: about X, Y, Z, right-hand rule, ISO 841) contributes
``A_k(θ) = Trans(o_k) · L_k · E_k(θ) · Rot(u_k, θ) · L_k⁻¹``:

- ``Rot(u_k, θ)``: the exact nominal rotation about the axis;
- ``E_k(θ)``: its six error motions (``EXC, EYC, EZC, EAC, EBC, ECC`` for C) in the same first-order
  form as a linear axis, expressed in the body that carries the rotary axis (they are measured
  there, ISO 230-7);
- ``L_k = Trans(d) · (I + [s]x)``: the location of the axis average line (ISO 230-1/-7), its
  position ``d`` (``EX0C, EY0C``) and orientation ``s`` (``EA0C, EB0C``) relative to the nominal
  line through ``o_k``. A pure offset ``d`` moves a point turned by θ by ``(I - R(θ)) d``.

:func:`pose_error` carries the functional point and the tool direction (+Z of the last tool-side
carriage) through such a chain, vectorised; the orientation error of the tool axis is returned as
its rotation about the nominal tool frame's X and Y axes.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from axiscal.conventions import AXIS_INDEX, ROTARY_INDEX
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_choice, check_instance, check_mapping, check_number
from axiscal.model.tables import ErrorTable

__all__ = [
    "ChainLink",
    "RotaryLink",
    "pose_error",
    "volumetric_error",
    "translation_matrix",
    "error_matrix",
    "link_matrix",
    "reference_volumetric_error",
]

@dataclass(frozen=True)
class ChainLink:
    """One linear axis in a kinematic chain (SI units).

    Parameters
    ----------
    letter : str
        X, Y or Z.
    table : ErrorTable
        Its six error motions.
    origin_m : ndarray, shape (3,)
        Origin of the carriage frame at position 0 in its parent's frame, metres.
    squareness_rad : ndarray, shape (3,)
        The rotation vector ``s`` of ``M_k = I + [s]x``, radians.
    """

    letter: str
    table: ErrorTable
    origin_m: np.ndarray
    squareness_rad: np.ndarray

    def __post_init__(self) -> None:
        check_choice("letter", self.letter, tuple(AXIS_INDEX))
        _check_link(self, ("origin_m", "squareness_rad"))

    @property
    def index(self) -> int:
        """0, 1 or 2: the coordinate the axis moves along."""
        return AXIS_INDEX[self.letter]


@dataclass(frozen=True)
class RotaryLink:
    """One rotary axis in a kinematic chain (SI units).

    Parameters
    ----------
    letter : str
        A, B or C (turning about X, Y, Z).
    table : ErrorTable
        Its six error motions against its angle (radians).
    origin_m : ndarray, shape (3,)
        Nominal pivot: a point of the axis line in its parent's frame, metres.
    offset_m : ndarray, shape (3,)
        Position error ``d`` of the axis average line, metres (its component along the axis is zero).
    tilt_rad : ndarray, shape (3,)
        Orientation error ``s`` of the average line, radians (its component about the axis is zero).
    """

    letter: str
    table: ErrorTable
    origin_m: np.ndarray
    offset_m: np.ndarray
    tilt_rad: np.ndarray

    def __post_init__(self) -> None:
        check_choice("letter", self.letter, tuple(ROTARY_INDEX))
        _check_link(self, ("origin_m", "offset_m", "tilt_rad"))

    @property
    def index(self) -> int:
        """0, 1 or 2: the coordinate axis the rotary axis turns about."""
        return ROTARY_INDEX[self.letter]


def _turn(index, c, s, px, py, pz):
    """Exact rotation of p about coordinate axis ``index`` by the angle with cosine c and sine s."""
    if index == 0:
        return px, c * py - s * pz, s * py + c * pz
    if index == 1:
        return c * px + s * pz, py, -s * px + c * pz
    return c * px - s * py, s * px + c * py, pz


def _carry(link, q, v, p, forward, errors, point):
    """Apply link ``A_k`` (forward) or its inverse to p (a point, or a direction if not ``point``).

    For a rotary link ``q`` is the pair (cos θ, sin θ)."""
    px, py, pz = p
    if isinstance(link, RotaryLink):
        c, s = q
        d = link.offset_m if errors else np.zeros(3)
        tilt = link.tilt_rad if errors else np.zeros(3)
        o = link.origin_m if point else np.zeros(3)
        if not point:
            d = np.zeros(3)
        if forward:
            px, py, pz = _unrotate(*tilt, px - d[0], py - d[1], pz - d[2])
            px, py, pz = _turn(link.index, c, s, px, py, pz)
            if errors:
                px, py, pz = _rotate(v[3], v[4], v[5], px, py, pz)
                if point:
                    px, py, pz = px + v[0], py + v[1], pz + v[2]
            px, py, pz = _rotate(*tilt, px, py, pz)
            return px + d[0] + o[0], py + d[1] + o[1], pz + d[2] + o[2]
        px, py, pz = _unrotate(*tilt, px - d[0] - o[0], py - d[1] - o[1], pz - d[2] - o[2])
        if errors:
            if point:
                px, py, pz = px - v[0], py - v[1], pz - v[2]
            px, py, pz = _unrotate(v[3], v[4], v[5], px, py, pz)
        px, py, pz = _turn(link.index, c, -s, px, py, pz)
        px, py, pz = _rotate(*tilt, px, py, pz)
        return px + d[0], py + d[1], pz + d[2]
    square = link.squareness_rad if errors else np.zeros(3)
    shift = np.zeros(3) if not point else link.origin_m
    if forward:
        if errors:
            px, py, pz = _rotate(v[3], v[4], v[5], px, py, pz)
            if point:
                px, py, pz = px + v[0], py + v[1], pz + v[2]
        p = [px + shift[0], py + shift[1], pz + shift[2]]
        if point:
            p[link.index] = p[link.index] + q
        return _rotate(*square, *p) if errors else tuple(p)
    if errors:
        px, py, pz = _unrotate(*square, px, py, pz)
    p = [px - shift[0], py - shift[1], pz - shift[2]]
    if point:
        p[link.index] = p[link.index] - q
        if errors:
            p = [p[0] - v[0], p[1] - v[1], p[2] - v[2]]
    return _unrotate(v[3], v[4], v[5], *p) if errors else tuple(p)


def _check_link(link, vectors: tuple[str, ...]) -> None:
    """The table and the 3-vectors of a link, checked once when it is made."""
    check_instance("table", link.table, ErrorTable)
    if link.table.letter != link.letter:
        raise AxiscalError(f"table is of axis {link.table.letter}, not of the link's axis {link.letter}")
    for name in vectors:
        object.__setattr__(link, name, check_array(name, getattr(link, name), ndim=1, last=3))


def _checked_chain(tool_links, workpiece_links, tool_m, positions_m, errors, workpiece_m=None):
    """The arguments of the chain functions checked once at the public entry (the inner passes
    run unchecked): links, the tool (and workpiece) point, one finite 1-D array per axis of the
    chain, all of one length, and error motions of shape (6, N)."""
    links = []
    for name, given in (("tool_links", tool_links), ("workpiece_links", workpiece_links)):
        if isinstance(given, (str, bytes)) or not isinstance(given, Sequence):
            raise AxiscalError(f"{name} must be a sequence of ChainLink or RotaryLink, not {given!r}"[:120])
        for link in given:
            check_instance(name, link, (ChainLink, RotaryLink), what="a sequence of ChainLink or RotaryLink")
            links.append(link)
    tool = check_array("tool_m", tool_m, ndim=1, last=3)
    workpiece = None if workpiece_m is None else check_array("workpiece_m", workpiece_m, ndim=1, last=3)
    check_mapping("positions_m", positions_m, [link.letter for link in links],
                  what="a mapping of every axis letter of the chain to its positions")
    if not links and not positions_m:
        raise AxiscalError("positions_m must give the positions of at least one axis")
    positions = {}
    size = None
    for letter in [link.letter for link in links] or list(positions_m):
        q = check_array(f"positions_m[{letter!r}]", positions_m[letter], ndim=1, unit="")
        if size is not None and q.size != size:
            raise AxiscalError(f"positions_m of every axis must have the same length, not {size} and {q.size}")
        size = q.size
        positions[letter] = q
    if errors is not None:
        check_mapping("errors", errors, [link.letter for link in links],
                      what="a mapping of every axis letter of the chain to its error motions")
        errors = {link.letter: check_array(f"errors[{link.letter!r}]", errors[link.letter], ndim=2, unit="") for link in links}
        for letter, e in errors.items():
            if e.shape != (6, size):
                raise AxiscalError(f"errors[{letter!r}] must have shape (6, {size}), not {e.shape}")
    return positions, errors, tool, workpiece


def _link_inputs(links, positions_m):
    """Per link: its position, or (cos θ, sin θ) for a rotary link (computed once for every pass)."""
    out = {}
    for link in links:
        q = positions_m[link.letter]
        out[link.letter] = (np.cos(q), np.sin(q)) if isinstance(link, RotaryLink) else q
    return out


def _through_chain(tool_links, workpiece_links, positions_m, motions, start, point, errors, inputs=None):
    """``T_wp⁻¹ · T_tool`` applied to ``start`` (a point or a direction), with or without errors.

    ``motions``: the error motions (6, N) of each axis letter (unused without errors)."""
    if inputs is None:
        inputs = _link_inputs(tuple(tool_links) + tuple(workpiece_links), positions_m)
    p = start
    for link in reversed(tool_links):
        p = _carry(link, inputs[link.letter], motions[link.letter] if errors else None, p, True, errors, point)
    for link in workpiece_links:
        p = _carry(link, inputs[link.letter], motions[link.letter] if errors else None, p, False, errors, point)
    return p


def pose_error(
    tool_links: Sequence[ChainLink | RotaryLink],
    workpiece_links: Sequence[ChainLink | RotaryLink],
    tool_m: np.ndarray,
    positions_m: dict[str, np.ndarray],
    errors: Mapping[str, np.ndarray] | None = None,
    *,
    orientation: bool = True,
) -> tuple[np.ndarray, np.ndarray | None]:
    """Position error of the functional point and orientation error of the tool axis, any chain.

    Parameters
    ----------
    tool_links, workpiece_links : sequence of ChainLink or RotaryLink
        Each branch ordered from the frame outward.
    tool_m : ndarray, shape (3,)
        The functional point in the last tool-side carriage, metres.
    positions_m : dict of str to ndarray, shape (N,)
        Axis positions: metres for linear axes, radians for rotary axes.
    errors : mapping of str to ndarray, shape (6, N), optional
        Error motions of the axes given per point, instead of read from the links' tables.
    orientation : bool
        False: skip the orientation error (returned as None), for speed.

    Returns
    -------
    error_m : ndarray, shape (N, 3)
        Actual minus nominal functional point relative to the workpiece, in the workpiece frame, m.
    orientation_rad : ndarray, shape (N, 2) or None
        Rotation ``(ei, ej)`` of the tool direction (+Z of the last tool-side carriage) about the
        X and Y axes of the nominal tool frame, seen from the workpiece, radians.

    Raises
    ------
    AxiscalError
        A position outside an error table (unless it holds its ends or is periodic).
    """
    positions_m, errors, tool_m, _ = _checked_chain(tool_links, workpiece_links, tool_m, positions_m, errors)
    if not _compiled(positions_m):
        return _pose_error(tool_links, workpiece_links, tool_m, positions_m, errors, orientation=bool(orientation))
    kernel = _chain_kernel()
    chain = kernel.pack_chain(tool_links, workpiece_links)
    if not orientation:
        return kernel.run_chain(chain, positions_m, tool_m, mode=kernel.ERROR, errors=errors), None
    out = kernel.run_chain(chain, positions_m, tool_m, mode=kernel.POSE, errors=errors)
    return out[:, :3], out[:, 3:]


#: from this many points on, the chain runs compiled (:mod:`axiscal.model.chain_kernel`)
_COMPILED_FROM = 65536


def _compiled(positions_m: Mapping[str, np.ndarray]) -> bool:
    """Whether checked positions are enough points to run the chain compiled."""
    return len(next(iter(positions_m.values()))) >= _COMPILED_FROM


def _chain_kernel():
    """:mod:`axiscal.model.chain_kernel`, imported on first use (numba takes a moment to load)."""
    from axiscal.model import chain_kernel

    return chain_kernel


def _pose_error(tool_links, workpiece_links, tool_m, positions_m, errors=None, *, orientation=True):
    """:func:`pose_error` of checked arguments."""
    n = len(next(iter(positions_m.values())))
    links = tuple(tool_links) + tuple(workpiece_links)
    if errors is None:
        motions = {link.letter: link.table.evaluate(positions_m[link.letter]) for link in links}
    else:
        motions = errors
    inputs = _link_inputs(links, positions_m)

    def run(vector, point, with_errors):
        start = tuple(np.full(n, float(c)) for c in vector)
        return np.column_stack(
            _through_chain(tool_links, workpiece_links, positions_m, motions, start, point, with_errors, inputs)
        )

    error = run(tool_m, True, True) - run(tool_m, True, False)
    if not orientation:
        return error, None
    tool = run((0.0, 0.0, 1.0), False, True)
    nominal = run((0.0, 0.0, 1.0), False, False)
    cross = np.cross(nominal, tool)
    turn = np.column_stack([
        np.einsum("ij,ij->i", run((1.0, 0.0, 0.0), False, False), cross),
        np.einsum("ij,ij->i", run((0.0, 1.0, 0.0), False, False), cross),
    ])
    return error, turn


def _rotate(ex, ey, ez, px, py, pz):
    """``(I + [e]x) p``: p + e × p, component-wise."""
    return px + (ey * pz - ez * py), py + (ez * px - ex * pz), pz + (ex * py - ey * px)


def _unrotate(ex, ey, ez, px, py, pz):
    """``(I + [e]x)⁻¹ p = (p - e × p + e (e · p)) / (1 + |e|²)``, exact."""
    dot = ex * px + ey * py + ez * pz
    scale = 1.0 / (1.0 + ex * ex + ey * ey + ez * ez)
    return (
        (px - (ey * pz - ez * py) + ex * dot) * scale,
        (py - (ez * px - ex * pz) + ey * dot) * scale,
        (pz - (ex * py - ey * px) + ez * dot) * scale,
    )


def volumetric_error(
    tool_links: Sequence[ChainLink],
    workpiece_links: Sequence[ChainLink],
    tool_m: np.ndarray,
    workpiece_m: np.ndarray,
    positions_m: dict[str, np.ndarray],
    errors: Mapping[str, np.ndarray] | None = None,
) -> np.ndarray:
    """Error of the tool point relative to the workpiece, in the workpiece frame.

    Parameters
    ----------
    tool_links, workpiece_links : sequence of ChainLink
        Each branch ordered from the frame outward.
    tool_m, workpiece_m : ndarray, shape (3,)
        The functional point in the last tool-side carriage, the reference point in the last
        workpiece-side carriage, metres.
    positions_m : dict of str to ndarray, shape (N,)
        Axis positions, metres, one entry per axis of the chain.
    errors : mapping of str to ndarray, shape (6, N), optional
        Error motions of the axes given per point (rows tx, ty, tz in m, ea, eb, ec in rad), e.g.
        measured live, instead of read from the links' tables.

    Returns
    -------
    ndarray, shape (N, 3)
        Volumetric error (ex, ey, ez), metres.

    Raises
    ------
    AxiscalError
        A position outside an error table (unless it holds its ends).
    """
    positions_m, errors, tool_m, workpiece_m = _checked_chain(
        tool_links, workpiece_links, tool_m, positions_m, errors, workpiece_m)
    if not _compiled(positions_m):
        return _volumetric_error(tool_links, workpiece_links, tool_m, workpiece_m, positions_m, errors)
    # T_wp⁻¹ ends with Trans(-workpiece), which shifts actual and nominal alike: workpiece_m cancels.
    kernel = _chain_kernel()
    return kernel.run_chain(kernel.pack_chain(tool_links, workpiece_links), positions_m, tool_m, mode=kernel.ERROR, errors=errors)


def _volumetric_error(tool_links, workpiece_links, tool_m, workpiece_m, positions_m, errors=None):
    """:func:`volumetric_error` of checked arguments."""
    n = len(next(iter(positions_m.values())))
    px = np.full(n, float(tool_m[0]))
    py = np.full(n, float(tool_m[1]))
    pz = np.full(n, float(tool_m[2]))
    # T_wp⁻¹ ends with Trans(-workpiece), which shifts actual and nominal alike: it cancels.
    nominal = np.array(tool_m, dtype=float)
    nominal_q = [np.zeros(n), np.zeros(n), np.zeros(n)]
    def motions(link: ChainLink, q: np.ndarray) -> np.ndarray:
        return link.table.evaluate(q) if errors is None else errors[link.letter]

    for link in reversed(tool_links):
        q = positions_m[link.letter]
        v = motions(link, q)
        px, py, pz = _rotate(v[3], v[4], v[5], px, py, pz)
        p = [px + v[0], py + v[1], pz + v[2]]
        p[link.index] = p[link.index] + q
        nominal_q[link.index] = nominal_q[link.index] + q
        px, py, pz = p[0] + link.origin_m[0], p[1] + link.origin_m[1], p[2] + link.origin_m[2]
        nominal = nominal + link.origin_m
        if np.any(link.squareness_rad):
            px, py, pz = _rotate(*link.squareness_rad, px, py, pz)
    for link in workpiece_links:
        q = positions_m[link.letter]
        v = motions(link, q)
        if np.any(link.squareness_rad):
            px, py, pz = _unrotate(*link.squareness_rad, px, py, pz)
        p = [px - link.origin_m[0] - v[0], py - link.origin_m[1] - v[1], pz - link.origin_m[2] - v[2]]
        p[link.index] = p[link.index] - q
        nominal_q[link.index] = nominal_q[link.index] - q
        nominal = nominal - link.origin_m
        px, py, pz = _unrotate(v[3], v[4], v[5], *p)
    out = np.empty((n, 3))
    out[:, 0] = px - nominal[0] - nominal_q[0]
    out[:, 1] = py - nominal[1] - nominal_q[1]
    out[:, 2] = pz - nominal[2] - nominal_q[2]
    return out


def translation_matrix(t: Sequence[float]) -> np.ndarray:
    """4x4 homogeneous translation.

    Parameters
    ----------
    t : sequence of 3 floats
        Translation, metres.

    Returns
    -------
    ndarray, shape (4, 4)
    """
    return _translation(check_array("t_m", t, ndim=1, last=3))


def _translation(t) -> np.ndarray:
    m = np.eye(4)
    m[:3, 3] = t
    return m


def error_matrix(tx: float, ty: float, tz: float, ea: float, eb: float, ec: float) -> np.ndarray:
    """The 4x4 error matrix of paper 000 eq (6).

    Parameters
    ----------
    tx, ty, tz : float
        Translation errors, metres.
    ea, eb, ec : float
        Rotation errors about X, Y, Z, radians.

    Returns
    -------
    ndarray, shape (4, 4)
        Rotation part ``I + [eps]x`` (first order, as the paper writes it), translation ``t``.
    """
    tx, ty, tz = (check_number(name, v) for name, v in (("tx_m", tx), ("ty_m", ty), ("tz_m", tz)))
    ea, eb, ec = (check_number(name, v) for name, v in (("ea_rad", ea), ("eb_rad", eb), ("ec_rad", ec)))
    return _error(tx, ty, tz, ea, eb, ec)


def _error(tx, ty, tz, ea, eb, ec) -> np.ndarray:
    return np.array(
        [[1.0, -ec, eb, tx], [ec, 1.0, -ea, ty], [-eb, ea, 1.0, tz], [0.0, 0.0, 0.0, 1.0]],
    )


def link_matrix(link: ChainLink, q: float, *, with_errors: bool = True) -> np.ndarray:
    """``A_k(q)`` of the module docstring as a 4x4 matrix.

    Parameters
    ----------
    link : ChainLink
        The axis.
    q : float
        Its position, metres.
    with_errors : bool
        False: the nominal ``Trans(o_k + q u_k)``.

    Returns
    -------
    ndarray, shape (4, 4)

    Raises
    ------
    AxiscalError
        A position outside the axis' table (unless it holds its ends).
    """
    check_instance("link", link, ChainLink)
    return _link_matrix(link, check_number("q_m", q), bool(with_errors))


def _link_matrix(link, q, with_errors):
    u = np.zeros(3)
    u[link.index] = 1.0
    if not with_errors:
        return _translation(link.origin_m + q * u)
    s = link.squareness_rad
    m = _error(0.0, 0.0, 0.0, s[0], s[1], s[2])
    values = link.table.evaluate(np.array([q]))[:, 0]
    return m @ _translation(link.origin_m) @ _translation(q * u) @ _error(*values)


def reference_volumetric_error(
    tool_links: Sequence[ChainLink],
    workpiece_links: Sequence[ChainLink],
    tool_m: np.ndarray,
    workpiece_m: np.ndarray,
    positions_m: dict[str, np.ndarray],
) -> np.ndarray:
    """Plain per-point product of 4x4 matrices: the reference :func:`volumetric_error` is tested against.

    Parameters
    ----------
    tool_links, workpiece_links, tool_m, workpiece_m, positions_m
        As :func:`volumetric_error`.

    Returns
    -------
    ndarray, shape (N, 3)
        Volumetric error, metres.

    Raises
    ------
    AxiscalError
        A position outside an error table (unless it holds its ends).
    """
    for name, given in (("tool_links", tool_links), ("workpiece_links", workpiece_links)):
        for link in given if isinstance(given, Sequence) and not isinstance(given, str) else (None,):
            check_instance(name, link, ChainLink, what="a sequence of ChainLink (linear axes)")
    positions_m, _, tool_m, workpiece_m = _checked_chain(tool_links, workpiece_links, tool_m, positions_m, None, workpiece_m)
    n = len(next(iter(positions_m.values())))
    out = np.empty((n, 3))
    for i in range(n):
        origins = []
        for with_errors in (True, False):
            t_tool = np.eye(4)
            for link in tool_links:
                t_tool = t_tool @ _link_matrix(link, positions_m[link.letter][i], with_errors)
            t_tool = t_tool @ _translation(tool_m)
            t_wp = np.eye(4)
            for link in workpiece_links:
                t_wp = t_wp @ _link_matrix(link, positions_m[link.letter][i], with_errors)
            t_wp = t_wp @ _translation(workpiece_m)
            origins.append((np.linalg.inv(t_wp) @ t_tool)[:3, 3])
        out[i] = origins[0] - origins[1]
    return out
