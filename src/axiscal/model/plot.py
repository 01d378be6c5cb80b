"""Plots of the machine model: error tables, volumetric map, diagonal tests (matplotlib imported lazily).

Every error plotted is actual minus nominal (docs/conventions.md), in um (translations) and urad
(rotations).
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_instance, check_mapping, check_path
from axiscal.io.figures import OVERLAY_STYLE, overlay_label, overlay_series, pyplot, save_figure, set_up_axes
from axiscal.model.machine import AXIS_UNITS, Machine
from axiscal.units import ANGLE_UNITS, MM, UM

if TYPE_CHECKING:  # the result types only annotate: their modules import this one to plot
    from axiscal.model.diagonal import DiagonalResult

__all__ = ["plot_error_tables", "plot_volumetric", "plot_diagonal", "plot_diagonal_experiment"]

_URAD = ANGLE_UNITS["urad"]


def plot_error_tables(machine: Machine, path: str | Path) -> None:
    """The six error motions of every axis against position (um and urad).

    Parameters
    ----------
    machine : Machine
        Its error tables are plotted, one row of two panels (translations, rotations) per axis.
    path : str or Path
        Figure file; the format follows the suffix (``.png``, ``.svg``, ...).

    Returns
    -------
    None
        The figure is written to ``path``.

    Raises
    ------
    AxiscalError
        If the suffix is not a figure format or the file cannot be written.
    """
    check_instance("machine", machine, Machine)
    check_path("path", path)
    plt = pyplot()
    letters = machine.letters
    fig, axes = plt.subplots(len(letters), 2, figsize=(11, 3.2 * len(letters)), squeeze=False)
    for row, letter in enumerate(letters):
        table = machine.table(letter)
        factor, unit = AXIS_UNITS[letter]
        q_mm = table.position_m / factor
        for k, name in enumerate(table.names):
            target = axes[row, 0] if k < 3 else axes[row, 1]
            scale = 1.0 / UM if k < 3 else 1.0 / _URAD
            target.plot(q_mm, table.values[k] * scale, marker=".", label=f"{name}")
        for ax, ylabel in zip(axes[row], ("translation error / µm", "rotation error / urad")):
            set_up_axes(ax, xlabel=f"{letter} position / {unit}", ylabel=ylabel, grid=True, legend=True,
                        legend_options={"ncol": 3})
    fig.suptitle(f"Error motions: {machine.name or machine.chain}")
    fig.tight_layout()
    save_figure(fig, path, dpi=120)


def plot_volumetric(
    positions_m: dict[str, np.ndarray],
    error_m: np.ndarray,
    path: str | Path,
    *,
    title: str = "",
    orientation_rad: np.ndarray | None = None,
) -> None:
    """Map of the volumetric error and, for a chain with rotary axes, of the tool axis orientation error.

    Drawn against the axis positions: on a 2-axis grid a colour map of |e| (with arrows of the
    in-plane components when both axes are linear) and, given ``orientation_rad``, a second map of
    its length; on a 3-axis grid colour maps of |e| over the first two axes in slices of the
    third (one colour scale); along one axis the components and |e| against its position; other
    point sets as points over the first two moving axes coloured by |e|.

    Parameters
    ----------
    positions_m : dict of str to ndarray, shape (N,)
        Axis positions: metres, radians for rotary axes (plotted in degrees).
    error_m : ndarray, shape (N, 3)
        Volumetric error (actual minus nominal), metres.
    path : str or Path
        Figure file; the format follows the suffix.
    title : str, optional
        Figure title.
    orientation_rad : ndarray, shape (N, 2), optional
        Orientation error ``(ei, ej)`` of the tool axis, radians.

    Returns
    -------
    None
        The figure is written to ``path``.

    Raises
    ------
    AxiscalError
        If the suffix is not a figure format or the file cannot be written.
    """
    check_mapping("positions_m", positions_m, what="a mapping of axis letters to positions")
    positions_m = {k: check_array(f"positions_m[{k!r}]", q, ndim=1, unit="") for k, q in positions_m.items()}
    error_m = check_array("error_m", error_m, ndim=2, last=3)
    n = error_m.shape[0]
    if any(q.size != n for q in positions_m.values()):
        raise AxiscalError(f"positions_m must hold one position per row of error_m ({n}) for every axis")
    if orientation_rad is not None:
        orientation_rad = check_array("orientation_rad", orientation_rad, ndim=2, last=2)
        if orientation_rad.shape[0] != n:
            raise AxiscalError(f"orientation_rad must have one row per point ({n}), not {orientation_rad.shape[0]}")
    check_instance("title", title, str)
    check_path("path", path)
    plt = pyplot()
    error_um = np.asarray(error_m) / UM
    panels = [("|e| / µm", error_um, ("ex", "ey", "ez"))]
    if orientation_rad is not None:
        panels.append(("|(ei, ej)| / µrad", np.asarray(orientation_rad) / _URAD, ("ei", "ej")))
    moving = [k for k, q in positions_m.items() if np.ptp(q) > 0]
    if len(moving) == 3 and orientation_rad is None and _is_grid([positions_m[k] for k in moving]):
        _slices(plt, positions_m, moving, np.linalg.norm(error_um, axis=1), path, title)
        return
    fig, axes = plt.subplots(1, len(panels), figsize=(8 * len(panels), 6.5), squeeze=False)
    for ax, (label, values, names) in zip(axes[0], panels):
        magnitude = np.linalg.norm(values, axis=1)
        if len(moving) == 2:
            a, b = moving
            (fa, unit_a), (fb, unit_b) = AXIS_UNITS[a], AXIS_UNITS[b]
            qa, qb = positions_m[a] / fa, positions_m[b] / fb
            ua, ub = np.unique(qa), np.unique(qb)
            if ua.size * ub.size == qa.size:
                order = np.lexsort((qb, qa))
                grid = magnitude[order].reshape(ua.size, ub.size)
                mesh = ax.pcolormesh(ua, ub, grid.T, shading="auto", cmap="viridis")
                fig.colorbar(mesh, ax=ax, label=label)
            else:
                sc = ax.scatter(qa, qb, c=magnitude, cmap="viridis")
                fig.colorbar(sc, ax=ax, label=label)
            if len(names) == 3 and a in "XYZ" and b in "XYZ" and np.any(values[:, ["XYZ".index(a), "XYZ".index(b)]]):
                # (arrows of zero length have no scale: none are drawn for an error-free plane)
                ia, ib = "XYZ".index(a), "XYZ".index(b)
                arrows = slice(None, None, max(1, qa.size // 150))
                ax.quiver(qa[arrows], qb[arrows], values[arrows, ia], values[arrows, ib], color="white", alpha=0.8)
                ax.set_aspect("equal")
                ax.set_title(f"arrows: e{a.lower()}, e{b.lower()}")
            else:
                ax.set_title("tool point position error" if len(names) == 3 else "tool axis orientation error")
            set_up_axes(ax, xlabel=f"{a} / {unit_a}", ylabel=f"{b} / {unit_b}")
        elif len(moving) == 1:
            (a,) = moving
            fa, unit_a = AXIS_UNITS[a]
            qa = positions_m[a] / fa
            order = np.argsort(qa, kind="stable")
            for i, name in enumerate(names):
                ax.plot(qa[order], values[order, i], label=name)
            ax.plot(qa[order], magnitude[order], "k", label=label.split(" /")[0])
            set_up_axes(ax, xlabel=f"{a} / {unit_a}", ylabel=label.replace("|e|", "error").replace("|(ei, ej)|", "orientation error"),
                        grid=True, legend=True)
        else:
            # points that are no grid (or one point): where they are, coloured by |e|
            keys = moving + [k for k in positions_m if k not in moving]
            a, b = (keys * 2)[:2]
            (fa, unit_a), (fb, unit_b) = AXIS_UNITS[a], AXIS_UNITS[b]
            sc = ax.scatter(positions_m[a] / fa, positions_m[b] / fb, c=magnitude, cmap="viridis")
            fig.colorbar(sc, ax=ax, label=label)
            set_up_axes(ax, xlabel=f"{a} / {unit_a}", ylabel=f"{b} / {unit_b}", grid=True)
    fig.suptitle(title or "Volumetric error")
    fig.tight_layout()
    save_figure(fig, path, dpi=120)


def _is_grid(columns: list[np.ndarray]) -> bool:
    """Whether the points are every combination of each axis' distinct positions (a full grid)."""
    sizes = [np.unique(q).size for q in columns]
    return int(np.prod(sizes)) == columns[0].size and all(s > 1 for s in sizes)


def _slices(plt: Any, positions_m: dict[str, np.ndarray], moving: list[str], magnitude_um: np.ndarray, path: str | Path,
            title: str) -> None:
    """|e| of a 3-axis grid as colour maps over the first two axes, in up to four slices of the third."""
    a, b, c = moving
    (fa, unit_a), (fb, unit_b), (fc, unit_c) = AXIS_UNITS[a], AXIS_UNITS[b], AXIS_UNITS[c]
    qa, qb, qc = positions_m[a] / fa, positions_m[b] / fb, positions_m[c] / fc
    ua, ub, uc = np.unique(qa), np.unique(qb), np.unique(qc)
    levels = uc[np.unique(np.linspace(0, uc.size - 1, min(4, uc.size)).round().astype(int))]
    fig, axes = plt.subplots(1, levels.size, figsize=(4.6 * levels.size + 1.2, 4.6), squeeze=False, sharey=True)
    low, high = float(magnitude_um.min()), float(magnitude_um.max())
    mesh = None
    for ax, level in zip(axes[0], levels):
        at = qc == level
        order = np.lexsort((qb[at], qa[at]))
        grid = magnitude_um[at][order].reshape(ua.size, ub.size)
        mesh = ax.pcolormesh(ua, ub, grid.T, shading="auto", cmap="viridis", vmin=low, vmax=high)
        set_up_axes(ax, xlabel=f"{a} / {unit_a}", title=f"{c} = {level:g} {unit_c}")
        ax.set_aspect("equal")
    set_up_axes(axes[0][0], ylabel=f"{b} / {unit_b}")
    fig.colorbar(mesh, ax=list(axes[0]), label="|e| / µm")
    fig.suptitle(title or "Volumetric error")
    save_figure(fig, path, dpi=120)


def plot_diagonal(
    result: DiagonalResult,
    path: str | Path,
    *,
    title: str = "Diagonal displacement error",
    overlay: Mapping[str, Any] | None = None,
) -> None:
    """Paper 000 Fig. 22 style: the model's diagonal error and, with readings, E_BD and E_AD.

    All three are actual minus nominal along the diagonal (:mod:`axiscal.model.diagonal`): the
    model's prediction ``predicted - nominal``, ``E_BD = P - nominal`` and ``E_AD = P - predicted``,
    so where the model is right E_BD lies on the prediction and E_AD on zero.

    Parameters
    ----------
    result : DiagonalResult
        From :func:`axiscal.model.diagonal.diagonal_check` or :func:`axiscal.model.diagonal.diagonal_test`.
    path : str or Path
        Figure file; the format follows the suffix.
    title : str
        Figure title.
    overlay : mapping, keyword-only
        Another test of the same diagonal (e.g. before compensation), drawn behind in grey: the
        ``points`` of its ``axiscal diagonal --json`` (``nominal_mm``, ``model_error_um`` and, with
        readings, ``E_BD_um`` and ``E_AD_um``, shape (m,)) and an optional ``label`` for the legend
        (default "before").

    Returns
    -------
    None
        The figure is written to ``path``.

    Raises
    ------
    AxiscalError
        If the suffix is not a figure format or the file cannot be written; an overlay whose
        series are not lists of numbers of one length.
    """
    from axiscal.model.diagonal import DiagonalResult

    check_instance("result", result, DiagonalResult)
    check_path("path", path)
    before = []
    if overlay is not None:
        check_mapping("overlay", overlay, what="the points of another diagonal test (nominal_mm, E_BD_um ...)")
        x_before = overlay_series(overlay, "nominal_mm")
        label = overlay_label(overlay)
        for key, dashes, name in (("model_error_um", (0, (6, 2)), "model prediction"), ("E_BD_um", (0, (4, 2)), "E_BD"),
                                  ("E_AD_um", (0, (1, 1.5)), "E_AD")):
            values = None if x_before is None else overlay_series(overlay, key, length=x_before.size)
            if values is not None:
                before.append((x_before, values, dashes, f"{label}: {name}"))
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(8, 4.5))
    for x_before, values, dashes, name in before:
        ax.plot(x_before, values, **{**OVERLAY_STYLE, "linestyle": dashes}, label=name)
    nominal_mm = result.nominal_m / MM
    ax.plot(nominal_mm, result.model_error_m / UM, "k--", label="model prediction (predicted - nominal)")
    if result.error_before_m is not None and result.error_after_m is not None:
        ax.plot(nominal_mm, result.error_before_m / UM, "o-", label=f"E_BD = measured - nominal (P-V {result.range_before_m / UM:.1f} µm)")
        ax.plot(nominal_mm, result.error_after_m / UM, "s-", label=f"E_AD = measured - predicted (P-V {result.range_after_m / UM:.1f} µm)")
    set_up_axes(ax, xlabel="nominal displacement along the diagonal / mm", ylabel="error, actual - nominal / µm", title=title,
                grid=True, zero_line=True, legend=True, legend_options={"fontsize": 9})
    fig.tight_layout()
    save_figure(fig, path, dpi=120)


def plot_diagonal_experiment(result, path: str | Path) -> None:
    """Paper 000 Fig. 22 in simulation: the diagonal error before the model, with the scales only, and after it.

    The experiment's values follow paper 000 eq (13), nominal (or model) minus reading; they are
    plotted with the sign of docs/conventions.md, actual (the reading) minus nominal.

    Parameters
    ----------
    result : axiscal.measurement.experiment.DiagonalExperiment
        The simulated experiment (``x_m``, ``z_m``, ``before_m``, ``after_m``, ``scales_only_m``, SI).
    path : str or Path
        Figure file; the format follows the suffix.

    Returns
    -------
    None
        The figure is written to ``path``.

    Raises
    ------
    AxiscalError
        If the suffix is not a figure format or the file cannot be written.
    """
    if not all(hasattr(result, name) for name in ("x_m", "z_m", "before_m", "after_m", "scales_only_m")):
        raise AxiscalError(
            f"result must be the DiagonalExperiment axiscal.measurement.diagonal_experiment returns, not {type(result).__name__}"
        )
    check_path("path", path)
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(7.0, 4.2))
    diagonal_mm = np.hypot(result.x_m, result.z_m) / MM
    ax.plot(diagonal_mm, -result.before_m / UM, "o-", label=f"before the model, E_BD (max {result.before_max_m / UM:.1f} µm)")
    ax.plot(diagonal_mm, -result.scales_only_m / UM, "^--", label=f"scales only (max {result.scales_only_max_m / UM:.1f} µm)")
    ax.plot(diagonal_mm, -result.after_m / UM, "s-", label=f"after the model, E_AD (max {result.after_max_m / UM:.2f} µm)")
    set_up_axes(ax, xlabel="position along the XZ diagonal / mm", ylabel="diagonal error, actual - nominal / µm",
                title=f"Virtual XZ module, {result.load_kg:g} kg on Z: diagonal vs laser (paper 000 eq 13)", grid=True,
                zero_line=True, legend=True, legend_options={"loc": "best"})
    fig.tight_layout()
    save_figure(fig, path, dpi=120)
