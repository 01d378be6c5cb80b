"""The figure of ``axiscal on-the-fly --plot``: each target's deviation as the axis passed it, and its speed.

It takes the :class:`~axiscal.capture.on_the_fly.OnTheFly` result and draws; targets in mm,
deviations in um, speeds in mm/min.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from axiscal.capture.on_the_fly import OnTheFly
from axiscal.io.arguments import check_instance, check_path
from axiscal.io.figures import pyplot, save_figure, set_up_axes
from axiscal.units import MM, UM

__all__ = ["plot_on_the_fly"]


def plot_on_the_fly(path: str | Path, result: OnTheFly) -> Path:
    """Plot the deviations of each direction against the target (top) and the speed at each crossing (bottom).

    Parameters
    ----------
    path : str or Path
        Image to write (format from the suffix).
    result : OnTheFly
        What :func:`axiscal.capture.on_the_fly.on_the_fly` returned.

    Returns
    -------
    Path
        The image written.

    Raises
    ------
    AxiscalError
        A result of the wrong kind, an unknown image format or a file that cannot be written.
    """
    check_instance("result", result, OnTheFly, what="an OnTheFly (on_the_fly)")
    path = check_path("path", path)
    capture = result.capture
    k = np.array([r.index for r in capture.readings], dtype=int)
    target = capture.steps.target_m[k] / MM
    deviation = np.array([r.deviation_m for r in capture.readings]) / UM
    direction = capture.steps.direction[k]
    plt = pyplot()
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(7, 6), sharex=True, height_ratios=(3, 1))
    for d, marker in (("+", "^"), ("-", "v")):
        sel = direction == d
        if sel.any():
            top.plot(target[sel], deviation[sel], marker, ms=4, ls="none", label=f"{d} direction")
            bottom.plot(target[sel], np.abs(result.speed_m_s[sel]) / MM * 60, marker, ms=4, ls="none")
    set_up_axes(top, ylabel="deviation (raw reading) / µm", title_size=9, legend=True,
                title=f"On the fly: delay {result.delay_s * 1e3:.3f} ms {'estimated' if result.delay_estimated else 'given'},"
                      f" reading fitted over {result.window_s * 1e3:.3g} ms")
    set_up_axes(bottom, xlabel="target / mm", ylabel="speed / (mm/min)")
    bottom.set_ylim(0.0, 1.15 * float(np.max(np.abs(result.speed_m_s))) / MM * 60 if result.speed_m_s.size else 1.0)
    bottom.ticklabel_format(axis="y", useOffset=False, style="plain")
    fig.tight_layout()
    return save_figure(fig, path)
