"""Running a campaign: every test through the library call of its kind, figures against tolerances.

Each kind calls the same library function as the command of the same name, so the figures in the
report and in results.json are the numbers that command prints for the same file.
"""

from __future__ import annotations

import re
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.campaign.config import Campaign, TestSpec, load_campaign
from axiscal.campaign.results import CampaignResults, Figure, Plot, TestResult, check_figures
from axiscal.errors import AxiscalError
from axiscal.units import ARCSEC, MM, UM

__all__ = ["KIND_RUNNERS", "run_campaign", "run_test", "svg_of"]


def svg_of(draw: Callable[[Path], Any]) -> str:
    """The SVG text of a plot that ``draw(path)`` writes to an ``.svg`` path."""
    with tempfile.TemporaryDirectory(prefix="axiscal-plot-") as folder:
        path = Path(folder) / "plot.svg"
        draw(path)
        text = path.read_text(encoding="utf-8")
    start = text.find("<svg")
    text = text[start:] if start >= 0 else text
    return re.sub(r"\s*<metadata>.*?</metadata>", "", text, count=1, flags=re.S)


def _relative(campaign: Campaign, path: Path) -> str:
    return path.relative_to(campaign.folder).as_posix()


def _environment(path: Path) -> dict[str, Any]:
    """Mean, min and max of the air and material sensor columns of a run file, where it has them."""
    from axiscal.io.tabular import read_csv

    table = read_csv(path)
    out: dict[str, Any] = {}
    for column, name, unit in (
        ("air_temperature_c", "air temperature", "degC"),
        ("pressure_pa", "air pressure", "Pa"),
        ("humidity_pct", "relative humidity", "%"),
        ("material_temperature_c", "material temperature", "degC"),
    ):
        if table.has(column):
            values = table.numeric(column)
            out[name] = {"mean": float(values.mean()), "min": float(values.min()), "max": float(values.max()), "unit": unit}
    return out


def _positioning(campaign: Campaign, spec: TestSpec) -> TestResult:
    from axiscal.positioning.evaluation import iso230_2, iso_edition, vdi3441
    from axiscal.positioning.plot import plot_positioning
    from axiscal.positioning.reader import read_positioning_run

    path = spec.options["file"]
    standard = spec.options.get("standard", "iso230-2:2014")
    wavelength = spec.options.get("wavelength_nm", campaign.instrument.get("vacuum_wavelength_nm"))
    kwargs = {"wavelength_nm": wavelength} if wavelength is not None else {}
    if "expansion_per_k" in spec.options:
        kwargs["expansion_per_k"] = spec.options["expansion_per_k"]
    try:
        data = read_positioning_run(path, **kwargs)
    except TypeError:  # pragma: no cover - guarded by the config's option types
        raise
    result = vdi3441(data.run) if standard == "vdi3441" else iso230_2(data.run, edition=iso_edition(standard))
    figures = {name: value / UM for name, value in result.figures().items()}
    checks = check_figures(figures, {k: v for k, v in spec.tolerances.items()}, {})
    table = [Figure(name, value, "um") for name, value in figures.items()]
    title = f"{spec.axis} axis positioning ({result.standard})"
    plot = svg_of(lambda p: plot_positioning(data.run, result, p, title=title, compensated=data.compensated))
    return TestResult(
        id=spec.id, kind=spec.kind, axis=spec.axis, files=[_relative(campaign, path)],
        figures={"standard": result.standard, "unit": "um", **figures, "runs": data.run.runs,
                 "target_count": int(data.run.targets.size), "compensated": data.compensated},
        checks=checks, plots=[Plot(title, plot)], table=table, environment=_environment(path),
        warnings=list(result.warnings), method=f"Positioning: {result.standard}",
    )


def _straightness(campaign: Campaign, spec: TestSpec) -> TestResult:
    from axiscal.squareness.evaluation import read_straightness_run
    from axiscal.straightness.reference import reference_line

    path = spec.options["file"]
    reference = spec.options.get("reference", "least-squares")
    position, deviation = read_straightness_run(path)
    try:
        line = reference_line(position, deviation, reference=reference)
    except AxiscalError as exc:
        raise exc.located(path=path) from None
    figures = {
        "straightness_um": line.straightness_m / UM,
        "slope_urad": line.slope / 1e-6,
        "intercept_um": line.intercept_m / UM,
        "reference": line.reference,
    }
    checks = check_figures(figures, spec.tolerances, {"straightness_um": "um"})
    direction = spec.options.get("direction")
    label = f"E{direction}{spec.axis}" if direction else f"straightness of {spec.axis}"
    plots = [Plot(f"{label}: profile and {reference} reference line", svg_of(lambda p: _plot_profile(p, position, deviation, line)))]
    return TestResult(
        id=spec.id, kind=spec.kind, axis=spec.axis, files=[_relative(campaign, path)], figures=figures,
        checks=checks, plots=plots,
        table=[Figure(f"straightness {label}", figures["straightness_um"], "um"), Figure("slope", figures["slope_urad"], "urad")],
        method=f"Straightness: ISO 230-1 {reference} reference line",
    )


def _plot_profile(path: Path, position_m: np.ndarray, deviation_m: np.ndarray, line) -> None:
    from axiscal.io.figures import pyplot, save_figure

    plt = pyplot()
    order = np.argsort(position_m, kind="stable")
    x = position_m[order]
    fit = line.slope * x + line.intercept_m
    residual = line.residuals(position_m, deviation_m)
    fig, ax = plt.subplots(figsize=(7, 3.2))
    ax.plot(x / MM, deviation_m[order] / UM, "o-", ms=3, label="profile")
    ax.plot(x / MM, fit / UM, "-", label=f"{line.reference} line")
    for bound in (residual.min(), residual.max()):
        ax.plot(x / MM, (fit + bound) / UM, "--", color="gray", lw=0.8)
    ax.set_xlabel("position / mm")
    ax.set_ylabel("deviation / um")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    save_figure(fig, path)


def _squareness(campaign: Campaign, spec: TestSpec) -> TestResult:
    from axiscal.squareness.evaluation import read_straightness_run, squareness

    first, second = spec.options["first"], spec.options["second"]
    p1, d1 = read_straightness_run(first)
    p2, d2 = read_straightness_run(second)
    result = squareness(
        p1, d1, p2, d2, plane=spec.options["plane"],
        prism_deviation_rad=spec.options.get("prism_deviation_arcsec", 0.0) * ARCSEC,
        reference=spec.options.get("reference", "least-squares"),
        convention=spec.options.get("convention", "included-angle"),
    )
    figures = {
        "plane": result.plane,
        "convention": result.convention,
        "squareness_arcsec": result.squareness_rad / ARCSEC,
        "included_angle_deg": float(np.degrees(result.included_angle_rad)),
        "iso_term": result.iso_term,
        "iso_value_arcsec": result.iso_value_rad / ARCSEC,
        "prism_deviation_arcsec": result.prism_deviation_rad / ARCSEC,
    }
    checks = check_figures(figures, spec.tolerances, {"squareness_arcsec": "arcsec"})
    return TestResult(
        id=spec.id, kind=spec.kind, axis=spec.axis, files=[_relative(campaign, first), _relative(campaign, second)],
        figures=figures, checks=checks,
        table=[Figure(f"squareness {result.plane} ({result.convention})", figures["squareness_arcsec"], "arcsec"),
               Figure(f"{result.iso_term} (ISO 230-1 sign)", figures["iso_value_arcsec"], "arcsec")],
        method="Squareness: two straightness runs and a pentaprism (included angle minus 90 degrees)",
    )


#: kind -> the function that runs a test of that kind
KIND_RUNNERS: dict[str, Callable[[Campaign, TestSpec], TestResult]] = {
    "positioning": _positioning,
    "straightness": _straightness,
    "squareness": _squareness,
}


def run_test(campaign: Campaign, spec: TestSpec) -> TestResult:
    """Run one test of ``campaign``; errors name the test's data file or campaign.toml's line."""
    runner = KIND_RUNNERS.get(spec.kind)
    if runner is None:
        raise AxiscalError(f"tests of kind '{spec.kind}' cannot be run yet", path=campaign.folder / "campaign.toml", line=spec.line)
    return runner(campaign, spec)


def run_campaign(
    campaign: Campaign | str | Path,
    *,
    progress: Callable[[int, int, TestSpec], None] | None = None,
) -> CampaignResults:
    """Run every test of a campaign.

    Parameters
    ----------
    campaign : Campaign, str or Path
        A checked campaign, or its folder (read with :func:`~axiscal.campaign.config.load_campaign`).
    progress : callable, keyword-only
        Called as ``progress(done, total, spec)`` before each test and once at the end with
        ``done == total`` (the command line draws a progress bar with it).

    Returns
    -------
    CampaignResults

    Raises
    ------
    AxiscalError
        For a bad campaign or a bad data file (naming the file and line).
    """
    if not isinstance(campaign, Campaign):
        campaign = load_campaign(campaign)
    results = []
    total = len(campaign.tests)
    for index, spec in enumerate(campaign.tests):
        if progress is not None:
            progress(index, total, spec)
        results.append(run_test(campaign, spec))
    if progress is not None and total:
        progress(total, total, campaign.tests[-1])
    return CampaignResults(campaign.campaign, campaign.machine, campaign.instrument, results)
