"""The figure of ``axiscal thermal etve|drift --plot``: the displacements over time above the temperatures.

Drawn through :func:`axiscal.io.figures.pyplot` and saved atomically; time in hours,
displacements in um, tilts in urad, temperatures in degC; heating phases shaded.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_instance, check_path
from axiscal.io.figures import pyplot, save_figure, set_up_axes
from axiscal.thermal.files import HOUR, DriftEvaluation, EtveEvaluation, ThermalRun
from axiscal.units import UM, URAD

__all__ = ["plot_thermal", "plot_etve", "plot_drift"]


def plot_thermal(path: str | Path, run: ThermalRun, *, title: str = "") -> Path:
    """Plot a thermal run: displacements (top; tilts on a right-hand axis) and temperatures (bottom).

    Parameters
    ----------
    path : str or Path
        Image to write (format from the suffix).
    run : ThermalRun
        The run (:func:`axiscal.thermal.read_thermal_run`).
    title : str, keyword-only
        The figure's title.

    Returns
    -------
    Path
        The image written.

    Raises
    ------
    AxiscalError
        A run of the wrong kind, a title that is not a text, an unknown image format, a file that
        cannot be written.
    """
    check_instance("run", run, ThermalRun, what="a ThermalRun (read_thermal_run)")
    if not isinstance(title, str):
        raise AxiscalError(f"title must be a text, not {title!r}")
    path = check_path("path", path)
    plt = pyplot()
    hours = run.time_s / HOUR
    rows = 2 if run.temperatures_c else 1
    fig, axes = plt.subplots(rows, 1, figsize=(8, 5.5 if rows == 2 else 3.4), sharex=True, squeeze=False)
    top = axes[0, 0]
    for name, d in run.displacements.items():
        if name in "XYZ":
            top.plot(hours, d / UM, label=name)
    tilts = {k: v for k, v in run.displacements.items() if k in "AB"}
    if tilts:
        right = top.twinx()
        for name, d in tilts.items():
            right.plot(hours, d / URAD, "--", label=f"{name} (urad)")
        set_up_axes(right, ylabel="tilt / urad", legend=True, legend_options={"loc": "lower right"})
    set_up_axes(top, ylabel="displacement / µm", title=title, title_size=10, grid=True, legend=True,
                legend_options={"loc": "upper left"})
    if run.running is not None:
        on = np.asarray(run.running) == 1
        for ax in axes[:, 0]:
            ax.fill_between(hours, 0, 1, where=on, step="post", color="orange", alpha=0.12,
                            transform=ax.get_xaxis_transform(), label="_heating")
    if rows == 2:
        bottom = axes[1, 0]
        for place, temperature in run.temperatures_c.items():
            bottom.plot(hours, temperature, label=place)
        set_up_axes(bottom, ylabel="temperature / degC", grid=True, legend=True, legend_options={"ncol": 3})
    set_up_axes(axes[-1, 0], xlabel="time / h")
    fig.tight_layout()
    return save_figure(fig, path)


def _figures(values: dict, fmt: str) -> str:
    return ", ".join(f"{k} {v / (URAD if k in 'AB' else UM):{fmt}} {'urad' if k in 'AB' else 'um'}" for k, v in values.items())


def plot_etve(path: str | Path, evaluation: EtveEvaluation) -> Path:
    """Plot an ETVE run (:func:`plot_thermal`) titled with its ETVE per direction.

    Parameters
    ----------
    path : str or Path
        Image to write (format from the suffix).
    evaluation : EtveEvaluation
        What :func:`axiscal.thermal.evaluate_etve` gave.

    Returns
    -------
    Path

    Raises
    ------
    AxiscalError
        An evaluation of another kind, an unknown image format, a file that cannot be written.
    """
    check_instance("evaluation", evaluation, EtveEvaluation, what="an EtveEvaluation (evaluate_etve)")
    return plot_thermal(path, evaluation.run, title="ETVE " + _figures(evaluation.result.etve, ".2f"))


def plot_drift(path: str | Path, evaluation: DriftEvaluation) -> Path:
    """Plot a thermal drift run (:func:`plot_thermal`) titled with its largest drift per direction.

    Parameters
    ----------
    path : str or Path
        Image to write (format from the suffix).
    evaluation : DriftEvaluation
        What :func:`axiscal.thermal.evaluate_drift` gave.

    Returns
    -------
    Path

    Raises
    ------
    AxiscalError
        An evaluation of another kind, an unknown image format, a file that cannot be written.
    """
    check_instance("evaluation", evaluation, DriftEvaluation, what="a DriftEvaluation (evaluate_drift)")
    return plot_thermal(path, evaluation.run, title="Thermal drift, " + _figures(evaluation.result.drift_max, "+.2f")
                        + " (largest)")
