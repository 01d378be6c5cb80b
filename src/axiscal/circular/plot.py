"""The polar plot of a ballbar test: both directions about the least-squares circle, the deviation magnified, the figures in a box.

Plots only; every number comes from :mod:`axiscal.circular.report`. matplotlib is imported when a
plot is asked for.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.circular.report import BallbarResult, ballbar_payload, circle_deviations, format_number
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_instance, check_mapping, check_path
from axiscal.io.figures import OVERLAY_STYLE, check_figure_path, overlay_label, overlay_series, pyplot, save_figure
from axiscal.units import MM, UM

__all__ = ["plot_ballbar"]

_COLOURS = {"ccw": "tab:blue", "cw": "tab:red"}


def _nice_ceiling(value: float) -> float:
    """The smallest of 1, 2, 5 times a power of ten that is at least ``value`` (> 0)."""
    exponent = math.floor(math.log10(value))
    for m in (1.0, 2.0, 5.0, 10.0):
        if m * 10.0**exponent >= value * (1 - 1e-12):
            return m * 10.0**exponent
    return 10.0 ** (exponent + 1)


def _figure_lines(result: BallbarResult) -> list[str]:
    p = ballbar_payload(result)
    a, b = p["axes"]
    lines = [
        f"{p['standard']}",
        f"G ccw      {format_number(p['G_ccw_um'], '{:8.2f}')} µm",
        f"G cw       {format_number(p['G_cw_um'], '{:8.2f}')} µm",
        f"H          {format_number(p['H_um'], '{:8.2f}')} µm",
        f"F max      {format_number(p['F_max_um'], '{:8.2f}')} µm",
        f"F min      {format_number(p['F_min_um'], '{:8.2f}')} µm",
        f"centre {a}   {format_number(p['centre_x_um'], '{:8.2f}')} µm",
        f"centre {b}   {format_number(p['centre_y_um'], '{:8.2f}')} µm",
        "",
        f"squareness {format_number(p['squareness_urad'], '{:+8.2f}')} µrad",
        f"scale {a}-{b}  {format_number(p['scale_mismatch_ppm'], '{:+8.2f}')} ppm",
        f"servo {a}-{b}  {format_number(p['servo_mismatch_ms'], '{:+8.3f}')} ms",
    ]
    for axis in (a, b):
        lines.append(f"backlash {axis} {format_number(p['backlash_um'][axis], '{:+8.2f}')} µm")
    for axis in (a, b):
        for d, value in p["reversal_spike_um"][axis].items():
            lines.append(f"spike {axis} {d:<3} {format_number(value, '{:+7.2f}')} µm")
    for axis in (a, b):
        pitch = p["cyclic_pitch_mm"][axis]
        where = f" / {pitch:.2f} mm" if pitch is not None else " (noise)"
        lines.append(f"cyclic {axis}   {format_number(p['cyclic_error_um'][axis], '{:8.2f}')} µm{where}")
    return lines


def _ballbar_overlay(overlay: Mapping[str, Any]) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """Each direction of the overlay as (angle in radians, deviation in um)."""
    check_mapping("overlay", overlay, what="another circular test's trace ({'ccw': ..., 'cw': ...})")
    paths = {}
    for d in ("ccw", "cw"):
        trace = overlay.get(d)
        if trace is None:
            continue
        name = f"overlay['{d}']"
        check_mapping(name, trace, what="a path (angle_deg, deviation_um)")
        angle = overlay_series(trace, "angle_deg", name=name)
        deviation = None if angle is None else overlay_series(trace, "deviation_um", length=angle.size, name=name)
        if deviation is not None and angle.size:
            paths[d] = (np.radians(angle), deviation)
    return paths


def plot_ballbar(result: BallbarResult, path: str | Path, *, title: str = "", overlay: Mapping[str, Any] | None = None) -> Path:
    """Write the polar plot of a ballbar test to ``path`` (format from its suffix, e.g. .png, .svg, .pdf).

    Each direction's path is drawn as its distance from the least-squares centre of all points,
    minus the least-squares radius, magnified: the dashed circle is the least-squares circle and
    the rings mark the deviation scale in µm. Angles run from +first axis (right) towards +second
    axis (up). The ISO 230-4 figures and the diagnostics are listed in a box beside it.

    Parameters
    ----------
    result : BallbarResult
    path : str or Path
        The figure file.
    title : str, keyword-only
        Replaces the default title (file, plane, radius).
    overlay : mapping, keyword-only
        Another circular test of the same plane (e.g. before compensation), drawn behind in grey,
        dashed: ``ccw`` and ``cw``, each a mapping of ``angle_deg`` and ``deviation_um`` (from its
        own least-squares circle), shape (m,); and an optional ``label`` for the legend (default
        "before"). The deviation scale is chosen so both fit.

    Returns
    -------
    Path
        ``path``.

    Raises
    ------
    AxiscalError
        If the suffix names no figure format, or the file cannot be written; an overlay whose
        series are not lists of numbers of one length per direction.
    """
    check_instance("result", result, BallbarResult, what="a BallbarResult (evaluate_ballbar)")
    if not isinstance(title, str):
        raise AxiscalError(f"title must be text, not {title!r}")
    path = check_figure_path(check_path("path", path))
    before = {} if overlay is None else _ballbar_overlay(overlay)
    plt = pyplot()
    trace = result.trace
    deviations = {d: (np.append(a, a[0] + 2 * math.pi), np.append(r, r[0]) / UM) for d, (a, r) in circle_deviations(result).items()}
    span = max(float(np.max(np.abs(r))) for _, r in deviations.values())
    spans = [np.abs(r[np.isfinite(r)]) for _, r in before.values()]
    span = max([span, *(float(v.max()) for v in spans if v.size)])
    limit = _nice_ceiling(max(span, 0.1))
    fig = plt.figure(figsize=(11.0, 6.6))
    ax = fig.add_axes([0.04, 0.08, 0.6, 0.82], projection="polar")
    ax.set_rorigin(-3.0 * limit)
    ax.set_ylim(-limit, limit)
    ax.set_rticks([-limit, -limit / 2, 0.0, limit / 2, limit])
    ax.set_yticklabels([f"{v:+g}" if v else "0" for v in (-limit, -limit / 2, 0.0, limit / 2, limit)], fontsize=7, color="0.35")
    ax.set_rlabel_position(22.5)
    first, second = trace.axes
    ax.set_thetagrids(
        np.arange(0, 360, 45),
        [f"+{first}", "", f"+{second}", "", f"−{first}", "", f"−{second}", ""],
    )
    ring = np.linspace(0, 2 * math.pi, 721)
    ax.plot(ring, np.zeros_like(ring), "--", color="0.2", linewidth=1.0, label="least-squares circle")
    for d, (a, r) in before.items():
        style = OVERLAY_STYLE if d == "ccw" else {**OVERLAY_STYLE, "linestyle": (0, (1, 1.5))}
        ax.plot(a, np.clip(r, -limit, limit), **style, label=f"{overlay_label(overlay)}: {d}")
    for d, (a, r) in deviations.items():
        arrow = "↺" if d == "ccw" else "↻"
        ax.plot(a, np.clip(r, -limit, limit), "-", color=_COLOURS[d], linewidth=1.0, label=f"{d} {arrow}")
    handles, labels = ax.get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower left", bbox_to_anchor=(0.68, 0.1), fontsize=9, framealpha=0.85)
    fig.text(
        0.34, 0.03, f"deviation from the least-squares circle, magnified: rings every {limit / 2:g} µm, outer ring +{limit:g} µm",
        ha="center", fontsize=8.5, color="0.3",
    )
    radius_mm = trace.radius / MM
    ax.set_title(title or f"{Path(trace.source).name}: ballbar in {trace.plane}, radius {radius_mm:g} mm", fontsize=11, pad=18)
    box = fig.add_axes([0.68, 0.06, 0.3, 0.86])
    box.axis("off")
    box.text(
        0.0, 1.0, "\n".join(_figure_lines(result)), va="top", ha="left", family="monospace", fontsize=8.5,
        bbox={"boxstyle": "round,pad=0.6", "facecolor": "0.97", "edgecolor": "0.6"},
    )
    return save_figure(fig, path, dpi=120)
