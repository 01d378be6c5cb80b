"""The figure of ``axiscal flatness --plot``: a contour map of the surface with its lines, and a 3-D view.

Drawn through :func:`axiscal.io.figures.pyplot` and saved atomically; plan coordinates in mm,
heights in um about the least-squares plane.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.flatness.surface import FlatnessSurface
from axiscal.io.arguments import check_instance, check_path
from axiscal.io.figures import pyplot, save_figure, set_up_axes
from axiscal.units import MM, UM

__all__ = ["plot_flatness"]


def plot_flatness(path: str | Path, surface: FlatnessSurface, *, title: str = "") -> Path:
    """Plot the surface: a filled contour map with the measured lines (left), a 3-D view (right).

    Parameters
    ----------
    path : str or Path
        Image to write (format from the suffix).
    surface : FlatnessSurface
        What :func:`axiscal.flatness.surface_from_lines` or :func:`axiscal.flatness.moody_union_jack` returned.
    title : str, keyword-only
        A title above the figure (the flatness figures follow it).

    Returns
    -------
    Path
        The image written.

    Raises
    ------
    AxiscalError
        A surface of the wrong kind, a title that is not a text, an unknown image format, a file
        that cannot be written.
    """
    check_instance("surface", surface, FlatnessSurface, what="a FlatnessSurface")
    if not isinstance(title, str):
        raise AxiscalError(f"title must be a text, not {title!r}")
    path = check_path("path", path)
    plt = pyplot()
    x, y, z = surface.x_m / MM, surface.y_m / MM, surface.z_m / UM
    fig = plt.figure(figsize=(10, 4.4))
    left = fig.add_subplot(1, 2, 1)
    right = fig.add_subplot(1, 2, 2, projection="3d")
    flat = np.ptp(z) == 0.0
    if not flat:
        filled = left.tricontourf(x, y, z, levels=14, cmap="viridis")
        fig.colorbar(filled, ax=left, label="height / µm")
        right.plot_trisurf(x, y, z, cmap="viridis", linewidth=0.2, antialiased=True)
    for line in surface.lines:
        ends = np.array([line.start_m, line.end_m]) / MM
        left.plot(ends[:, 0], ends[:, 1], "-", color="white" if not flat else "gray", lw=0.8)
    left.plot(x, y, "k.", ms=2)
    seen: dict[tuple[float, float], int] = {}
    for closure in surface.closures:
        spot = (round(closure.x_m / MM, 3), round(closure.y_m / MM, 3))
        above = seen.get(spot, 0)
        seen[spot] = above + 1
        left.annotate(f"{closure.value_m / UM:.2f}", spot, xytext=(3, 3 + 8 * above), textcoords="offset points",
                      fontsize=7, color="red")
    left.set_aspect("equal")
    set_up_axes(left, xlabel="x / mm", ylabel="y / mm", title="heights about the least-squares plane (red: closure / µm)",
                title_size=8)
    right.scatter(x, y, z, s=3, color="k")
    set_up_axes(right, xlabel="x / mm", ylabel="y / mm")
    right.set_zlabel("height / µm")  # the third axis of the 3-D view
    zone = surface.zone
    fig.suptitle(f"{title + ': ' if title else ''}flatness {zone.minimum_zone_m / UM:.3f} um (minimum zone), "
                 f"{zone.least_squares_m / UM:.3f} um (least squares), {surface.evaluation}", fontsize=10)
    fig.tight_layout()
    return save_figure(fig, path)
