"""The familiar positioning plot: mean deviation per direction with +-k s bands, the runs, the figures.

Plots only; every number comes from :mod:`axiscal.positioning`. matplotlib is imported when a plot
is asked for.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.positioning import Iso230Result, PositioningRun, Vdi3441Result
from axiscal.units import MM, UM


def _format_um(value: float) -> str:
    return "n/a" if not np.isfinite(value) else f"{value / UM:.2f}"


def plot_positioning(run: PositioningRun, result: Iso230Result | Vdi3441Result, path: str | Path, *, title: str = "") -> Path:
    """Write the positioning plot to ``path`` (format from its suffix, e.g. .png, .svg, .pdf).

    Mean deviation per direction against target (um over mm), bands of mean +- k s (k = 2 for
    ISO 230-2:1997 and later, 3 for 1988 and VDI/DGQ 3441), each run as faint points, and the
    axis figures in a table on the figure. Bands are left out when s cannot be estimated.
    """
    from axiscal.cli.common import ensure_parent, pyplot

    plt = pyplot()
    suffix = Path(path).suffix.lstrip(".").lower()
    supported = plt.figure().canvas.get_supported_filetypes()
    plt.close("all")
    if suffix not in supported:
        raise AxiscalError(f"cannot write a plot as '.{suffix}'; use one of .{', .'.join(sorted(supported))}", path=path)
    st = result.stats
    k = result.coverage if isinstance(result, Iso230Result) else 3
    x = run.targets / MM
    fig, (ax, tab) = plt.subplots(1, 2, figsize=(11, 5.2), gridspec_kw={"width_ratios": [3.2, 1]})
    for devs, mean, s, color, label in (
        (run.deviations_up, st.mean_up, st.s_up, "tab:red", "+ (up)"),
        (run.deviations_down, st.mean_down, st.s_down, "tab:blue", "- (down)"),
    ):
        for j in range(devs.shape[1]):
            ax.plot(x, devs[:, j] / UM, ".", color=color, alpha=0.25, markersize=4)
        ax.plot(x, mean / UM, "-o", color=color, markersize=3, label=f"mean {label}")
        if np.all(np.isfinite(s)):
            ax.fill_between(x, (mean - k * s) / UM, (mean + k * s) / UM, color=color, alpha=0.12, label=f"mean {label} ± {k}s")
    ax.plot(x, st.mean / UM, "--", color="0.3", linewidth=1, label="bidirectional mean")
    ax.axhline(0.0, color="0.6", linewidth=0.6)
    ax.set_xlabel("target position / mm")
    ax.set_ylabel("deviation (actual − target) / µm")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, loc="best")
    ax.set_title(title or f"Positioning test, {result.standard}, {run.runs} runs each way")
    rows = [[name, _format_um(value)] for name, value in result.figures().items()]
    tab.axis("off")
    table = tab.table(cellText=rows, colLabels=["figure", "µm"], loc="center", cellLoc="right")
    table.auto_set_font_size(False)
    table.set_fontsize(9)
    table.scale(1.0, 1.25)
    fig.tight_layout()
    out = ensure_parent(path)
    fig.savefig(out, dpi=120)
    plt.close(fig)
    return out
