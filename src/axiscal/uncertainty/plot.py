"""Plots of the uncertainty room: the volumetric error |e| and its coverage interval against the axis positions (matplotlib imported lazily).

The error is actual minus nominal (docs/conventions.md), in um; the interval is the Monte Carlo
probabilistically symmetric coverage interval (JCGM 101:2008, 7.7).
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_mapping
from axiscal.io.figures import check_figure_path, pyplot, save_figure, set_up_axes
from axiscal.io.arguments import check_instance
from axiscal.uncertainty.volumetric import VolumetricUncertainty
from axiscal.units import MM, UM

__all__ = ["plot_volumetric_uncertainty"]


def plot_volumetric_uncertainty(
    positions_m: Mapping[str, np.ndarray], result: VolumetricUncertainty, path: str | Path, *, title: str = ""
) -> None:
    """|e| of the model and its coverage interval against the position of each axis that moves.

    One panel per moving axis (every axis when none moves), the axis position in mm on the
    horizontal axis. Where one axis alone moves, |e| is a line inside a shaded band; on a grid of
    several axes every point is a marker with its interval as a vertical bar, so the spread at one
    position shows the other axes' influence.

    Parameters
    ----------
    positions_m : mapping of str to ndarray, shape (N,)
        Axis positions of the points, metres.
    result : VolumetricUncertainty
        The Monte Carlo result at those points.
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
        A suffix that is not a figure format, a file that cannot be written, positions that are
        not finite or do not match the result's points, a result that is not a
        :class:`VolumetricUncertainty`.
    """
    check_instance("result", result, VolumetricUncertainty)
    check_mapping("positions_m", positions_m, what="a mapping of axis letters to positions in metres")
    if not positions_m:
        raise AxiscalError("positions_m must give the position of at least one axis")
    if not isinstance(title, str):
        raise AxiscalError(f"title must be a str, not {title!r}")
    n = result.error.shape[0]
    q_mm = {k: check_array(f"positions_m['{k}']", q, ndim=1) / MM for k, q in positions_m.items()}
    for k, q in q_mm.items():
        if q.shape != (n,):
            raise AxiscalError(f"positions_m['{k}']: {q.size} values for {n} points")
    check_figure_path(path)
    plt = pyplot()
    moving = [k for k, q in q_mm.items() if np.ptp(q) > 0] or list(q_mm)
    e_um = result.magnitude / UM
    low, high = result.magnitude_low / UM, result.magnitude_high / UM
    label = f"{result.probability:.0%} interval ({result.draws:,d} draws)"
    fig, axes = plt.subplots(1, len(moving), figsize=(max(8.0, 4.8 * len(moving) + 1.5), 4.5), squeeze=False, sharey=True)
    for ax, letter in zip(axes[0], moving):
        x = q_mm[letter]
        if len(moving) == 1:
            order = np.argsort(x, kind="stable")
            ax.fill_between(x[order], low[order], high[order], color="tab:blue", alpha=0.25, label=label)
            ax.plot(x[order], e_um[order], color="tab:blue", marker=".", label="|e| of the model")
        else:
            ax.errorbar(x, e_um, yerr=np.vstack([e_um - low, high - e_um]).clip(min=0.0), fmt="o", markersize=3,
                        elinewidth=0.8, capsize=2, alpha=0.6, color="tab:blue", ecolor="tab:gray", label=f"|e| and its {label}")
        set_up_axes(ax, xlabel=f"{letter} position / mm", grid=True)
    set_up_axes(axes[0, 0], ylabel="|e| / µm", legend=True, legend_options={"loc": "best"})
    fig.suptitle(title or "Volumetric error with its coverage interval", fontsize=11)
    fig.tight_layout()
    save_figure(fig, path, dpi=120)
