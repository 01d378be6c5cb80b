"""Plots of the machine model: error tables, volumetric map, diagonal tests (matplotlib imported lazily).

Every error plotted is actual minus nominal (docs/conventions.md), in um (translations) and urad
(rotations).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from axiscal.io.figures import pyplot, save_figure
from axiscal.model.diagonal import DiagonalResult
from axiscal.model.machine import Machine
from axiscal.units import ANGLE_UNITS, MM, UM

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
    plt = pyplot()
    letters = machine.letters
    fig, axes = plt.subplots(len(letters), 2, figsize=(11, 3.2 * len(letters)), squeeze=False)
    for row, letter in enumerate(letters):
        table = machine.table(letter)
        q_mm = table.position_m / MM
        for k, name in enumerate(table.names):
            target = axes[row, 0] if k < 3 else axes[row, 1]
            scale = 1.0 / UM if k < 3 else 1.0 / _URAD
            target.plot(q_mm, table.values[k] * scale, marker=".", label=f"{name}")
        axes[row, 0].set_ylabel("translation error / um")
        axes[row, 1].set_ylabel("rotation error / urad")
        for ax in axes[row]:
            ax.set_xlabel(f"{letter} position / mm")
            ax.grid(True, alpha=0.3)
            ax.legend(fontsize=8, ncol=3)
    fig.suptitle(f"Error motions: {machine.name or machine.chain}")
    fig.tight_layout()
    save_figure(fig, path, dpi=120)


def plot_volumetric(positions_m: dict[str, np.ndarray], error_m: np.ndarray, path: str | Path, *, title: str = "") -> None:
    """Map of the volumetric error.

    On a 2-axis grid a colour map of |e| with arrows of the in-plane components; otherwise |e| and
    its components against point number.

    Parameters
    ----------
    positions_m : dict of str to ndarray, shape (N,)
        Axis positions, metres.
    error_m : ndarray, shape (N, 3)
        Volumetric error (actual minus nominal), metres.
    path : str or Path
        Figure file; the format follows the suffix.
    title : str, optional
        Figure title.

    Returns
    -------
    None
        The figure is written to ``path``.

    Raises
    ------
    AxiscalError
        If the suffix is not a figure format or the file cannot be written.
    """
    plt = pyplot()
    error_um = np.asarray(error_m) / UM
    magnitude_um = np.linalg.norm(error_um, axis=1)
    moving = [k for k, q in positions_m.items() if np.ptp(q) > 0]
    fig, ax = plt.subplots(figsize=(8, 6.5))
    if len(moving) == 2:
        a, b = moving
        qa, qb = positions_m[a] / MM, positions_m[b] / MM
        ua, ub = np.unique(qa), np.unique(qb)
        if ua.size * ub.size == qa.size:
            order = np.lexsort((qb, qa))
            grid = magnitude_um[order].reshape(ua.size, ub.size)
            mesh = ax.pcolormesh(ua, ub, grid.T, shading="auto", cmap="viridis")
            fig.colorbar(mesh, ax=ax, label="|e| / um")
        else:
            sc = ax.scatter(qa, qb, c=magnitude_um, cmap="viridis")
            fig.colorbar(sc, ax=ax, label="|e| / um")
        ia, ib = "XYZ".index(a), "XYZ".index(b)
        arrows = slice(None, None, max(1, qa.size // 150))
        ax.quiver(qa[arrows], qb[arrows], error_um[arrows, ia], error_um[arrows, ib], color="white", alpha=0.8)
        ax.set_xlabel(f"{a} / mm")
        ax.set_ylabel(f"{b} / mm")
        ax.set_aspect("equal")
        ax.set_title(title or f"Volumetric error (arrows: e{a.lower()}, e{b.lower()})")
    else:
        for i, label in enumerate(("ex", "ey", "ez")):
            ax.plot(error_um[:, i], label=label)
        ax.plot(magnitude_um, "k", label="|e|")
        ax.set_xlabel("point")
        ax.set_ylabel("error / um")
        ax.legend()
        ax.grid(True, alpha=0.3)
        ax.set_title(title or "Volumetric error")
    fig.tight_layout()
    save_figure(fig, path, dpi=120)


def plot_diagonal(result: DiagonalResult, path: str | Path, *, title: str = "Diagonal displacement error") -> None:
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

    Returns
    -------
    None
        The figure is written to ``path``.

    Raises
    ------
    AxiscalError
        If the suffix is not a figure format or the file cannot be written.
    """
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(8, 4.5))
    nominal_mm = result.nominal_m / MM
    ax.plot(nominal_mm, result.model_error_m / UM, "k--", label="model prediction (predicted - nominal)")
    if result.error_before_m is not None and result.error_after_m is not None:
        ax.plot(nominal_mm, result.error_before_m / UM, "o-", label=f"E_BD = measured - nominal (P-V {result.range_before_m / UM:.1f} um)")
        ax.plot(nominal_mm, result.error_after_m / UM, "s-", label=f"E_AD = measured - predicted (P-V {result.range_after_m / UM:.1f} um)")
    ax.axhline(0.0, color="grey", lw=0.8)
    ax.set_xlabel("nominal displacement along the diagonal / mm")
    ax.set_ylabel("error, actual - nominal / um")
    ax.set_title(title)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=9)
    fig.tight_layout()
    save_figure(fig, path, dpi=120)


def plot_diagonal_experiment(result, path: str | Path) -> None:
    """Paper 000 Fig. 22 in simulation: the diagonal error before the model, with the scales only, and after it.

    The experiment's values follow paper 000 eq (13), nominal (or model) minus reading; they are
    plotted with the sign of docs/conventions.md, actual (the reading) minus nominal.

    Parameters
    ----------
    result : axiscal.measurement.virtual.DiagonalExperiment
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
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(7.0, 4.2))
    diagonal_mm = np.hypot(result.x_m, result.z_m) / MM
    ax.plot(diagonal_mm, -result.before_m / UM, "o-", label=f"before the model, E_BD (max {result.before_max_m / UM:.1f} um)")
    ax.plot(diagonal_mm, -result.scales_only_m / UM, "^--", label=f"scales only (max {result.scales_only_max_m / UM:.1f} um)")
    ax.plot(diagonal_mm, -result.after_m / UM, "s-", label=f"after the model, E_AD (max {result.after_max_m / UM:.2f} um)")
    ax.axhline(0.0, color="0.6", lw=0.8)
    ax.set_xlabel("position along the XZ diagonal (mm)")
    ax.set_ylabel("diagonal error, actual - nominal (um)")
    ax.set_title(f"Virtual XZ module, {result.load_kg:g} kg on Z: diagonal vs laser (paper 000 eq 13)")
    ax.legend(loc="best", fontsize=8)
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    save_figure(fig, path, dpi=120)
