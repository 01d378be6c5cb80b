"""Plots of the squareness room: two runs and their lines (paper 002 eqs 1 and 21), and paper 002 Fig. 5.

Drawn through :func:`axiscal.io.figures.pyplot` and saved atomically with
:func:`axiscal.io.figures.save_figure`; positions in mm, deviations in um, angles in arcsec/arcmin.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from axiscal.conventions import PLANES
from axiscal.instruments.optics import PentaprismSensitivity
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_instance, check_mapping, check_path
from axiscal.io.figures import OVERLAY_STYLE, overlay_label, overlay_series, pyplot, save_figure, set_up_axes
from axiscal.units import ARCMIN, ARCSEC, MM, UM

if TYPE_CHECKING:  # the result type only annotates: its module imports this one to plot
    from axiscal.squareness.evaluation import SquarenessResult

__all__ = ["plot_squareness", "plot_pentaprism"]


def _squareness_overlay(overlay: Mapping[str, Any]) -> list[tuple[np.ndarray, np.ndarray, np.ndarray | None] | None]:
    """Each run of the overlay as (position_mm, deviation_um, line_um or None), None for a run it lacks."""
    check_mapping("overlay", overlay, what="another squareness test's runs ({'first': ..., 'second': ...})")
    runs = []
    for which in ("first", "second"):
        run = overlay.get(which)
        if run is None:
            runs.append(None)
            continue
        name = f"overlay['{which}']"
        check_mapping(name, run, what="a run (position_mm, deviation_um, line_um)")
        x = overlay_series(run, "position_mm", name=name)
        y = None if x is None else overlay_series(run, "deviation_um", length=x.size, name=name)
        runs.append(None if y is None else (x, y, overlay_series(run, "line_um", length=x.size, name=name)))
    return runs


def plot_squareness(
    path: str | Path,
    result: SquarenessResult,
    runs: tuple[tuple[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]],
    *,
    overlay: Mapping[str, Any] | None = None,
) -> Path:
    """Plot both runs with their fitted lines, deviation in um against position in mm.

    With ``overlay``, the runs of another squareness test of the same plane (e.g. before
    compensation) and their lines are drawn behind, grey: the runs as hollow points, the lines dashed.

    Parameters
    ----------
    path : str or Path
        Image to write (format from the suffix).
    result : SquarenessResult
        From :func:`axiscal.squareness.evaluation.squareness` (it carries both fitted lines).
    runs : ((position_m, deviation_m), (position_m, deviation_m))
        The first and the second run, metres.
    overlay : mapping, keyword-only
        The other test's runs: ``first`` and ``second``, each a mapping of ``position_mm``,
        ``deviation_um`` and ``line_um`` (its fitted line at each position), shape (m,); and an
        optional ``label`` for the legend (default "before").

    Returns
    -------
    Path
        The image written.

    Raises
    ------
    AxiscalError
        An unknown image format or a file that cannot be written; an overlay whose series are not
        lists of numbers of one length per run.
    """
    from axiscal.squareness.evaluation import SquarenessResult

    path = check_path("path", path)
    if not isinstance(result, SquarenessResult) or result.first_line is None or result.second_line is None:
        raise AxiscalError("result must be a SquarenessResult fitted to data (squareness or squareness_from_files)")
    if isinstance(runs, (str, bytes)) or not hasattr(runs, "__len__") or len(runs) != 2 or any(
        isinstance(run, (str, bytes)) or not hasattr(run, "__len__") or len(run) != 2 for run in runs
    ):
        raise AxiscalError("runs must be ((position_m, deviation_m), (position_m, deviation_m)), one pair per run")
    runs = tuple(
        (check_array(f"runs[{k}] position_m", x, ndim=1, min_len=1), check_array(f"runs[{k}] deviation_m", y, ndim=1, min_len=1))
        for k, (x, y) in enumerate(runs)
    )
    before = [None, None] if overlay is None else _squareness_overlay(overlay)
    label = None if overlay is None else overlay_label(overlay)
    plt = pyplot()
    a, b = PLANES[result.plane][:2]
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.6), constrained_layout=True)
    for ax, (position, deviation), line, (moving, across), other in zip(
        axes, runs, (result.first_line, result.second_line), ((a, b), (b, a)), before
    ):
        if other is not None:
            x_before, y_before, line_before = other
            ax.plot(x_before, y_before, "o", ms=4, mfc="none", mec=OVERLAY_STYLE["color"], label=f"{label}: measured")
            if line_before is not None:
                ax.plot(x_before, line_before, **OVERLAY_STYLE, label=f"{label}: line")
        ax.plot(position / MM, deviation / UM, "o", ms=4, label="measured")
        ends = np.array([position.min(), position.max()])
        ax.plot(ends / MM, (line.slope * ends + line.intercept_m) / UM, "-", label=f"{line.reference} line")
        set_up_axes(ax, xlabel=f"{moving} position / mm", ylabel=f"deviation along {across} / µm", grid=True, legend=True,
                    title=f"{moving} run: slope {line.slope:+.3e} ({math.atan(line.slope) / ARCSEC:+.2f} arcsec)")
    # the judged figure under the name and sign the report's tables give it (docs/conventions.md)
    fig.suptitle(
        f"{a}{b} squareness: {result.name} = {result.squareness_rad / ARCSEC:+.2f} arcsec"
        f"  (included angle {math.degrees(result.included_angle_rad):.6f} deg)"
    )
    return save_figure(fig, path, dpi=110)


def plot_pentaprism(path: str | Path, table: PentaprismSensitivity) -> Path:
    """Paper 002 Fig. 5: the change of the prism's deviation against rotation about X, Y, Z, and against shifts.

    Parameters
    ----------
    path : str or Path
        Image to write (format from the suffix).
    table : PentaprismSensitivity
        From :func:`axiscal.instruments.optics.pentaprism_sensitivity`.

    Returns
    -------
    Path
        The image written.

    Raises
    ------
    AxiscalError
        An unknown image format or a file that cannot be written.
    """
    path = check_path("path", path)
    check_instance("table", table, PentaprismSensitivity, what="a PentaprismSensitivity (pentaprism_sensitivity)")
    plt = pyplot()
    fig, axes = plt.subplots(1, 4, figsize=(13, 3.6), sharey=True, constrained_layout=True)
    rotation_arcmin = table.rotation_rad / ARCMIN
    for k, ax in enumerate(axes[:3]):
        ax.plot(rotation_arcmin, table.change_rad[k] / ARCSEC, "-o", ms=3, label="ray trace")
        set_up_axes(ax, xlabel="rotation / arcmin", title=f"({'abc'[k]}) rotation about {'XYZ'[k]}", grid=True)
    fine = np.linspace(table.rotation_rad.min(), table.rotation_rad.max(), 200)
    axes[2].plot(fine / ARCMIN, -(fine**2) / ARCSEC, "--", color="tab:red", label="eq (12): -gamma^2 (rad)")
    set_up_axes(axes[2], legend=True, legend_options={"loc": "lower center"})
    for k, marker in enumerate("os^"):
        # falling marker sizes keep all three visible where they coincide (all zero)
        axes[3].plot(table.translation_m / MM, table.translation_change_rad[k] / ARCSEC, marker + "-", ms=8 - 2 * k,
                     label=f"along {'XYZ'[k]}")
    set_up_axes(axes[3], xlabel="shift / mm", title="(d) translation: no effect", grid=True, legend=True,
                legend_options={"loc": "lower center"})
    set_up_axes(axes[0], ylabel="angle between beams - 90 deg / arcsec")
    fig.suptitle(f"pentaprism of paper 002, index {table.index:g}: incident beam [-1, 0, 0]")
    return save_figure(fig, path, dpi=110)
