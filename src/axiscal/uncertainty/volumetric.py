"""The volumetric error map with its uncertainty, by Monte Carlo through the HTM model (JCGM 101:2008, GUM Supplement 1).

Every error motion of every axis is drawn around its table value with the standard uncertainty of
its ``<name>_u`` column (e.g. ``EXX_um_u``, same unit as ``EXX_um``; independent normal draws per
table row, carried to the points by the table's own interpolation), every squareness term around
its value with its ``<term>_u`` key (``EC0Y_arcsec_u``), and each draw goes through
:meth:`axiscal.model.Machine.volumetric_error` with the error motions given per point, for all draws
and points in one vectorised call per chunk of draws. The squareness draws enter through the
model's sensitivity to each term (central differences of the model; what is left out is of
order u^2 * travel, 2e-11 m for a squareness known to 1 arcsec over 1 m of travel). The output per point is the error of the nominal model and the probabilistically
symmetric 95 % coverage interval of each component.

Chunks of draws get their own seeds from one :class:`numpy.random.SeedSequence`, so the result
for a seed does not depend on where the chunks run: :func:`volumetric_monte_carlo` runs them here,
or on a Dask cluster with ``scheduler=`` (a ``dask.distributed`` Client, a scheduler address, or
``"local"`` for a LocalCluster).
"""

from __future__ import annotations

import csv
import io
import tempfile
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from axiscal.conventions import AXIS_INDEX, SQUARENESS_TERMS, component_names
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_count, check_mapping, check_number, check_path
from axiscal.io.atomic import write_text
from axiscal.io.arguments import check_instance, type_name
from axiscal.io.jsonio import write_sidecar
from axiscal.io.schema import confined_path
from axiscal.io.tabular import read_csv, read_text, read_toml, write_csv
from axiscal.model.machine import Machine, machine_from_dict
from axiscal.io.schema import TomlLines
from axiscal.uncertainty.montecarlo import _probability, _whole_draws, coverage_interval
from axiscal.units import MM, UM, angle_factor, length_factor

__all__ = [
    "MAX_DRAW_POINTS",
    "SCHEDULER_TIMEOUT_S",
    "MachineUncertainty",
    "VolumetricUncertainty",
    "load_machine_uncertainty",
    "volumetric_monte_carlo",
    "write_volumetric_uncertainty",
    "volumetric_uncertainty_columns",
]

_SUFFIX = "_u"
#: the most draws x points one run holds in memory (16 bytes each: three components and |e|, float32)
MAX_DRAW_POINTS = 10**8
#: seconds to wait for a Dask scheduler given by address before giving up
SCHEDULER_TIMEOUT_S = 10.0
_SQUARENESS_STEP_RAD = 1e-6


@dataclass(frozen=True)
class MachineUncertainty:
    """Standard uncertainties of a machine's error motions and squareness terms, SI.

    Attributes
    ----------
    tables : dict of str to ndarray, shape (6, rows)
        Per axis letter, the standard uncertainty of each error motion at each row of its table
        (rows tx, ty, tz in m; ea, eb, ec in rad); zero where no ``_u`` column was given.
    squareness_rad : dict of str to float
        Standard uncertainty of each squareness term (EC0Y, EB0Z, EA0Z), rad.

    Raises
    ------
    AxiscalError
        For tables that are not a mapping of axis letters to 2-D arrays of finite, non-
        negative numbers, or squareness terms other than EC0Y, EB0Z, EA0Z with non-negative
        values.
    """

    tables: dict[str, np.ndarray]
    squareness_rad: dict[str, float]

    def __post_init__(self) -> None:
        check_mapping("tables", self.tables, what="a mapping of axis letters to arrays of standard uncertainties")
        for letter, u in self.tables.items():
            u = check_array(f"tables['{letter}']", u, ndim=2, unit="")
            if np.any(u < 0):
                raise AxiscalError(f"tables['{letter}'] must hold non-negative standard uncertainties")
        check_mapping("squareness_rad", self.squareness_rad, what="a mapping of squareness terms to standard uncertainties in radians")
        for term, u in self.squareness_rad.items():
            if not isinstance(term, str) or term not in SQUARENESS_TERMS:
                raise AxiscalError(f"squareness_rad: unknown squareness term {term!r}; use one of {', '.join(SQUARENESS_TERMS)}")
            check_number(f"squareness_rad['{term}']", u, unit="radians", nonnegative=True)


@dataclass(frozen=True)
class VolumetricUncertainty:
    """The volumetric error at each point and its coverage interval from Monte Carlo, metres.

    Attributes
    ----------
    error : ndarray, shape (N, 3)
        Volumetric error of the nominal model (the table values).
    mean, std : ndarray, shape (N, 3)
        Mean and standard deviation of the draws.
    low, high : ndarray, shape (N, 3)
        Ends of the probabilistically symmetric coverage interval per component.
    draws : int
        Number of Monte Carlo draws.
    probability : float
        Coverage probability of the intervals.
    magnitude_std : ndarray, shape (N,)
        Standard deviation of the draws of the error's length |e|.
    magnitude_low, magnitude_high : ndarray, shape (N,)
        Ends of the coverage interval of |e|.
    """

    error: np.ndarray
    mean: np.ndarray
    std: np.ndarray
    low: np.ndarray
    high: np.ndarray
    draws: int
    probability: float
    magnitude_std: np.ndarray
    magnitude_low: np.ndarray
    magnitude_high: np.ndarray

    @property
    def magnitude(self) -> np.ndarray:
        """Length |e| of the nominal model's error at each point, shape (N,), metres."""
        return np.linalg.norm(self.error, axis=1)


def _split_uncertainty_columns(path: Path, letter: str):
    """The CSV text without its ``_u`` columns, the table, and {u column: (row, factor to SI)}."""
    table = read_csv(path, min_rows=2)
    names = component_names(letter)
    rows: dict[str, tuple[int, float]] = {}
    for column in (c for c in table.header if c.endswith(_SUFFIX)):
        value = column[: -len(_SUFFIX)]
        stem, _, unit = value.rpartition("_")
        if value not in table.header or stem not in names:
            raise AxiscalError(f"column '{column}' has no error column '{value}' beside it", path=path, line=table.header_line)
        row = names.index(stem)
        try:
            factor = length_factor(unit, what=value) if row < 3 else angle_factor(unit, what=value)
        except AxiscalError as exc:
            raise exc.located(path=path, line=table.header_line) from None
        rows[column] = (row, factor)
    keep = [i for i, c in enumerate(table.header) if not c.endswith(_SUFFIX)]
    out = io.StringIO()
    for line in read_text(path).splitlines():  # every line kept, so errors keep their line numbers
        if not line.strip() or line.lstrip().startswith("#"):
            out.write(line + "\n")
            continue
        cells = next(csv.reader([line]))
        out.write(",".join(cells[i] for i in keep if i < len(cells)) + "\n")
    return out.getvalue(), table, rows


def load_machine_uncertainty(path: str | Path) -> tuple[Machine, MachineUncertainty]:
    """Read a machine description whose error tables and squareness carry standard uncertainties.

    The files are those of :func:`axiscal.model.load_machine` (docs/formats.md) with, optionally, a
    ``<column>_u`` column beside any error column of a table (``EXX_um_u``: the standard
    uncertainty of ``EXX_um`` in the same unit) and a ``<key>_u`` key beside any squareness key
    (``EC0Y_arcsec_u``).

    Parameters
    ----------
    path : str or Path
        The machine TOML file.

    Returns
    -------
    (Machine, MachineUncertainty)
        The model of the table values and the uncertainties.

    Raises
    ------
    AxiscalError
        What :func:`axiscal.model.load_machine` raises, naming the original file; a ``_u`` column or
        key without its value, a negative or non-finite uncertainty.
    """
    path = check_path("path", path)
    data = read_toml(path)
    data = {k: (dict(v) if isinstance(v, Mapping) else v) for k, v in data.items()}
    squareness = data.get("squareness", {})
    squareness_u: dict[str, float] = {}
    if isinstance(squareness, dict):
        for key in [k for k in squareness if k.endswith(_SUFFIX)]:
            value_key = key[: -len(_SUFFIX)]
            stem, _, unit = value_key.rpartition("_")
            where = {"path": path, "line": TomlLines(read_text(path)).of("squareness", key=key)}
            if value_key not in squareness or stem not in SQUARENESS_TERMS:
                raise AxiscalError(f"[squareness] '{key}' has no squareness term '{value_key}' beside it", **where)
            u = squareness.pop(key)
            if not isinstance(u, (int, float)) or isinstance(u, bool) or not np.isfinite(u) or u < 0:
                raise AxiscalError(f"[squareness] {key} must be a non-negative number", **where)
            try:
                squareness_u[stem] = float(u) * angle_factor(unit, what=key)
            except AxiscalError as exc:
                raise exc.located(**where) from None
    axes = data.get("axes", {})
    originals: dict[str, Path] = {}
    u_columns: dict[str, tuple] = {}
    with tempfile.TemporaryDirectory(prefix="axiscal-u-") as folder:
        if isinstance(axes, dict):
            axes = {k: (dict(v) if isinstance(v, Mapping) else v) for k, v in axes.items()}
            data["axes"] = axes
            for letter, section in axes.items():
                if not isinstance(section, dict) or "errors" not in section:
                    continue
                try:
                    original = confined_path(path.parent, str(section["errors"]))
                except AxiscalError as exc:
                    raise exc.located(path=path) from None
                if letter not in AXIS_INDEX:
                    continue  # machine_from_dict names the stray section
                text, table, rows = _split_uncertainty_columns(original, letter)
                copy = Path(folder) / f"{letter}_{original.name}"
                copy.write_text(text)
                originals[str(copy)] = original
                u_columns[letter] = (table, rows)
                section["errors"] = copy.name  # the copies lie together in the temporary folder
        try:
            machine = machine_from_dict(data, base_dir=Path(folder), source=str(path))
        except AxiscalError as exc:
            for copy, original in originals.items():
                if exc.path == copy:
                    raise AxiscalError(exc.message, path=original, line=exc.line) from None
            raise
    tables: dict[str, np.ndarray] = {}
    for letter in machine.letters:
        table = machine.table(letter)
        u = np.zeros_like(table.values)
        csv_table, rows = u_columns.get(letter, (None, {}))
        for u_column, (row, factor) in rows.items():
            values = csv_table.numeric(u_column) * factor
            bad = np.flatnonzero(values < 0)
            if bad.size:
                raise AxiscalError(f"column '{u_column}': a standard uncertainty must not be negative",
                                   path=csv_table.path, line=csv_table.lines[bad[0]])
            u[row] = values
        u.setflags(write=False)
        tables[letter] = u
    return machine, MachineUncertainty(tables, squareness_u)


def _weights(machine: Machine, letter: str, q: np.ndarray):
    """How the table of ``letter`` interpolates at ``q``: values @ W = evaluate(q).

    Linear tables: ``(index, fraction)``, each point between rows index and index + 1 (two
    non-zero weights per point, gathered instead of multiplied); cubic: the dense (rows, N) W.
    """
    table = machine.table(letter)
    table.check_range(q)
    q = np.clip(q, table.start_m, table.end_m)
    rows = table.position_m.size
    if table.interpolation == "cubic":
        from scipy.interpolate import CubicSpline

        return CubicSpline(table.position_m, np.eye(rows), axis=1)(q)
    index = np.clip(np.searchsorted(table.position_m, q, side="right") - 1, 0, rows - 2)
    fraction = (q - table.position_m[index]) / (table.position_m[index + 1] - table.position_m[index])
    return index, fraction


def _interpolate(delta: np.ndarray, weights) -> np.ndarray:
    """Row perturbations (draws, 6, rows) carried to the points: (draws, 6, N)."""
    if isinstance(weights, tuple):
        index, fraction = weights
        lower = delta[..., index]
        return lower + (delta[..., index + 1] - lower) * fraction
    return delta @ weights


def _chunk(machine: Machine, setup: dict, seed: np.random.SeedSequence, draws: int) -> np.ndarray:
    """The volumetric error of ``draws`` draws at the setup's points: (draws, N, 3), float32."""
    rng = np.random.default_rng(seed)
    positions, n = setup["positions"], setup["n"]
    tiled = {k: np.tile(v, draws) for k, v in positions.items()}
    errors = {}
    for letter in machine.letters:
        mean = setup["mean"][letter]  # (6, N)
        u = setup["u"][letter]  # (6, rows)
        if np.any(u):
            delta = rng.standard_normal((draws,) + u.shape) * u
            perturbed = mean[None] + _interpolate(delta, setup["weights"][letter])  # (draws, 6, N)
        else:
            perturbed = np.broadcast_to(mean[None], (draws,) + mean.shape)
        errors[letter] = np.ascontiguousarray(perturbed.transpose(1, 0, 2).reshape(6, draws * n))
    out = machine.volumetric_error(tiled, errors=errors).reshape(draws, n, 3)
    for term, (u, sensitivity) in setup["squareness"].items():
        out += rng.normal(0.0, u, draws)[:, None, None] * sensitivity[None]
    return out.astype(np.float32)


def volumetric_monte_carlo(
    machine: Machine,
    uncertainty: MachineUncertainty,
    positions: Mapping[str, np.ndarray],
    draws: int,
    *,
    seed: int = 0,
    probability: float = 0.95,
    chunk_draws: int = 250,
    scheduler=None,
    timeout_s: float = SCHEDULER_TIMEOUT_S,
    progress=None,
) -> VolumetricUncertainty:
    """Propagate the uncertainties of the error motions and squareness to the volumetric error.

    Parameters
    ----------
    machine : Machine
        The model (table values), e.g. from :func:`load_machine_uncertainty`.
    uncertainty : MachineUncertainty
        Standard uncertainties of its error motions and squareness terms.
    positions : mapping of str to ndarray, shape (N,)
        Axis positions of the points, metres.
    draws : int
        Number of Monte Carlo draws M.
    seed : int, keyword-only
        Seed; the same seed gives the same result wherever the chunks run.
    probability : float, keyword-only
        Coverage probability (default 0.95).
    chunk_draws : int, keyword-only
        Draws per chunk (memory: about 150 bytes per draw and point).
    scheduler : optional, keyword-only
        None: run here. ``"local"``: a ``dask.distributed`` LocalCluster; an address string
        (``"tcp://host:8786"``) or a ``dask.distributed.Client``: that cluster. Needs the optional
        extra ``axiscal[dask]``.
    timeout_s : float, keyword-only
        Seconds to wait for a scheduler given by address (default :data:`SCHEDULER_TIMEOUT_S`).
    progress : callable, optional, keyword-only
        Called as ``progress(done, total)`` with the number of draws done, once before the first
        chunk and after each (the command line draws a progress bar with it).

    Returns
    -------
    VolumetricUncertainty

    Raises
    ------
    AxiscalError
        Positions outside a table, uncertainties that do not fit the tables, a number of draws
        that is not a whole number, too few for the coverage probability or more than
        :data:`MAX_DRAW_POINTS` draw-points, a scheduler given without dask installed or one
        that does not answer within ``timeout_s``.
    """
    check_instance("machine", machine, Machine)
    check_instance("uncertainty", uncertainty, MachineUncertainty)
    check_mapping("positions", positions, what="a mapping of axis letters to positions in metres")
    draws = _whole_draws(draws, "draws (the number of Monte Carlo draws)")
    chunk_draws = _whole_draws(chunk_draws, "chunk_draws")
    probability = _probability(probability)
    seed = check_count("seed", seed, minimum=0)
    if scheduler is not None and not isinstance(scheduler, str) and not callable(getattr(scheduler, "submit", None)):
        raise AxiscalError(f"scheduler must be None, 'local', a scheduler address or a dask.distributed.Client, not {type_name(scheduler)}")
    if progress is not None and not callable(progress):
        raise AxiscalError(f"progress must be a function of (done, total), not {type_name(progress)}")
    if draws < max(2.0, 1.0 / (1.0 - probability)):  # two at least: the standard deviation needs them
        raise AxiscalError(f"draws: {draws} are too few for a {probability:.0%} coverage interval;"
                           f" use at least {max(2, int(np.ceil(1.0 / (1.0 - probability))))}")
    error = machine.volumetric_error(positions)  # also checks the positions
    q = {k: np.atleast_1d(np.asarray(positions[k], dtype=float)) for k in machine.letters}
    n = error.shape[0]
    if draws * n > MAX_DRAW_POINTS:
        raise AxiscalError(f"{draws:,d} draws x {n:,d} points exceed the {MAX_DRAW_POINTS:.0e} draw-points one run"
                           " holds in memory; use fewer draws or points")
    setup: dict = {"positions": q, "n": n, "mean": {}, "u": {}, "weights": {}, "squareness": {}}
    for letter in machine.letters:
        table = machine.table(letter)
        u = np.asarray(uncertainty.tables.get(letter, np.zeros_like(table.values)), dtype=float)
        if u.shape != table.values.shape or not np.all(np.isfinite(u)) or np.any(u < 0):
            raise AxiscalError(f"axis {letter}: uncertainties must be non-negative numbers of shape {table.values.shape}")
        setup["mean"][letter] = table.evaluate(q[letter])
        setup["u"][letter] = u
        setup["weights"][letter] = _weights(machine, letter, q[letter]) if np.any(u) else None
    for term, u in uncertainty.squareness_rad.items():
        if term not in SQUARENESS_TERMS or not np.isfinite(u) or u < 0:
            raise AxiscalError(f"squareness uncertainty {term}: use EC0Y, EB0Z, EA0Z with a non-negative value")
        if u == 0:
            continue
        shifted = []
        for sign in (1.0, -1.0):
            terms = dict(machine.squareness_rad)
            terms[term] = terms.get(term, 0.0) + sign * _SQUARENESS_STEP_RAD
            shifted.append(replace(machine, squareness_rad=terms).volumetric_error(q))
        setup["squareness"][term] = (float(u), (shifted[0] - shifted[1]) / (2 * _SQUARENESS_STEP_RAD))
    sizes = [min(chunk_draws, draws - start) for start in range(0, draws, chunk_draws)]
    seeds = np.random.SeedSequence(seed).spawn(len(sizes))
    report = _Progress(progress, draws)
    if scheduler is None:
        parts = [report.after(_chunk(machine, setup, s, m)) for s, m in zip(seeds, sizes)]
    else:
        parts = _run_on_dask(scheduler, machine, setup, seeds, sizes, timeout_s, report)
    samples = np.concatenate(parts, axis=0)
    low, high = coverage_interval(samples, probability)
    length = np.linalg.norm(samples, axis=2)
    length_low, length_high = coverage_interval(length, probability)
    return VolumetricUncertainty(
        error=error,
        mean=samples.mean(axis=0, dtype=float),
        std=samples.std(axis=0, ddof=1, dtype=float),
        low=np.asarray(low, dtype=float),
        high=np.asarray(high, dtype=float),
        draws=draws,
        probability=probability,
        magnitude_std=length.std(axis=0, ddof=1, dtype=float),
        magnitude_low=np.asarray(length_low, dtype=float),
        magnitude_high=np.asarray(length_high, dtype=float),
    )


class _Progress:
    """Counts the draws done and tells the caller's ``progress(done, total)``."""

    def __init__(self, callback, total: int):
        self.callback, self.total, self.done = callback, total, 0
        if callback is not None:
            callback(0, total)

    def after(self, part: np.ndarray) -> np.ndarray:
        self.done += part.shape[0]
        if self.callback is not None:
            self.callback(self.done, self.total)
        return part


def _run_on_dask(scheduler, machine, setup, seeds, sizes, timeout_s, report: _Progress) -> list[np.ndarray]:
    try:
        from dask.distributed import Client, LocalCluster, as_completed
    except ImportError:
        raise AxiscalError("running on a cluster needs dask: pip install 'axiscal[dask]'") from None
    own = None
    if isinstance(scheduler, str):
        if scheduler == "local":
            own = LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None)
            client = Client(own)
        else:
            if not (isinstance(timeout_s, (int, float)) and np.isfinite(timeout_s) and timeout_s > 0):
                raise AxiscalError(f"timeout_s must be a positive number of seconds, got {timeout_s!r}")
            try:
                client = Client(scheduler, timeout=float(timeout_s))
            except (OSError, TimeoutError) as exc:
                raise AxiscalError(f"no dask scheduler answered at '{scheduler}' within {timeout_s:g} s"
                                   f" ({' '.join(str(exc).split()) or type(exc).__name__})") from None
            except Exception as exc:  # not an address, or something else listening there
                raise AxiscalError(f"cannot use '{scheduler}' as a dask scheduler: {type(exc).__name__}"
                                   f" {' '.join(str(exc).split())[:200]}".rstrip()) from None
    else:
        client = scheduler
    try:
        machine_f, setup_f = client.scatter([machine, setup], broadcast=True)
        futures = [client.submit(_chunk, machine_f, setup_f, s, m, pure=False) for s, m in zip(seeds, sizes)]
        order = {future.key: i for i, future in enumerate(futures)}
        parts: list = [None] * len(futures)
        for future in as_completed(futures):
            parts[order[future.key]] = report.after(future.result())
        return parts
    finally:
        if own is not None:
            client.close()
            own.close()


def write_volumetric_uncertainty(
    path: str | Path, positions: Mapping[str, np.ndarray], result: VolumetricUncertainty, *, sources=(), **metadata
) -> Path:
    """Write the volumetric map with its coverage intervals as a plain CSV and its JSON sidecar.

    Columns: ``<axis>_mm`` for each axis of ``positions``, then for each of ex, ey, ez and the
    length e = |e|: ``e?_um`` (the model's error), ``e?_u_um`` (standard deviation of the draws),
    ``e?_low_um`` and ``e?_high_um`` (the coverage interval). The sidecar (``path`` with ``.json``)
    holds the number of draws and the coverage probability. The write is atomic.

    Parameters
    ----------
    path : str or Path
        The CSV to write.
    positions : mapping of str to ndarray, shape (N,)
        The points' axis positions, metres (as given to :func:`volumetric_monte_carlo`).
    result : VolumetricUncertainty
    sources : sequence of paths, keyword-only
        Input files, for the sidecar.
    **metadata
        More for the sidecar (the seed, the machine's name ...).

    Returns
    -------
    Path
        The CSV written.

    Raises
    ------
    AxiscalError
        Positions that do not match the result's points, or a file that cannot be written.
    """
    path = check_path("path", path)
    if isinstance(sources, (str, bytes, Path)) or not isinstance(sources, Iterable):
        raise AxiscalError(f"sources must be a sequence of file names, not {sources!r}")
    written = write_text(path, write_csv(None, volumetric_uncertainty_columns(positions, result), fmt="{:.6f}"))
    write_sidecar(written, kind="volumetric uncertainty", sources=list(sources), method="Monte Carlo (JCGM 101)",
                  frame="tool point relative to the workpiece, workpiece frame; actual minus nominal",
                  draws=result.draws, probability=result.probability, **metadata)
    return written


def volumetric_uncertainty_columns(positions: Mapping[str, np.ndarray], result: VolumetricUncertainty) -> dict[str, np.ndarray]:
    """The columns of :func:`write_volumetric_uncertainty`, in mm and um.

    Parameters
    ----------
    positions : mapping of str to ndarray, shape (N,)
        The points' axis positions, metres.
    result : VolumetricUncertainty
        The Monte Carlo result at those points.

    Returns
    -------
    dict of str to ndarray, shape (N,)
        ``<axis>_mm``, then ``e?_um``, ``e?_u_um``, ``e?_low_um``, ``e?_high_um`` for ex, ey, ez
        and the length e.

    Raises
    ------
    AxiscalError
        Positions that do not match the result's points or are not finite numbers; a result that
        is not a :class:`VolumetricUncertainty`.
    """
    check_instance("result", result, VolumetricUncertainty)
    check_mapping("positions", positions, what="a mapping of axis letters to positions in metres")
    n = result.error.shape[0]
    columns: dict[str, np.ndarray] = {}
    for letter, q in positions.items():
        q = np.atleast_1d(check_array(f"positions['{letter}'] (metres)", q, unit=""))
        if q.shape != (n,):
            raise AxiscalError(f"positions of axis {letter}: {q.size} values for {n} points")
        columns[f"{letter.lower()}_mm"] = q / MM  # spelled as `axiscal volumetric` writes it
    for i, name in enumerate(("ex", "ey", "ez")):
        columns[f"{name}_um"] = result.error[:, i] / UM
        columns[f"{name}_u_um"] = result.std[:, i] / UM
        columns[f"{name}_low_um"] = result.low[:, i] / UM
        columns[f"{name}_high_um"] = result.high[:, i] / UM
    columns["e_um"] = result.magnitude / UM
    columns["e_u_um"] = result.magnitude_std / UM
    columns["e_low_um"] = result.magnitude_low / UM
    columns["e_high_um"] = result.magnitude_high / UM
    return columns
