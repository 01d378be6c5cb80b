"""Campaign kinds of an axis in motion: dynamics (timebase recording), periodic error (step cycle), on-the-fly capture."""

from __future__ import annotations

import math
import re
from collections.abc import Callable
from typing import Any

from axiscal.campaign.config import Campaign, TestSpec
from axiscal.campaign.keys import key_line
from axiscal.campaign.results import Figure, Plot, TestResult, check_figures
from axiscal.campaign.svg import relative_name, svg_of
from axiscal.errors import AxiscalError
from axiscal.units import MM, UM

__all__: list[str] = []


#: the library's argument (SI) -> the campaign key it is given by: (key, its unit, low, high; None: above low)
_KEYS = {
    "window_s": ("window_ms", "milliseconds", 0.0, None),
    "band_m": ("band_um", "micrometres", 0.0, None),
    "period_m": ("period_mm", "millimetres", 0.0, None),
    "delay_s": ("delay_ms", "milliseconds", -10_000.0, 10_000.0),
}


def _check_options(campaign: Campaign, spec: TestSpec) -> None:
    """The test's numeric options in the file's units and ranges, refused naming the key and its line."""
    for key, unit, low, high in _KEYS.values():
        value = spec.options.get(key)
        if value is None:
            continue
        inside = math.isfinite(value) and (value > low if high is None else low <= value <= high)
        if not inside:
            bound = f"a positive number of {unit}" if high is None else f"{low:g} to {high:g} {unit}"
            raise AxiscalError(f"{key} must be {bound}, not {value:g}", path=campaign.folder / "campaign.toml",
                               line=key_line(campaign, spec, key))


def _located(campaign: Campaign, spec: TestSpec, call: Callable[[], Any]) -> Any:
    """``call()`` after the options' own checks; an option the library refuses (no file named) named as the file
    writes it (``window_ms``, not the library's ``window_s``), at its line in campaign.toml."""
    _check_options(campaign, spec)
    try:
        return call()
    except AxiscalError as exc:
        named = [(si, key) for si, (key, *_) in _KEYS.items() if key in spec.options and re.search(rf"\b{si}\b", exc.message)]
        message = exc.message
        for si, key in named:
            message = re.sub(rf"\b{si}\b", key, message)
        if exc.path is not None:  # about a data file: its place stays
            raise AxiscalError(message, path=exc.path, line=exc.line) from None
        line = key_line(campaign, spec, named[0][1]) if named else spec.line
        raise AxiscalError(message, path=campaign.folder / "campaign.toml", line=line) from None


def _dynamics(campaign: Campaign, spec: TestSpec) -> TestResult:
    from axiscal.dynamics.analysis import DynamicsSettings, dynamics_from_file
    from axiscal.dynamics.plot import plot_dynamics

    options = spec.options
    path, plan = options["file"], options.get("plan")

    def run():
        settings = DynamicsSettings(window_s=options.get("window_ms", 20.0) * 1e-3, band_m=options.get("band_um", 1.0) * UM)
        return dynamics_from_file(path, plan, channel=options.get("channel"), settings=settings)

    result = _located(campaign, spec, run)
    figures = result.payload()
    checks = check_figures(figures, spec.tolerances, {"settling_s": "s", "overshoot_um": "um"}, rule=campaign.decision_rule)
    d = figures["differentiator"]
    table = [Figure("largest velocity", figures["peak_velocity_mm_s"], "mm/s"),
             Figure("largest acceleration", figures["peak_acceleration_m_s2"], "m/s^2"),
             Figure("largest jerk", figures["peak_jerk_m_s3"], "m/s^3"),
             Figure(f"longest settling to +/-{result.settings.band_m / UM:g} um", figures["settling_s"], "s"),
             Figure("largest overshoot", figures["overshoot_um"], "um"),
             Figure("ringing frequency (median of the stops)", figures["ringing_hz"], "Hz"),
             Figure("damping ratio (median of the stops)", figures["damping_ratio"], ""),
             Figure("differentiator bandwidth (-3 dB)", d["bandwidth_hz"], "Hz")]
    files = [relative_name(campaign, path)] + ([relative_name(campaign, plan)] if plan is not None else [])
    return TestResult(
        id=spec.id, kind=spec.kind, axis=spec.axis, files=files, figures=figures, checks=checks,
        plots=[Plot(f"Dynamics: {len(result.moves)} moves, {len(result.stops)} stops; the spectrum", svg_of(
            lambda p: plot_dynamics(p, result)))],
        table=table,
        method=f"Dynamics: Savitzky-Golay differentiator ({d['window_ms']:.3g} ms, degree {d['polyorder']},"
               f" {d['bandwidth_hz']:.3g} Hz), Welch spectrum, settling to a band",
    )


def _periodic(campaign: Campaign, spec: TestSpec) -> TestResult:
    from axiscal.dynamics.periodic import periodic_from_file
    from axiscal.dynamics.plot import plot_periodic

    path = spec.options["file"]
    period = spec.options.get("period_mm")
    result = _located(campaign, spec, lambda: periodic_from_file(path, period_m=None if period is None else period * MM))
    figures = result.payload()
    checks = check_figures(figures, spec.tolerances, {"periodic_um": "um"}, rule=campaign.decision_rule)
    table = [Figure("periodic error (peak to peak, fit)", figures["periodic_um"], "um"),
             Figure("period (fit" + (", given)" if result.period_given else ")"), figures["period_mm"], "mm"),
             Figure("amplitude at the spectrum's peak", figures["spectrum_amplitude_um"], "um"),
             Figure("period at the spectrum's peak", figures["spectrum_period_mm"], "mm")]
    return TestResult(
        id=spec.id, kind=spec.kind, axis=spec.axis, files=[relative_name(campaign, path)], figures=figures, checks=checks,
        plots=[Plot(f"Periodic error of {spec.axis}: mean deviations with the fitted sine; the amplitude spectrum",
                    svg_of(lambda p: plot_periodic(p, result)))],
        table=table, method="Periodic positioning error: ISO 230-2 Annexes B and C, least-squares fit and spectrum",
    )


def _on_the_fly(campaign: Campaign, spec: TestSpec) -> TestResult:
    from axiscal.capture.on_the_fly import on_the_fly
    from axiscal.capture.on_the_fly_plot import plot_on_the_fly
    from axiscal.positioning.evaluation import iso230_2, iso_edition

    options = spec.options
    path, plan = options["file"], options["plan"]
    delay = options.get("delay_ms")
    result = _located(campaign, spec, lambda: on_the_fly(plan, path, channel=options.get("channel"),
                                                          delay_s=None if delay is None else delay * 1e-3))
    edition = iso_edition(options.get("standard", "iso230-2:2014"))
    iso = iso230_2(result.run, edition=edition)
    axis_figures = {k: (None if not math.isfinite(v) else v / UM) for k, v in iso.figures().items()}
    figures = {**{k: v for k, v in axis_figures.items()}, **{k: v for k, v in result.payload().items() if k != "crossings"}}
    checks = check_figures({k: v for k, v in axis_figures.items() if v is not None}, spec.tolerances, {},
                           rule=campaign.decision_rule)
    table = [Figure(k, v, "um") for k, v in axis_figures.items() if v is not None]
    table += [Figure("delay of the position stream" + (" (estimated)" if result.delay_estimated else " (given)"),
                     result.delay_s * 1e3, "ms"),
              Figure("speed through the targets", figures["speed_mm_min"], "mm/min")]
    return TestResult(
        id=spec.id, kind=spec.kind, axis=spec.axis, files=[relative_name(campaign, path), relative_name(campaign, plan)],
        figures=figures, checks=checks,
        plots=[Plot(f"{spec.axis} axis positioning on the fly: deviations as the axis passed each target",
                    svg_of(lambda p: plot_on_the_fly(p, result)))],
        table=table, method=f"Positioning on the fly (readings where the position stream crosses each target): ISO 230-2:{edition}",
    )
