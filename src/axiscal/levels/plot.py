"""The figure of ``axiscal levels --plot``: the integrated profile in its zone and the readings.

Drawn through :func:`axiscal.io.figures.pyplot` and saved atomically; lengths in mm along the axis
and um across it, angles in urad.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from axiscal.io.arguments import check_instance, check_path
from axiscal.io.figures import pyplot, save_figure, set_up_axes
from axiscal.levels.files import LevelEvaluation
from axiscal.units import MM, UM, URAD

__all__ = ["plot_levels"]


def plot_levels(path: str | Path, evaluation: LevelEvaluation) -> Path:
    """Plot the profile with its reference line and zone (top) and the corrected readings (bottom).

    Parameters
    ----------
    path : str or Path
        Image to write (format from the suffix).
    evaluation : LevelEvaluation
        What :func:`axiscal.levels.evaluate_levels` returned.

    Returns
    -------
    Path
        The image written.

    Raises
    ------
    AxiscalError
        An evaluation of the wrong kind, an unknown image format or a file that cannot be written.
    """
    check_instance("evaluation", evaluation, LevelEvaluation, what="a LevelEvaluation (evaluate_levels)")
    path = check_path("path", path)
    profile, line = evaluation.profile, evaluation.line
    x, z = profile.position_m, profile.deviation_m
    fit = line.slope * x + line.intercept_m
    residual = z - fit
    plt = pyplot()
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(7, 6), sharex=True, height_ratios=(3, 2))
    top.plot(x / MM, z / UM, "o-", ms=3, label="profile from the levels")
    top.plot(x / MM, fit / UM, "-", label=f"{line.reference} line")
    for bound in (residual.min(), residual.max()):
        top.plot(x / MM, (fit + bound) / UM, "--", color="gray", lw=0.8)
    set_up_axes(top, ylabel="deviation / µm", legend=True,
                title=f"straightness {line.straightness_m / UM:.3f} µm, angular error {profile.angular_error_rad / URAD:.2f} µrad")
    middle = profile.reading_position_m + 0.5 * profile.foot_m
    bottom.step(middle / MM, profile.angle_rad / URAD, where="mid")
    bottom.axhline(float(np.mean(profile.angle_rad)) / URAD, ls="--", color="gray", lw=0.8)
    set_up_axes(bottom, xlabel="position / mm", ylabel="reading / urad")
    fig.tight_layout()
    return save_figure(fig, path)
