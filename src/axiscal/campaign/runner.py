"""Running a campaign: every test through the library call of its kind, figures against tolerances.

Each kind calls the same library function as the command of the same name, so the figures in the
report and in results.json are the numbers that command prints for the same file.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.campaign.config import Campaign, TestSpec, load_campaign
from axiscal.campaign.results import (
    CampaignResults,
    Figure,
    Plot,
    TestResult,
    check_figures,
)
from axiscal.campaign.cmm_kinds import _cmm_acceptance, _cmm_probing
from axiscal.campaign.sensor_kinds import _sensor_calibration, _sixdof, _sixdof_diagonal
from axiscal.campaign.standard_kinds import _flatness, _levels, _thermal_drift, _thermal_etve
from axiscal.campaign.dynamics_kinds import _dynamics, _on_the_fly, _periodic
from axiscal.campaign.svg import relative_name, svg_of
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_mapping, check_path
from axiscal.io.arguments import check_instance, type_name
from axiscal.positioning.evaluation import Iso230Result
from axiscal.units import ARCSEC, MM, UM, URAD

__all__ = ["COMPENSATION_FILES", "KIND_RUNNERS", "evaluation_is_raw", "run_campaign", "run_test", "svg_of"]


def _environment(path: Path) -> dict[str, Any]:
    """Mean, min and max of the air and material sensor columns of a run file, where it has them."""
    from axiscal.io.tabular import read_csv

    table = read_csv(path)
    out: dict[str, Any] = {}
    for column, name, unit, digits in (
        ("air_temperature_c", "air temperature", "degC", 2),
        ("pressure_pa", "air pressure", "Pa", 0),
        ("humidity_pct", "relative humidity", "%", 1),
        ("material_temperature_c", "material temperature", "degC", 2),
    ):
        if table.has(column):
            values = table.numeric(column)
            out[name] = {"mean": round(float(values.mean()), digits + 2), "min": float(values.min()),
                         "max": float(values.max()), "unit": unit, "digits": digits}
    return out


#: controller -> the compensation file name of an axis (in the report's compensation/ folder)
COMPENSATION_FILES = {
    "linuxcnc": "{axis}.comp",
    "fanuc": "{axis}_pitch_error.txt",
    "siemens": "{axis}_enc_comp.mpf",
    "heidenhain": "{axis}.COM",
}


def _uncertainty(campaign: Campaign, spec: TestSpec, evaluation: Any) -> dict[str, float]:
    """U (k = 2) of the test's figures from the campaign's budget, in their display units (none
    without a budget, or for a rotary, one-direction or VDI 3441 positioning test)."""
    if campaign.budget is None:
        return {}
    from axiscal.uncertainty.figures import figure_uncertainties

    if spec.kind == "positioning":
        run = evaluation.run
        if not isinstance(evaluation.result, Iso230Result) or getattr(run, "rotary", False) or not getattr(run, "bidirectional", True):
            return {}
    return figure_uncertainties(spec.kind, evaluation, campaign.budget)


def _positioning(campaign: Campaign, spec: TestSpec, campaign_compare: Mapping[str, Any] | None = None) -> TestResult:
    from axiscal.compensation.formats import compensation_table
    from axiscal.positioning.report import evaluate_positioning_file

    path = spec.options["file"]
    wavelength = spec.options.get("wavelength_nm", campaign.instrument.get("vacuum_wavelength_nm"))
    evaluation = evaluate_positioning_file(
        path,
        standard=spec.options.get("standard", "iso230-2:2014"),
        wavelength_nm=wavelength if evaluation_is_raw(path) else None,
        expansion_per_k=spec.options.get("expansion_per_k"),
    )
    payload = evaluation.to_dict()
    figures = {k: v for k, v in payload.items()}
    rotary = bool(getattr(evaluation.run, "rotary", False))
    unit, factor = ("arcsec", ARCSEC) if rotary else ("um", UM)
    wrong = [k for k in spec.tolerances if k.endswith("_arcsec" if not rotary else "_um")]
    if wrong:
        kind = "rotary" if rotary else "linear"
        raise AxiscalError(
            f"{spec.id}: tolerance {wrong[0]} does not fit a {kind} axis; its figures are in {unit}"
            f" (e.g. E_{unit})", path=campaign.folder / "campaign.toml", line=spec.line,
        )
    axis_figures = {name: value / factor for name, value in evaluation.result.figures().items()}
    uncertainty = _uncertainty(campaign, spec, evaluation)
    checks = check_figures(axis_figures, spec.tolerances, {}, uncertainty=uncertainty, rule=campaign.decision_rule)
    title = f"{spec.axis} axis positioning ({evaluation.result.standard})"
    overlay = _overlay(spec, campaign_compare, "targets")
    if overlay is not None:
        # a compared positioning test is the axis as found; this campaign's, the axis as left
        overlay = {**overlay, "label": "as found", "current_label": "as left"}
    # the report shows the figures in its own table beside the plot
    svg = _drawn(spec, lambda p: evaluation.plot(p, title=title, overlay=overlay, figures_table=False), overlay)
    compensation = []
    if campaign.controller is not None:
        options = {"axis": spec.axis} if campaign.controller in ("siemens", "heidenhain") else {}
        table = compensation_table(evaluation.run, campaign.controller, **options)
        name = "compensation/" + COMPENSATION_FILES[campaign.controller].format(axis=spec.axis)
        compensation.append({"controller": campaign.controller, "axis": spec.axis, "file": name, "text": table.text})
    return TestResult(
        id=spec.id, kind=spec.kind, axis=spec.axis, files=[relative_name(campaign, path)], figures=figures,
        checks=checks, plots=[Plot(title, svg)], table=[Figure(k, v, unit) for k, v in axis_figures.items()],
        environment=_environment(path), warnings=list(evaluation.warnings), compensation=compensation,
        method=f"Positioning: {evaluation.result.standard}", uncertainty=uncertainty,
    )


def evaluation_is_raw(path: Path) -> bool:
    """Whether a run file holds raw laser readings, which need a wavelength.

    Parameters
    ----------
    path : Path
        A positioning run file.

    Returns
    -------
    bool
        True when it has an ``actual_<unit>`` column.

    Raises
    ------
    AxiscalError
        For a ``path`` that is not a file name, or a file that cannot be read.
    """
    from axiscal.io.tabular import read_csv

    path = check_path("path", path)
    header = read_csv(path).header
    # raw readings: actual_<unit>, or a deviation beside the air columns (the raw reading less the target)
    return any(name.startswith("actual_") for name in header) or "air_temperature_c" in header


#: decimals of the series results.json carries for the plots of a compared campaign
SERIES_DECIMALS = 4


def _series(values: np.ndarray, unit: float) -> list[float]:
    """A series in a display unit, rounded for results.json (NaN kept; it is written null)."""
    return np.round(np.asarray(values, dtype=float) / unit, SERIES_DECIMALS).tolist()


def _overlay(spec: TestSpec, compare: Mapping[str, Any] | None, key: str) -> dict[str, Any] | None:
    """The compared campaign's series ``key`` of the test with this id, labelled for the legend; None
    when there is no comparison, no such test, or its results.json is older than the key."""
    from axiscal.io.figures import OVERLAY_LABEL

    previous = (compare or {}).get(spec.id)
    series = previous.get(key) if isinstance(previous, Mapping) else None
    return {**series, "label": OVERLAY_LABEL} if isinstance(series, Mapping) else None


def _drawn(spec: TestSpec, draw: Callable[[Path], Any], overlay: Mapping[str, Any] | None) -> str:
    """The SVG of ``draw``; a compared campaign's series that cannot be drawn is named as such."""
    try:
        return svg_of(draw)
    except AxiscalError as exc:
        if overlay is None or not exc.message.startswith("overlay"):
            raise
        raise AxiscalError(f"test '{spec.id}' of the compared results.json: {exc.message}") from None


def _straightness(campaign: Campaign, spec: TestSpec, compare: Mapping[str, Any] | None = None) -> TestResult:
    from axiscal.straightness.files import evaluate_straightness_file
    from axiscal.straightness.plot import plot_straightness

    path = spec.options["file"]
    reference = spec.options.get("reference", "least-squares")
    evaluation = evaluate_straightness_file(path, reference=reference)
    profile, line = evaluation.profile, evaluation.line
    overlay = _overlay(spec, compare, "profile")
    svg = _drawn(spec, lambda p: plot_straightness(p, profile.position_m, profile.deviation_m, line, overlay=overlay), overlay)
    figures = evaluation.payload()
    figures["profile"] = {
        "position_mm": _series(profile.position_m, MM),
        "deviation_um": _series(profile.deviation_m, UM),
        "residual_um": _series(line.residuals(profile.position_m, profile.deviation_m), UM),
    }
    uncertainty = _uncertainty(campaign, spec, evaluation)
    checks = check_figures(figures, spec.tolerances, {"straightness_um": "um"}, uncertainty=uncertainty,
                           rule=campaign.decision_rule)
    direction = spec.options.get("direction")
    label = f"E{direction}{spec.axis}" if direction else f"straightness of {spec.axis}"
    return TestResult(
        id=spec.id, kind=spec.kind, axis=spec.axis, files=[relative_name(campaign, path)], figures=figures,
        checks=checks, plots=[Plot(f"{label}: profile and {reference} reference line", svg)],
        table=[Figure(f"straightness {label}", figures["straightness_um"], "um"), Figure("slope", figures["slope_urad"], "urad")],
        method=f"Straightness: ISO 230-1 {reference} reference line", uncertainty=uncertainty,
    )


def _separation(campaign: Campaign, spec: TestSpec, compare: Mapping[str, Any] | None = None) -> TestResult:
    from axiscal.straightness.files import separate_file
    from axiscal.straightness.plot import plot_separation
    from axiscal.straightness.reference import reference_line

    options = spec.options
    path = options["file"]
    method = options.get("method", "combined")
    reference = options.get("reference", "least-squares")
    spacing = options.get("spacing_mm")
    spacing_bc = options.get("spacing_bc_mm")
    calibration = options.get("calibration_mm")
    run = separate_file(
        path, method=method,
        spacing_ab_m=None if spacing is None else spacing * MM,
        spacing_bc_m=None if spacing_bc is None else spacing_bc * MM,
        reversed_path=options.get("reversed"),
        probes=2 if options.get("two_probe") else None,
        min_gain=options.get("min_gain", 0.05),
        parabola=not options.get("periodic", False),
        calibration_m=None if calibration is None else (calibration[0] * MM, calibration[1] * MM),
    )
    separation = run.separation
    overlay = _overlay(spec, compare, "columns")
    svg = _drawn(spec, lambda p: plot_separation(p, separation, overlay=overlay, reference=reference), overlay)
    motion = np.isfinite(separation.motion_m)
    slide = reference_line(separation.position_m[motion], separation.motion_m[motion], reference=reference)
    workpiece = reference_line(separation.position_m, separation.profile_m, reference=reference)
    figures = {
        "method": separation.method,
        "straightness_um": slide.straightness_m / UM,
        "slope_urad": slide.slope / URAD,
        "profile_straightness_um": workpiece.straightness_m / UM,
        "reference": reference,
        "points": int(separation.position_m.size),
        "columns": {"position_mm": _series(separation.position_m, MM), "profile_um": _series(separation.profile_m, UM),
                    "motion_um": _series(separation.motion_m, UM)},
    }
    if np.any(np.isfinite(separation.yaw_rad)):
        figures["columns"]["yaw_urad"] = _series(separation.yaw_rad, URAD)
    checks = check_figures(figures, spec.tolerances, {"straightness_um": "um"})
    direction = options.get("direction")
    label = f"E{direction}{spec.axis}" if direction and spec.axis else "slide motion"
    files = [relative_name(campaign, path)] + ([relative_name(campaign, options["reversed"])] if "reversed" in options else [])
    return TestResult(
        id=spec.id, kind=spec.kind, axis=spec.axis, files=files, figures=figures, checks=checks,
        plots=[Plot(f"{separation.method} separation: workpiece profile and slide motion", svg)],
        table=[Figure(f"straightness {label} (slide motion)", figures["straightness_um"], "um"),
               Figure("straightness of the workpiece profile", figures["profile_straightness_um"], "um")],
        method=f"Straightness by error separation ({separation.method}), ISO 230-1 {reference} reference line",
    )


def _squareness(campaign: Campaign, spec: TestSpec, compare: Mapping[str, Any] | None = None) -> TestResult:
    from axiscal.squareness.evaluation import squareness_from_files
    from axiscal.squareness.plot import plot_squareness

    first, second = spec.options["first"], spec.options["second"]
    evaluation = squareness_from_files(
        first, second, plane=spec.options["plane"],
        prism_deviation_rad=spec.options.get("prism_deviation_arcsec", 0.0) * ARCSEC,
        reference=spec.options.get("reference", "least-squares"),
        convention=spec.options.get("convention", "included-angle"),
    )
    runs = ((evaluation.first.position_m, evaluation.first.deviation_m),
            (evaluation.second.position_m, evaluation.second.deviation_m))
    overlay = _overlay(spec, compare, "runs")
    svg = _drawn(spec, lambda p: plot_squareness(p, evaluation.result, runs, overlay=overlay), overlay)
    figures = evaluation.payload()
    figures["runs"] = {
        which: {"position_mm": _series(x, MM), "deviation_um": _series(y, UM),
                "line_um": _series(line.slope * x + line.intercept_m, UM)}
        for which, (x, y), line in zip(("first", "second"), runs, (evaluation.result.first_line, evaluation.result.second_line))
    }
    uncertainty = _uncertainty(campaign, spec, evaluation)
    checks = check_figures(figures, spec.tolerances, {"squareness_arcsec": "arcsec"}, uncertainty=uncertainty,
                           rule=campaign.decision_rule)
    result = evaluation.result
    return TestResult(
        id=spec.id, kind=spec.kind, axis=spec.axis, files=[relative_name(campaign, first), relative_name(campaign, second)],
        figures=figures, checks=checks, plots=[Plot(f"{result.plane} squareness: both runs and their lines", svg)],
        # one figure, one sign (docs/conventions.md): the judged squareness under the name that says its
        # convention, as the verdict table and the plot show it; the included angle itself has no sign to read
        table=[Figure(result.name, figures["squareness_arcsec"], "arcsec"),
               Figure(f"included angle of {result.plane[0]} and {result.plane[1]}", figures["included_angle_deg"], "deg")],
        method="Squareness: ISO 230-1, two straightness runs referred to each other by a pentaprism (optical square), its deviation removed", uncertainty=uncertainty,
    )


def _ballbar(campaign: Campaign, spec: TestSpec, compare: Mapping[str, Any] | None = None) -> TestResult:
    from axiscal.circular.evaluation import MM_PER_MIN
    from axiscal.circular.plot import plot_ballbar
    from axiscal.circular.report import ballbar_payload, evaluate_ballbar_file, trace_payload

    path = spec.options["file"]
    feed = spec.options.get("feed_mm_min")
    result = evaluate_ballbar_file(
        path, radius=spec.options["radius_mm"] * MM, plane=spec.options["plane"],
        feed=None if feed is None else feed * MM_PER_MIN,
    )
    figures = ballbar_payload(result)
    deviations = [figures[k] for k in ("G_ccw_um", "G_cw_um") if figures.get(k) is not None]
    figures["circular_deviation_um"] = max(deviations) if deviations else None
    checks = check_figures(figures, spec.tolerances, {"circular_deviation_um": "um"})
    title = f"{spec.axis} circular test (ISO 230-4), radius {spec.options['radius_mm']:g} mm"
    overlay = _overlay(spec, compare, "trace")
    svg = _drawn(spec, lambda p: plot_ballbar(result, p, title=title, overlay=overlay), overlay)
    figures["trace"] = trace_payload(result)
    table = [Figure(label, figures[key], unit) for key, label, unit in (
        ("G_ccw_um", "circular deviation G ccw", "um"), ("G_cw_um", "circular deviation G cw", "um"),
        ("H_um", "circular hysteresis H", "um"), ("squareness_urad", "squareness", "urad"),
        ("scale_mismatch_ppm", "scale mismatch", "ppm"),
    ) if figures.get(key) is not None]
    return TestResult(
        id=spec.id, kind=spec.kind, axis=spec.axis, files=[relative_name(campaign, path)], figures=figures,
        checks=checks, plots=[Plot(title, svg)], table=table, method="Circular test: ISO 230-4 (ballbar)",
    )


def _diagonal(campaign: Campaign, spec: TestSpec, compare: Mapping[str, Any] | None = None) -> TestResult:
    from axiscal.model.diagonal import diagonal_test
    from axiscal.model.plot import plot_diagonal

    options = spec.options
    readings = options.get("interferometer")
    result = diagonal_test(
        campaign.model, options["from"], options["to"], steps=options.get("steps"), readings=readings,
        measure=options.get("measure", "projection"),
    )
    figures = result.summary()
    figures["points"] = {k: np.asarray(v, dtype=float).tolist() for k, v in figures["points"].items()}
    figures["diagonal_error_um"] = figures.get("E_BD_range_um", figures["model_error_range_um"])
    # the tolerance is keyed diagonal_um; the figure it holds, and a compared campaign's, is diagonal_error_um
    checks = [replace(c, figure="diagonal_error_um")
              for c in check_figures({"diagonal": figures["diagonal_error_um"]}, spec.tolerances, {"diagonal_um": "um"})]
    title = f"Diagonal {options['from']} to {options['to']}: displacement error (actual minus nominal)"
    overlay = _overlay(spec, compare, "points")
    svg = _drawn(spec, lambda p: plot_diagonal(result, p, title=title, overlay=overlay), overlay)
    table = [Figure("model error range", figures["model_error_range_um"], "um")]
    if "E_BD_range_um" in figures:
        table += [Figure("measured error range, before the model (E_BD)", figures["E_BD_range_um"], "um"),
                  Figure("left after the model (E_AD)", figures["E_AD_range_um"], "um")]
    files = [relative_name(campaign, campaign.model)] + ([relative_name(campaign, readings)] if readings is not None else [])
    uncertainty = _diagonal_uncertainty(campaign, figures) if readings is not None else {}
    if uncertainty:
        checks = [replace(c, U=uncertainty.get(c.figure)) for c in checks]
    return TestResult(
        id=spec.id, kind=spec.kind, axis=None, files=files, figures=figures, checks=checks,
        plots=[Plot(title, svg)], table=table,
        method=f"Diagonal displacement test (ISO 230-6), reading as {options.get('measure', 'projection')}",
        uncertainty=uncertainty,
    )


def _diagonal_uncertainty(campaign: Campaign, figures: Mapping[str, Any]) -> dict[str, float]:
    """U (k = 2, um) of the measured ranges of a diagonal test: the laser read along the diagonal, the budget's
    U of a positioning test's E over the diagonal's length (ISO 230-6 measures as ISO 230-2 does, along another
    line); none without a budget. The model's range is predicted, not measured: it has none."""
    if campaign.budget is None:
        return {}
    from axiscal.uncertainty.positioning import positioning_uncertainty

    nominal = figures["points"].get("nominal_mm") or [0.0]
    length_m = abs(nominal[-1] - nominal[0]) * MM
    if length_m <= 0:
        return {}
    U = positioning_uncertainty(campaign.budget, length_m).U["E"] / UM
    return {key: U for key in ("E_BD_range_um", "E_AD_range_um", "diagonal_error_um") if key in figures}


KIND_RUNNERS: dict[str, Callable[[Campaign, TestSpec], TestResult]] = {
    "positioning": _positioning,
    "straightness": _straightness,
    "separation": _separation,
    "squareness": _squareness,
    "ballbar": _ballbar,
    "diagonal": _diagonal,
    "sixdof": _sixdof,
    "levels": _levels,
    "flatness": _flatness,
    "thermal_etve": _thermal_etve,
    "thermal_drift": _thermal_drift,
    "sensor_calibration": _sensor_calibration,
    "sixdof_diagonal": _sixdof_diagonal,
    "cmm_acceptance": _cmm_acceptance,
    "cmm_probing": _cmm_probing,
    "dynamics": _dynamics,
    "periodic": _periodic,
    "on_the_fly": _on_the_fly,
}

#: kinds whose plot draws the compared campaign's test of the same id behind its own
OVERLAID_KINDS = ("positioning", "straightness", "separation", "squareness", "ballbar", "diagonal")


def run_test(campaign: Campaign, spec: TestSpec, *, compare: Mapping[str, Any] | None = None) -> TestResult:
    """Run one test of a campaign through the library call of its kind.

    Parameters
    ----------
    campaign : Campaign
    spec : TestSpec
        One of ``campaign.tests``.
    compare : mapping, keyword-only
        Figures of another campaign by test id (its results.json): the plot of a kind in
        :data:`OVERLAID_KINDS` draws the other campaign's series of the same test id behind this
        one's (none when that results.json does not carry them).

    Returns
    -------
    TestResult

    Raises
    ------
    AxiscalError
        For a bad data file (naming it and the line).
    """
    check_instance("campaign", campaign, Campaign)
    check_instance("spec", spec, TestSpec)
    if compare is not None:
        check_mapping("compare", compare, what="a mapping of test ids to figures")
    runner = KIND_RUNNERS.get(spec.kind)
    if runner is None:
        raise AxiscalError(f"tests of kind '{spec.kind}' cannot be run yet", path=campaign.folder / "campaign.toml", line=spec.line)
    if spec.kind in OVERLAID_KINDS:
        return runner(campaign, spec, compare)
    return runner(campaign, spec)


def run_campaign(
    campaign: Campaign | str | Path,
    *,
    progress: Callable[[int, int, TestSpec], None] | None = None,
    compare: Mapping[str, Any] | None = None,
) -> CampaignResults:
    """Run every test of a campaign.

    Parameters
    ----------
    campaign : Campaign, str or Path
        A checked campaign, or its folder (read with :func:`~axiscal.campaign.config.load_campaign`).
    progress : callable, keyword-only
        Called as ``progress(done, total, spec)`` before each test and once at the end with
        ``done == total`` (the command line draws a progress bar with it).
    compare : mapping, keyword-only
        Another campaign's results.json: each plot draws its test of the same id behind this
        one's, and the volumetric section maps the change of the volumetric error.

    Returns
    -------
    CampaignResults

    Raises
    ------
    AxiscalError
        For a bad campaign or a bad data file (naming the file and line).
    """
    if not isinstance(campaign, Campaign):
        if not isinstance(campaign, (str, Path)):
            raise AxiscalError(f"campaign must be a Campaign or its folder, not {type_name(campaign)}")
        campaign = load_campaign(campaign)
    if progress is not None and not callable(progress):
        raise AxiscalError(f"progress must be a function of (done, total, spec), not {type_name(progress)}")
    if compare is not None:
        check_mapping("compare", compare, what="a results.json object (a mapping)")
    results = []
    previous = None
    if compare is not None:
        previous = {t.get("id"): t.get("figures", {}) for t in compare.get("tests", []) if isinstance(t, Mapping)}
    total = len(campaign.tests)
    for index, spec in enumerate(campaign.tests):
        if progress is not None:
            progress(index, total, spec)
        results.append(run_test(campaign, spec, compare=previous))
    model: dict[str, Any] = {}
    if campaign.model is not None:
        from axiscal.campaign.volumetric import volumetric_section

        before = compare.get("volumetric") if compare is not None else None
        model = volumetric_section(campaign.model, svg_of, before=before if isinstance(before, Mapping) else None,
                                   compensation=campaign.compensation, controller=campaign.controller)
    if progress is not None and total:
        progress(total, total, campaign.tests[-1])
    issuer = {"laboratory": campaign.laboratory, "certificate": campaign.certificate,
              "signatories": [dict(s) for s in campaign.signatories]}
    return CampaignResults(campaign.campaign, campaign.machine, campaign.instrument, results, model=model,
                           decision_rule=campaign.decision_rule, warnings=list(model.get("warnings", [])),
                           issuer={k: v for k, v in issuer.items() if v})
