"""Campaign kinds of the tests beside positioning: electronic levels, flatness, ISO 230-3 thermal tests."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from axiscal.campaign.config import Campaign, TestSpec
from axiscal.campaign.keys import key_line
from axiscal.campaign.results import Figure, Plot, TestResult, check_figures
from axiscal.campaign.svg import relative_name, svg_of
from axiscal.errors import AxiscalError
from axiscal.units import MM

__all__: list[str] = []


def _options_refused(campaign: Campaign, spec: TestSpec, call: Callable[[], Any]) -> Any:
    """``call()``, an option the library refuses (no file named) naming campaign.toml and the test's line."""
    for key, low in (("foot_mm", "positive"), ("max_lag_h", "non-negative")):
        value = spec.options.get(key)
        if value is not None and (value < 0 or low == "positive" and value == 0):
            raise AxiscalError(f"{spec.id}: {key} must be a {low} number, not {value:g}",
                               path=campaign.folder / "campaign.toml", line=key_line(campaign, spec, key))
    try:
        return call()
    except AxiscalError as exc:
        raise exc.located(path=campaign.folder / "campaign.toml", line=spec.line) from None


def _levels(campaign: Campaign, spec: TestSpec) -> TestResult:
    from axiscal.levels.files import evaluate_levels
    from axiscal.levels.plot import plot_levels

    path = spec.options["file"]
    reference = spec.options.get("reference", "least-squares")
    evaluation = _options_refused(campaign, spec, lambda: evaluate_levels(
        path, foot_m=spec.options["foot_mm"] * MM, reference=reference))
    figures = evaluation.payload()
    checks = check_figures(figures, spec.tolerances, {"straightness_um": "um"}, rule=campaign.decision_rule)
    direction = spec.options.get("direction")
    label = f"straightness E{direction}{spec.axis}" if direction else f"straightness of {spec.axis}"
    svg = svg_of(lambda p: plot_levels(p, evaluation))
    return TestResult(
        id=spec.id, kind=spec.kind, axis=spec.axis, files=[relative_name(campaign, path)], figures=figures, checks=checks,
        plots=[Plot(f"{label.capitalize()} from electronic levels: profile in its {reference} zone, and the readings", svg)],
        table=[Figure(label, figures["straightness_um"], "um"),
               Figure("angular error motion (range of the readings)", figures["angular_error_arcsec"], "arcsec"),
               Figure("foot spacing", figures["foot_mm"], "mm")],
        method=f"Straightness and angular error from electronic levels: ISO 230-1 {reference} reference line"
        + (", differential set-up" if figures["differential"] else ""),
    )


def _flatness(campaign: Campaign, spec: TestSpec) -> TestResult:
    from axiscal.flatness.files import evaluate_flatness
    from axiscal.flatness.plot import plot_flatness

    path = spec.options["file"]
    evaluation = spec.options.get("evaluation", "least-squares")
    result = evaluate_flatness(path, evaluation=evaluation)
    figures = result.payload()
    checks = check_figures(figures, spec.tolerances, {"flatness_um": "um"}, rule=campaign.decision_rule)
    svg = svg_of(lambda p: plot_flatness(p, result.surface, title=result.source.title))
    table = [Figure("flatness (minimum zone)", figures["flatness_um"], "um"),
             Figure("flatness (least-squares plane)", figures["flatness_least_squares_um"], "um")]
    if "flatness_moody_um" in figures:
        table.append(Figure("flatness (Moody's reference)", figures["flatness_moody_um"], "um"))
    table.append(Figure("largest closure error", figures["closure_max_um"], "um"))
    return TestResult(
        id=spec.id, kind=spec.kind, axis=None, files=[relative_name(campaign, path)], figures=figures, checks=checks,
        plots=[Plot(f"Flatness{': ' + result.source.title if result.source.title else ''}: heights about the "
                    "least-squares plane, closure errors at the crossings", svg)],
        table=table, warnings=list(figures["warnings"]),
        method="Flatness: ISO 230-1 minimum zone and least-squares plane, lines joined by "
        + ("Moody's method (1955)" if evaluation == "moody" else "least squares"),
    )


def _thermal_etve(campaign: Campaign, spec: TestSpec) -> TestResult:
    from axiscal.thermal.files import evaluate_etve
    from axiscal.thermal.plot import plot_etve

    path = spec.options["file"]
    lag = spec.options.get("max_lag_h")
    evaluation = _options_refused(campaign, spec, lambda: evaluate_etve(path, max_lag_s=None if lag is None else lag * 3600.0))
    svg = svg_of(lambda p: plot_etve(p, evaluation))
    figures = evaluation.payload()
    linear = [v for k, v in figures["etve_um"].items() if k in "XYZ"]
    checks = check_figures({"etve": max(linear)} if linear else {}, spec.tolerances, {"etve_um": "um"},
                           rule=campaign.decision_rule)
    table = [Figure(f"ETVE {k}", v, "um") for k, v in figures["etve_um"].items()]
    table += [Figure(f"ETVE {k}", v, "urad") for k, v in figures.get("etve_urad", {}).items()]
    table += [Figure(f"temperature range, {k}", v, "K") for k, v in figures["temperature_range_c"].items()]
    for c in figures["correlations"]:
        if c["r_at_lag"] is not None and abs(c["r_at_lag"]) >= 0.8:
            unit = "um/K" if "sensitivity_um_per_k" in c else "urad/K"
            value = c.get("sensitivity_um_per_k", c.get("sensitivity_urad_per_k"))
            table.append(Figure(f"{c['direction']} follows {c['sensor']} {c['lag_h']:.2f} h late (r {c['r_at_lag']:.2f})",
                                value, unit))
    return TestResult(
        id=spec.id, kind=spec.kind, axis=None, files=[relative_name(campaign, path)], figures=figures, checks=checks,
        plots=[Plot(f"Environmental temperature variation over {figures['duration_h']:.1f} h: displacements and temperatures", svg)],
        table=table, method="Thermal: ISO 230-3 environmental temperature variation error (ETVE)",
    )


def _thermal_drift(campaign: Campaign, spec: TestSpec) -> TestResult:
    from axiscal.thermal.files import evaluate_drift
    from axiscal.thermal.plot import plot_drift

    path = spec.options["file"]
    evaluation = evaluate_drift(path)
    svg = svg_of(lambda p: plot_drift(p, evaluation))
    figures = evaluation.payload()
    largest = [abs(v) for v in figures.get("drift_max_um", {}).values()]
    checks = check_figures({"thermal_drift": max(largest)} if largest else {}, spec.tolerances,
                           {"thermal_drift_um": "um"}, rule=campaign.decision_rule)
    table = []
    for unit in ("um", "urad"):
        for k, v in figures.get(f"drift_max_{unit}", {}).items():
            table.append(Figure(f"largest drift {k}", v, unit))
            if k in figures.get(f"drift_heating_end_{unit}", {}):
                table.append(Figure(f"drift {k} at the end of heating", figures[f"drift_heating_end_{unit}"][k], unit))
            tau = figures["time_constant_h"].get(k)
            table.append(Figure(f"time constant {k}", "none found" if tau is None else tau, "h"))
    return TestResult(
        id=spec.id, kind=spec.kind, axis=None, files=[relative_name(campaign, path)], figures=figures, checks=checks,
        plots=[Plot(f"Thermal drift over {figures['heating_phases']} heating phase(s) (shaded) and the temperatures", svg)],
        table=table, method="Thermal: ISO 230-3 thermal distortion (drift over heating and cooling cycles)",
    )


#: kind -> the function that runs a test of that kind
