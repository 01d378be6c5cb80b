"""``axiscal demo``: the main job on the built-in example (paper 000's XZ module).

Writes to the output folder: the error motions plot, the volumetric error map (CSV and PNG) over
the XZ plane, the diagonal check against the (simulated) interferometer readings (CSV and PNG),
paper 000's diagonal experiment with the virtual module (0 and 2 kg), a machine-readable
``summary.json`` and a ``report.md`` that ties them together.
"""

from __future__ import annotations

import json
from importlib import resources
from pathlib import Path

import click
import numpy as np

from axiscal.io.tabular import read_csv, write_csv
from axiscal.model.diagonal import diagonal_check
from axiscal.model.machine import axis_positions_from_grid, load_machine
from axiscal.units import ARCSEC, UM

__all__ = ["builtin_example", "demo_command", "register"]


def builtin_example() -> Path:
    """Folder of the built-in XZ module example (machine.toml, error tables, diagonal readings)."""
    return Path(str(resources.files("axiscal") / "data" / "xz_module"))


@click.command("demo")
@click.option("--output", type=click.Path(file_okay=False), default="axiscal-demo", show_default=True, help="Folder to write to.")
def demo_command(output):
    """Run the volumetric model of paper 000's XZ module and write a report."""
    from axiscal.model.plot import plot_diagonal, plot_error_tables, plot_volumetric

    folder = Path(output)
    folder.mkdir(parents=True, exist_ok=True)
    example = builtin_example()
    machine = load_machine(example / "machine.toml")

    plot_error_tables(machine, folder / "error_motions.png")

    positions = axis_positions_from_grid("X=0:190:5,Z=0:190:5")
    error = machine.volumetric_error(positions)
    magnitude = np.linalg.norm(error, axis=1)
    columns = {"x_mm": positions["X"] * 1e3, "z_mm": positions["Z"] * 1e3}
    columns |= {f"e{c}_um": error[:, i] * 1e6 for i, c in enumerate("xyz")}
    columns["e_um"] = magnitude * 1e6
    write_csv(folder / "volumetric_map.csv", columns, fmt="{:.4f}")
    plot_volumetric(positions, error, folder / "volumetric_map.png", title="Volumetric error of the XZ module (y = -40 mm tool)")

    readings = read_csv(example / "diagonal_laser.csv").numeric("measured_mm") * 1e-3
    diagonal = diagonal_check(machine, {"X": 0.0, "Z": 0.0}, {"X": 0.19, "Z": 0.19}, 19, measured_m=readings)
    write_csv(
        folder / "diagonal.csv",
        {
            "x_mm": diagonal.positions_m["X"] * 1e3,
            "z_mm": diagonal.positions_m["Z"] * 1e3,
            "nominal_mm": diagonal.nominal_m * 1e3,
            "measured_mm": readings * 1e3,
            "model_error_um": diagonal.model_error_m * 1e6,
            "E_BD_um": diagonal.error_before_m * 1e6,
            "E_AD_um": diagonal.error_after_m * 1e6,
        },
    )
    plot_diagonal(diagonal, folder / "diagonal.png", title="Offline model vs interferometer, 2 kg on Z (paper 000 eq 13)")

    from axiscal.measurement.virtual import VirtualModule, diagonal_experiment
    from axiscal.model.plot import plot_diagonal_experiment

    experiments = {}
    for load_kg in (0.0, 2.0):
        experiment = diagonal_experiment(VirtualModule(seed=0, load_kg=load_kg))
        plot_diagonal_experiment(experiment, folder / f"experiment_{load_kg:g}kg.png")
        experiments[load_kg] = experiment

    worst = int(np.argmax(magnitude))
    summary = {
        "machine": machine.name,
        "chain": machine.chain,
        "squareness_EB0Z_arcsec": machine.squareness_rad.get("EB0Z", 0.0) / ARCSEC,
        "volumetric_max_um": float(magnitude[worst] * 1e6),
        "volumetric_max_at_mm": {"X": float(positions["X"][worst] * 1e3), "Z": float(positions["Z"][worst] * 1e3)},
        "volumetric_rms_um": float(np.sqrt(np.mean(magnitude**2)) * 1e6),
        "diagonal_E_BD_range_um": diagonal.range_before_m * 1e6,
        "diagonal_E_AD_range_um": diagonal.range_after_m * 1e6,
        "experiment": {
            f"{load:g}kg": {"before_max_um": e.before_max_m / UM, "after_max_um": e.after_max_m / UM, "scales_only_max_um": e.scales_only_max_m / UM}
            for load, e in experiments.items()
        },
    }
    (folder / "summary.json").write_text(json.dumps(summary, indent=2) + "\n")
    report = f"""# axiscal demo: {machine.name}

Chain `{machine.chain}`, functional point {tuple(round(v * 1e3, 3) for v in machine.tool_m)} mm in the Z
carriage frame, squareness EB0Z = {summary['squareness_EB0Z_arcsec']:.1f} arcsec. Error tables:
`{example / 'x_errors.csv'}`, `{example / 'z_errors.csv'}`.

![error motions](error_motions.png)

## Volumetric error over the XZ plane (5 mm grid)

Largest |e| = {summary['volumetric_max_um']:.2f} um at X = {summary['volumetric_max_at_mm']['X']:.0f} mm,
Z = {summary['volumetric_max_at_mm']['Z']:.0f} mm; RMS over the plane {summary['volumetric_rms_um']:.2f} um.
Values: `volumetric_map.csv` (ex_um, ey_um, ez_um: tool point relative to the workpiece, actual minus
nominal, workpiece frame).

![volumetric map](volumetric_map.png)

## Diagonal check with the offline model (paper 000 eq 13)

19 steps of 10 mm on each axis from (0, 0) to (190, 190) mm. The readings (`diagonal_laser.csv`,
simulated) were taken with 2 kg on the Z slide, while the error tables above were measured without
it: the classic offline calibration. Error before the model E_BD: P-V
{summary['diagonal_E_BD_range_um']:.2f} um; after the offline model E_AD: P-V
{summary['diagonal_E_AD_range_um']:.2f} um, because the tables cannot know what the load does to
the angular errors. Per point: `diagonal.csv`.

![diagonal](diagonal.png)

## Paper 000's experiment in simulation (section 5): the live measurement

The same virtual XZ module (`axiscal.measurement.virtual`, whose true error motions are the tables above)
measured live by its 6-DOF sensors, calibrated, against a simulated interferometer on the
diagonal (19 steps of 10 mm). Measuring the errors while the machine runs follows the load too. Largest diagonal error, before the model
(E_BD) -> after it (E_AD); paper 000: 68 -> 13 um without load, 56 -> 14 um with 2 kg.

| load | before (E_BD) | after (E_AD) | scales only |
|---|---|---|---|
| 0 kg | {summary['experiment']['0kg']['before_max_um']:.1f} um | {summary['experiment']['0kg']['after_max_um']:.2f} um | {summary['experiment']['0kg']['scales_only_max_um']:.1f} um |
| 2 kg | {summary['experiment']['2kg']['before_max_um']:.1f} um | {summary['experiment']['2kg']['after_max_um']:.2f} um | {summary['experiment']['2kg']['scales_only_max_um']:.1f} um |

The simulation holds only what the model covers, so far less is left after the model than in the
paper (docs/measurement.md says why; `axiscal experiment diagonal --help` for variations).

![experiment, no load](experiment_0kg.png)
![experiment, 2 kg](experiment_2kg.png)
"""
    (folder / "report.md").write_text(report)
    click.echo(f"wrote {folder}/report.md")
    click.echo(
        f"  paper 000 experiment (simulated): {summary['experiment']['0kg']['before_max_um']:.1f} -> {summary['experiment']['0kg']['after_max_um']:.2f} um, "
        f"2 kg: {summary['experiment']['2kg']['before_max_um']:.1f} -> {summary['experiment']['2kg']['after_max_um']:.2f} um"
    )
    click.echo(
        f"  volumetric |e| max {summary['volumetric_max_um']:.2f} um; diagonal P-V "
        f"{summary['diagonal_E_BD_range_um']:.2f} um before model, {summary['diagonal_E_AD_range_um']:.2f} um after"
    )


def register(group: click.Group) -> None:
    group.add_command(demo_command)
