"""Identification of a machine's error tables from artefacts: least squares with a rank analysis (Gauss-Newton, SVD).

The unknowns are the machine's terms θ (:mod:`axiscal.identification.parameters`) and each
artefact's own unknowns p (:mod:`axiscal.identification.artefacts`). The residuals r(θ, p) have the
Jacobian ``J = [direction · ∂e/∂θ | ∂r/∂p]``. With D the column scaling (each column to unit
length), the singular value decomposition ``J D = U S Vᵀ`` at the nominal machine (S and V from
the eigen-decomposition of ``(J D)ᵀ J D``) splits the
unknowns into the combinations the data determine (singular values above ``rank_tolerance`` times
the largest) and those it cannot separate (the null space). SciPy's ``least_squares`` solves for
the determined combinations only, ``x = x₀ + D V_r z``, with the Jacobian ``J D V_r``; what the data
cannot see keeps its starting value and is reported, never silently zeroed.

Each kind of artefact has its own residual variance (a plate and a step gauge are read with
different noise): after a first fit, the residuals of each kind are weighted by the inverse of
their standard deviation (each kind's share ``M_k (1 - r / M)`` of the degrees of freedom) and the
fit is repeated until the weights settle. Covariance (GUM 6.2 with the least-squares sensitivity): with ``A = W J D V_r`` at
the solution, ``Σ_x = D V_r (s² (AᵀA)⁻¹ + A⁺ W S diag(u²) Sᵀ W A⁺ᵀ) V_rᵀ D``: ``s²`` the weighted
residual variance ``rss_w / (M - r)`` and ``S, u`` the artefacts' calibration (certificate)
uncertainties.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np
from scipy.optimize import least_squares

from axiscal.errors import AxiscalError
from axiscal.identification.artefacts import Artefact
from axiscal.identification.basis import parse_model
from axiscal.identification.files import read_artefact
from axiscal.identification.output import write_identification
from axiscal.identification.parameters import ParameterSet
from axiscal.identification.result import Combination, Identification, Undetermined
from axiscal.io.arguments import check_array, check_instance, check_mapping, check_number, check_path
from axiscal.io.templates import render_template
from axiscal.model.machine import Machine, as_machine

__all__ = ["identify", "identify_files", "RANK_TOLERANCE"]

#: a singular value below this fraction of the largest (columns scaled to unit length) is a combination the data cannot
#: see: readings taken a few um off their nominal places break an exact degeneracy at 1e-6 to 1e-5, and a combination
#: determined only that way would carry the noise magnified 10^4 times
RANK_TOLERANCE = 1e-4
#: an entry of a null vector above this counts
_NULL_ENTRY = 1e-6
#: most weighted fits while the kinds' variances settle (to 1 %)
_REWEIGHTS = 8
#: coefficients of a named combination below this (the largest being 1) are left out of its name
_SHOWN = 1e-4


class _Problem:
    """The stacked residuals and Jacobian of all artefacts against (θ, p₁, p₂ ...)."""

    def __init__(self, parameters: ParameterSet, artefacts: Sequence[Artefact], machine: Machine):
        self.parameters = parameters
        self.artefacts = artefacts
        self.setups = []
        for artefact in artefacts:
            positions = artefact.positions(machine)
            tool = np.asarray(artefact.tool_m, dtype=float)
            nominal = artefact.reported(machine, positions)
            self.setups.append((positions, tool, nominal))
        self.p_slices = []
        start = len(parameters.terms)
        for artefact in artefacts:
            self.p_slices.append(slice(start, start + len(artefact.unknowns)))
            start += len(artefact.unknowns)
        self.size = start
        self.r_slices = []
        start = 0
        for artefact in artefacts:
            self.r_slices.append(slice(start, start + artefact.count))
            start += artefact.count
        self.count = start
        self._sensitivity: list[np.ndarray | None] = [None] * len(artefacts)

    @property
    def names(self) -> tuple[str, ...]:
        return self.parameters.names + tuple(n for a in self.artefacts for n in a.unknowns)

    def errors(self, x):
        theta = x[: len(self.parameters.terms)]
        return [self.parameters.errors(theta, positions, tool) for positions, tool, _ in self.setups]

    def starting(self, theta: np.ndarray) -> np.ndarray:
        x = np.zeros(self.size)
        x[: len(theta)] = theta
        for artefact, (_, _, nominal), error, part in zip(self.artefacts, self.setups, self.errors(x), self.p_slices):
            x[part] = artefact.start(nominal, error)
        return x

    def residuals(self, x: np.ndarray) -> np.ndarray:
        out = np.empty(self.count)
        for artefact, (_, _, nominal), error, p, r in zip(self.artefacts, self.setups, self.errors(x), self.p_slices, self.r_slices):
            out[r] = artefact.residuals(nominal, error, x[p])
        return out

    def sensitivity(self, index: int) -> np.ndarray:
        """∂e/∂θ (N, 3, P) at the points of artefact ``index``, taken once on the nominal machine.

        The volumetric error is linear in θ to first order; its change of slope over errors of
        1e-5 (rad) is a relative 1e-5 of the sensitivity, far below what moves an estimate.
        """
        if self._sensitivity[index] is None:
            positions, tool, _ = self.setups[index]
            self._sensitivity[index] = self.parameters.jacobian(np.zeros(len(self.parameters.terms)), positions, tool)
        return self._sensitivity[index]

    def jacobian(self, x: np.ndarray) -> np.ndarray:
        size = len(self.parameters.terms)
        out = np.zeros((self.count, self.size))
        for k, (artefact, (_, _, nominal), error, p, r) in enumerate(
            zip(self.artefacts, self.setups, self.errors(x), self.p_slices, self.r_slices)
        ):
            point, direction, d_p = artefact.partials(nominal, error, x[p])
            if size:
                out[r, :size] = np.einsum("mk,mkp->mp", direction, self.sensitivity(k)[point])
            out[r, p] = d_p
        return out

    def systematic(self) -> tuple[np.ndarray, np.ndarray]:
        blocks, u = [], []
        for artefact, r in zip(self.artefacts, self.r_slices):
            s, v = artefact.systematic()
            full = np.zeros((self.count, s.shape[1]))
            full[r] = s
            blocks.append(full)
            u.append(v)
        return np.hstack(blocks), np.concatenate(u)


def _singular(matrix: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Singular values (descending) and right singular vectors (rows, all n) of an (M, n) matrix.

    From the eigen-decomposition of the n x n Gram matrix ``MᵀM``: its eigenvalues are the squared
    singular values. The columns are scaled to unit length before, so singular values down to
    about 1e-7 of the largest are resolved, below the rank tolerance; and forming ``MᵀM`` costs a
    fraction of a decomposition of the tall matrix itself.
    """
    w, v = np.linalg.eigh(matrix.T @ matrix)
    order = np.argsort(w)[::-1]
    return np.sqrt(np.maximum(w[order], 0.0)), v[:, order].T


def _groups(null: np.ndarray) -> list[np.ndarray]:
    """Unknowns that the null space ties together: connected components of its projector."""
    projector = null @ null.T
    linked = np.abs(projector) > _NULL_ENTRY
    involved = np.flatnonzero(np.diag(linked))
    seen: set[int] = set()
    groups = []
    for k in involved:
        if k in seen:
            continue
        group, frontier = {int(k)}, [int(k)]
        while frontier:
            j = frontier.pop()
            for i in np.flatnonzero(linked[j]):
                if int(i) not in group:
                    group.add(int(i))
                    frontier.append(int(i))
        seen |= group
        groups.append(np.array(sorted(group)))
    return groups


def _combination(names, coefficients, x=None, covariance=None) -> Combination:
    """The combination ``coefficients`` (scaled so the largest is 1), named by its terms above 1e-4."""
    c = coefficients / coefficients[np.argmax(np.abs(coefficients))]
    terms = {names[k]: float(c[k]) for k in np.flatnonzero(np.abs(c) > _SHOWN)}
    if x is None:
        return Combination(terms)
    return Combination(terms, float(c @ x), float(np.sqrt(max(c @ covariance @ c, 0.0))))


def _pivoted(basis: np.ndarray, weight: np.ndarray) -> np.ndarray:
    """The same span with one pivot unknown per column (coefficient 1, 0 in the others), pivots
    chosen among the heavier-weighted unknowns first: combinations a reader can name."""
    from scipy.linalg import qr

    _, _, pivots = qr((basis * weight[:, None]).T, pivoting=True)
    return basis @ np.linalg.inv(basis[pivots[: basis.shape[1]]])


def _travel(machine: Machine, artefacts: Sequence[Artefact], travel) -> dict[str, tuple[float, float]]:
    """The travel of each axis the artefacts move: the positions they reach joined with the range of
    the axis' table in the machine file, or as ``travel`` states it."""
    spans: dict[str, list[float]] = {}
    for artefact in artefacts:
        for letter, q in artefact.positions(machine).items():
            low, high = spans.get(letter, [np.inf, -np.inf])
            spans[letter] = [min(low, float(q.min())), max(high, float(q.max()))]
    for letter in spans:
        table = machine.axes[letter].table
        if table is not None and not table.periodic:  # a table in the machine file states the travel
            spans[letter] = [min(spans[letter][0], table.start_m), max(spans[letter][1], table.end_m)]
    if travel is not None:
        check_mapping("travel", travel, what="a mapping of axis letters to (start, end)")
        for letter, given in travel.items():
            if letter not in machine.letters:
                raise AxiscalError(f"travel: chain '{machine.chain}' has no axis {letter!r}")
            start, end = check_array(f"travel[{letter!r}]", given, ndim=1, last=2, unit="")
            if end <= start:
                raise AxiscalError(f"travel of axis {letter} must end after it starts, not {start:g} to {end:g}")
            if letter in spans and (spans[letter][0] < start - 1e-9 or spans[letter][1] > end + 1e-9):
                raise AxiscalError(
                    f"the artefacts move axis {letter} from {spans[letter][0]:g} to {spans[letter][1]:g}, outside its travel {start:g} to {end:g}"
                )
            spans[letter] = [float(start), float(end)]
    return {k: (v[0], v[1]) for k, v in spans.items()}


def _fit(problem: _Problem, x0: np.ndarray, basis: np.ndarray, rank: int):
    """Least squares over the determined combinations ``x = x₀ + basis z``, each kind of artefact
    weighted by its own residual standard deviation; returns (x, residuals, covariance of x,
    condition number, standard deviation by kind)."""
    artefacts = problem.artefacts
    # one variance per kind of artefact: a fit, the kinds' residual variances, a weighted fit again
    kinds = sorted({a.kind for a in artefacts})
    rows = {kind: np.concatenate([np.arange(problem.count)[r] for a, r in zip(artefacts, problem.r_slices) if a.kind == kind]) for kind in kinds}
    weight = np.ones(problem.count)
    z = np.zeros(rank)
    for _ in range(_REWEIGHTS if len(kinds) > 1 else 1):
        before = weight.copy()
        solution = least_squares(
            lambda z: weight * problem.residuals(x0 + basis @ z),
            z,
            jac=lambda z: weight[:, None] * (problem.jacobian(x0 + basis @ z) @ basis),
            method="lm", xtol=1e-13, ftol=1e-13, gtol=1e-13,
        )
        z = solution.x
        residual = problem.residuals(x0 + basis @ z)
        for kind, k in rows.items():  # each kind's share of the degrees of freedom
            weight[k] = 1.0 / max(np.sqrt(float(residual[k] @ residual[k]) / (k.size * (1.0 - rank / problem.count))), 1e-15)
        if np.allclose(weight / weight[0], before / before[0], rtol=0.01):
            break
    x = x0 + basis @ z
    residual = problem.residuals(x)
    a = weight[:, None] * (problem.jacobian(x) @ basis)
    s_a, vt_a = _singular(a)
    dof = problem.count - rank
    variance = float((weight * residual) @ (weight * residual)) / dof
    inverse = (vt_a.T / s_a**2) @ vt_a  # (AᵀA)⁻¹
    cov_z = variance * inverse
    systematic, u_sys = problem.systematic()
    if u_sys.size:
        spread = inverse @ (a.T @ (weight[:, None] * systematic)) * u_sys  # A⁺ W S diag(u)
        cov_z = cov_z + spread @ spread.T
    covariance = basis @ cov_z @ basis.T
    kind_std = {kind: float(1.0 / weight[k][0]) for kind, k in rows.items()}
    return x, residual, covariance, float(s_a[0] / s_a[-1]), kind_std


def _undetermined(problem: _Problem, null: np.ndarray, scale: np.ndarray, x: np.ndarray, covariance: np.ndarray):
    """The unknowns' standard uncertainties (NaN where the null space touches them) and the groups
    the data cannot separate, each with the combinations hidden and those determined instead."""
    p = len(problem.parameters.terms)
    all_names = problem.names
    undetermined_mask = np.linalg.norm(null, axis=1) > _NULL_ENTRY if null.size else np.zeros(problem.size, bool)
    std = np.where(undetermined_mask, np.nan, np.sqrt(np.maximum(np.diag(covariance), 0.0)))
    undetermined = []
    for group in _groups(null) if null.size else []:
        block = (null @ null.T)[np.ix_(group, group)]
        w, v = np.linalg.eigh(block)
        preference = np.where(group < p, 1.0, 1e-3)  # a machine term names a combination before an artefact's own unknown
        hidden_basis = _pivoted(scale[group][:, None] * v[:, w > 0.5], preference)
        hidden = [_combination([all_names[k] for k in group], hidden_basis[:, i]) for i in range(hidden_basis.shape[1])]
        seen_basis = _pivoted(v[:, w <= 0.5] / scale[group][:, None], preference) if np.any(w <= 0.5) else np.zeros((len(group), 0))
        seen = []
        for i in range(seen_basis.shape[1]):
            c = np.zeros(problem.size)
            c[group] = seen_basis[:, i]
            seen.append(_combination(all_names, c, x, covariance))
        undetermined.append(Undetermined(tuple(all_names[k] for k in group), tuple(hidden), tuple(seen)))
    return all_names, std, tuple(undetermined)


def identify(
    machine: Machine | str | Path,
    artefacts: Sequence[Artefact | str | Path],
    *,
    model: str = "poly:3",
    fix: Sequence[str] = (),
    rank_tolerance: float = RANK_TOLERANCE,
    travel: Mapping[str, tuple[float, float]] | None = None,
) -> Identification:
    """Identify a machine's error tables (with their covariance) from artefact measurements.

    Parameters
    ----------
    machine : Machine, str or Path
        The chain and axes; its error tables, squareness and location terms are the starting
        guess (zero when absent), and stay as they are for the terms in ``fix``.
    artefacts : sequence of Artefact, str or Path
        The artefacts, or the paths of their TOML files (:func:`axiscal.identification.read_artefact`).
    model : str, keyword-only
        The error functions: ``"poly:N"`` (Legendre polynomials up to degree N) or ``"spline:K"``
        (a linear spline on K intervals over each axis' travel).
    fix : sequence of str, keyword-only
        Terms kept at their starting value: ``"EBX:2"``, ``"EBX"``, ``"EC0Y"``, ``"EX0C"``, an axis
        letter, ``"squareness"`` or ``"location"``.
    rank_tolerance : float, keyword-only
        Singular values below this fraction of the largest (columns scaled to unit length) are
        combinations the data cannot see.
    travel : mapping of str to (float, float), keyword-only
        The travel of some axes (metres, radians for rotary axes): the error functions are
        normalised over it, zero at its start, and the tables written over it. Default: the
        range of the axis' error table in the machine file joined with the positions the
        artefacts reach (those positions alone for an axis without a table).

    Returns
    -------
    Identification
        The identified machine, every unknown with its standard uncertainty, the covariance, the
        residuals per artefact and the combinations the data cannot separate.

    Raises
    ------
    AxiscalError
        An unknown model or fixed term, a bad artefact (naming its file and line), readings that do
        not fit the artefact's nominal geometry, or fewer readings than determined unknowns.
    """

    machine = as_machine(machine)
    if isinstance(artefacts, (str, Path, Artefact)) or not isinstance(artefacts, Sequence) or not artefacts:
        raise AxiscalError("artefacts must be a non-empty sequence of artefacts or paths of artefact files")
    artefacts = [a if isinstance(a, Artefact) else read_artefact(a) for a in artefacts]
    for artefact in artefacts:
        check_instance("artefact", artefact, Artefact)
    names = [a.name for a in artefacts]
    if len(set(names)) != len(names):
        raise AxiscalError(f"two artefacts share the name {next(n for n in names if names.count(n) > 1)!r}; name each one")
    model = parse_model(model)
    rank_tolerance = check_number("rank_tolerance", rank_tolerance, positive=True, high=1.0)
    if isinstance(fix, str) or not isinstance(fix, Sequence):
        raise AxiscalError(f"fix must be a sequence of term names, not {fix!r:.40}")

    spans = _travel(machine, artefacts, travel)
    parameters = ParameterSet(machine, model, spans, fix)
    problem = _Problem(parameters, artefacts, machine)
    theta0 = parameters.start()

    # the rank analysis on the nominal machine, where the model's degeneracies are exact
    nominal = problem.starting(np.zeros(len(theta0)))
    j0 = problem.jacobian(nominal)
    norms = np.linalg.norm(j0, axis=0)
    scale = np.where(norms > 0, 1.0 / np.where(norms > 0, norms, 1.0), 1.0)
    s, vt = _singular(j0 * scale)
    rank = int(np.sum(s > rank_tolerance * s[0]))
    row_space, null = vt[:rank].T, vt[rank:].T
    if rank == 0:
        raise AxiscalError("the artefacts determine nothing of this machine: every term is fixed or unseen")
    if problem.count <= rank:
        raise AxiscalError(f"{problem.count} readings cannot determine {rank} unknowns with a residual to spare; measure more")

    x0 = problem.starting(theta0)
    basis = scale[:, None] * row_space

    x, residual, covariance, condition, kind_std = _fit(problem, x0, basis, rank)

    all_names, std, undetermined = _undetermined(problem, null, scale, x, covariance)
    p = len(parameters.terms)
    residuals = {a.name: residual[r] for a, r in zip(artefacts, problem.r_slices)}
    return Identification(
        machine=parameters.identified_machine(x[:p]),
        model=model.text,
        names=all_names,
        terms=parameters.terms,
        values=x,
        std=std,
        covariance_all=covariance,
        residuals=residuals,
        kinds={a.name: a.kind for a in artefacts},
        undetermined=undetermined,
        rank=rank,
        condition=condition,
        residual_std=float(np.sqrt(float(residual @ residual) / (problem.count - rank))),
        kind_std=kind_std,
        fixed=parameters.fixed,
        spans=dict(parameters.spans),
    )


def identify_files(machine, artefacts, folder: str | Path, *, model: str = "poly:3", fix=()) -> tuple:
    """What ``axiscal identify`` does: identify from files and write the machine folder and the report.

    Parameters
    ----------
    machine : Machine, str or Path
        The machine or its TOML file (the starting guess).
    artefacts : sequence of str or Path
        Artefact files.
    folder : str or Path
        The output machine folder.
    model : str, keyword-only
        ``"poly:N"`` or ``"spline:K"``.
    fix : sequence of str, keyword-only
        Terms kept at their starting values.

    Returns
    -------
    (Identification, str)
        The result and its summary as text.
    """
    folder = check_path("folder", folder)
    result = identify(machine, list(artefacts), model=model, fix=tuple(fix))
    write_identification(result, folder)
    text = render_template("identification/identify.txt.j2", summary=result.summary(), folder=str(folder))
    return result, text
