"""The demo job: paper 000's XZ module modelled, checked on its diagonal and measured live in simulation.

Paper 000 (eqs 6-13, section 5) on the built-in example (``axiscal/data/xz_module``): the error
motions of the two axes, the volumetric error over the XZ plane (5 mm grid), the ISO 230-6 diagonal
check of the offline model against simulated interferometer readings taken with 2 kg on Z, and the
paper's diagonal experiment with the virtual module's live measurement (0 and 2 kg). Everything is
written to one folder with a ``summary.json`` and a ``report.md`` rendered from the template
``axiscal/templates/demo_report.md.j2``.
"""

from __future__ import annotations

from dataclasses import dataclass
from importlib import resources
from pathlib import Path
from typing import Any

from axiscal.errors import AxiscalError
from axiscal.io.atomic import write_text
from axiscal.io.jsonio import write_json
from axiscal.measurement.virtual import (
    DiagonalExperiment,
    VirtualModule,
    diagonal_experiment,
)
from axiscal.model.diagonal import DiagonalResult, diagonal_test
from axiscal.model.machine import Machine, load_machine
from axiscal.model.output import render_template
from axiscal.model.plot import plot_diagonal_experiment, plot_error_tables
from axiscal.model.volumetric import VolumetricMap, volumetric_map
from axiscal.units import ARCSEC, MM, UM

__all__ = ["DEMO_FILES", "DemoResult", "builtin_example", "run_demo"]

#: the files the demo writes into its folder
DEMO_FILES = (
    "error_motions.png",
    "volumetric_map.csv",
    "volumetric_map.png",
    "diagonal.csv",
    "diagonal.png",
    "experiment_0kg.png",
    "experiment_2kg.png",
    "summary.json",
    "report.md",
)
_GRID = "X=0:190:5,Z=0:190:5"
_LOADS_KG = (0.0, 2.0)


def builtin_example() -> Path:
    """Folder of the built-in XZ module example (machine.toml, error tables, diagonal readings).

    Returns
    -------
    Path
        The folder inside the installed package.
    """
    return Path(str(resources.files("axiscal") / "data" / "xz_module"))


@dataclass(frozen=True)
class DemoResult:
    """What :func:`run_demo` computed and wrote (SI units in the result objects).

    Attributes
    ----------
    folder : Path
        The output folder.
    machine : Machine
        The XZ module's model.
    volumetric : VolumetricMap
        Volumetric error over the XZ plane.
    diagonal : DiagonalResult
        The offline model's diagonal check against the interferometer readings (2 kg on Z).
    experiments : dict of float to DiagonalExperiment
        Paper 000's experiment simulated with the live measurement, per load in kg (0 and 2).
    summary : dict
        The content of ``summary.json`` (display units, in the key names).
    """

    folder: Path
    machine: Machine
    volumetric: VolumetricMap
    diagonal: DiagonalResult
    experiments: dict[float, DiagonalExperiment]
    summary: dict[str, Any]

    @property
    def files(self) -> dict[str, Path]:
        """Every file written, by name.

        Returns
        -------
        dict of str to Path
        """
        return {name: self.folder / name for name in DEMO_FILES}

    def text(self) -> str:
        """The lines ``axiscal demo`` prints: where the report is and the headline numbers.

        Returns
        -------
        str
            Rendered from the template ``demo_summary.txt.j2``, ending in a newline.
        """
        return render_template("demo_summary.txt.j2", report=self.folder / "report.md", summary=self.summary)


def _summary(machine: Machine, volumetric: VolumetricMap, diagonal: DiagonalResult, experiments: dict) -> dict[str, Any]:
    return {
        "machine": machine.name,
        "chain": machine.chain,
        "squareness_EB0Z_arcsec": machine.squareness_rad.get("EB0Z", 0.0) / ARCSEC,
        "volumetric_max_um": volumetric.max_m / UM,
        "volumetric_max_at_mm": {k: q / MM for k, q in volumetric.max_at_m.items()},
        "volumetric_rms_um": volumetric.rms_m / UM,
        "diagonal_E_BD_range_um": diagonal.range_before_m / UM,
        "diagonal_E_AD_range_um": diagonal.range_after_m / UM,
        "experiment": {
            f"{load:g}kg": {
                "before_max_um": e.before_max_m / UM,
                "after_max_um": e.after_max_m / UM,
                "scales_only_max_um": e.scales_only_max_m / UM,
            }
            for load, e in experiments.items()
        },
    }


def run_demo(output_dir: str | Path = "axiscal-demo", *, example: str | Path | None = None) -> DemoResult:
    """Run the demo job and write its figures, data, ``summary.json`` and ``report.md``.

    Parameters
    ----------
    output_dir : str or Path
        Folder to write to (created if missing; files of the same names are replaced atomically).
    example : str or Path, optional
        Folder holding ``machine.toml``, its error tables and ``diagonal_laser.csv`` (default: the
        built-in XZ module, :func:`builtin_example`). The diagonal runs from X = Z = 0 to
        X = Z = 190 mm in 19 steps; the machine must be an XZ machine covering that travel.

    Returns
    -------
    DemoResult
        The results and the folder; ``DemoResult.files`` lists what was written.

    Raises
    ------
    AxiscalError
        If an input is missing or malformed, or a file cannot be written.

    Examples
    --------
    >>> result = run_demo("axiscal-demo")  # doctest: +SKIP
    >>> round(result.summary["diagonal_E_BD_range_um"], 2)  # doctest: +SKIP
    56.42
    """
    folder = Path(output_dir)
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise AxiscalError(f"cannot make the output folder: {exc.strerror or exc}", path=folder) from None
    example = builtin_example() if example is None else Path(example)
    machine = load_machine(example / "machine.toml")

    plot_error_tables(machine, folder / "error_motions.png")

    volumetric = volumetric_map(machine, grid=_GRID)
    volumetric.write_csv(folder / "volumetric_map.csv", sidecar=False)
    volumetric.plot(folder / "volumetric_map.png", title="Volumetric error of the XZ module (y = -40 mm tool)")

    diagonal = diagonal_test(machine, "X=0,Z=0", "X=190,Z=190", readings=example / "diagonal_laser.csv")
    diagonal.write_csv(folder / "diagonal.csv", sidecar=False)
    diagonal.plot(folder / "diagonal.png", title="Offline model vs interferometer, 2 kg on Z (paper 000 eq 13)")

    experiments = {}
    for load_kg in _LOADS_KG:
        experiment = diagonal_experiment(VirtualModule(seed=0, load_kg=load_kg))
        plot_diagonal_experiment(experiment, folder / f"experiment_{load_kg:g}kg.png")
        experiments[load_kg] = experiment

    summary = _summary(machine, volumetric, diagonal, experiments)
    write_json(folder / "summary.json", summary)
    report = render_template(
        "demo_report.md.j2",
        machine=machine,
        tool_mm=tuple(round(v / MM, 3) for v in machine.tool_m),
        tables=[example / "x_errors.csv", example / "z_errors.csv"],
        summary=summary,
        experiments=experiments,
    )
    write_text(folder / "report.md", report)
    return DemoResult(folder, machine, volumetric, diagonal, experiments, summary)
