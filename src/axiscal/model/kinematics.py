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
through the chain as three coordinates, point by point in one compiled pass
(:mod:`axiscal.model.chain_kernel`), which is exact (no linearisation: the inverse of
``I + [eps]x`` is applied in closed form).
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
carriage) through such a chain, in the same pass; the orientation error of the tool axis is returned as
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
    kernel = _chain_kernel()
    chain = kernel.pack_chain(tool_links, workpiece_links)
    if not orientation:
        return kernel.run_chain(chain, positions_m, tool_m, mode=kernel.ERROR, errors=errors), None
    out = kernel.run_chain(chain, positions_m, tool_m, mode=kernel.POSE, errors=errors)
    return out[:, :3], out[:, 3:]


def _chain_kernel():
    """:mod:`axiscal.model.chain_kernel`, imported on first use (numba takes a moment to load)."""
    from axiscal.model import chain_kernel

    return chain_kernel


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
    # T_wp⁻¹ ends with Trans(-workpiece), which shifts actual and nominal alike: workpiece_m cancels.
    positions_m, errors, tool_m, workpiece_m = _checked_chain(
        tool_links, workpiece_links, tool_m, positions_m, errors, workpiece_m)
    kernel = _chain_kernel()
    return kernel.run_chain(kernel.pack_chain(tool_links, workpiece_links), positions_m, tool_m, mode=kernel.ERROR, errors=errors)


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
