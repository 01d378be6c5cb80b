"""The machine model: a kinematic chain of axes with their error tables, squareness and location errors (paper 000 §3; ISO 230-1, ISO 230-7).

:class:`Machine` is the model (:mod:`axiscal.model.kinematics` has the contract); its axes and the
chain notation are :mod:`axiscal.model.axes`, the TOML description of docs/formats.md is read by
:func:`~axiscal.model.machine_file.load_machine`. The volumetric error is the tool point relative to
the workpiece.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

from axiscal.conventions import ROTARY_LETTERS, SQUARENESS_TERMS, location_names
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_count, check_instance
from axiscal.io.schema import finite_number
from axiscal.model.kinematics import (
    AXIS_INDEX,
    ChainLink,
    RotaryLink,
    _chain_kernel,
    _compiled,
    _pose_error,
    _through_chain,
    _volumetric_error,
    reference_volumetric_error,
)
from axiscal.model.tables import ErrorTable, _floats
from axiscal.units import LENGTH_UNITS, MM
from axiscal.model.axes import _SQUARENESS_PLACE, SQUARENESS_PLACEMENTS, Axis, parse_chain

__all__ = ["Machine"]


@dataclass(frozen=True)
class Machine:
    """The HTM model of a machine (SI units; contract in :mod:`axiscal.model.kinematics`).

    Parameters
    ----------
    chain : str
        Workpiece-side axes, F, tool-side axes (``"FXZ"``, ``"XFYZ"``).
    axes : mapping of str to Axis
        One entry per axis letter of the chain.
    squareness_rad : mapping of str to float
        ``EC0Y``, ``EB0Z``, ``EA0Z`` in radians (missing: zero), ISO 230-1 signs (docs/conventions.md).
    tool_m : sequence of 3 floats
        Functional point in the frame of the last tool-side carriage, metres.
    workpiece_m : sequence of 3 floats
        Point of the workpiece frame the error is measured from, metres.
    location : mapping of str to float
        Location errors of the rotary axes' average lines (ISO 230-7, docs/conventions.md):
        ``EX0C``, ``EY0C`` in metres, ``EA0C``, ``EB0C`` in radians (missing: zero).
    squareness_placement : {"relative", "guideway"}
        A squareness term is what was measured: the included angle between two axes
        (docs/conventions.md). ``"relative"`` (default) keeps that angle in every chain: the term
        turns the guideway of the axis it names (EC0Y: Y; EB0Z, EA0Z: Z), except where that axis
        carries its reference axis in the same branch (``"FYXZ"``, ``"XYFZ"``: Y carries X); there
        it turns the carried reference axis by the opposite angle. ``"guideway"`` always turns the
        named axis' guideway; where it carries its reference axis, both turn together and the
        term is lost (a rigid rotation; the included angle stays 90 degrees).
    name : str
        Free text for reports and titles.

    Raises
    ------
    AxiscalError
        An axis of the chain without a description or a description not in the chain, an
        unknown squareness or location term or placement, a term for an axis not in the chain,
        a non-finite value, or a table of the wrong axis.

    Examples
    --------
    >>> machine = Machine("FXZ", {"X": Axis("X"), "Z": Axis("Z")}, squareness_rad={"EB0Z": 1e-4})
    >>> machine.volumetric_error({"X": [0.0], "Z": [0.1]}).round(9).tolist()
    [[1e-05, 0.0, 0.0]]
    """

    chain: str
    axes: Mapping[str, Axis]
    squareness_rad: Mapping[str, float] = field(default_factory=dict)
    tool_m: tuple[float, float, float] = (0.0, 0.0, 0.0)
    workpiece_m: tuple[float, float, float] = (0.0, 0.0, 0.0)
    name: str = ""
    squareness_placement: str = "relative"
    location: Mapping[str, float] = field(default_factory=dict)

    def __post_init__(self) -> None:
        workpiece_side, tool_side = parse_chain(self.chain)
        letters = set(workpiece_side + tool_side)
        if not all(isinstance(m, Mapping) for m in (self.axes, self.squareness_rad, self.location)):
            raise AxiscalError("axes, squareness_rad and location must be mappings by axis letter and term")
        offsets = {letter: np.zeros(3) for letter in ROTARY_LETTERS}
        tilts = {letter: np.zeros(3) for letter in ROTARY_LETTERS}
        for term, value in self.location.items():
            letter = term[-1:] if isinstance(term, str) else ""
            if letter not in ROTARY_LETTERS or term not in location_names(letter):
                raise AxiscalError(f"unknown location term {term!r}; e.g. {', '.join(location_names('C'))}")
            if letter not in letters:
                raise AxiscalError(f"location {term}: chain '{self.chain}' has no axis {letter}")
            if isinstance(value, bool) or not isinstance(value, (int, float, np.floating)) or not np.isfinite(value):
                raise AxiscalError(f"location {term} must be a finite number, not {value!r}")
            target = offsets if term[1] in AXIS_INDEX else tilts
            target[letter]["XYZABC".index(term[1]) % 3] = float(value)
        missing = sorted(letters - set(self.axes))
        if missing:
            raise AxiscalError(f"chain '{self.chain}' has axis {', '.join(missing)} but no axis description for it")
        extra = sorted(set(self.axes) - letters)
        if extra:
            raise AxiscalError(f"axis {', '.join(extra)} is described but not in chain '{self.chain}'")
        unknown = sorted(set(self.squareness_rad) - set(SQUARENESS_TERMS))
        if unknown:
            raise AxiscalError(f"unknown squareness term {', '.join(unknown)}; use {', '.join(SQUARENESS_TERMS)}")
        check_instance("name", self.name, str)
        if not isinstance(self.squareness_placement, str) or self.squareness_placement not in SQUARENESS_PLACEMENTS:
            raise AxiscalError(
                f"unknown squareness placement '{self.squareness_placement}'; use {' or '.join(SQUARENESS_PLACEMENTS)}"
            )
        rotation = {letter: np.zeros(3) for letter in AXIS_INDEX}
        for term, value in self.squareness_rad.items():
            if isinstance(value, bool) or not isinstance(value, (int, float, np.floating)) or not np.isfinite(value):
                raise AxiscalError(f"squareness {term} must be a finite number of radians, not {value!r}")
            letter, reference, component = _SQUARENESS_PLACE[term]
            if letter not in letters or reference not in letters:
                raise AxiscalError(f"squareness {term} needs axes {reference} and {letter}, which chain '{self.chain}' does not have")
            sign = 1.0
            if self.squareness_placement == "relative":
                for branch in (workpiece_side, tool_side):
                    if letter in branch and reference in branch and branch.index(reference) > branch.index(letter):
                        letter, sign = reference, -1.0
            rotation[letter][component] += sign * float(value)

        def link(letter: str) -> ChainLink | RotaryLink:
            axis = self.axes[letter]
            if not isinstance(axis, Axis):
                raise AxiscalError(f"axis description under '{letter}' must be an Axis, not {axis!r:.40}")
            if axis.letter != letter:
                raise AxiscalError(f"axis description under '{letter}' is for axis '{axis.letter}'")
            table = axis.table if axis.table is not None else ErrorTable.zeros(letter)
            if table.letter != letter:
                raise AxiscalError(f"axis {letter} was given the error table of axis {table.letter}")
            origin = _floats(axis.origin_m, f"axis {letter}: origin")
            if origin.shape != (3,) or not np.all(np.isfinite(origin)):
                raise AxiscalError(f"axis {letter}: origin must be 3 finite numbers")
            if letter in ROTARY_LETTERS:
                return RotaryLink(letter, table, origin, offsets[letter], tilts[letter])
            return ChainLink(letter, table, origin, rotation[letter])

        object.__setattr__(self, "_workpiece_links", tuple(link(k) for k in workpiece_side))
        object.__setattr__(self, "_tool_links", tuple(link(k) for k in tool_side))
        object.__setattr__(self, "_packed", None)  # the chain packed for the compiled kernel, on first use
        for label in ("tool_m", "workpiece_m"):
            value = _floats(getattr(self, label), label)
            if value.shape != (3,) or not np.all(np.isfinite(value)):
                raise AxiscalError(f"{label} must be 3 finite numbers")
            object.__setattr__(self, label, tuple(float(v) for v in value))

    @property
    def letters(self) -> tuple[str, ...]:
        """Axis letters in chain order (workpiece side from F outward, then tool side)."""
        return tuple(link.letter for link in self._workpiece_links + self._tool_links)

    @property
    def rotary(self) -> tuple[str, ...]:
        """The rotary axes of the chain (empty for a linear machine)."""
        return tuple(k for k in self.letters if k in ROTARY_LETTERS)

    @property
    def tool_side(self) -> tuple[str, ...]:
        """Tool-side axis letters, from the frame outward."""
        return tuple(link.letter for link in self._tool_links)

    @property
    def workpiece_side(self) -> tuple[str, ...]:
        """Workpiece-side axis letters, from the frame outward."""
        return tuple(link.letter for link in self._workpiece_links)

    def table(self, letter: str) -> ErrorTable:
        """The error table used for axis ``letter`` (zeros for an ideal axis).

        Parameters
        ----------
        letter : str
            An axis of the chain.

        Returns
        -------
        ErrorTable

        Raises
        ------
        AxiscalError
            If the axis is not in the chain.
        """
        if isinstance(letter, str):
            for link in self._workpiece_links + self._tool_links:
                if link.letter == letter:
                    return link.table
        raise AxiscalError(f"axis {letter if isinstance(letter, str) else repr(letter)} is not in chain '{self.chain}'")

    def travel_m(self, letter: str) -> tuple[float, float]:
        """Travel covered by the error table of axis ``letter``.

        Parameters
        ----------
        letter : str
            An axis of the chain.

        Returns
        -------
        (float, float)
            First and last position of the table, metres.

        Raises
        ------
        AxiscalError
            If the axis is not in the chain.
        """
        table = self.table(letter)
        return table.start_m, table.end_m

    def _positions(self, positions: Mapping[str, np.ndarray]) -> dict[str, np.ndarray]:
        if not isinstance(positions, Mapping):
            raise AxiscalError(f"positions must map the axis letters of chain '{self.chain}' to arrays of metres")
        out: dict[str, np.ndarray] = {}
        size = None
        for letter in self.letters:
            if letter not in positions:
                raise AxiscalError(f"no positions given for axis {letter} of chain '{self.chain}'")
            q = np.atleast_1d(_floats(positions[letter], f"positions of axis {letter}"))
            if q.ndim != 1:
                raise AxiscalError(f"positions of axis {letter} must be one-dimensional")
            if not np.all(np.isfinite(q)):
                raise AxiscalError(f"positions of axis {letter} hold non-finite values")
            if size is not None and q.size != size:
                raise AxiscalError("all axes must be given the same number of positions")
            size = q.size
            out[letter] = q
        return out

    def nominal_point(self, positions: Mapping[str, np.ndarray]) -> np.ndarray:
        """Nominal tool point relative to the workpiece point, in the workpiece frame.

        Parameters
        ----------
        positions : mapping of str to ndarray, shape (N,)
            Position of every axis of the chain: metres, radians for rotary axes.

        Returns
        -------
        ndarray, shape (N, 3)
            Metres.

        Raises
        ------
        AxiscalError
            A missing axis, non-finite positions or axes of different lengths.
        """
        q = self._positions(positions)
        n = len(next(iter(q.values())))
        if self.rotary:
            start = tuple(np.full(n, c) for c in self.tool_m)
            p = _through_chain(self._tool_links, self._workpiece_links, q, {}, start, True, False)
            return np.column_stack(p) - np.array(self.workpiece_m)
        p = np.tile(np.subtract(self.tool_m, self.workpiece_m), (n, 1))
        for link in self._tool_links:
            p += link.origin_m
            p[:, link.index] += q[link.letter]
        for link in self._workpiece_links:
            p -= link.origin_m
            p[:, link.index] -= q[link.letter]
        return p

    def volumetric_error(
        self,
        positions: Mapping[str, np.ndarray],
        *,
        errors: Mapping[str, np.ndarray] | None = None,
        workers: int | None = None,
    ) -> np.ndarray:
        """Volumetric error of the functional point at the given axis positions.

        Parameters
        ----------
        positions : mapping of str to ndarray, shape (N,)
            Position of every axis of the chain, metres.
        errors : mapping of str to ndarray, shape (6, N), optional
            The axes' error motions given per point (rows tx, ty, tz in m; ea, eb, ec in rad),
            e.g. measured live; default: read from the error tables at ``positions``.
        workers : int, optional
            Threads for N of 65536 points or more (default: the number of cores), which then run
            compiled, in chunks of 65536 points the threads share.

        Returns
        -------
        ndarray, shape (N, 3)
            Actual minus nominal tool point relative to the workpiece, in the workpiece frame, m.

        Raises
        ------
        AxiscalError
            A missing axis, non-finite positions, axes of different lengths, a position outside
            an error table (unless it holds its ends), or ``errors`` of the wrong shape.

        Examples
        --------
        >>> machine = load_machine("examples/xz_module/machine.toml")  # doctest: +SKIP
        >>> machine.volumetric_error({"X": [0.1], "Z": [0.19]})  # (1, 3), metres  # doctest: +SKIP
        """
        q = self._positions(positions)
        n = len(next(iter(q.values())))
        if errors is not None:
            if not isinstance(errors, Mapping):
                raise AxiscalError("errors must map axis letters to arrays of shape (6, N)")
            errors = {k: _floats(errors[k], f"errors of axis {k}") for k in self.letters if k in errors}
            wrong = [k for k in self.letters if errors.get(k, np.empty(0)).shape != (6, n)]
            if wrong:
                raise AxiscalError(f"errors of axis {', '.join(wrong)} must have shape (6, {n})")
            bad = [k for k, v in errors.items() if not np.isfinite(v).all()]
            if bad:
                raise AxiscalError(f"errors of axis {bad[0]} hold non-finite values")
        if workers is not None:
            check_count("workers", workers)
        return self._run(q, pose=False, errors=errors, workers=workers)

    def pose_error(
        self, positions: Mapping[str, np.ndarray], *, workers: int | None = None
    ) -> tuple[np.ndarray, np.ndarray]:
        """Position error of the functional point and orientation error of the tool axis.

        The orientation error is the turn of the tool direction (+Z of the last tool-side
        carriage) about the X and Y axes of the nominal tool frame, seen from the workpiece
        (``ei``, ``ej``; docs/conventions.md). It is zero for a chain of linear axes only when
        their angular errors cancel; it is computed for every chain.

        Parameters
        ----------
        positions : mapping of str to ndarray, shape (N,)
            Position of every axis of the chain: metres, radians for rotary axes.
        workers : int, optional
            Threads for large N (default: the number of cores).

        Returns
        -------
        error_m : ndarray, shape (N, 3)
            As :meth:`volumetric_error`, metres.
        orientation_rad : ndarray, shape (N, 2)
            ``(ei, ej)``, radians.

        Raises
        ------
        AxiscalError
            As :meth:`volumetric_error`.

        Examples
        --------
        >>> machine = Machine("CFZ", {"C": Axis("C"), "Z": Axis("Z")}, location={"EX0C": 1e-5})
        >>> error, tilt = machine.pose_error({"C": [np.pi], "Z": [0.0]})
        >>> error.round(9).tolist()  # a 10 um offset of the C axis line, turned half a turn
        [[2e-05, 0.0, 0.0]]
        """
        q = self._positions(positions)
        if workers is not None:
            check_count("workers", workers)
        out = self._run(q, pose=True, workers=workers)
        return out[:, :3], out[:, 3:]

    def _run(self, q: dict[str, np.ndarray], *, pose: bool, errors=None, workers: int | None = None) -> np.ndarray:
        """The chain over checked positions (and error motions): the error (N, 3), with the tool
        axis orientation (N, 5) when ``pose``. Up to 65536 points as NumPy arrays, beyond that
        compiled (:func:`axiscal.model.chain_kernel.run_chain`), on threads."""
        tool = np.array(self.tool_m)
        if not _compiled(q):
            if pose:
                return np.column_stack(_pose_error(self._tool_links, self._workpiece_links, tool, q))
            if self.rotary:
                return _pose_error(self._tool_links, self._workpiece_links, tool, q, errors, orientation=False)[0]
            return _volumetric_error(self._tool_links, self._workpiece_links, tool, np.array(self.workpiece_m), q, errors)
        kernel = _chain_kernel()
        if self._packed is None:
            object.__setattr__(self, "_packed", kernel.pack_chain(self._tool_links, self._workpiece_links))
        return kernel.run_chain(self._packed, q, tool, mode=kernel.POSE if pose else kernel.ERROR, errors=errors, workers=workers)

    def reference_volumetric_error(self, positions: Mapping[str, np.ndarray]) -> np.ndarray:
        """:meth:`volumetric_error` by a plain per-point loop of 4x4 matrix products (slow; for checks).

        Parameters
        ----------
        positions : mapping of str to ndarray, shape (N,)
            Position of every axis of the chain, metres.

        Returns
        -------
        ndarray, shape (N, 3)
            Volumetric error, metres.

        Raises
        ------
        AxiscalError
            As :meth:`volumetric_error`.
        """
        q = self._positions(positions)
        if self.rotary:
            raise AxiscalError("the 4x4 reference model is written for linear chains; use volumetric_error")
        return reference_volumetric_error(
            self._tool_links, self._workpiece_links, np.array(self.tool_m), np.array(self.workpiece_m), q
        )

    def actual_point(self, positions: Mapping[str, np.ndarray]) -> np.ndarray:
        """Where the tool point really is relative to the workpiece point: nominal plus volumetric error.

        Parameters
        ----------
        positions : mapping of str to ndarray, shape (N,)
            Position of every axis of the chain, metres.

        Returns
        -------
        ndarray, shape (N, 3)
            In the workpiece frame, metres.

        Raises
        ------
        AxiscalError
            As :meth:`volumetric_error`.
        """
        return self.nominal_point(positions) + self.volumetric_error(positions)

    def command_for(
        self, target_m: np.ndarray, *, tolerance_m: float = 1e-12, max_iterations: int = 50
    ) -> dict[str, np.ndarray]:
        """Axis commands that put the tool point on ``target_m`` (the inverse of :meth:`actual_point`).

        Fixed-point iteration on the nominal (linear) kinematics: the error's change with position
        is small (its slope is the error's gradient, of order 1e-4), so each step shrinks the miss
        by that factor. Only the directions of the chain's axes can be reached; the remaining
        components of ``target_m`` are ignored (with fewer than 3 axes).

        Parameters
        ----------
        target_m : ndarray, shape (N, 3) or (3,)
            Wanted tool points relative to the workpiece point, in the workpiece frame, metres.
        tolerance_m : float
            Largest miss accepted along each axis, metres.
        max_iterations : int
            Iterations before giving up.

        Returns
        -------
        dict of str to ndarray, shape (N,)
            Commanded position of every axis, metres.

        Raises
        ------
        AxiscalError
            Targets that are not finite or not of shape (N, 3), a tolerance that is not positive,
            ``max_iterations < 1``, commands outside an error table, or no convergence within
            ``max_iterations``; the message names the first bad point (1-based).

        Examples
        --------
        >>> command = machine.command_for(machine.actual_point({"X": [0.1], "Z": [0.05]}))  # doctest: +SKIP
        >>> command["X"]  # array([0.1]) to better than 1e-12 m  # doctest: +SKIP
        """
        if self.rotary:
            raise AxiscalError(f"inverse kinematics is solved for linear chains only, not '{self.chain}'")
        command, bad, message = self._solve(target_m, tolerance_m, max_iterations)
        if bad is not None:
            raise AxiscalError(f"point {bad + 1}: {message}")
        return command

    def _solve(
        self, target_m: np.ndarray, tolerance_m: float, max_iterations: int
    ) -> tuple[dict[str, np.ndarray], int | None, str]:
        """:meth:`command_for`, returning (commands, index of the first bad point or None, why)."""
        if self.rotary:
            raise AxiscalError(f"inverse kinematics is solved for linear chains only, not '{self.chain}'")
        if isinstance(max_iterations, bool) or not isinstance(max_iterations, (int, np.integer)) or max_iterations < 1:
            raise AxiscalError(f"max_iterations must be a whole number >= 1, not {max_iterations!r}")
        if not finite_number(tolerance_m) or tolerance_m <= 0:
            raise AxiscalError(f"tolerance_m must be a positive number of metres, not {tolerance_m!r}")
        target = np.atleast_2d(_floats(target_m, "target points"))
        if target.ndim != 2 or target.shape[1] != 3:
            raise AxiscalError(f"target points must have shape (N, 3), not {target.shape}")
        finite = np.all(np.isfinite(target), axis=1)
        if not np.all(finite):
            return {}, int(np.argmin(finite)), "target is not a finite point"
        sign = {link.letter: 1.0 for link in self._tool_links} | {link.letter: -1.0 for link in self._workpiece_links}
        if self._invert_compiled(len(target)):
            return self._solve_compiled(target, sign, tolerance_m, max_iterations)
        zero = {letter: np.zeros(len(target)) for letter in self.letters}
        offset = self.nominal_point(zero)
        command = {k: sign[k] * (target[:, AXIS_INDEX[k]] - offset[:, AXIS_INDEX[k]]) for k in self.letters}
        for _ in range(max_iterations):
            for letter in self.letters:
                k = self.table(letter).first_outside(command[letter])
                if k is not None:
                    table = self.table(letter)
                    return command, k, (
                        f"needs {letter} = {command[letter][k] / MM:.6g} mm, outside the error table of axis "
                        f"{letter} ({table.start_m / MM:.6g} to {table.end_m / MM:.6g} mm)"
                    )
            miss = self.actual_point(command) - target
            axis_miss = np.max(np.abs(np.column_stack([miss[:, AXIS_INDEX[k]] for k in self.letters])), axis=1)
            if not np.any(axis_miss > tolerance_m):
                return command, None, ""
            command = {k: command[k] - sign[k] * miss[:, AXIS_INDEX[k]] for k in self.letters}
        worst = int(np.argmax(axis_miss))
        return command, worst, f"inverse kinematics did not converge (miss {axis_miss[worst] / LENGTH_UNITS['nm']:.3g} nm)"

    def _invert_compiled(self, n: int) -> bool:
        """Whether the inverse of ``n`` points runs compiled: as many points as the forward chain
        runs compiled from, every table interpolated linearly (a linear chain)."""
        return _compiled({"n": range(n)}) and all(self.table(k).interpolation == "linear" for k in self.letters)

    def _solve_compiled(self, target: np.ndarray, sign: dict[str, float], tolerance_m: float, max_iterations: int):
        """:meth:`_solve` of checked finite targets, compiled (:func:`axiscal.model.inverse_kernel.solve`)."""
        from axiscal.model import inverse_kernel

        if self._packed is None:
            object.__setattr__(self, "_packed", _chain_kernel().pack_chain(self._tool_links, self._workpiece_links))
        zero = self.nominal_point({letter: np.zeros(1) for letter in self.letters})[0]
        return inverse_kernel.solve(self._packed, target, sign, self.tool_m, self.workpiece_m, zero, tolerance_m,
                                    max_iterations, order=self.letters)
