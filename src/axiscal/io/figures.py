"""The one place that imports matplotlib, lazily, and saves figures atomically.

Plot modules of every room call :func:`pyplot` when a plot is asked for, so importing axiscal
never imports matplotlib. A plot that draws another campaign's series behind its own (an
*overlay*, as ``axiscal report --compare`` asks) reads them with :func:`overlay_series` and draws
them in :data:`OVERLAY_STYLE`, so every kind of plot shows the compared campaign the same way.
Every plot labels and dresses its axes through :func:`set_up_axes` (labels, title, a light grid,
a legend, a zero line), so the figures of every room look alike.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_mapping, check_path
from axiscal.io.atomic import atomic_write

__all__ = [
    "FIGURE_FORMATS", "OVERLAY_LABEL", "OVERLAY_STYLE", "check_figure_path", "pyplot", "save_figure", "overlay_label",
    "overlay_series", "GRID_STYLE", "ZERO_LINE_STYLE", "LEGEND_FONT_SIZE", "set_up_axes",
]

#: file suffixes a figure can be written as
FIGURE_FORMATS = ("png", "svg", "pdf", "jpg", "jpeg", "eps", "ps", "tif", "tiff", "webp")


#: how every plot draws another campaign's series behind its own: a muted purple, dashed
OVERLAY_STYLE = {"color": "#8e7cc3", "linestyle": (0, (4, 2)), "linewidth": 1.2}
#: the legend's name of an overlay that does not say its own
OVERLAY_LABEL = "before"

#: the light grid of every plot that has one
GRID_STYLE = {"alpha": 0.3}
#: the line at zero of every plot of deviations about zero
ZERO_LINE_STYLE = {"color": "gray", "lw": 0.5}
#: the legend's font size, points, unless a plot asks for another
LEGEND_FONT_SIZE = 8


def set_up_axes(
    ax: Any,
    *,
    xlabel: str | None = None,
    ylabel: str | None = None,
    title: str | None = None,
    title_size: float | None = None,
    grid: bool = False,
    legend: bool = False,
    legend_options: Mapping[str, Any] | None = None,
    zero_line: bool = False,
) -> Any:
    """Label and dress one matplotlib axes the way every plot of axiscal does.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes, its lines already drawn.
    xlabel, ylabel, title : str, optional, keyword-only
        Axis labels (with their unit, ``"position / mm"``) and the title; None leaves one unset.
    title_size : float, optional, keyword-only
        The title's font size, points (default: matplotlib's).
    grid : bool, keyword-only
        Draw the light grid (:data:`GRID_STYLE`); default False.
    legend : bool, keyword-only
        Draw a legend of the labelled lines (none when no line has a label); default False.
    legend_options : mapping, optional, keyword-only
        Options of ``Axes.legend`` over the default font size :data:`LEGEND_FONT_SIZE`
        (``{"ncol": 3, "loc": "upper left"}``).
    zero_line : bool, keyword-only
        Draw a horizontal line at zero (:data:`ZERO_LINE_STYLE`); default False.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``.

    Examples
    --------
    >>> fig, ax = pyplot().subplots()
    >>> _ = ax.plot([0, 1], [0, 2], label="run")
    >>> set_up_axes(ax, xlabel="position / mm", ylabel="deviation / µm", grid=True, legend=True) is ax
    True
    >>> ax.get_legend().get_texts()[0].get_text(), ax.get_xlabel()
    ('run', 'position / mm')
    >>> pyplot().close(fig)
    """
    if zero_line:
        ax.axhline(0.0, **ZERO_LINE_STYLE)
    if xlabel is not None:
        ax.set_xlabel(xlabel)
    if ylabel is not None:
        ax.set_ylabel(ylabel)
    if title is not None:
        ax.set_title(title, **({} if title_size is None else {"fontsize": title_size}))
    if grid:
        ax.grid(True, **GRID_STYLE)
    if legend and ax.get_legend_handles_labels()[0]:
        ax.legend(**{"fontsize": LEGEND_FONT_SIZE, **(legend_options or {})})
    return ax


def overlay_label(overlay: Mapping[str, Any]) -> str:
    """The legend's name of an overlay: its ``label`` when it is a non-empty text, else :data:`OVERLAY_LABEL`."""
    label = overlay.get("label")
    return label if isinstance(label, str) and label.strip() else OVERLAY_LABEL


def overlay_series(overlay: Mapping[str, Any], key: str, *, length: int | None = None, name: str = "overlay") -> np.ndarray | None:
    """One series of an overlay (another campaign's values, as its results.json holds them).

    Parameters
    ----------
    overlay : mapping
        The overlay: series by key, in the units their keys spell.
    key : str
        The series to take.
    length : int, optional
        The length the series must have (that of another series of the same overlay).
    name : str
        How messages name the overlay.

    Returns
    -------
    ndarray of float, shape (n,), or None
        The values, None (JSON null) read as NaN; None when ``key`` is absent.

    Raises
    ------
    AxiscalError
        For an overlay that is not a mapping, a series that is not a list of numbers or nulls, or
        one of the wrong length.

    Examples
    --------
    >>> overlay_series({"deviation_um": [1.0, None]}, "deviation_um")
    array([ 1., nan])
    """
    check_mapping(name, overlay, what="a mapping of series")
    values = overlay.get(key)
    if values is None:
        return None
    if isinstance(values, (list, tuple)):
        if any(isinstance(v, (bool, np.bool_)) for v in values):
            raise AxiscalError(f"{name} {key} must be numbers (or null), not {values!r:.60}")
        values = [np.nan if v is None else v for v in values]
    series = check_array(f"{name} {key}", values, ndim=1, finite=False, unit="")
    if length is not None and series.size != length:
        raise AxiscalError(f"{name} {key} must have {length} values, one per point, not {series.size}")
    return series


def pyplot():
    """matplotlib.pyplot on the non-interactive Agg backend, imported only when a plot is asked for."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def check_figure_path(path: str | Path) -> Path:
    """``path`` if its suffix names a figure format; otherwise AxiscalError naming the formats."""
    path = check_path("path", path)
    suffix = path.suffix.lower().lstrip(".")
    if suffix not in FIGURE_FORMATS:
        raise AxiscalError(
            f"cannot tell the figure format from '{path.suffix or 'no suffix'}'; end the name in one of"
            f" .{', .'.join(FIGURE_FORMATS)}",
            path=path,
        )
    return path


def save_figure(fig: Any, path: str | Path, *, dpi: int = 120, close: bool = True) -> Path:
    """Save a matplotlib figure to ``path`` atomically (format from the suffix) and close it."""
    path = check_figure_path(path)
    fmt = path.suffix.lstrip(".").lower()
    # reproducible files: no creation date; SVG text stays text (small, searchable, inline-safe)
    metadata = {"Date": None} if fmt in ("svg", "pdf", "eps", "ps") else None
    plt = pyplot()
    try:
        with plt.rc_context({"svg.fonttype": "none", "svg.hashsalt": "axiscal"}):
            return atomic_write(path, lambda target: fig.savefig(target, dpi=dpi, format=fmt, metadata=metadata))
    finally:
        if close:
            pyplot().close(fig)
