"""A machine's trends read from the history: one figure for ``history trend``, all for reports.

No standard clause: the stored campaigns fed to :mod:`axiscal.history.trend` (weighted drift fit,
Fieller's crossing interval, ILAC-G24 / OIML D 10 intervals).
"""

from __future__ import annotations

from pathlib import Path

from axiscal.errors import AxiscalError
from axiscal.history.store import MachineHistory, machine_history
from axiscal.history.trend import TREND_METHODS, Trend, trend_of
from axiscal.io.arguments import check_choice, check_instance

__all__ = ["history_trend", "figure_trend", "machine_trends"]


def history_trend(history: MachineHistory, figure: str, *, method: str = "wls", risk: float = 0.05) -> Trend:
    """The trend of one figure of a machine's history.

    Parameters
    ----------
    history : MachineHistory
    figure : str
        ``KIND.AXIS.FIGURE``, e.g. ``positioning.X.E``.
    method : {"wls", "robust"}, keyword-only
    risk : float, keyword-only
        For the fixed-risk interval.

    Returns
    -------
    Trend

    Raises
    ------
    AxiscalError
        When fewer than three campaigns hold the figure, or its latest campaign gives it no
        tolerance.
    """
    check_instance("history", history, MachineHistory)
    check_instance("figure", figure, str, what="a figure key (KIND.AXIS.FIGURE)")
    method = check_choice("method", method, TREND_METHODS)
    series = [(d, f) for d, f in history.series(figure) if f.value is not None]
    if not series and figure not in history.keys:
        known = ", ".join(k for k in history.keys if any(f.tolerance is not None for _, f in history.series(k)))
        raise AxiscalError(f"{history.label} has no figure '{figure}' (toleranced figures: {known or 'none'})")
    if len(series) < 3:
        raise AxiscalError(f"a trend needs three campaigns at least: {history.label} has {len(series)} with "
                           f"'{figure}'")
    tolerance = series[-1][1].tolerance
    if tolerance is None or tolerance <= 0:
        raise AxiscalError(f"'{figure}' of {history.label} has no tolerance in its latest campaign: "
                           "a crossing date needs one")
    return trend_of(history.label, figure, [d for d, _ in series], [f.value for _, f in series],
                    [f.U for _, f in series], tolerance, [f.result == "pass" for _, f in series],
                    unit=series[-1][1].unit, method=method, risk=risk)


def figure_trend(
    machine: str,
    figure: str,
    *,
    url: str | None = None,
    method: str = "wls",
    risk: float = 0.05,
    plot: str | Path | None = None,
) -> Trend:
    """The trend of one figure of a stored machine: what ``axiscal history trend`` does.

    Parameters
    ----------
    machine : str
        Its name, ``name (serial)``, serial or id.
    figure : str
        ``KIND.AXIS.FIGURE``.
    url : str, keyword-only
        The database.
    method : {"wls", "robust"}, keyword-only
    risk : float, keyword-only
        For the fixed-risk interval (default 5 %).
    plot : str or Path, keyword-only
        Also write the trend plot there.

    Returns
    -------
    Trend

    Raises
    ------
    AxiscalError
        As :func:`history_trend` and :func:`~axiscal.history.store.machine_history`.

    Examples
    --------
    >>> trend = figure_trend("VMC 1", "positioning.X.E")  # doctest: +SKIP
    >>> trend.next_date  # doctest: +SKIP
    """
    trend = history_trend(machine_history(machine, url=url), figure, method=method, risk=risk)
    if plot is not None:
        from axiscal.history.plot import plot_trend

        plot_trend(trend, plot)
    return trend


def machine_trends(history: MachineHistory, *, method: str = "wls") -> list[Trend]:
    """The trend of every figure of a machine that has a tolerance and three campaigns.

    Parameters
    ----------
    history : MachineHistory
    method : {"wls", "robust"}, keyword-only

    Returns
    -------
    list of Trend
        In the order the figures first appear; figures with too few campaigns are left out.

    Raises
    ------
    AxiscalError
        For a ``history`` that is not a MachineHistory.
    """
    check_instance("history", history, MachineHistory)
    out = []
    for key in history.keys:
        series = [f for _, f in history.series(key) if f.value is not None]
        if len(series) >= 3 and series[-1].tolerance:
            out.append(history_trend(history, key, method=method))
    return out
