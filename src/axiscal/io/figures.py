"""The one place that imports matplotlib, lazily, and saves figures atomically.

Plot modules of every room call :func:`pyplot` when a plot is asked for, so importing axiscal
never imports matplotlib. A plot that draws another campaign's series behind its own (an
*overlay*, as ``axiscal report --compare`` asks) reads them with :func:`overlay_series` and draws
them in :data:`OVERLAY_STYLE`, so every kind of plot shows the compared campaign the same way.
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
    "overlay_series",
]

#: file suffixes a figure can be written as
FIGURE_FORMATS = ("png", "svg", "pdf", "jpg", "jpeg", "eps", "ps", "tif", "tiff", "webp")


#: how every plot draws another campaign's series behind its own: a muted purple, dashed
OVERLAY_STYLE = {"color": "#8e7cc3", "linestyle": (0, (4, 2)), "linewidth": 1.2}
#: the legend's name of an overlay that does not say its own
OVERLAY_LABEL = "before"


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
