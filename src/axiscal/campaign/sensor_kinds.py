"""Campaign kinds of the 6-DOF sensors: a recording, their calibration runs, paper 000's diagonal experiment."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from axiscal.campaign.config import Campaign, TestSpec
from axiscal.campaign.results import Figure, Plot, TestResult, check_figures
from axiscal.campaign.svg import relative_name, svg_of
from axiscal.units import MM, UM

__all__: list[str] = []


def _sixdof(campaign: Campaign, spec: TestSpec) -> TestResult:
    from axiscal.measurement.offline import measure_file

    path = spec.options["file"]
    machine = spec.options.get("machine")
    result = measure_file(path, machine=machine)
    figures = result.summary()
    svg = svg_of(lambda p: _plot_recording(result, p))
    files = [relative_name(campaign, path)] + ([relative_name(campaign, machine)] if machine is not None else [])
    return TestResult(
        id=spec.id, kind=spec.kind, axis=spec.axis, files=files, figures=figures, checks=[],
        plots=[Plot("Spatial error of the functional point during the recording", svg)],
        table=[Figure("frames", figures["frames"], ""), Figure("faulty frames", figures["faulty_frames"], ""),
               Figure("largest spatial error |e|", figures["max_e_um"], "um"),
               Figure("mean spatial error |e|", figures["mean_e_um"], "um")],
        method="6-DOF measurement from raw sensor frames: the six error motions of each axis (ISO 230-1) in a homogeneous transformation model",
    )


def _sensor_calibration(campaign: Campaign, spec: TestSpec) -> TestResult:
    from axiscal.measurement.sensor_runs import calibrate_sensor_runs

    path = spec.options["file"]
    machine = spec.options.get("machine")
    runs = calibrate_sensor_runs(path, machine=machine)
    figures = runs.figures()
    checks = check_figures(figures, spec.tolerances, {"calibration_um": "um", "calibration_arcsec": "arcsec"},
                           rule=campaign.decision_rule)
    table = []
    for row in runs.rows():
        figures[f"{row['channel']}_gain"] = row["gain"]
        figures[f"{row['channel']}_residual_max_{row['unit']}"] = row["residual_max"]
        if row["residual_max_arcsec"] is not None:
            figures[f"{row['channel']}_residual_max_arcsec"] = row["residual_max_arcsec"]
        table.append(Figure(f"{row['channel']}: gain", row["gain"], ""))
        table.append(Figure(f"{row['channel']}: largest residual", row["residual_max"], row["unit"]))
        if row["residual_max_arcsec"] is not None:
            table.append(Figure(f"{row['channel']}: largest residual as an angle", row["residual_max_arcsec"], "arcsec"))
    files = [relative_name(campaign, path)] + ([relative_name(campaign, machine)] if machine is not None else [])
    return TestResult(
        id=spec.id, kind=spec.kind, axis=None, files=files, figures=figures, checks=checks, plots=[], table=table,
        method="Sensor calibration against reference instruments: least-squares gain and offset of each channel",
    )


def _sixdof_diagonal(campaign: Campaign, spec: TestSpec) -> TestResult:
    from axiscal.measurement.sensor_diagonal import sensor_diagonal
    from axiscal.model.inputs import parse_point

    options = spec.options
    readings, frames, machine = options["file"], options["frames"], options.get("machine")
    result = sensor_diagonal(readings, frames, start=parse_point(options["from"], "from"), end=parse_point(options["to"], "to"),
                             machine=machine)
    figures = result.figures()
    title = f"Diagonal {options['from']} to {options['to']} with the 6-DOF sensors (ISO 230-6 diagonal displacement)"
    svg = svg_of(lambda p: _plot_sensor_diagonal(result, p))
    files = [relative_name(campaign, readings), relative_name(campaign, frames)] + ([relative_name(campaign, machine)] if machine else [])
    return TestResult(
        id=spec.id, kind=spec.kind, axis=None, files=files, figures=figures, checks=[], plots=[Plot(title, svg)],
        table=[Figure("largest error before the model (E_BD)", figures["E_BD_max_um"], "um"),
               Figure("largest error left with the measured spatial error (E_AD)", figures["E_AD_max_um"], "um"),
               Figure("largest error left with the scales alone", figures["scales_only_max_um"], "um"),
               Figure("stops", figures["stops"], ""), Figure("frames per stop", figures["samples_per_stop"], "")],
        method="Diagonal displacement test (ISO 230-6) against a laser interferometer, with the live 6-DOF measurement",
    )


def _plot_sensor_diagonal(result, path: Path) -> None:
    from axiscal.io.figures import pyplot, save_figure, set_up_axes

    plt = pyplot()
    along = np.hypot(result.x_m, result.z_m) / MM
    fig, ax = plt.subplots(figsize=(7.5, 3.4))
    ax.plot(along, result.before_m / UM, "o-", label="E_BD: before the model")
    ax.plot(along, result.scales_only_m / UM, "s--", label="scales alone")
    ax.plot(along, result.after_m / UM, "k^-", label="E_AD: with the measured spatial error")
    set_up_axes(ax, xlabel="nominal displacement along the diagonal / mm", ylabel="error / µm", grid=True, legend=True)
    fig.tight_layout()
    save_figure(fig, path)


def _plot_recording(result, path: Path) -> None:
    from axiscal.io.figures import pyplot, save_figure, set_up_axes

    plt = pyplot()
    r = result.results
    good = result.fault == 0
    fig, ax = plt.subplots(figsize=(7.5, 3.4))
    for name in ("ex_m", "ey_m", "ez_m", "e_m"):
        if name in r:
            ax.plot(r["t_s"][good], r[name][good] / UM, "k" if name == "e_m" else "-", lw=1.2 if name == "e_m" else 0.9,
                    label="|e|" if name == "e_m" else name[:2])
    bad = ~good
    if bad.any():
        ax.plot(r["t_s"][bad], np.zeros(int(bad.sum())), "rx", label="faulty frame")
    set_up_axes(ax, xlabel="time / s", ylabel="error / µm", grid=True, legend=True, legend_options={"ncol": 5})
    fig.tight_layout()
    save_figure(fig, path)
