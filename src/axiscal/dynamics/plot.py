"""The figures of ``axiscal dynamics --plot`` and ``axiscal periodic --plot``: they take the results and draw.

Drawn through :func:`axiscal.io.figures.pyplot` and saved atomically; positions in mm, deviations
in um, speeds in mm/s.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from axiscal.dynamics.analysis import AxisDynamics
from axiscal.dynamics.periodic import PeriodicError
from axiscal.io.arguments import check_instance, check_path
from axiscal.io.figures import pyplot, save_figure, set_up_axes
from axiscal.units import MM, UM

__all__ = ["plot_dynamics", "plot_periodic"]


def plot_dynamics(path: str | Path, result: AxisDynamics) -> Path:
    """Plot position, velocity and acceleration over time (stops marked) and the Welch spectrum.

    Parameters
    ----------
    path : str or Path
        Image to write (format from the suffix).
    result : AxisDynamics
        What :func:`axiscal.dynamics.axis_dynamics` returned.

    Returns
    -------
    Path
        The image written.

    Raises
    ------
    AxiscalError
        A result of the wrong kind, an unknown image format or a file that cannot be written.
    """
    check_instance("result", result, AxisDynamics, what="an AxisDynamics (axis_dynamics)")
    path = check_path("path", path)
    d, s = result.derivatives, result.spectrum
    every = max(1, d.time_s.size // 2000)  # at most some 2000 points a line: the figure shows the shape, not each sample
    t = d.time_s[::every]
    plt = pyplot()
    fig, axes = plt.subplots(4, 1, figsize=(8, 9))
    fig.subplots_adjust(left=0.11, right=0.97, top=0.96, bottom=0.06, hspace=0.45)
    axes[0].plot(t, d.position_m[::every] / MM, lw=0.8)
    for stop in result.stops:
        axes[0].axvspan(stop.arrival_s, stop.arrival_s + (stop.settling_s if np.isfinite(stop.settling_s) else 0.0),
                        color="tab:orange", alpha=0.4, lw=0)
    set_up_axes(axes[0], ylabel="position / mm", title_size=9,
                title=f"Savitzky-Golay {d.window_s * 1e3:.3g} ms, degree {d.polyorder}, bandwidth {d.bandwidth_hz:.3g} Hz;"
                " settling shaded")
    axes[1].plot(t, d.velocity_m_s[::every] / MM, lw=0.8)
    set_up_axes(axes[1], ylabel="velocity / (mm/s)")
    axes[2].plot(t, d.acceleration_m_s2[::every], lw=0.8)
    set_up_axes(axes[2], xlabel="time / s", ylabel="acceleration / (m/s^2)")
    axes[3].loglog(s.frequency_hz[1:], s.density_m_rthz[1:] / UM, lw=0.8)
    set_up_axes(axes[3], xlabel="frequency / Hz", ylabel="µm/√Hz", title_size=9,
                title=f"Welch, segments {s.segment_s:.3g} s; peak {s.peak_hz:.3g} Hz")
    return save_figure(fig, path)


def plot_periodic(path: str | Path, result: PeriodicError) -> Path:
    """Plot the mean deviations with the fitted line and sine (top) and the amplitude spectrum (bottom).

    Parameters
    ----------
    path : str or Path
        Image to write (format from the suffix).
    result : PeriodicError
        What :func:`axiscal.dynamics.periodic_error` returned.

    Returns
    -------
    Path
        The image written.

    Raises
    ------
    AxiscalError
        A result of the wrong kind, an unknown image format or a file that cannot be written.
    """
    check_instance("result", result, PeriodicError, what="a PeriodicError (periodic_error)")
    path = check_path("path", path)
    plt = pyplot()
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(7, 6))
    for c in result.components:
        dense = np.linspace(c.targets_m[0], c.targets_m[-1], 400)
        label = "bidirectional mean" if c.direction == "mean" else f"mean {c.direction}"
        line = top.plot(c.targets_m / MM, c.mean_m / UM, "o", ms=3, label=label)[0]
        top.plot(dense / MM, c.fitted(dense) / UM, "-", color=line.get_color(), lw=0.8)
        bottom.plot(c.periods_m / MM, c.amplitudes_m / UM, color=line.get_color(), lw=0.8, label=label)
    main = result.main
    set_up_axes(top, xlabel="target / mm", ylabel="deviation / µm", legend=True, title_size=9,
                title=f"periodic error {2 * main.amplitude_m / UM:.3g} µm peak to peak, period {main.period_m / MM:.4g} mm"
                f" (spectrum: {main.spectrum_period_m / MM:.4g} mm)")
    set_up_axes(bottom, xlabel="period / mm", ylabel="amplitude / µm", legend=True)
    fig.tight_layout()
    return save_figure(fig, path)
