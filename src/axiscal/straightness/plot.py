"""Plots of the straightness room: a profile in its zone (ISO 230-1) and a separation (paper 001).

Drawn through :func:`axiscal.io.figures.pyplot` and saved atomically with
:func:`axiscal.io.figures.save_figure`; lengths in mm along and um across, yaw in urad.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from axiscal.io.arguments import check_array, check_instance, check_path
from axiscal.io.figures import pyplot, save_figure
from axiscal.straightness.reference import ReferenceLine, reference_line
from axiscal.straightness.separation import Separation
from axiscal.units import ANGLE_UNITS, MM, UM

__all__ = ["plot_straightness", "plot_separation"]

URAD = ANGLE_UNITS["urad"]


def plot_straightness(path: str | Path, position_m: np.ndarray, deviation_m: np.ndarray, line: ReferenceLine) -> Path:
    """Plot a profile with its reference line and zone (top) and the residuals about the line (bottom).

    Parameters
    ----------
    path : str or Path
        Image to write (format from the suffix).
    position_m, deviation_m : ndarray, shape (n,)
        The profile, metres.
    line : ReferenceLine
        Its reference line (from :func:`axiscal.straightness.reference.reference_line`).

    Returns
    -------
    Path
        The image written.

    Raises
    ------
    AxiscalError
        An unknown image format or a file that cannot be written.
    """
    check_instance("line", line, ReferenceLine, what="a ReferenceLine (reference_line)")
    path = check_path("path", path)
    position_m = check_array("position_m", position_m, ndim=1, min_len=1)
    deviation_m = check_array("deviation_m", deviation_m, ndim=1)
    residual = line.residuals(position_m, deviation_m)
    plt = pyplot()
    order = np.argsort(position_m, kind="stable")
    x = position_m[order]
    fit = line.slope * x + line.intercept_m
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(7, 6), sharex=True, height_ratios=(3, 2))
    top.plot(x / MM, deviation_m[order] / UM, "o-", ms=3, label="profile")
    top.plot(x / MM, fit / UM, "-", label=f"{line.reference} line")
    for bound in (residual.min(), residual.max()):
        top.plot(x / MM, (fit + bound) / UM, "--", color="gray", lw=0.8)
    top.set_ylabel("deviation / um")
    top.set_title(f"straightness {line.straightness_m / UM:.4f} um ({line.reference})")
    top.legend(fontsize=8)
    bottom.plot(x / MM, residual[order] / UM, "o-", ms=3)
    for bound in (residual.min(), residual.max()):
        bottom.axhline(bound / UM, ls="--", color="gray", lw=0.8)
    bottom.set_ylabel("about the line / um")
    bottom.set_xlabel("position / mm")
    fig.tight_layout()
    return save_figure(fig, path, dpi=120)


def plot_separation(path: str | Path, result: Separation) -> Path:
    """Plot a separation: profile R and motion S about R's least-squares line, and the yaw when resolved.

    R and S share an undetermined straight line, so the same line (the profile's least-squares
    line) is taken from both: what is left is their shape, and S keeps its place relative to R.

    Parameters
    ----------
    path : str or Path
        Image to write (format from the suffix).
    result : Separation
        From :func:`axiscal.straightness.separation.separate` or ``reversal``.

    Returns
    -------
    Path
        The image written.

    Raises
    ------
    AxiscalError
        An unknown image format or a file that cannot be written.
    """
    check_instance("result", result, Separation, what="a Separation (separate or reversal)")
    path = check_path("path", path)
    plt = pyplot()
    x = result.position_m
    line = reference_line(x, result.profile_m)
    profile = line.residuals(x, result.profile_m)
    motion = line.residuals(x, result.motion_m)
    has_yaw = bool(np.any(np.isfinite(result.yaw_rad)))
    marker = "o-" if x.size <= 60 else "-"
    fig, axes = plt.subplots(2 if has_yaw else 1, 1, figsize=(8, 6 if has_yaw else 4), sharex=True, squeeze=False)
    ax = axes[0, 0]
    finite = np.isfinite(motion)
    motion_zone = np.ptp(motion[finite]) if finite.any() else np.nan
    ax.plot(x / MM, profile / UM, marker, ms=3, label=f"profile R (P-V {np.ptp(profile) / UM:.3f} um)")
    ax.plot(x / MM, motion / UM, marker, ms=3, label=f"motion S (P-V {motion_zone / UM:.3f} um)")
    ax.set_ylabel("deviation / um")
    ax.set_title(f"error separation: {result.method} (R and S less R's least-squares line)")
    ax.legend(fontsize=8)
    if has_yaw:
        yaw = axes[1, 0]
        yaw.plot(x / MM, result.yaw_rad / URAD, marker, ms=3, color="C2", label="yaw (up to a constant)")
        yaw.set_ylabel("yaw / urad")
        yaw.legend(fontsize=8)
    axes[-1, 0].set_xlabel("position along the workpiece / mm")
    fig.tight_layout()
    return save_figure(fig, path, dpi=120)
