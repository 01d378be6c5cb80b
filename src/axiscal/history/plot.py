"""The trend plot of a figure: its values with U as error bars, the drift line and its band, the tolerance.

No standard clause: the control-chart picture of ILAC-G24 / OIML D 10 (2007), method 2. The plot
takes a :class:`~axiscal.history.trend.Trend`; the trend does not know its plot.
"""

from __future__ import annotations

import datetime as _dt
from pathlib import Path

import numpy as np

from axiscal.history.trend import Trend, date_of, years
from axiscal.io.arguments import check_instance
from axiscal.io.figures import check_figure_path, pyplot, save_figure, set_up_axes

__all__ = ["plot_trend"]


def plot_trend(trend: Trend, path: str | Path) -> Path:
    """Write the trend plot of ``trend`` to ``path`` (format from its suffix).

    Parameters
    ----------
    trend : Trend
    path : str or Path
        ``.png``, ``.svg``, ``.pdf`` ...

    Returns
    -------
    Path

    Raises
    ------
    AxiscalError
        For a ``trend`` that is not a Trend or a path whose suffix is not a figure format.
    """
    check_instance("trend", trend, Trend)
    path = check_figure_path(path)
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(7.5, 4.0))
    t = np.array([years(d) for d in trend.dates])
    end = max([t[-1]] + [years(d) for d in (trend.next_date, trend.crossing_date) if d is not None])
    end = min(end, t[-1] + 3.0)
    grid = np.linspace(t[0], end + 0.05 * (end - t[0] + 1e-9), 200)
    dates = [date_of(x) for x in grid]
    line, band = trend.fit.at(grid), trend.k * trend.fit.u_at(grid)
    U = np.where(np.isfinite(trend.U), trend.U, 0.0)
    ax.errorbar(list(trend.dates), trend.values, yerr=U, fmt="o", color="k", capsize=3, label="campaigns (U, k=2)")
    ax.plot(dates, line, color="tab:blue", label=f"drift {trend.fit.b:+.3g} {trend.unit}/year")
    ax.fill_between(dates, line - band, line + band, color="tab:blue", alpha=0.15, label=f"line ± {trend.k:g} u")
    # the limits the trend holds against: +tolerance only for a figure that cannot be negative
    for limit in trend.limits:
        if np.min(line - band) <= limit <= np.max(line + band) or limit == trend.tolerance * np.sign(trend.fit.b or 1) \
                or trend.one_sided:
            ax.axhline(limit, color="tab:red", linestyle="--", linewidth=1,
                       label=f"tolerance {limit:+g} {trend.unit}".rstrip())
    if trend.crossing_date is not None and trend.crossing_date <= dates[-1]:
        ax.axvline(trend.crossing_date, color="tab:red", linewidth=1, label=f"crossing {trend.crossing_date}")
    ax.axvline(trend.next_date, color="tab:green", linewidth=1, label=f"next calibration {trend.next_date}")
    set_up_axes(ax, xlabel="date", ylabel=f"{trend.figure} / {trend.unit}" if trend.unit else trend.figure,
                title=f"{trend.machine}: {trend.figure}", title_size=10, legend=True,
                legend_options={"fontsize": 7, "loc": "best"})
    ax.set_xlim(_dt.date.fromordinal(dates[0].toordinal() - 15), dates[-1])
    fig.autofmt_xdate()
    fig.tight_layout()
    return save_figure(fig, path)
