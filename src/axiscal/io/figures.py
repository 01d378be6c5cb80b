"""The one place that imports matplotlib, lazily, and saves figures atomically.

Plot modules of every room call :func:`pyplot` when a plot is asked for, so importing axiscal
never imports matplotlib.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_path
from axiscal.io.atomic import atomic_write

__all__ = ["FIGURE_FORMATS", "check_figure_path", "pyplot", "save_figure"]

#: file suffixes a figure can be written as
FIGURE_FORMATS = ("png", "svg", "pdf", "jpg", "jpeg", "eps", "ps", "tif", "tiff", "webp")


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
