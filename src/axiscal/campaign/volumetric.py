"""The volumetric section of a campaign: the model's error over the working volume.

The map is always drawn against the axis positions: a line per component for one axis, a colour
map of |e| for two axes, and for three axes a colour map in the plane of the first two axes at the
start, middle and end of the third.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.campaign.results import Figure, Plot
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_count, check_path
from axiscal.io.arguments import check_instance, type_name
from axiscal.model.machine import Machine, load_machine
from axiscal.model.volumetric import volumetric_map
from axiscal.units import MM, UM

__all__ = ["GRID_POINTS", "volumetric_section", "plot_volume"]

#: grid points along each linear axis of the report's map
GRID_POINTS = 21


def _axis_grid(machine: Machine, letter: str, count: int) -> np.ndarray:
    start, end = machine.travel_m(letter)
    return np.linspace(start, end, count)


def plot_volume(machine: Machine, path: str | Path, *, count: int = GRID_POINTS) -> dict[str, Any]:
    """Draw the volumetric error over the machine's travel and return its figures.

    Parameters
    ----------
    machine : Machine
    path : str or Path
        The figure to write (format from the suffix).
    count : int
        Grid points along each axis.

    Returns
    -------
    dict
        ``max_um``, ``rms_um``, ``max_at_mm`` (axis -> position) over the grid.

    Raises
    ------
    AxiscalError
        For a ``machine`` that is not a :class:`~axiscal.model.Machine`, a path without a figure
        suffix, a ``count`` below 2.
    """
    from axiscal.io.figures import check_figure_path, pyplot, save_figure

    check_instance("machine", machine, Machine)
    check_figure_path(path)
    count = check_count("count", count, minimum=2)
    letters = [letter for letter in machine.axes if letter in "XYZ"]
    axes = {letter: _axis_grid(machine, letter, count) for letter in letters}
    mesh = np.meshgrid(*axes.values(), indexing="ij")
    positions = {letter: grid.ravel() for letter, grid in zip(letters, mesh)}
    result = volumetric_map(machine, positions=positions)
    error = result.error_m
    magnitude = np.linalg.norm(error, axis=1) / UM
    plt = pyplot()
    if len(letters) == 1:
        (a,) = letters
        fig, ax = plt.subplots(figsize=(7.5, 3.6))
        x = positions[a] / MM
        for i, name in enumerate(("ex", "ey", "ez")):
            ax.plot(x, error[:, i] / UM, label=name)
        ax.plot(x, magnitude, "k", label="|e|")
        ax.set_xlabel(f"{a} / mm")
        ax.set_ylabel("error / um")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    else:
        a, b = letters[:2]
        if len(letters) == 2:
            slices = [(None, np.ones(magnitude.size, bool))]
        else:
            c = letters[2]
            values = axes[c]
            picks = (values[0], values[values.size // 2], values[-1])
            slices = [(f"{c} = {v / MM:g} mm", np.isclose(positions[c], v)) for v in picks]
        fig, grid_axes = plt.subplots(1, len(slices), figsize=(4.2 * len(slices) + 1.2, 4.0), squeeze=False,
                                      layout="constrained")
        lo, hi = float(magnitude.min()), float(magnitude.max())
        for ax, (label, keep) in zip(grid_axes[0], slices):
            qa, qb = positions[a][keep] / MM, positions[b][keep] / MM
            ua, ub = np.unique(qa), np.unique(qb)
            order = np.lexsort((qb, qa))
            image = magnitude[keep][order].reshape(ua.size, ub.size)
            mesh_plot = ax.pcolormesh(ua, ub, image.T, shading="auto", cmap="viridis", vmin=lo, vmax=hi)
            ax.set_xlabel(f"{a} / mm")
            if ax is grid_axes[0][0]:
                ax.set_ylabel(f"{b} / mm")
            ax.set_aspect("equal")
            if label:
                ax.set_title(label, fontsize=10)
        fig.colorbar(mesh_plot, ax=grid_axes[0].tolist(), label="|e| / um")
    fig.suptitle(f"Volumetric error: {machine.name or machine.chain}", fontsize=11)
    save_figure(fig, path)
    return {
        "max_um": result.max_m / UM,
        "rms_um": result.rms_m / UM,
        "max_at_mm": {k: v / MM for k, v in result.max_at_m.items()},
    }


def volumetric_section(model: str | Path, svg_of: Callable[[Callable[[Path], Any]], str]) -> dict[str, Any]:
    """The report's volumetric section for a machine description.

    Parameters
    ----------
    model : str or Path
        The machine description (TOML).
    svg_of : callable
        Turns a plot-writing function into SVG text (:func:`axiscal.campaign.runner.svg_of`).

    Returns
    -------
    dict
        ``method``, ``table`` (list of Figure), ``plots`` (list of Plot) and ``figures`` (for results.json).

    Raises
    ------
    AxiscalError
        For a bad machine description (naming the file and line) or an ``svg_of`` that is not callable.
    """
    model = check_path("model", model)
    if not callable(svg_of):
        raise AxiscalError(f"svg_of must be a function that turns a plot into SVG text, not {type_name(svg_of)}")
    machine = load_machine(model)
    holder: list[dict[str, Any]] = []
    svg = svg_of(lambda p: holder.append(plot_volume(machine, p)))
    figures = holder[0]
    where = ", ".join(f"{k} = {v:g}" for k, v in figures["max_at_mm"].items())
    return {
        "method": f"HTM model of {machine.name or machine.chain} (chain {machine.chain}), {GRID_POINTS} points along each axis",
        "table": [Figure("largest |e|", figures["max_um"], "um"), Figure("rms |e|", figures["rms_um"], "um"),
                  Figure("largest |e| at", where, "mm")],
        "plots": [Plot("Volumetric error |e| against the axis positions", svg)],
        "figures": figures,
    }
