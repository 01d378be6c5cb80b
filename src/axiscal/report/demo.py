"""The demo job: a whole calibration campaign of paper 000's XZ module on the virtual instrument, reported.

Paper 000 (sections 4 and 5) end to end: :func:`axiscal.measurement.campaign_sim.write_campaign`
simulates the sensor calibration, a 6-DOF recording, ISO 230-2 laser runs with air and material
sensors, straightness by error separation, squareness by pentaprism, the diagonal check unloaded
and with 2 kg, and the paper's diagonal experiment with the 6-DOF sensors read at the same stops
(eq 13, 0 and 2 kg: the figures the offline model cannot reach under load), and writes them as a
campaign folder; :func:`axiscal.report.report_campaign` reports it (report.html, results.json,
LinuxCNC compensation files). The console lines come from the template
``axiscal/templates/demo_summary.txt.j2``.
"""

from __future__ import annotations

from dataclasses import dataclass
from importlib import resources
from pathlib import Path
from typing import Any

from axiscal.io.arguments import check_count, check_path
from axiscal.io.jsonio import write_json
from axiscal.io.templates import render_template
from axiscal.measurement.campaign_sim import (
    DIAGONAL_LOADS_KG,
    SimulatedCampaign,
    write_campaign,
)
from axiscal.report.writer import ReportFiles, report_campaign

__all__ = ["DEMO_FILES", "DemoResult", "builtin_example", "run_demo"]

#: the main files the demo writes, relative to its folder (the campaign's data files and the
#: report's compensation files besides)
DEMO_FILES = (
    "campaign/campaign.toml",
    "report/report.html",
    "report/results.json",
    "summary.json",
)


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
    """What :func:`run_demo` simulated, reported and wrote.

    Attributes
    ----------
    folder : Path
        The output folder.
    campaign : SimulatedCampaign
        The simulated campaign folder (``folder / "campaign"``).
    report : ReportFiles
        The report of the campaign (``folder / "report"``), with its results (among them paper
        000's diagonal experiment with the 6-DOF sensors, tests ``sixdof-diagonal-0kg`` and
        ``sixdof-diagonal-2kg``).
    summary : dict
        The content of ``summary.json`` (display units in the key names).
    """

    folder: Path
    campaign: SimulatedCampaign
    report: ReportFiles
    summary: dict[str, Any]

    @property
    def files(self) -> dict[str, Path]:
        """The main files written, by what they are.

        Returns
        -------
        dict of str to Path
            ``"campaign"``, ``"report"``, ``"results"``, ``"compensation"`` (a folder) and ``"summary"``.
        """
        return {
            "campaign": self.campaign.toml,
            "report": self.report.html,
            "results": self.report.results,
            "compensation": self.report.folder / "compensation",
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


def _summary(report: ReportFiles) -> dict[str, Any]:
    results = report.results_data
    tests = {t.id: t for t in results.tests}
    return {
        "machine": results.machine.get("name"),
        "verdict": results.verdict,
        "tests": {t.id: t.verdict for t in results.tests},
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
    """Simulate a whole campaign on the virtual XZ module, report it and write a summary.

    Writes ``OUTPUT_DIR/campaign/`` (campaign.toml and its data, see
    :func:`~axiscal.measurement.campaign_sim.write_campaign`), ``OUTPUT_DIR/report/``
    (report.html, results.json, compensation/, as ``axiscal report`` writes them) and
    ``OUTPUT_DIR/summary.json`` (the verdicts, the diagonal checks and paper 000's experiment).

    Parameters
    ----------
    output_dir : str or Path
        Folder to write to (created if missing; the campaign's files and the report are replaced).
    seed : int, keyword-only
        Seed of the virtual module and of every simulated reading (default 0).

    Returns
    -------
    DemoResult
        The campaign and its report; ``DemoResult.files`` lists the main files.

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
    campaign = write_campaign(folder / "campaign", seed=seed)
    report = report_campaign(campaign.folder, folder / "report")
    summary = _summary(report)
    write_json(folder / "summary.json", summary)
    return DemoResult(folder, campaign, report, summary)
