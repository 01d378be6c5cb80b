"""The campaign report: one self-contained HTML page rendered from the templates shipped with axiscal.

The page has no external resource (styles inline, plots as inline SVG), so it can be mailed,
archived or opened offline. Numbers come from :class:`~axiscal.campaign.results.CampaignResults`;
this module only arranges them.
"""

from __future__ import annotations

import datetime as _dt
import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from axiscal.campaign.config import TABLE_KEYS
from axiscal.campaign.results import CampaignResults, TestResult
from axiscal.errors import AxiscalError
from axiscal.squareness.evaluation import squareness_name
from axiscal.io.arguments import check_choice, check_count, check_mapping, is_real
from axiscal.io.arguments import check_instance, type_name
from axiscal.version import __version__

__all__ = [
    "template_environment",
    "render_html",
    "format_number",
    "display_unit",
    "decision_statement",
    "previous_figures",
    "previous_uncertainty",
    "compare_label",
    "verdict_rows",
    "sections",
    "report_facts",
    "page_context",
]

_SECTION_ORDER = ("positioning", "straightness", "separation", "squareness", "ballbar", "diagonal", "sixdof")
#: kinds with a section of their own after the others: kind -> (anchor, title)
_OWN_SECTIONS = {
    "flatness": ("flatness", "Flatness"),
    "thermal_etve": ("thermal", "Thermal tests (ISO 230-3)"),
    "thermal_drift": ("thermal", "Thermal tests (ISO 230-3)"),
    "cmm_acceptance": ("cmm", "CMM tests (ISO 10360)"),
    "cmm_probing": ("cmm", "CMM tests (ISO 10360)"),
    "dynamics": ("dynamics", "Dynamics, periodic errors and on-the-fly positioning"),
    "periodic": ("dynamics", "Dynamics, periodic errors and on-the-fly positioning"),
    "on_the_fly": ("dynamics", "Dynamics, periodic errors and on-the-fly positioning"),
}
_SECTION_TITLES = {"sensor_calibration": "Sensor calibration", "sixdof_diagonal": "Diagonal with the 6-DOF sensors"}


def template_environment():
    """The Jinja2 environment over the templates shipped as package data.

    Returns
    -------
    jinja2.Environment
        HTML templates autoescaped; ``fmt`` (:func:`format_number`) available in every template.
    """
    import jinja2

    env = jinja2.Environment(
        loader=jinja2.PackageLoader("axiscal", "templates"),
        autoescape=jinja2.select_autoescape(("html", "html.j2")),
        trim_blocks=True,
        lstrip_blocks=True,
        extensions=["jinja2.ext.i18n"],
    )
    env.install_null_translations(newstyle=True)  # English; a certificate installs its language's catalog
    env.globals["fmt"] = format_number
    env.filters["unit"] = lambda unit: _DISPLAY_UNITS.get(unit, unit) if isinstance(unit, str) else unit
    return env


def format_number(value: Any, digits: int = 3) -> str:
    """A figure as the report prints it.

    Parameters
    ----------
    value : float, str or None
        The figure (a text is returned as it is).
    digits : int
        Decimals.

    Returns
    -------
    str
        Fixed decimals, ``n/a`` for a missing or non-finite value.

    Raises
    ------
    AxiscalError
        For a value that is not a number, a text or None, or ``digits`` below 0.

    Examples
    --------
    >>> format_number(2.23333), format_number(float("nan"))
    ('2.233', 'n/a')
    """
    digits = check_count("digits", digits, minimum=0)
    if value is None:
        return "n/a"
    if isinstance(value, str):
        return value
    if not is_real(value):
        raise AxiscalError(f"value must be a number, a text or None, not {type_name(value)}")
    if isinstance(value, (int, np.integer)) and not isinstance(value, bool):
        return str(int(value))
    value = float(value)
    if not math.isfinite(value):
        return "n/a"
    return f"{value:.{digits}f}"


def check_compare(compare: Any) -> Mapping[str, Any]:
    """``compare`` if it is a results.json object (a mapping with a list of tests), else refused."""
    check_mapping("compare", compare, what="another campaign's results.json (a mapping)")
    if not isinstance(compare.get("tests", []), list):
        raise AxiscalError("compare must be another campaign's results.json (its 'tests' is not a list)")
    return compare


def decision_statement(rule: str) -> str:
    """How the report states the decision rule it held the figures to.

    Parameters
    ----------
    rule : {"simple", "guard-band"}

    Returns
    -------
    str
        One sentence, with the standard it comes from.

    Raises
    ------
    AxiscalError
        For an unknown rule.
    """
    from axiscal.uncertainty.decision import DECISION_RULES

    return "Decision rule: " + DECISION_RULES[check_choice("decision rule", rule, DECISION_RULES)]


def previous_figures(compare: Mapping[str, Any] | None) -> dict[str, Any] | None:
    """The figures of another campaign, by test id.

    Parameters
    ----------
    compare : mapping or None
        Another campaign's results.json.

    Returns
    -------
    dict or None
        Test id -> its figures; None without a comparison.

    Raises
    ------
    AxiscalError
        For a ``compare`` that is not a results.json object.
    """
    if compare is None:
        return None
    check_compare(compare)
    return {t.get("id"): t.get("figures", {}) for t in compare.get("tests", []) if isinstance(t, Mapping)}


def previous_uncertainty(compare: Mapping[str, Any] | None) -> dict[str, dict[str, float]] | None:
    """The expanded uncertainties (k = 2) of another campaign's figures, by test id.

    Parameters
    ----------
    compare : mapping or None
        Another campaign's results.json.

    Returns
    -------
    dict or None
        Test id -> figure key -> U, in the figure's unit, for the tests whose results carry an
        uncertainty (a campaign with a budget); None without a comparison.

    Raises
    ------
    AxiscalError
        For a ``compare`` that is not a results.json object.
    """
    if compare is None:
        return None
    check_compare(compare)
    out = {}
    for test in compare.get("tests", []):
        if isinstance(test, Mapping) and isinstance(test.get("uncertainty"), Mapping):
            out[test.get("id")] = {k: float(v) for k, v in test["uncertainty"].items()
                                   if k != "k" and is_real(v) and math.isfinite(v)}
    return out


def compare_label(compare: Mapping[str, Any] | None) -> str | None:
    """How the report names the campaign it is compared with.

    Parameters
    ----------
    compare : mapping or None
        Another campaign's results.json.

    Returns
    -------
    str or None
        Its title and date; None without a comparison.

    Raises
    ------
    AxiscalError
        For a ``compare`` that is not a results.json object.
    """
    if compare is None:
        return None
    check_compare(compare)
    info = compare.get("campaign", {})
    info = info.get("campaign", {}) if isinstance(info, Mapping) else {}
    info = info if isinstance(info, Mapping) else {}
    return f"{info.get('title', 'another campaign')} ({info.get('date', 'undated')})"


def verdict_rows(
    results: CampaignResults,
    before: Mapping[str, Any] | None,
    *,
    before_uncertainty: Mapping[str, Any] | None = None,
) -> list[dict[str, str]]:
    """The rows of the verdict table: each figure, and with a comparison its value before and the change.

    Parameters
    ----------
    results : CampaignResults
    before : mapping or None
        Figures of a campaign to compare with, by test id (see :func:`previous_figures`).
    before_uncertainty : mapping, keyword-only
        Expanded uncertainties of that campaign's figures, by test id (see
        :func:`previous_uncertainty`).

    Returns
    -------
    list of dict
        One row per toleranced figure, or per test without a tolerance; texts ready to print:
        ``value`` (this campaign's, the *after* of a comparison), ``U``, ``limit``, ``before``,
        ``before_U``, ``change`` (``|after| - |before|``, signed), ``result`` and ``css``.

    Raises
    ------
    AxiscalError
        For ``results`` that are not a CampaignResults, ``before`` or ``before_uncertainty``
        that is not a mapping.
    """
    check_instance("results", results, CampaignResults)
    if before is not None:
        check_mapping("before", before, what="a mapping of test ids to figures")
    if before_uncertainty is not None:
        check_mapping("before_uncertainty", before_uncertainty, what="a mapping of test ids to uncertainties")
    return _verdict_rows(results, before, before_uncertainty)


def _verdict_rows(results: CampaignResults, before: Mapping[str, Any] | None,
                  before_uncertainty: Mapping[str, Any] | None) -> list[dict[str, str]]:
    """:func:`verdict_rows` of checked arguments."""
    rows = []
    for test in results.tests:
        old = (before or {}).get(test.id, {})
        old_u = (before_uncertainty or {}).get(test.id, {})
        if not test.checks:
            rows.append({"test_id": test.id, "axis": test.axis or "", "figure": "no tolerance given", "value": "",
                         "U": "", "limit": "", "before": "", "before_U": "", "change": "", "result": "not assessed",
                         "css": "na"})
            continue
        for check in test.checks:
            name = check.figure.removesuffix('_' + check.unit)
            if test.kind == "squareness" and check.figure == "squareness_arcsec" and "convention" in test.figures:
                # the signed figure under the name that says its sign, as its section and plot show it
                name = squareness_name(test.figures["plane"], test.figures["convention"])
            previous = old.get(check.figure) if isinstance(old, Mapping) else None
            previous = float(previous) if is_real(previous) and math.isfinite(previous) else None
            previous_u = old_u.get(check.figure) if isinstance(old_u, Mapping) else None
            change = "" if previous is None or not math.isfinite(check.value) else f"{abs(check.value) - abs(previous):+.3f}"
            rows.append({
                "test_id": test.id, "axis": test.axis or "",
                "figure": f"{name} / {_DISPLAY_UNITS.get(check.unit, check.unit)}",
                "value": format_number(check.value), "limit": format_number(check.limit),
                "U": "" if check.U is None else format_number(check.U),
                "before": "" if previous is None else format_number(previous),
                "before_U": format_number(previous_u) if is_real(previous_u) else "",
                "change": change, "result": check.result, "css": check.result,
            })
    return rows


#: units as a page shows them (files and flags spell them in ASCII)
_DISPLAY_UNITS = {"um": "µm", "urad": "µrad", "um/m": "µm/m", "um/year": "µm/year", "degC": "°C"}


def display_unit(unit: str) -> str:
    """A unit as a page shows it: ``um`` -> ``µm``, ``urad`` -> ``µrad``; others unchanged.

    Parameters
    ----------
    unit : str

    Returns
    -------
    str

    Raises
    ------
    AxiscalError
        For a unit that is not a text.

    Examples
    --------
    >>> display_unit("um"), display_unit("arcsec")
    ('µm', 'arcsec')
    """
    check_instance("unit", unit, str)
    return _DISPLAY_UNITS.get(unit, unit)


def sections(tests: list[TestResult]) -> list[dict[str, Any]]:
    """The report's sections.

    Parameters
    ----------
    tests : list of TestResult

    Returns
    -------
    list of dict
        ``anchor``, ``title`` and ``tests`` of each section: one per axis, then squareness,
        circular tests, diagonal checks, 6-DOF recordings.

    Raises
    ------
    AxiscalError
        For ``tests`` that are not a list of TestResult.
    """
    if isinstance(tests, (str, bytes)) or not isinstance(tests, (list, tuple)) or not all(isinstance(t, TestResult) for t in tests):
        raise AxiscalError(f"tests must be a list of TestResult, not {type_name(tests)}")
    groups: dict[str, list[TestResult]] = {}
    titles: dict[str, str] = {}
    for test in sorted(tests, key=lambda t: (_SECTION_ORDER.index(t.kind) if t.kind in _SECTION_ORDER else 99)):
        if test.kind in ("positioning", "straightness", "separation") and test.axis:
            key, title = f"axis-{test.axis}", f"{test.axis} axis"
        elif test.kind == "squareness":
            key, title = "squareness", "Squareness"
        elif test.kind == "ballbar":
            key, title = "ballbar", "Circular tests"
        elif test.kind == "diagonal":
            key, title = "diagonal", "Diagonal checks"
        elif test.kind == "sixdof":
            key, title = "sixdof", "6-DOF recordings"
        elif test.kind == "levels" and test.axis:
            key, title = f"axis-{test.axis}", f"{test.axis} axis"
        elif test.kind in _OWN_SECTIONS:
            key, title = _OWN_SECTIONS[test.kind]
        else:
            key, title = test.kind, _SECTION_TITLES.get(test.kind, test.kind.capitalize())
        groups.setdefault(key, []).append(test)
        titles[key] = title
    axis_keys = sorted(k for k in groups if k.startswith("axis-"))
    other = [k for k in ("squareness", "ballbar", "diagonal", "sixdof") if k in groups]
    rest = [k for k in groups if k not in axis_keys and k not in other]
    return [{"anchor": k, "title": titles[k], "tests": groups[k]} for k in (*axis_keys, *other, *rest)]


# (table, key) -> the label of its line in the report's facts, in the order they are printed; the
# instrument's name, serial, certificate and calibration date share one line, as the machine's name
# and serial do
_FACT_LABELS = {
    ("machine", "name"): "Machine",
    ("machine", "manufacturer"): "Manufacturer",
    ("machine", "condition"): "Condition as received",
    ("machine", "model"): "Machine model",
    ("machine", "controller"): "Controller",
    ("machine", "compensation"): "Compensation loaded",
    ("campaign", "date"): "Date",
    ("campaign", "operator"): "Operator",
    ("campaign", "customer"): "Customer",
    ("campaign", "customer_address"): "Customer's address",
    ("instrument", "name"): "Instrument",
    ("instrument", "vacuum_wavelength_nm"): "Vacuum wavelength",
    ("campaign", "notes"): "Notes",
}
_JOINED = {("machine", "name"): ("serial",), ("instrument", "name"): ("serial", "certificate", "calibrated", "calibrated_by")}
_SHOWN_ELSEWHERE = {("campaign", "title")}  # the report's heading


def _fact_text(value: Any) -> str:
    """A field as the report shows it: a table of files (``[machine] compensation``) as ``X X.comp, Z Z.comp``."""
    if isinstance(value, Mapping):
        return ", ".join(f"{k} {v}" for k, v in value.items())
    return str(value)


def report_facts(results: CampaignResults) -> list[tuple[str, str]]:
    """The lines that head the report: every field of [campaign], [machine] and [instrument] stated.

    Parameters
    ----------
    results : CampaignResults

    Returns
    -------
    list of (str, str)
        ``(label, text)``: ``("Machine", "XZ module, serial 7")``, ``("Vacuum wavelength",
        "632.99137 nm")`` ... The instrument's line says ``not stated`` when the campaign has no
        ``[instrument]``; a field without a label of its own is shown under its key.

    Raises
    ------
    AxiscalError
        For ``results`` that are not a CampaignResults.
    """
    check_instance("results", results, CampaignResults)
    return _report_facts(results)


def _report_facts(results: CampaignResults) -> list[tuple[str, str]]:
    """:func:`report_facts` of a checked CampaignResults."""
    tables = {"campaign": results.campaign, "machine": results.machine, "instrument": results.instrument}
    joined = {(table, key) for (table, _), keys in _JOINED.items() for key in keys}
    facts: list[tuple[str, str]] = []
    for (table, key), label in _FACT_LABELS.items():
        values = tables[table]
        if (table, key) in _JOINED:
            parts = [str(values[key])] if values.get(key) not in (None, "") else []
            parts += [f"{extra} {values[extra]}" for extra in _JOINED[(table, key)] if values.get(extra) not in (None, "")]
            if parts or table == "instrument":
                facts.append((label, ", ".join(parts) or "not stated"))
        elif values.get(key) not in (None, ""):
            value = values[key]
            facts.append((label, f"{value} nm" if key.endswith("_nm") else _fact_text(value)))
    done = set(_FACT_LABELS) | joined | _SHOWN_ELSEWHERE
    for table, keys in TABLE_KEYS.items():
        facts += [(f"[{table}] {key}", _fact_text(tables[table][key])) for key in keys
                  if (table, key) not in done and tables[table].get(key) not in (None, "")]
    return facts


def render_html(
    results: CampaignResults,
    *,
    compare: Mapping[str, Any] | None = None,
    volumetric: Mapping[str, Any] | None = None,
    generated: str | None = None,
    history: Mapping[str, Any] | None = None,
) -> str:
    """The report page of a campaign.

    Parameters
    ----------
    results : CampaignResults
        What the campaign's tests gave.
    compare : mapping, keyword-only
        Another campaign's results.json (e.g. before compensation): the verdict table shows each
        figure before (with its U when that results.json has one), after, and the change.
    volumetric : mapping, keyword-only
        The volumetric section (``method``, ``table``, ``plots``), when the campaign has a model.
    generated : str, keyword-only
        When the report was made (default: now, UTC, to the minute).
    history : mapping, keyword-only
        The history section (:func:`~axiscal.report.history.history_section`): shown when the
        machine has earlier campaigns.

    Returns
    -------
    str
        The HTML text.

    Raises
    ------
    AxiscalError
        For ``results`` that are not a CampaignResults, a ``compare`` that is not a
        results.json object, a ``volumetric`` that is not a mapping, a ``generated`` that is
        not a str.
    """
    check_instance("results", results, CampaignResults)
    if volumetric is not None:
        check_mapping("volumetric", volumetric, what="the volumetric section (a mapping)")
    if generated is not None and not isinstance(generated, str):
        raise AxiscalError(f"generated must be a str (when the report was made), not {type_name(generated)}")
    return template_environment().get_template("report/report.html.j2").render(
        **page_context(results, compare=compare, volumetric=volumetric, generated=generated, history=history))


def page_context(results: CampaignResults, *, compare: Mapping[str, Any] | None = None,
                 volumetric: Mapping[str, Any] | None = None, generated: str | None = None,
                 history: Mapping[str, Any] | None = None) -> dict[str, Any]:
    """The names the report page's template reads (the certificate's template too, which extends it).

    Parameters
    ----------
    results : CampaignResults
    compare, volumetric, generated, history : keyword-only
        As for :func:`render_html`, which checks them; this trusts its caller.

    Returns
    -------
    dict
        Template name -> value.
    """
    check_instance("results", results, CampaignResults)
    label = compare_label(compare)
    rows = _verdict_rows(results, previous_figures(compare), previous_uncertainty(compare))
    methods = sorted({t.method for t in results.tests if t.method})
    methods.append(decision_statement(results.decision_rule))
    return dict(
        version=__version__,
        generated=generated or _dt.datetime.now(_dt.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
        campaign=results.campaign,
        machine=results.machine,
        instrument=results.instrument,
        facts=_report_facts(results),
        verdict=results.verdict,
        verdict_rows=rows,
        has_u=any(c.U is not None for test in results.tests for c in test.checks),
        has_u_before=any(row["before_U"] for row in rows),
        warnings=results.all_warnings,
        sections=sections(results.tests),
        volumetric=volumetric if volumetric is not None else (results.model or None),
        compensation=results.compensation,
        methods=methods,
        compare={"label": label} if compare is not None else None,
        history=history if history is not None and history.get("campaigns", 0) > 1 else None,
    )
