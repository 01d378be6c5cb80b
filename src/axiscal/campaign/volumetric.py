"""The volumetric section of a campaign: the model's error over the working volume, and its change.

A campaign measured with a controller's pitch compensation loaded (``[machine] compensation``, an
as-left campaign) draws the model of the compensated machine (:func:`compensated_machine`): the
controller moves each compensated axis to ``m = c + correction(c)`` when ``c`` is commanded, so
what is left at ``c`` is ``e(m) + correction(c)`` (the relation
:mod:`axiscal.compensation.readback` states and the virtual machine simulates).

The map is always drawn against the axis positions: a line per component for one axis, a colour
map of |e| for two axes, and for three axes a colour map in the plane of the first two axes at the
start, middle and end of the third. Against another campaign's map on the same grid, the change
|e| now - |e| before is drawn the same way on a diverging colour scale centred on zero.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.campaign.results import Figure, Plot
from axiscal.compensation.readback import CONTROLLERS, ControllerCompensation, read_compensation
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_choice, check_count, check_mapping, check_path
from axiscal.io.arguments import check_instance, type_name
from axiscal.io.tabular import read_text
from axiscal.model.machine import Machine, load_machine
from axiscal.model.tables import ErrorTable
from axiscal.model.volumetric import volumetric_map
from axiscal.units import MM, UM

__all__ = ["GRID_POINTS", "volumetric_section", "plot_volume", "plot_volume_change", "same_grid", "compensated_machine",
           "read_loaded_compensation"]

#: grid points along each linear axis of the report's map
GRID_POINTS = 21


def compensated_machine(machine: Machine, corrections: Mapping[str, ControllerCompensation]) -> Machine:
    """The model of the machine with a controller's pitch compensation loaded.

    For each compensated linear axis the controller moves to ``m = c + k(c)`` when ``c`` is
    commanded, ``k`` the mean of its corrections for travel in + and in - (the model holds one
    curve per error motion, no reversal). The axis' six error motions are then those at ``m``,
    and its own positioning error (``EXX`` of X, ``EZZ`` of Z) gains ``k(c)``: the compensated
    axis' error at ``c`` is ``e(m) + k(c)``. The new table is sampled at the old table's positions
    and the correction's points within them (the correction is linear between its points), and
    keeps the old table's interpolation and travel.

    Parameters
    ----------
    machine : Machine
        The model of the machine as found (no compensation loaded).
    corrections : mapping of str to ControllerCompensation
        Axis letter (X, Y or Z) -> the correction its controller applies
        (:func:`~axiscal.compensation.readback.read_compensation`).

    Returns
    -------
    Machine
        The same machine but for the compensated axes' error tables.

    Raises
    ------
    AxiscalError
        For a ``machine`` that is not a Machine, corrections that are not a mapping of
        ControllerCompensation, or a letter that is not a linear axis of the machine.

    Examples
    --------
    >>> from axiscal.model.machine import Axis
    >>> table = ErrorTable.from_components("X", [0.0, 0.2], {"EXX": [0.0, 20e-6]})
    >>> machine = Machine("FX", {"X": Axis("X", table)})
    >>> loaded = ControllerCompensation("linuxcnc", np.array([0.0, 0.2]), np.array([0.0, -20e-6]), np.array([0.0, -20e-6]))
    >>> left = compensated_machine(machine, {"X": loaded})
    >>> round(float(left.table("X").evaluate(np.array([0.1]))[0, 0]) * 1e9, 3)  # EXX at 100 mm, nm: 10 um less 10 um
    -1.0

    The -1 nm is real: sent 10 um short, the axis stands where ``EXX`` is 1 nm smaller.
    """
    check_instance("machine", machine, Machine)
    check_mapping("corrections", corrections, what="a mapping of axis letters to ControllerCompensation")
    axes = dict(machine.axes)
    for letter, correction in corrections.items():
        check_instance(f"corrections[{letter!r}]", correction, ControllerCompensation)
        if not isinstance(letter, str) or letter not in "XYZ" or letter not in axes:
            raise AxiscalError(f"a compensation for axis {letter!r}: the machine's linear axes are "
                               f"{', '.join(k for k in machine.letters if k in 'XYZ')}")
        table = machine.table(letter)
        inside = correction.nodes_m[(correction.nodes_m > table.start_m) & (correction.nodes_m < table.end_m)]
        command = np.union1d(table.position_m, inside)
        mean = 0.5 * (correction.correction(command, "+") + correction.correction(command, "-"))
        values = table.evaluate(np.clip(command + mean, table.start_m, table.end_m))
        values["XYZ".index(letter)] += mean
        left = ErrorTable(letter, command, values, interpolation=table.interpolation, hold_ends=table.hold_ends)
        axes[letter] = dataclasses.replace(axes[letter], table=left)
    return dataclasses.replace(machine, axes=axes)


def read_loaded_compensation(files: Mapping[str, str | Path], controller: str) -> dict[str, ControllerCompensation]:
    """The compensation files a controller has loaded, read as it reads them.

    Parameters
    ----------
    files : mapping of str to str or Path
        Axis letter -> its compensation file (``[machine] compensation`` of a campaign).
    controller : {"linuxcnc", "fanuc", "siemens", "heidenhain"}
        Whose files they are; each is read with
        :func:`~axiscal.compensation.readback.read_compensation`'s defaults (LinuxCNC's
        ``COMP_FILE_TYPE`` 1 in mm; FANUC's reference at 0 and units of 1 um).

    Returns
    -------
    dict of str to ControllerCompensation

    Raises
    ------
    AxiscalError
        For a file that is missing or that the controller would refuse, naming it.
    """
    check_mapping("files", files, what="a mapping of axis letters to compensation files")
    check_choice("controller", controller, CONTROLLERS)
    loaded = {}
    for letter, name in files.items():
        path = check_path(f"files[{letter!r}]", name)
        try:
            loaded[letter] = read_compensation(read_text(path), controller)
        except AxiscalError as exc:
            raise exc.located(path=path) from None
    return loaded


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
        ``max_um``, ``rms_um``, ``max_at_mm`` (axis -> position) over the grid, and ``map``: the
        values drawn, ``axes`` (letters), ``grid_mm`` (letter -> positions drawn: every grid
        position of the first two axes, the three slices of a third), ``e_um`` (|e| on that
        grid, nested in the order of ``axes``) and, for one axis, ``components_um`` (``ex``,
        ``ey``, ``ez``).

    Raises
    ------
    AxiscalError
        For a ``machine`` that is not a :class:`~axiscal.model.Machine`, a path without a figure
        suffix, a ``count`` below 2.
    """
    from axiscal.io.figures import check_figure_path, pyplot, save_figure, set_up_axes

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
        set_up_axes(ax, xlabel=f"{a} / mm", ylabel="error / µm", grid=True, legend=True)
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
        fig.colorbar(mesh_plot, ax=grid_axes[0].tolist(), label="|e| / µm")
    fig.suptitle(f"Volumetric error: {machine.name or machine.chain}", fontsize=11)
    save_figure(fig, path)
    return {
        "max_um": result.max_m / UM,
        "rms_um": result.rms_m / UM,
        "max_at_mm": {k: v / MM for k, v in result.max_at_m.items()},
        "map": _drawn_map(letters, axes, magnitude, error),
    }


def _drawn_map(letters: list[str], axes: dict[str, np.ndarray], magnitude_um: np.ndarray, error_m: np.ndarray) -> dict[str, Any]:
    """The values the map draws, for results.json: |e| (um) on the grid of the plotted axes and slices."""
    grid = {letter: axes[letter] for letter in letters}
    e_um = magnitude_um.reshape([axes[letter].size for letter in letters])
    if len(letters) == 3:
        values = grid[letters[2]]
        picks = [0, values.size // 2, values.size - 1]
        grid[letters[2]] = values[picks]
        e_um = e_um[:, :, picks]
    out: dict[str, Any] = {
        "axes": list(letters),
        "grid_mm": {letter: np.round(q / MM, 6).tolist() for letter, q in grid.items()},
        "e_um": np.round(e_um, 4).tolist(),
    }
    if len(letters) == 1:
        out["components_um"] = {name: np.round(error_m[:, i] / UM, 4).tolist() for i, name in enumerate(("ex", "ey", "ez"))}
    return out


def _map_arrays(name: str, drawn: Mapping[str, Any]) -> tuple[list[str], dict[str, np.ndarray], np.ndarray, dict[str, np.ndarray]]:
    """A map of :func:`plot_volume` checked: axes, grid (mm), |e| (um) and components (um, one axis only)."""
    from axiscal.io.arguments import check_array

    check_mapping(name, drawn, ("axes", "grid_mm", "e_um"), what="a volumetric map (axes, grid_mm, e_um)")
    letters = drawn["axes"]
    if not isinstance(letters, list) or not 1 <= len(letters) <= 3 or not all(isinstance(k, str) for k in letters):
        raise AxiscalError(f"{name} axes must be a list of one to three axis letters, not {letters!r}")
    check_mapping(f"{name} grid_mm", drawn["grid_mm"], letters, what="a mapping of axis letters to positions")
    grid = {k: check_array(f"{name} grid_mm[{k!r}]", drawn["grid_mm"][k], ndim=1, min_len=1, unit="mm") for k in letters}
    e_um = check_array(f"{name} e_um", drawn["e_um"], ndim=len(letters), finite=False, unit="um")
    if e_um.shape != tuple(grid[k].size for k in letters):
        raise AxiscalError(f"{name} e_um must have shape {tuple(grid[k].size for k in letters)} (its grid), not {e_um.shape}")
    components = {}
    if len(letters) == 1 and isinstance(drawn.get("components_um"), Mapping):
        for key in ("ex", "ey", "ez"):
            if key in drawn["components_um"]:
                components[key] = check_array(f"{name} components_um[{key!r}]", drawn["components_um"][key], ndim=1,
                                              finite=False, unit="um")
                if components[key].size != e_um.size:
                    raise AxiscalError(f"{name} components_um[{key!r}] must have {e_um.size} values, not {components[key].size}")
    return letters, grid, e_um, components


def same_grid(now: Mapping[str, Any], before: Mapping[str, Any]) -> bool:
    """Whether two maps of :func:`plot_volume` were drawn on the same axes and grid (to 1 nm).

    Parameters
    ----------
    now, before : mapping
        The ``map`` of two volumetric sections.

    Returns
    -------
    bool

    Raises
    ------
    AxiscalError
        For a map that is not one (see :func:`plot_volume`).
    """
    a_axes, a_grid, _, _ = _map_arrays("now", now)
    b_axes, b_grid, _, _ = _map_arrays("before", before)
    return a_axes == b_axes and all(
        a_grid[k].shape == b_grid[k].shape and np.allclose(a_grid[k], b_grid[k], rtol=0.0, atol=1e-6) for k in a_axes
    )


def plot_volume_change(now: Mapping[str, Any], before: Mapping[str, Any], path: str | Path, *, label: str = "before") -> Path:
    """Draw the change of the volumetric error between two maps on the same grid: |e| now - |e| before.

    Two or three axes: a colour map per slice on a diverging scale centred on zero (blue where the
    error is smaller now, red where it is larger), the same scale for every slice. One axis: the
    change of |e| and of each component against the position.

    Parameters
    ----------
    now, before : mapping
        The ``map`` of :func:`plot_volume` for this campaign and the compared one (as results.json
        holds it, ``volumetric.map``), on the same grid.
    path : str or Path
        The figure to write (format from the suffix).
    label : str, keyword-only
        How the figure names the compared campaign (default "before").

    Returns
    -------
    Path
        ``path``.

    Raises
    ------
    AxiscalError
        For a map that is not one, maps on different grids (see :func:`same_grid`), a path
        without a figure suffix, a label that is not text.
    """
    from axiscal.io.figures import check_figure_path, pyplot, save_figure, set_up_axes

    letters, grid, e_now, c_now = _map_arrays("now", now)
    _, _, e_before, c_before = _map_arrays("before", before)
    if not same_grid(now, before):
        raise AxiscalError("the two volumetric maps are on different grids (axes or travel differ): no change can be drawn")
    check_figure_path(path)
    check_instance("label", label, str)
    change = e_now - e_before
    plt = pyplot()
    title = f"Change of the volumetric error: |e| now − |e| {label}"
    if len(letters) == 1:
        (a,) = letters
        fig, ax = plt.subplots(figsize=(7.5, 3.6))
        for key in ("ex", "ey", "ez"):
            if key in c_now and key in c_before:
                ax.plot(grid[a], c_now[key] - c_before[key], label=f"{key} now − {key} {label}")
        ax.plot(grid[a], change, "k", label=f"|e| now − |e| {label}")
        set_up_axes(ax, xlabel=f"{a} / mm", ylabel="change / µm", grid=True, zero_line=True, legend=True)
    else:
        a, b = letters[:2]
        if len(letters) == 2:
            panels = [(None, change)]
        else:
            c = letters[2]
            panels = [(f"{c} = {v:g} mm", change[:, :, k]) for k, v in enumerate(grid[c])]
        finite = change[np.isfinite(change)]
        span = float(np.max(np.abs(finite))) if finite.size else 0.0
        span = span if span > 0 else 1e-3
        fig, grid_axes = plt.subplots(1, len(panels), figsize=(4.2 * len(panels) + 1.2, 4.0), squeeze=False,
                                      layout="constrained")
        for ax, (caption, image) in zip(grid_axes[0], panels):
            mesh_plot = ax.pcolormesh(grid[a], grid[b], image.T, shading="auto", cmap="RdBu_r", vmin=-span, vmax=span)
            ax.set_xlabel(f"{a} / mm")
            if ax is grid_axes[0][0]:
                ax.set_ylabel(f"{b} / mm")
            ax.set_aspect("equal")
            if caption:
                ax.set_title(caption, fontsize=10)
        fig.colorbar(mesh_plot, ax=grid_axes[0].tolist(), label=f"|e| now − |e| {label} / µm")
    fig.suptitle(title, fontsize=11)
    return save_figure(fig, path)


def volumetric_section(
    model: str | Path, svg_of: Callable[[Callable[[Path], Any]], str], *, before: Mapping[str, Any] | None = None,
    compensation: Mapping[str, str | Path] | None = None, controller: str | None = None,
) -> dict[str, Any]:
    """The report's volumetric section for a machine description.

    Parameters
    ----------
    model : str or Path
        The machine description (TOML).
    svg_of : callable
        Turns a plot-writing function into SVG text (:func:`axiscal.campaign.runner.svg_of`).
    before : mapping, keyword-only
        The ``volumetric`` object of another campaign's results.json: when it holds a ``map`` on
        the same grid, a second plot draws the change |e| now - |e| before
        (:func:`plot_volume_change`); on another grid, a warning says why none is drawn; a
        results.json without a map (older than the key) draws none.
    compensation : mapping of str to str or Path, keyword-only
        The compensation files the controller had loaded while the campaign was measured (axis
        letter -> file, ``[machine] compensation``): the section draws the model of the
        compensated machine (:func:`compensated_machine`), what is left.
    controller : str, keyword-only
        Whose files ``compensation`` holds (needed with it).

    Returns
    -------
    dict
        ``method``, ``table`` (list of Figure), ``plots`` (list of Plot), ``figures`` (for
        results.json) and ``warnings`` (list of str).

    Raises
    ------
    AxiscalError
        For a bad machine description (naming the file and line), an ``svg_of`` that is not
        callable, a ``before`` that is not a mapping or whose map is not one, a compensation
        file the controller would refuse or without its controller.
    """
    model = check_path("model", model)
    if not callable(svg_of):
        raise AxiscalError(f"svg_of must be a function that turns a plot into SVG text, not {type_name(svg_of)}")
    if before is not None:
        check_mapping("before", before, what="the volumetric object of another campaign's results.json")
    machine = load_machine(model)
    loaded = ""
    if compensation:
        if controller is None:
            raise AxiscalError("compensation files need the controller that loaded them")
        machine = compensated_machine(machine, read_loaded_compensation(compensation, controller))
        loaded = (f", with the {controller} compensation loaded "
                  f"({', '.join(f'{k}: {Path(v).name}' for k, v in compensation.items())}): what is left")
    holder: list[dict[str, Any]] = []
    svg = svg_of(lambda p: holder.append(plot_volume(machine, p)))
    figures = holder[0]
    where = ", ".join(f"{k} = {v:g}" for k, v in figures["max_at_mm"].items())
    plots = [Plot("Volumetric error |e| against the axis positions", svg)]
    warnings = []
    previous = None if before is None else before.get("map")
    if previous is not None:
        try:
            matched = same_grid(figures["map"], previous)
        except AxiscalError as exc:
            raise AxiscalError(f"the compared results.json's volumetric map: {exc.message}") from None
        if matched:
            change = svg_of(lambda p: plot_volume_change(figures["map"], previous, p))
            plots.append(Plot("Change of the volumetric error since the compared campaign: |e| now − |e| before on the "
                              "same grid (blue: smaller now, red: larger)", change))
        else:
            warnings.append("volumetric: the compared campaign's map is on another grid (axes or travel differ), "
                            "so no change of the volumetric error is drawn")
    return {
        "method": f"HTM model of {machine.name or machine.chain} (chain {machine.chain}){loaded}, {GRID_POINTS} points"
                  " along each axis",
        "table": [Figure("largest |e|", figures["max_um"], "um"), Figure("rms |e|", figures["rms_um"], "um"),
                  Figure("largest |e| at", where, "mm")],
        "plots": plots,
        "figures": figures,
        "warnings": warnings,
    }
