"""The volumetric error map with its uncertainty as one job: the machine file with ``_u`` columns, the points, Monte Carlo (JCGM 101:2008).

:func:`volumetric_uncertainty_map` is what ``axiscal uncertainty volumetric`` runs: it reads the
machine description with its standard uncertainties (:func:`load_machine_uncertainty`), takes
the points from a points file, a grid or arrays exactly as ``axiscal volumetric`` does
(:func:`axiscal.model.volumetric_map`), propagates the uncertainties by
:func:`volumetric_monte_carlo` (here or on a Dask cluster) and returns the map, which writes its
plain CSV with a sidecar, its plot and its JSON summary.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.figures import check_figure_path
from axiscal.io.arguments import type_name
from axiscal.io.tabular import write_csv
from axiscal.model.machine import Machine
from axiscal.model.volumetric import volumetric_map
from axiscal.uncertainty.volumetric import (
    SCHEDULER_TIMEOUT_S,
    MachineUncertainty,
    VolumetricUncertainty,
    load_machine_uncertainty,
    volumetric_monte_carlo,
    volumetric_uncertainty_columns,
    write_volumetric_uncertainty,
)
from axiscal.units import MM, UM

__all__ = ["VolumetricUncertaintyMap", "volumetric_uncertainty_map"]


@dataclass(frozen=True)
class VolumetricUncertaintyMap:
    """The volumetric error at a set of points with its Monte Carlo coverage intervals, SI.

    Attributes
    ----------
    positions_m : dict of str to ndarray, shape (N,)
        Position of every axis, in the machine's chain order, metres.
    result : VolumetricUncertainty
        The model's error, the draws' standard deviations and the coverage intervals, metres.
    name : str
        The machine's name (or chain), for titles.
    seed : int
        The seed of the draws (the same seed gives the same map, here or on a cluster).
    sources : tuple of str
        Files the map was computed from.
    """

    positions_m: dict[str, np.ndarray]
    result: VolumetricUncertainty
    name: str = ""
    seed: int = 0
    sources: tuple[str, ...] = field(default=())

    def columns(self) -> dict[str, np.ndarray]:
        """The CSV columns in mm and um (:func:`volumetric_uncertainty_columns`).

        Returns
        -------
        dict of str to ndarray, shape (N,)
        """
        return volumetric_uncertainty_columns(self.positions_m, self.result)

    def csv(self) -> str:
        """The map as plain CSV text (header first, one line per point).

        Returns
        -------
        str
        """
        return write_csv(None, self.columns(), fmt="{:.6f}")

    def write_csv(self, path: str | Path) -> Path:
        """Write the map as a plain CSV and its JSON sidecar, atomically.

        Parameters
        ----------
        path : str or Path
            The CSV; the sidecar is the same name ending in ``.json``.

        Returns
        -------
        Path
            The CSV written.

        Raises
        ------
        AxiscalError
            A file that cannot be written.
        """
        return write_volumetric_uncertainty(path, self.positions_m, self.result, sources=self.sources,
                                            machine=self.name, seed=self.seed)

    def summary(self) -> dict[str, Any]:
        """The JSON object of ``axiscal uncertainty volumetric --json``, lengths in um.

        Returns
        -------
        dict
            ``machine``, ``points``, ``draws``, ``seed``, ``probability``, ``unit`` ("um");
            ``max_e_um`` (the largest |e| of the model) with ``max_e_at_mm`` and its coverage
            interval ``max_e_interval_um`` [low, high]; ``max_e_high_um`` (the largest upper end
            of the interval of |e|) with ``max_e_high_at_mm``; ``max_half_width_um`` (the widest
            interval of |e|, half its width).
        """
        r = self.result
        magnitude = r.magnitude
        worst, highest = int(np.argmax(magnitude)), int(np.argmax(r.magnitude_high))
        at = {index: {k: float(q[index] / MM) for k, q in self.positions_m.items()} for index in (worst, highest)}
        return {
            "machine": self.name,
            "points": int(magnitude.size),
            "draws": r.draws,
            "seed": self.seed,
            "probability": r.probability,
            "unit": "um",
            "max_e_um": float(magnitude[worst] / UM),
            "max_e_at_mm": at[worst],
            "max_e_interval_um": [float(r.magnitude_low[worst] / UM), float(r.magnitude_high[worst] / UM)],
            "max_e_high_um": float(r.magnitude_high[highest] / UM),
            "max_e_high_at_mm": at[highest],
            "max_half_width_um": float(np.max(r.magnitude_high - r.magnitude_low) / 2.0 / UM),
        }

    def plot(self, path: str | Path, *, title: str | None = None) -> Path:
        """Plot |e| and its coverage interval against the axis positions (:func:`plot_volumetric_uncertainty`).

        Parameters
        ----------
        path : str or Path
            Figure file; the format follows the suffix.
        title : str, optional
            Default: ``"Volumetric error with its 95 % interval: <machine>"``.

        Returns
        -------
        Path
            ``path``.

        Raises
        ------
        AxiscalError
            A suffix that is not a figure format, a file that cannot be written.
        """
        from axiscal.uncertainty.plot import plot_volumetric_uncertainty

        if title is None:
            title = f"Volumetric error with its {self.result.probability:.0%} interval: {self.name}"
        plot_volumetric_uncertainty(self.positions_m, self.result, path, title=title)
        return Path(path)


def volumetric_uncertainty_map(
    machine: str | Path | tuple[Machine, MachineUncertainty],
    *,
    points: str | Path | None = None,
    grid: str | None = None,
    positions: Mapping[str, np.ndarray] | None = None,
    draws: int = 10_000,
    seed: int = 0,
    probability: float = 0.95,
    scheduler=None,
    timeout_s: float = SCHEDULER_TIMEOUT_S,
    progress: Callable[[int, int], None] | None = None,
    output: str | Path | None = None,
    plot_path: str | Path | None = None,
) -> VolumetricUncertaintyMap:
    """The volumetric error at the given points with its uncertainty, by Monte Carlo.

    Give exactly one of ``points``, ``grid`` or ``positions`` (as :func:`axiscal.model.volumetric_map`).

    Parameters
    ----------
    machine : str, Path or (Machine, MachineUncertainty)
        The machine description (TOML) whose error tables may carry ``<column>_u`` columns and
        whose squareness may carry ``<key>_u`` keys (:func:`load_machine_uncertainty`), or the
        model and its uncertainties.
    points : str or Path, optional, keyword-only
        CSV with one ``<axis>_mm`` column per axis of the chain.
    grid : str, optional, keyword-only
        Grid of positions in mm, ``"X=0:600:100,Y=0:400:100,Z=0:300:100"`` (ends inclusive).
    positions : mapping of str to ndarray, shape (N,), optional, keyword-only
        Position of every axis of the chain, metres.
    draws : int, keyword-only
        Number of Monte Carlo draws (default 10 000).
    seed : int, keyword-only
        Seed of the draws.
    probability : float, keyword-only
        Coverage probability (default 0.95).
    scheduler : optional, keyword-only
        None (here), ``"local"`` (a 2-worker Dask LocalCluster), a scheduler address
        (``"tcp://host:8786"``) or a ``dask.distributed.Client``.
    timeout_s : float, keyword-only
        Seconds to wait for a scheduler given by address.
    progress : callable, optional, keyword-only
        ``progress(done, total)`` in draws, as the chunks finish.
    output : str or Path, optional, keyword-only
        Also write the map there (:meth:`VolumetricUncertaintyMap.write_csv`).
    plot_path : str or Path, optional, keyword-only
        Also plot it there (:meth:`VolumetricUncertaintyMap.plot`); the suffix is checked before
        the draws start.

    Returns
    -------
    VolumetricUncertaintyMap

    Raises
    ------
    AxiscalError
        A bad machine file or ``_u`` column (naming the file and line), not exactly one source of
        points, a point outside a table, a bad number of draws, a scheduler that does not answer,
        a plot suffix that is not a figure format, a file that cannot be written.

    Examples
    --------
    >>> machine = "examples/xfyz_machine_u/machine.toml"
    >>> result = volumetric_uncertainty_map(machine, grid="X=0:600:300,Y=200,Z=100", draws=200, seed=1)
    >>> result.result.magnitude_high.shape
    (3,)
    """
    if sum(source is not None for source in (points, grid, positions)) != 1:
        raise AxiscalError("give exactly one of points, grid or positions")
    if plot_path is not None:
        check_figure_path(plot_path)
    if isinstance(machine, (str, Path)):
        model, uncertainty = load_machine_uncertainty(machine)
        sources: list[str] = [str(machine)]
    elif isinstance(machine, tuple) and len(machine) == 2 and isinstance(machine[0], Machine) \
            and isinstance(machine[1], MachineUncertainty):
        model, uncertainty = machine
        sources = []
    else:
        raise AxiscalError(f"machine must be a machine file or a (Machine, MachineUncertainty) pair, not {type_name(machine)}")
    nominal = volumetric_map(model, points=points, grid=grid, positions=positions)
    if points is not None:
        sources.append(str(points))
    result = volumetric_monte_carlo(model, uncertainty, nominal.positions_m, draws, seed=seed, probability=probability,
                                    scheduler=scheduler, timeout_s=timeout_s, progress=progress)
    out = VolumetricUncertaintyMap(nominal.positions_m, result, name=nominal.name, seed=int(seed), sources=tuple(sources))
    if output is not None:
        out.write_csv(output)
    if plot_path is not None:
        out.plot(plot_path)
    return out
