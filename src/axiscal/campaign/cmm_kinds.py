"""Campaign kinds of coordinate measuring machines: the ISO 10360-2 length test and the ISO 10360-5 probing test.

The maker's MPE are the test's tolerances: ``cmm_e0_a_um``, ``cmm_e0_k``, ``cmm_e0_b_um`` (E0,MPE =
min(A + L/K, B)), the same for E150, ``cmm_r0_um`` (R0,MPL); ``pform_um``, ``psize_um``,
``pform_ms_um``, ``psize_ms_um``, ``ploc_um`` for the probing figures. Each value is decided by the
campaign's rule with the test's own uncertainty (``uncertainty_um``, ``uncertainty_um_per_m``).
Limits and uncertainties in um are at most 10000 and K is 1 to 1000000, as the command's flags.
"""

from __future__ import annotations

from axiscal.campaign.config import Campaign, TestSpec
from axiscal.campaign.results import Check, Figure, Plot, TestResult
from axiscal.campaign.svg import relative_name, svg_of
from axiscal.errors import AxiscalError
from axiscal.units import MM, UM

__all__: list[str] = []


def _located(campaign: Campaign, spec: TestSpec, message: str) -> AxiscalError:
    return AxiscalError(f"{spec.id}: {message}", path=campaign.folder / "campaign.toml", line=spec.line)


def _bounded(campaign: Campaign, spec: TestSpec, *keys: str) -> None:
    """Refuse an uncertainty (an option) that is negative or beyond 10000 um, or a tolerance of the test out of its range."""
    from axiscal.cmm.mpe import K_RANGE, LIMIT_M

    high = LIMIT_M / UM
    for key in keys:
        value = spec.options.get(key)
        if value is not None and not 0 <= value <= high:
            raise _located(campaign, spec, f"{key} must be 0 to {high:g}, not {value:g}")
    for key, value in spec.tolerances.items():
        if key.endswith("_k") and not K_RANGE[0] <= value <= K_RANGE[1]:
            raise _located(campaign, spec, f"tolerances: {key} must be {K_RANGE[0]:g} to {K_RANGE[1]:g}, not {value:g}")
        if key.endswith("_um") and not 0 < value <= high:
            raise _located(campaign, spec, f"tolerances: {key} must be above 0 and at most {high:g}, not {value:g}")


def _evaluated(campaign: Campaign, spec: TestSpec, call, names: dict[str, str]):
    """``call()``; a refusal that opens with a library argument (``mpe_150 is given ...``) names the test's key at the
    test's line; one that names it in brackets (``(calibrated_diameter_m 2500 mm)``) names the key where it stands."""
    try:
        return call()
    except AxiscalError as exc:
        head, sep, rest = exc.message.partition(" ")
        if head in names:
            raise _located(campaign, spec, names[head] + sep + rest) from None
        for name, key in names.items():
            if f"({name} " in exc.message:
                raise AxiscalError(exc.message.replace(f"({name} ", f"({key} "), path=exc.path, line=exc.line) from None
        raise


def _stated_mpe(campaign: Campaign, spec: TestSpec, test: str):
    from axiscal.cmm.mpe import Mpe

    t = spec.tolerances
    a, k, b = t.get(f"cmm_{test}_a_um"), t.get(f"cmm_{test}_k"), t.get(f"cmm_{test}_b_um")
    if a is None:
        if k is not None or b is not None:
            raise _located(campaign, spec, f"cmm_{test}_k and cmm_{test}_b_um need cmm_{test}_a_um (the MPE's constant A)")
        return None
    try:
        return Mpe(a * UM, k=k, b_m=None if b is None else b * UM)
    except AxiscalError as exc:
        raise _located(campaign, spec, exc.message.replace("b_m", f"cmm_{test}_b_um").replace("a_m", f"cmm_{test}_a_um")) from None


def _cmm_acceptance(campaign: Campaign, spec: TestSpec) -> TestResult:
    from axiscal.cmm.acceptance import evaluate_acceptance
    from axiscal.cmm.plot import plot_acceptance

    path = spec.options["file"]
    _bounded(campaign, spec, "uncertainty_um", "uncertainty_um_per_m")
    mpe, mpe_150 = _stated_mpe(campaign, spec, "e0"), _stated_mpe(campaign, spec, "e150")
    r0 = spec.tolerances.get("cmm_r0_um")
    result = _evaluated(campaign, spec, lambda: evaluate_acceptance(
        path, mpe=mpe, mpe_150=mpe_150, r0_mpl_m=None if r0 is None else r0 * UM,
        uncertainty_m=spec.options.get("uncertainty_um", 0.0) * UM,
        uncertainty_per_m=spec.options.get("uncertainty_um_per_m", 0.0) * UM, rule=campaign.decision_rule),
        {"mpe": "tolerances: cmm_e0_a_um", "mpe_150": "tolerances: cmm_e150_a_um", "r0_mpl_m": "tolerances: cmm_r0_um"})
    figures = result.payload()
    checks, table = [], []
    for test in ("E0", "E150"):
        summary = figures[test]
        if summary is None:
            continue
        table.append(Figure(f"{test}: largest |E| ({summary['count']} values)", summary["max_abs_um"], "um"))
        if summary["mpe"] is not None:
            table.append(Figure(f"{test},MPE", summary["mpe"]["statement"], ""))
            counts = summary["counts"]
            table.append(Figure(f"{test}: values passing / no decision / failing",
                                f"{counts['pass']} / {counts['inconclusive']} / {counts['fail']}", ""))
        decisive = summary.get("decisive")
        if decisive is not None:
            key = f"{test}_decisive_um"
            figures[key] = abs(decisive["error_um"])
            checks.append(Check(key, key, abs(decisive["error_um"]), decisive["mpe_um"], "um", decisive["U_um"],
                                campaign.decision_rule))
            table.append(Figure(f"{test}: decisive value, position {decisive['position']}, {decisive['nominal_mm']:g} mm "
                                f"(MPE {decisive['mpe_um']:.3f} um, U {decisive['U_um']:.3f} um)", decisive["error_um"], "um"))
    if figures["R0_um"] is not None:
        table.append(Figure("R0: largest range of three repeats", figures["R0_um"], "um"))
        if figures["R0_mpl_um"] is not None:
            checks.append(Check("R0_um", "R0_um", figures["R0_um"], figures["R0_mpl_um"], "um"))
    svg = svg_of(lambda p: plot_acceptance(p, result))
    warnings = list(result.warnings) + [
        f"{s['test']} position {s['position']}, length {s['length']} may be measured again (ISO 10360-2 7.1)"
        for s in result.retest_sets()]
    return TestResult(
        id=spec.id, kind=spec.kind, axis=None, files=[relative_name(campaign, path)], figures=figures, checks=checks,
        plots=[Plot("Errors of indication against the calibrated length, by position, with the MPE"
                    + (" and the guard band" if campaign.decision_rule == "guard-band" else ""), svg)],
        table=table, warnings=warnings,
        uncertainty={c.figure: c.U for c in checks if c.U is not None},
        method="CMM length measurement test: ISO 10360-2:2009 (E0, E150, R0), conformance by ISO 14253-1 "
        f"({campaign.decision_rule}) with U = {result.uncertainty_m / UM:g} um + {result.uncertainty_per_m / UM:g} um/m x L",
    )


def _cmm_probing(campaign: Campaign, spec: TestSpec) -> TestResult:
    from axiscal.cmm.plot import plot_probing
    from axiscal.cmm.probing import evaluate_probing

    path = spec.options["file"]
    _bounded(campaign, spec, "uncertainty_um")
    if spec.options["diameter_mm"] <= 0:
        raise _located(campaign, spec, f"diameter_mm must be a positive number, not {spec.options['diameter_mm']:g}")
    mpe = {key.removesuffix("_um"): value * UM for key, value in spec.tolerances.items()}
    try:
        result = _evaluated(campaign, spec, lambda: evaluate_probing(
            path, calibrated_diameter_m=spec.options["diameter_mm"] * MM, mpe_m=mpe,
            uncertainty_m=spec.options.get("uncertainty_um", 0.0) * UM, rule=campaign.decision_rule),
            {"calibrated_diameter_m": "diameter_mm"})
    except AxiscalError as exc:
        if "several styli" in exc.message:
            raise _located(campaign, spec, exc.message.replace("MPE", "tolerance")) from None
        raise
    figures = result.payload()
    U = result.uncertainty_m / UM
    checks = [Check(f"{key}_um", f"{key}_um", abs(value["value_um"]), value["mpe_um"], "um", U, campaign.decision_rule)
              for key, value in figures["figures"].items() if value["mpe_um"] is not None]
    table = [Figure(value["name"], value["value_um"], "um") for value in figures["figures"].values()]
    if len(figures["styli"]) > 1:
        table += [Figure(f"stylus {s}: form / size", f"{v['form_um']:.3f} / {v['size_um']:.3f}", "um")
                  for s, v in figures["styli"].items()]
    svg = svg_of(lambda p: plot_probing(p, result))
    return TestResult(
        id=spec.id, kind=spec.kind, axis=None, files=[relative_name(campaign, path)], figures=figures, checks=checks,
        plots=[Plot(f"Radial deviations of the probed points on the {figures['calibrated_diameter_mm']:g} mm sphere", svg)],
        table=table, warnings=list(result.warnings), uncertainty={c.figure: U for c in checks},
        method="CMM probing test: ISO 10360-5:2010 on a calibrated sphere (least-squares sphere), conformance by "
        f"ISO 14253-1 ({campaign.decision_rule})",
    )
