"""The familiar positioning plot: mean deviation per direction with +-k s bands, the runs, the figures.

Draws the ISO 230-2 quantities of :mod:`axiscal.positioning.evaluation`: x̄_i↑ and x̄_i↓ against P_i
with their limits x̄ +- k s.

Plots only; every number comes from :mod:`axiscal.positioning.evaluation`. matplotlib is imported when a plot
is asked for.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_instance, check_mapping, check_path
from axiscal.io.figures import overlay_label, pyplot, save_figure, set_up_axes
from axiscal.positioning.evaluation import Iso230Result, PositioningRun, Vdi3441Result
from axiscal.units import ARCSEC, DEG, MM, UM

__all__ = ["plot_positioning"]


#: how the figures table names each axis figure: the standard's typography, then the JSON key
_LABELS = {
    "A_up": "A↑", "A_down": "A↓", "B_mean": r"$\bar{B}$", "E_up": "E↑", "E_down": "E↓",
    "R_up": "R↑", "R_down": "R↓", "S_up": "S↑ (max s↑)", "S_down": "S↓ (max s↓)",
    "Ps_max": "Ps max", "Ps_mean": "Ps mean", "U_max": "U max", "U_mean": "U mean",
}


def _format(value: float, factor: float) -> str:
    return "n/a" if not np.isfinite(value) else f"{value / factor:.2f}"


def plot_positioning(
    run: PositioningRun,
    result: Iso230Result | Vdi3441Result,
    path: str | Path,
    *,
    title: str = "",
    compensated: bool | str = False,
    overlay: Mapping[str, Any] | None = None,
    figures_table: bool = True,
) -> Path:
    """Write the positioning plot to ``path`` (format from its suffix, e.g. .png, .svg, .pdf).

    Mean deviation per direction against target (um over mm; arcsec over degrees for a rotary
    axis; the directions tested only), bands of mean +- k s (k = 2 for
    ISO 230-2:1997 and later, 3 for 1988 and VDI/DGQ 3441), each run as faint points, and the
    axis figures in a table on the figure. Bands are left out, and the plot says so, when s
    cannot be estimated (one run).

    Parameters
    ----------
    run : PositioningRun
        Targets and deviations, metres (plotted in mm and um), or radians for a rotary axis
        (plotted in degrees and arcseconds).
    result : Iso230Result or Vdi3441Result
        The evaluation of ``run`` whose means, s and figures are drawn.
    path : str or Path
        The figure file; its suffix gives the format.
    title : str, keyword-only
        Title of the plot (default: file name, standard, k, targets and runs).
    compensated : bool or str, keyword-only
        Note on the plot what was applied to raw laser readings: a text says it as given
        (:attr:`axiscal.positioning.RunFile.compensation`); True notes the air index only.
    overlay : mapping, keyword-only
        Another test of the same axis to draw behind this one (e.g. before compensation): the
        ``targets`` object of its ``axiscal positioning --json`` (``target_mm`` or ``target_deg``,
        ``mean_up_um``/``mean_down_um`` or the ``_arcsec`` forms), an optional ``label`` for
        the legend (default "before") and an optional ``current_label`` naming this run's curves
        (e.g. "as found" and "as left"). Each direction keeps its own colour, lighter and dashed
        for the overlay; when the overlay spans more than five times this run's range, it is drawn
        in an inset at its own scale so that the main plot stays readable for this run.
    figures_table : bool, keyword-only
        Draw the axis figures in a table beside the plot (default True).

    Returns
    -------
    Path
        ``path``, written atomically.

    Raises
    ------
    AxiscalError
        If matplotlib cannot write the suffix's format, or the file cannot be written.

    Examples
    --------
    >>> run = read_positioning_run("examples/positioning_run.csv").run  # doctest: +SKIP
    >>> plot_positioning(run, iso230_2(run), "positioning.png")  # doctest: +SKIP
    PosixPath('positioning.png')
    """
    check_instance("run", run, PositioningRun)
    check_instance("result", result, (Iso230Result, Vdi3441Result))
    path = check_path("path", path)
    check_instance("title", title, str)
    if result.stats.targets.shape != run.targets.shape:
        raise AxiscalError(f"result has {result.stats.targets.size} targets, the run {run.targets.size}: evaluate this run")
    if overlay is not None:
        check_mapping("overlay", overlay, what="the targets object of axiscal positioning --json")
    plt = pyplot()
    suffix = Path(path).suffix.lstrip(".").lower()
    supported = plt.figure().canvas.get_supported_filetypes()
    plt.close("all")
    if suffix not in supported:
        raise AxiscalError(f"cannot write a plot as '.{suffix}'; use one of .{', '.join(sorted(supported))}", path=path)
    st = result.stats
    k = result.coverage if isinstance(result, Iso230Result) else 3
    x_factor, unit, factor = (DEG, "″", ARCSEC) if run.rotary else (MM, "µm", UM)
    lines = [
        (devs, mean, s, color, arrow)
        for devs, mean, s, color, arrow in (
            (run.deviations_up, st.mean_up, st.s_up, "tab:red", "↑ (+)"),
            (run.deviations_down, st.mean_down, st.s_down, "tab:blue", "↓ (−)"),
        )
        if devs is not None
    ]
    has_s = bool(all(np.all(np.isfinite(s)) for _, _, s, _, _ in lines))
    x = run.targets / x_factor
    if figures_table:
        fig, (ax, tab) = plt.subplots(1, 2, figsize=(11.5, 5.4), gridspec_kw={"width_ratios": [3.2, 1]})
    else:
        fig, ax = plt.subplots(figsize=(9.5, 5.0))
    current = overlay.get("current_label") if overlay and isinstance(overlay.get("current_label"), str) else ""
    named = f"{current}: " if current else ""
    for devs, mean, s, color, arrow in lines:
        ax.plot(np.repeat(x, devs.shape[1]), devs.ravel() / factor, ".", color=color, alpha=0.3, markersize=4)
        ax.plot(x, mean / factor, "-o", color=color, markersize=3, label=f"{named}mean x̄{arrow}")
        if has_s:
            ax.fill_between(x, (mean - k * s) / factor, (mean + k * s) / factor, color=color, alpha=0.12,
                            label=f"x̄{arrow[0]} ± {k}s")
    if run.bidirectional:
        ax.plot(x, st.mean / factor, "--", color="0.3", linewidth=1, label="bidirectional mean x̄")
    if overlay:
        key_unit = "arcsec" if run.rotary else "um"
        targets = overlay.get("target_deg" if run.rotary else "target_mm")
        drawn = []
        for key, color in ((f"mean_up_{key_unit}", _OVERLAY_COLOURS["up"]), (f"mean_down_{key_unit}", _OVERLAY_COLOURS["down"])):
            values = overlay.get(key)
            if targets is not None and values is not None:
                arrow = "↑" if "up" in key else "↓"
                x_over = check_array(f"overlay {'target_deg' if run.rotary else 'target_mm'}", targets, ndim=1, unit="")
                y_over = check_array(f"overlay {key}", [np.nan if v is None else v for v in values], ndim=1, finite=False, unit="")
                if x_over.size != y_over.size:
                    raise AxiscalError(f"overlay {key} must have one value per target, not {y_over.size} for {x_over.size}")
                drawn.append((x_over, y_over, color, f"{overlay_label(overlay)}: mean x̄{arrow}"))
        _draw_overlay(ax, drawn, [d.ravel() / factor for d, _, _, _, _ in lines], unit)
    ax.plot([], [], ".", color="0.5", label="single runs")
    # the legend stays clear of the footnote (lower left) and of an overlay's inset (upper right)
    set_up_axes(ax, xlabel=f"target position / {'degree' if run.rotary else 'mm'}",
                ylabel=f"positional deviation (actual − target) / {'arcsec' if run.rotary else 'µm'}", grid=True,
                zero_line=True, legend=True, legend_options={"loc": "upper left", "framealpha": 0.85})
    way = "each way" if run.bidirectional else f"{run.directions[0]} only"
    runs = f"{run.runs} run{'s' if run.runs != 1 else ''} {way}"
    coverage = f", k = {k}" if isinstance(result, Iso230Result) else ""
    set_up_axes(ax, title=title or f"{Path(run.source).name}: {result.standard}{coverage}, {run.targets.size} targets, {runs}",
                title_size=11)
    notes = []
    if not has_s:
        notes.append("one run per direction: s cannot be estimated, so no ±ks bands, R, A or S")
    if compensated:
        # say what was applied: a run without a material temperature is not normalised to 20 degC
        notes.append(compensated if isinstance(compensated, str) else "raw laser readings compensated for the air index")
    if notes:
        ax.text(0.01, 0.01, "\n".join(notes), transform=ax.transAxes, fontsize=8, va="bottom", color="0.25")
    if figures_table:
        _figures_table(tab, result, unit, factor)
    fig.tight_layout()
    return save_figure(fig, path, dpi=120)


#: the overlay's colour for each direction: the direction's own, lighter (dashed)
_OVERLAY_COLOURS = {"up": "#f4a582", "down": "#92c5de"}
#: an overlay spanning more than this many times the run's range goes into an inset at its own scale
_INSET_RATIO = 5.0


def _draw_overlay(ax, drawn: list, current: list, unit: str) -> None:
    """Draw the overlay's mean curves on the plot, or in an inset when they would flatten this run's."""
    if not drawn:
        return
    values = np.concatenate([v[np.isfinite(v)] for v in current]) if current else np.array([0.0])
    over = np.concatenate([y[np.isfinite(y)] for _, y, _, _ in drawn])
    span = max(float(np.ptp(values)) if values.size else 0.0, 1e-12)
    if over.size and float(np.max(np.abs(over - np.median(values)))) > _INSET_RATIO * span:
        low, high = float(values.min()), float(values.max())
        margin = 0.15 * (high - low or 1.0)
        ax.set_ylim(low - margin, high + margin * 3)
        inset = ax.inset_axes([0.60, 0.58, 0.38, 0.38])
        for x_over, y_over, color, label in drawn:
            ax.plot([], [], linestyle=(0, (4, 2)), color=color, linewidth=1.4, label=f"{label} (inset)")
            inset.plot(x_over, y_over, linestyle=(0, (4, 2)), color=color, linewidth=1.4)
        set_up_axes(inset, title=f"{drawn[0][3].split(':')[0]}, own scale / {unit}", title_size=7, grid=True)
        inset.tick_params(labelsize=6)
        return
    for x_over, y_over, color, label in drawn:
        ax.plot(x_over, y_over, linestyle=(0, (4, 2)), color=color, linewidth=1.4, label=label)


def _figures_table(tab, result: Iso230Result | Vdi3441Result, unit: str, factor: float) -> None:
    rows = [[_LABELS.get(name, name), _format(value, factor)] for name, value in result.figures().items()]
    tab.axis("off")
    table = tab.table(cellText=rows, colLabels=["figure", unit], loc="center", cellLoc="right", colLoc="center")
    table.auto_set_font_size(False)
    table.set_fontsize(9)
    table.scale(1.0, 1.3)
    for (row, col), cell in table.get_celld().items():
        if col == 0 and row > 0:
            cell.set_text_props(ha="left")
            cell.PAD = 0.08
