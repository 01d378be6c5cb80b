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

from axiscal.campaign.results import CampaignResults, TestResult, results_payload
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_choice, check_count, check_mapping, is_real
from axiscal.io.arguments import check_instance, type_name
from axiscal.version import __version__

__all__ = [
    "template_environment",
    "render_html",
    "format_number",
    "decision_statement",
    "previous_figures",
    "compare_label",
    "verdict_rows",
    "sections",
]

_SECTION_ORDER = ("positioning", "straightness", "separation", "squareness", "ballbar", "diagonal", "sixdof")


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
    )
    env.globals["fmt"] = format_number
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


def verdict_rows(results: CampaignResults, before: Mapping[str, Any] | None) -> list[dict[str, str]]:
    """The rows of the verdict table.

    Parameters
    ----------
    results : CampaignResults
    before : mapping or None
        Figures of a campaign to compare with, by test id (see :func:`previous_figures`).

    Returns
    -------
    list of dict
        One row per toleranced figure, or per test without a tolerance; texts ready to print.

    Raises
    ------
    AxiscalError
        For ``results`` that are not a CampaignResults or ``before`` that is not a mapping.
    """
    check_instance("results", results, CampaignResults)
    if before is not None:
        check_mapping("before", before, what="a mapping of test ids to figures")
    rows = []
    for test in results.tests:
        old = (before or {}).get(test.id, {})
        if not test.checks:
            rows.append({"test_id": test.id, "axis": test.axis or "", "figure": "no tolerance given", "value": "",
                         "U": "", "limit": "", "before": "", "change": "", "result": "not assessed", "css": "na"})
            continue
        for check in test.checks:
            previous = old.get(check.figure) if isinstance(old, Mapping) else None
            change = "" if previous is None else f"{abs(check.value) - abs(float(previous)):+.3f}"
            rows.append({
                "test_id": test.id, "axis": test.axis or "",
                "figure": f"{check.figure.removesuffix('_' + check.unit)} / {check.unit}",
                "value": format_number(abs(check.value)), "limit": format_number(check.limit),
                "U": "" if check.U is None else format_number(check.U),
                "before": "" if previous is None else format_number(abs(float(previous))), "change": change,
                "result": check.result, "css": check.result,
            })
    return rows


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
        else:
            key, title = test.kind, test.kind.capitalize()
        groups.setdefault(key, []).append(test)
        titles[key] = title
    axis_keys = sorted(k for k in groups if k.startswith("axis-"))
    other = [k for k in ("squareness", "ballbar", "diagonal", "sixdof") if k in groups]
    rest = [k for k in groups if k not in axis_keys and k not in other]
    return [{"anchor": k, "title": titles[k], "tests": groups[k]} for k in (*axis_keys, *other, *rest)]


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
        figure's value there and its change.
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
    before = previous_figures(compare)
    label = compare_label(compare)
    payload = results_payload(results)
    methods = sorted({t.method for t in results.tests if t.method})
    methods.append(decision_statement(results.decision_rule))
    env = template_environment()
    return env.get_template("report/report.html.j2").render(
        version=__version__,
        generated=generated or _dt.datetime.now(_dt.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
        campaign=results.campaign,
        machine=results.machine,
        instrument=results.instrument,
        verdict=results.verdict,
        verdict_rows=verdict_rows(results, before),
        has_u=any(c.U is not None for test in results.tests for c in test.checks),
        warnings=payload["warnings"],
        sections=sections(results.tests),
        volumetric=volumetric if volumetric is not None else (results.model or None),
        compensation=results.compensation,
        methods=methods,
        compare={"label": label} if compare is not None else None,
        history=history if history is not None and history.get("campaigns", 0) > 1 else None,
    )
