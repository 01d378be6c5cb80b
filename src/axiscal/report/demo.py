"""The demo job: the closed calibration cycle of paper 000's XZ module on the virtual machine, reported.

As found: :func:`axiscal.measurement.campaign_sim.write_campaign` simulates the sensor calibration,
a 6-DOF recording, straightness by error separation, squareness by pentaprism and the diagonal check
unloaded and with 2 kg; each axis' ISO 230-2 test is planned, written as a LinuxCNC program, run on
the virtual machine and captured stop by stop from the laser's recording
(:func:`axiscal.capture.cycle.measure_axis`); the campaign, with its uncertainty budget, is reported
(report.html, results.json, the LinuxCNC compensation files). As left: those compensation files are
loaded into the virtual controller, each axis is measured again the same way, and the as-left
campaign is reported compared with the as-found results. The as-found campaign also holds paper
000's diagonal experiment with the 6-DOF sensors read at the same stops (eq 13, 0 and 2 kg: the
figures the offline model cannot reach under load). The console lines come from the template
``demo_summary.txt.j2``.
"""

from __future__ import annotations

from dataclasses import dataclass
from importlib import resources
from pathlib import Path
from typing import Any

from axiscal.capture.cycle import measure_axis
from axiscal.capture.virtual import VirtualAxis
from axiscal.io.arguments import check_count, check_path
from axiscal.io.atomic import write_text
from axiscal.io.jsonio import write_json
from axiscal.io.tabular import read_text
from axiscal.io.templates import render_template
from axiscal.measurement.campaign_sim import (
    DIAGONAL_LOADS_KG,
    VACUUM_WAVELENGTH_NM,
    SimulatedCampaign,
    campaign_toml,
    write_campaign,
)
from axiscal.measurement.virtual import STROKE_M
from axiscal.report.writer import ReportFiles, report_campaign
from axiscal.units import UM

__all__ = ["DEMO_FILES", "DEMO_AXES", "DemoResult", "builtin_example", "write_as_found_campaign",
           "write_as_left_campaign", "run_demo"]

#: the main files the demo writes, relative to its folder (the campaigns' data files and the
#: reports' compensation files besides)
DEMO_FILES = (
    "as-found/campaign/campaign.toml",
    "as-found/report/report.html",
    "as-found/report/results.json",
    "as-left/campaign/campaign.toml",
    "as-left/report/report.html",
    "as-left/report/results.json",
    "as-left/report/certificate.html",
    "as-left/report/certificate.pdf",
    "as-left/report/dcc.xml",
    "summary.json",
)
#: the virtual machine's axes in the demo: each with its reversal (the model holds no reversal)
DEMO_AXES = {"X": VirtualAxis(reversal_m=6 * UM), "Z": VirtualAxis(reversal_m=5 * UM)}
#: the demo's controller, whose compensation files the virtual controller loads
CONTROLLER = "linuxcnc"
#: the uncertainty budget both campaigns carry (package data beside the built-in module)
BUDGET = "uncertainty_budget.toml"
#: targets of each axis' ISO 230-2 test over the 190 mm stroke, and runs each way
TARGETS, RUNS = 11, 5
_MODEL = ("machine.toml", "x_errors.csv", "z_errors.csv")


def builtin_example() -> Path:
    """Folder of the built-in XZ module example (machine.toml, error tables, diagonal readings).

    Returns
    -------
    Path
        The folder inside the installed package.
    """
    return Path(str(resources.files("axiscal") / "data" / "xz_module"))


def _campaign_files(folder: Path, seed: int) -> SimulatedCampaign:
    return SimulatedCampaign(folder, seed, tuple(sorted(p.name for p in folder.iterdir() if p.is_file())))


def write_as_found_campaign(folder: str | Path, *, seed: int = 0) -> SimulatedCampaign:
    """The as-found campaign: the simulated campaign with each axis' positioning test captured by axiscal.

    Writes :func:`~axiscal.measurement.campaign_sim.write_campaign`'s folder without its laser runs;
    for X and Z the plan, the LinuxCNC program, the virtual machine's laser recording and the run
    captured from it (:func:`axiscal.capture.cycle.measure_axis`); the uncertainty budget; and a
    campaign.toml that names the budget.

    Parameters
    ----------
    folder : str or Path
        The campaign folder (created if missing; files of the same names are replaced).
    seed : int, keyword-only
        Seed of the virtual module, of the plans and of every simulated reading (default 0).

    Returns
    -------
    SimulatedCampaign

    Raises
    ------
    AxiscalError
        If a folder cannot be made or a file cannot be written.
    """
    folder = check_path("folder", folder)
    seed = check_count("seed", seed, minimum=0)
    write_campaign(folder, seed=seed, laser_runs=False)
    write_text(folder / BUDGET, (builtin_example() / BUDGET).read_text(encoding="utf-8"))
    for k, axis in enumerate(DEMO_AXES):
        measure_axis(folder, folder / "machine.toml", axis=axis, start_m=0.0, end_m=STROKE_M, targets=TARGETS, runs=RUNS,
                     seed=seed, run_seed=seed + 10 * k, spec=DEMO_AXES[axis], wavelength_nm=VACUUM_WAVELENGTH_NM)
    write_text(folder / "campaign.toml", campaign_toml(seed, budget=BUDGET, captured=True))
    return _campaign_files(folder, seed)


def write_as_left_campaign(folder: str | Path, compensation: str | Path, *, seed: int = 0) -> SimulatedCampaign:
    """The as-left campaign: the as-found compensation files loaded, each axis measured again.

    The compensation files are copied into the campaign folder and named by its ``[machine]
    compensation``, so that its model (and the report's volumetric section) is that of the
    compensated machine: what is left.

    Parameters
    ----------
    folder : str or Path
        The campaign folder (created if missing).
    compensation : str or Path
        The folder holding the LinuxCNC compensation files ``X.comp`` and ``Z.comp`` of the as-found report.
    seed : int, keyword-only
        Seed of the plans (the same targets as found) and of the readings (default 0).

    Returns
    -------
    SimulatedCampaign

    Raises
    ------
    AxiscalError
        If a compensation file is missing or refused, a folder cannot be made or a file written.
    """
    folder = check_path("folder", folder)
    compensation = check_path("compensation", compensation)
    seed = check_count("seed", seed, minimum=0)
    for name in (*_MODEL, BUDGET):
        write_text(folder / name, (builtin_example() / name).read_text(encoding="utf-8"))
    files = {}
    for k, axis in enumerate(DEMO_AXES):
        # the files the controller loaded are kept with the campaign: its model is the compensated machine's
        files[axis] = folder / f"{axis}.comp"
        write_text(files[axis], read_text(compensation / f"{axis}.comp"))
        measure_axis(folder, folder / "machine.toml", axis=axis, start_m=0.0, end_m=STROKE_M, targets=TARGETS, runs=RUNS,
                     seed=seed, run_seed=seed + 10 * k + 1, spec=DEMO_AXES[axis], wavelength_nm=VACUUM_WAVELENGTH_NM,
                     compensation=files[axis], controller=CONTROLLER)
    write_text(folder / "campaign.toml", render_template(
        "demo_as_left.toml.j2", keep_trailing_newline=True, seed=seed, budget=BUDGET, controller=CONTROLLER,
        wavelength_nm=VACUUM_WAVELENGTH_NM, axes=tuple(DEMO_AXES), compensation={a: p.name for a, p in files.items()},
    ))
    return _campaign_files(folder, seed)


@dataclass(frozen=True)
class DemoResult:
    """What :func:`run_demo` simulated, reported and wrote.

    Attributes
    ----------
    folder : Path
        The output folder.
    campaign : SimulatedCampaign
        The as-found campaign folder (``folder / "as-found" / "campaign"``).
    report : ReportFiles
        Its report (``folder / "as-found" / "report"``), with its results and compensation files.
    as_left : SimulatedCampaign
        The as-left campaign (``folder / "as-left" / "campaign"``): the compensation loaded, measured again.
    as_left_report : ReportFiles
        Its report, compared with the as-found results (``folder / "as-left" / "report"``).
    summary : dict
        The content of ``summary.json`` (display units in the key names).
    """

    folder: Path
    campaign: SimulatedCampaign
    report: ReportFiles
    as_left: SimulatedCampaign
    as_left_report: ReportFiles
    summary: dict[str, Any]

    @property
    def files(self) -> dict[str, Path]:
        """The main files written, by what they are.

        Returns
        -------
        dict of str to Path
            ``"campaign"``, ``"report"``, ``"results"``, ``"compensation"`` (a folder) of the
            as-found campaign, ``"as_left_campaign"``, ``"as_left_report"``, ``"as_left_results"``,
            ``"certificate"`` (the as-left certificate's PDF), ``"dcc"`` and ``"summary"``.
        """
        return {
            "campaign": self.campaign.toml,
            "report": self.report.html,
            "results": self.report.results,
            "compensation": self.report.folder / "compensation",
            "as_left_campaign": self.as_left.toml,
            "as_left_report": self.as_left_report.html,
            "as_left_results": self.as_left_report.results,
            "certificate": self.as_left_report.folder / "certificate.pdf",
            "dcc": self.as_left_report.dcc,
            "summary": self.folder / "summary.json",
        }

    def text(self) -> str:
        """The lines ``axiscal demo`` prints: where each main file is, the verdict and the headline numbers.

        Returns
        -------
        str
            Rendered from the template ``demo_summary.txt.j2``, ending in a newline.
        """
        return render_template("demo_summary.txt.j2", keep_trailing_newline=True, files=self.files, summary=self.summary)


def _cycle(found: ReportFiles, left: ReportFiles) -> dict[str, Any]:
    """Each toleranced figure of the tests measured both times: before, after, their U and the change."""
    before = {t.id: {c.figure: c for c in t.checks} for t in found.results_data.tests}
    out: dict[str, Any] = {}
    for test in left.results_data.tests:
        for check in test.checks:
            old = before.get(test.id, {}).get(check.figure)
            if old is None:
                continue
            unit = check.unit
            out.setdefault(test.id, {})[f"{check.figure}_{unit}"] = {
                "before": abs(old.value), "after": abs(check.value), "change": abs(check.value) - abs(old.value),
                "U_before": old.U, "U_after": check.U, "limit": check.limit,
            }
    return out


def _summary(report: ReportFiles, as_left: ReportFiles) -> dict[str, Any]:
    results = report.results_data
    tests = {t.id: t for t in results.tests}
    return {
        "machine": results.machine.get("name"),
        "verdict": results.verdict,
        "tests": {t.id: t.verdict for t in results.tests},
        "as_left": {
            "verdict": as_left.results_data.verdict,
            "tests": {t.id: t.verdict for t in as_left.results_data.tests},
        },
        "cycle": _cycle(report, as_left),
        "diagonal_check": {
            f"{load:g}kg": {
                "E_BD_range_um": tests[f"diagonal-{load:g}kg"].figures["E_BD_range_um"],
                "E_AD_range_um": tests[f"diagonal-{load:g}kg"].figures["E_AD_range_um"],
            }
            for load in DIAGONAL_LOADS_KG
        },
        "experiment": {
            f"{load:g}kg": {
                "before_max_um": tests[f"sixdof-diagonal-{load:g}kg"].figures["E_BD_max_um"],
                "after_max_um": tests[f"sixdof-diagonal-{load:g}kg"].figures["E_AD_max_um"],
                "scales_only_max_um": tests[f"sixdof-diagonal-{load:g}kg"].figures["scales_only_max_um"],
            }
            for load in DIAGONAL_LOADS_KG
        },
    }


def run_demo(output_dir: str | Path = "axiscal-demo", *, seed: int = 0) -> DemoResult:
    """The closed calibration cycle on the virtual XZ module: as found, compensated, as left; reported.

    Writes ``OUTPUT_DIR/as-found/campaign/`` (:func:`write_as_found_campaign`) and its report
    ``OUTPUT_DIR/as-found/report/`` (report.html, results.json, compensation/, as ``axiscal
    report`` writes them); ``OUTPUT_DIR/as-left/campaign/`` (:func:`write_as_left_campaign`: the
    compensation files loaded into the virtual controller, each axis measured again) and its
    report compared with the as-found results; and ``OUTPUT_DIR/summary.json`` (both verdicts, each
    figure before and after, the diagonal checks and paper 000's experiment).

    Parameters
    ----------
    output_dir : str or Path
        Folder to write to (created if missing; the campaign's files and the report are replaced).
    seed : int, keyword-only
        Seed of the virtual module and of every simulated reading (default 0).

    Returns
    -------
    DemoResult
        The campaign, its report and the experiment; ``DemoResult.files`` lists the main files.

    Raises
    ------
    AxiscalError
        If a folder cannot be made or a file cannot be written; for an ``output_dir`` that is not a
        folder name or a ``seed`` that is not a whole number of 0 or more.

    Examples
    --------
    >>> result = run_demo("axiscal-demo")  # doctest: +SKIP
    >>> round(result.summary["experiment"]["2kg"]["before_max_um"], 1)  # doctest: +SKIP
    56.4
    """
    folder = check_path("output_dir", output_dir)
    seed = check_count("seed", seed, minimum=0)
    campaign = write_as_found_campaign(folder / "as-found" / "campaign", seed=seed)
    report = report_campaign(campaign.folder, folder / "as-found" / "report")
    as_left = write_as_left_campaign(folder / "as-left" / "campaign", report.folder / "compensation", seed=seed)
    # the as-left report is the visit's calibration certificate, with its DCC
    as_left_report = report_campaign(as_left.folder, folder / "as-left" / "report", compare=report.results,
                                     certificate=True)
    summary = _summary(report, as_left_report)
    write_json(folder / "summary.json", summary)
    return DemoResult(folder, campaign, report, as_left, as_left_report, summary)
