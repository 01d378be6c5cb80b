"""Plots of the straightness room: a profile in its zone (ISO 230-1) and a separation (paper 001).

Drawn through :func:`axiscal.io.figures.pyplot` and saved atomically with
:func:`axiscal.io.figures.save_figure`; lengths in mm along and um across, yaw in urad.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.io.arguments import check_array, check_choice, check_instance, check_mapping, check_path
from axiscal.io.figures import OVERLAY_STYLE, overlay_label, overlay_series, pyplot, save_figure, set_up_axes
from axiscal.straightness.reference import REFERENCES, ReferenceLine, reference_line
from axiscal.straightness.separation import Separation
from axiscal.units import ANGLE_UNITS, MM, UM

__all__ = ["plot_straightness", "plot_separation"]

URAD = ANGLE_UNITS["urad"]


def plot_straightness(
    path: str | Path,
    position_m: np.ndarray,
    deviation_m: np.ndarray,
    line: ReferenceLine,
    *,
    overlay: Mapping[str, Any] | None = None,
) -> Path:
    """Plot a profile with its reference line and zone (top) and the residuals about the line (bottom).

    With ``overlay``, another profile of the same axis (e.g. before compensation) is drawn behind,
    dashed grey: its deviation on top and its residuals about its own line below.

    Parameters
    ----------
    path : str or Path
        Image to write (format from the suffix).
    position_m, deviation_m : ndarray, shape (n,)
        The profile, metres.
    line : ReferenceLine
        Its reference line (from :func:`axiscal.straightness.reference.reference_line`).
    overlay : mapping, keyword-only
        The other profile: ``position_mm``, ``deviation_um`` and ``residual_um`` (about its own
        reference line), each shape (m,), null for a missing value, and an optional ``label``
        for the legend (default "before").

    Returns
    -------
    Path
        The image written.

    Raises
    ------
    AxiscalError
        An unknown image format or a file that cannot be written; an overlay whose series are not
        lists of numbers of one length.
    """
    check_instance("line", line, ReferenceLine, what="a ReferenceLine (reference_line)")
    path = check_path("path", path)
    position_m = check_array("position_m", position_m, ndim=1, min_len=1)
    deviation_m = check_array("deviation_m", deviation_m, ndim=1)
    before = None
    if overlay is not None:
        check_mapping("overlay", overlay, what="another profile (position_mm, deviation_um, residual_um)")
        x_before = overlay_series(overlay, "position_mm")
        if x_before is not None:
            before = (x_before, overlay_series(overlay, "deviation_um", length=x_before.size),
                      overlay_series(overlay, "residual_um", length=x_before.size), overlay_label(overlay))
    residual = line.residuals(position_m, deviation_m)
    plt = pyplot()
    order = np.argsort(position_m, kind="stable")
    x = position_m[order]
    fit = line.slope * x + line.intercept_m
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(7, 6), sharex=True, height_ratios=(3, 2))
    if before is not None:
        x_before, deviation_before, residual_before, label = before
        if deviation_before is not None:
            top.plot(x_before, deviation_before, **OVERLAY_STYLE, label=f"{label}: profile")
        if residual_before is not None:
            bottom.plot(x_before, residual_before, **OVERLAY_STYLE, label=f"{label}: about its line")
    top.plot(x / MM, deviation_m[order] / UM, "o-", ms=3, label="profile")
    top.plot(x / MM, fit / UM, "-", label=f"{line.reference} line")
    for bound in (residual.min(), residual.max()):
        top.plot(x / MM, (fit + bound) / UM, "--", color="gray", lw=0.8)
    set_up_axes(top, ylabel="deviation / µm", title=f"straightness {line.straightness_m / UM:.4f} µm ({line.reference})",
                legend=True)
    bottom.plot(x / MM, residual[order] / UM, "o-", ms=3, label="about the line")
    for bound in (residual.min(), residual.max()):
        bottom.axhline(bound / UM, ls="--", color="gray", lw=0.8)
    set_up_axes(bottom, xlabel="position / mm", ylabel="about the line / µm", legend=before is not None)
    fig.tight_layout()
    return save_figure(fig, path, dpi=120)


def _separation_overlay(overlay: Mapping[str, Any]) -> dict[str, Any] | None:
    """The overlay's profile and motion less its profile's least-squares line, um over mm (None when it has no points)."""
    check_mapping("overlay", overlay, what="another separation (position_mm, profile_um, motion_um)")
    x = overlay_series(overlay, "position_mm")
    if x is None:
        return None
    profile = overlay_series(overlay, "profile_um", length=x.size)
    motion = overlay_series(overlay, "motion_um", length=x.size)
    yaw = overlay_series(overlay, "yaw_urad", length=x.size)
    fit = np.isfinite(x) & (np.isfinite(profile) if profile is not None else False)
    if profile is None or int(fit.sum()) < 2 or np.ptp(x[fit]) == 0:
        return None
    line = reference_line(x[fit] * MM, profile[fit] * UM)
    base = (line.slope * x * MM + line.intercept_m) / UM
    return {"x": x, "profile": profile - base, "motion": None if motion is None else motion - base, "yaw": yaw,
            "label": overlay_label(overlay)}


def plot_separation(path: str | Path, result: Separation, *, overlay: Mapping[str, Any] | None = None,
                    reference: str = "least-squares") -> Path:
    """Plot a separation: profile R and motion S about R's least-squares line, and the yaw when resolved.

    R and S share an undetermined straight line, so the same line (the profile's least-squares
    line) is taken from both: what is left is their shape, and S keeps its place relative to R.
    With ``overlay``, another separation of the same set-up (e.g. before compensation) is drawn
    behind, dashed grey, about its own profile's least-squares line.

    Parameters
    ----------
    path : str or Path
        Image to write (format from the suffix).
    result : Separation
        From :func:`axiscal.straightness.separation.separate` or ``reversal``.
    overlay : mapping, keyword-only
        The other separation as ``axiscal separate`` writes its columns: ``position_mm``,
        ``profile_um``, ``motion_um`` and optionally ``yaw_urad``, each shape (m,), null where not
        resolved, and an optional ``label`` for the legend (default "before").
    reference : {"least-squares", "end-points", "minimum-zone"}, keyword-only
        The ISO 230-1 reference line of the straightness each legend entry gives: the figure a
        report's table states for R and for S (each about its own line), not the spread of the
        curve drawn (which keeps S's tilt relative to R).

    Returns
    -------
    Path
        The image written.

    Raises
    ------
    AxiscalError
        An unknown image format or a file that cannot be written; an overlay whose series are not
        lists of numbers of one length.
    """
    check_instance("result", result, Separation, what="a Separation (separate or reversal)")
    path = check_path("path", path)
    before = None if overlay is None else _separation_overlay(overlay)
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
    reference = check_choice("reference", reference, REFERENCES)
    # the legend gives the straightness the report's table gives: each curve about its own reference line
    motion_straightness = (reference_line(x[finite], result.motion_m[finite], reference=reference).straightness_m
                           if finite.sum() >= 2 else np.nan)
    profile_straightness = reference_line(x, result.profile_m, reference=reference).straightness_m
    if before is not None:
        ax.plot(before["x"], before["profile"], **OVERLAY_STYLE, label=f"{before['label']}: profile R")
        if before["motion"] is not None:
            ax.plot(before["x"], before["motion"], **{**OVERLAY_STYLE, "linestyle": (0, (1, 1.5))},
                    label=f"{before['label']}: motion S")
    ax.plot(x / MM, profile / UM, marker, ms=3, label=f"profile R (straightness {profile_straightness / UM:.3f} µm)")
    ax.plot(x / MM, motion / UM, marker, ms=3, label=f"motion S (straightness {motion_straightness / UM:.3f} µm)")
    ax.text(0.01, 0.01, f"straightness: width of the zone about each curve's own {reference} line (ISO 230-1)",
            transform=ax.transAxes, fontsize=7, va="bottom", color="0.3")
    set_up_axes(ax, ylabel="deviation / µm", title=f"error separation: {result.method} (R and S less R's least-squares line)",
                legend=True)
    if has_yaw:
        yaw = axes[1, 0]
        if before is not None and before["yaw"] is not None:
            yaw.plot(before["x"], before["yaw"], **OVERLAY_STYLE, label=f"{before['label']}: yaw")
        yaw.plot(x / MM, result.yaw_rad / URAD, marker, ms=3, color="C2", label="yaw (up to a constant)")
        set_up_axes(yaw, ylabel="yaw / urad", legend=True)
    set_up_axes(axes[-1, 0], xlabel="position along the workpiece / mm")
    fig.tight_layout()
    return save_figure(fig, path, dpi=120)
