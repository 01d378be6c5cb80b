"""The calibration certificate: what a campaign report adds to become one (ISO/IEC 17025:2017, 7.8).

The certificate is a mode of the report, not a second report: the same results, the same
templates, with a layer on top that carries what 7.8.2.1 and 7.8.4.1 ask of a calibration
certificate: the laboratory, the certificate's number on every page, the customer, where the work
was done, the item and its condition, the method and any deviation from it, the dates, every
result with its unit and its expanded uncertainty (with k and the coverage probability, or the
words saying why there is none), the conditions of each test, the metrological traceability, the
decision rule (ILAC-G8) with the source of the limits, the people who authorise it, and the two
fixed statements. Recommended calibration intervals stay off the certificate (ILAC-G24).

:func:`missing_certificate_fields` lists what a campaign lacks for a certificate;
:func:`certificate_context` builds the layer's texts in one language (:mod:`axiscal.report.i18n`).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from axiscal.campaign.results import CampaignResults, Figure, TestResult
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_choice, check_instance
from axiscal.report.i18n import format_date_for, format_decimal_for, translations

__all__ = [
    "COVERAGE_FACTOR",
    "COVERAGE_PROBABILITY",
    "missing_certificate_fields",
    "check_certificate",
    "certificate_context",
    "figure_rows",
    "localised_rows",
    "certificate_environment",
    "render_certificate_html",
]

#: the coverage factor of every expanded uncertainty axiscal states (the budgets' U)
COVERAGE_FACTOR = 2
#: the coverage probability it stands for (a normal distribution; "about 95 %")
COVERAGE_PROBABILITY = 0.95

def _(text: str) -> str:
    """Marks a message for the catalogs; translated where it is used, in the certificate's language."""
    return text


#: what a certificate needs from the campaign: (table, key) in campaign.toml
_REQUIRED = (
    ("laboratory", "name"), ("laboratory", "address"), ("laboratory", "country"),
    ("certificate", "number"), ("certificate", "issue_date"), ("certificate", "location"),
    ("campaign", "customer"), ("campaign", "customer_address"),
    ("machine", "manufacturer"), ("machine", "condition"),
    ("instrument", "name"), ("instrument", "serial"), ("instrument", "certificate"),
    ("instrument", "calibrated"), ("instrument", "calibrated_by"),
)

#: where the work was done, as the certificate says it (the DCC's performanceLocation values)
_LOCATIONS = {
    "laboratory": _("at the laboratory's premises"),
    "customer": _("at the customer's site"),
    "laboratoryBranch": _("at a branch of the laboratory"),
    "customerBranch": _("at a branch of the customer"),
    "other": _("at another site"),
}


#: why a figure of a kind of test has no expanded uncertainty (no budget of the campaign covers it)
_NO_U = {
    "straightness": _("no uncertainty budget for the straightness instrument is stated"),
    "separation": _("no uncertainty budget for the probes of the error separation is stated"),
    "levels": _("no uncertainty budget for the electronic levels is stated"),
    "flatness": _("no uncertainty budget for the flatness instruments is stated"),
    "diagonal": _("predicted by the machine model, or measured without an uncertainty budget"),
    "sixdof_diagonal": _("the budget covers the laser along one axis; the diagonal's set-up is not budgeted"),
    "sixdof": _("6-DOF sensor readings, shown for information; not a calibration result"),
    "sensor_calibration": _("a residual of the sensors' calibration, shown as a check; not a calibration result"),
}
_NO_BUDGET = _("the campaign states no uncertainty budget")
_NOT_BUDGETED = _("not covered by the campaign's uncertainty budget")
_A_COUNT = _("a count: exact")
_PREDICTED = _("predicted by the machine model, not measured")

_STATEMENTS = (
    _("The results relate only to the item calibrated, at the time and under the conditions of the calibration."),
    _("This certificate shall not be reproduced except in full without the written approval of the issuing "
      "laboratory."),
)


def missing_certificate_fields(results: CampaignResults) -> list[str]:
    """What the campaign lacks for a calibration certificate, as campaign.toml spells it.

    Parameters
    ----------
    results : CampaignResults

    Returns
    -------
    list of str
        ``"[laboratory] name"``, ``"[[signatory]]"``, ``"[certificate] tolerance_source"`` (when a
        conformity statement is made) ...; empty when the certificate can be written.

    Raises
    ------
    AxiscalError
        For ``results`` that are not a CampaignResults.
    """
    check_instance("results", results, CampaignResults)
    tables = {"campaign": results.campaign, "machine": results.machine, "instrument": results.instrument,
              "laboratory": results.issuer.get("laboratory", {}), "certificate": results.issuer.get("certificate", {})}
    missing = [f"[{table}] {key}" for table, key in _REQUIRED if tables[table].get(key) in (None, "")]
    if not results.issuer.get("signatories"):
        missing.append("[[signatory]] name and role")
    if any(t.checks for t in results.tests) and not tables["certificate"].get("tolerance_source"):
        missing.append("[certificate] tolerance_source")
    return missing


def check_certificate(results: CampaignResults, campaign_file: Any = None) -> None:
    """Refuse, in one line listing every missing field, a campaign that cannot make a certificate.

    Parameters
    ----------
    results : CampaignResults
    campaign_file : path, optional
        campaign.toml, named in the error.

    Returns
    -------
    None

    Raises
    ------
    AxiscalError
        When :func:`missing_certificate_fields` is not empty.
    """
    missing = missing_certificate_fields(results)
    if missing:
        raise AxiscalError("a calibration certificate needs " + ", ".join(missing), path=campaign_file)


def _figure_key(test: TestResult, figure: Figure) -> str | None:
    """The key of ``figure`` in the test's figures (the table shows it under a label)."""
    if figure.label in test.figures:
        return figure.label
    same = [key for key, value in test.figures.items() if value is figure.value
            or (isinstance(value, float) and isinstance(figure.value, float) and value == figure.value)]
    return next((key for key in same if key in test.uncertainty), same[0] if same else None)


def figure_rows(results: CampaignResults, gettext: Callable[[str], str] = str) -> list[dict[str, Any]]:
    """Every figure the report shows, with its expanded uncertainty or why it has none.

    Parameters
    ----------
    results : CampaignResults
    gettext : callable
        Translates the reasons (default: English).

    Returns
    -------
    list of dict
        ``test_id``, ``kind``, ``label``, ``key`` (the figure's key in results.json, or None),
        ``value`` (number or text), ``unit`` (as files spell it), ``U`` (float or None, in the
        figure's unit, k = 2), ``why`` (the reason when U is None), ``limit`` and ``result`` (when
        the figure is held against a tolerance).
    """
    check_instance("results", results, CampaignResults)
    if not callable(gettext):
        raise AxiscalError(f"gettext must be a function that translates a message, not {gettext!r}"[:200])
    rows = []
    budget = any(t.uncertainty for t in results.tests)
    for test in results.tests:
        checks = {c.figure: c for c in test.checks}
        for figure in test.table:
            key = _figure_key(test, figure)
            U = test.uncertainty.get(key) if key is not None else None
            why = None
            if U is None:
                if isinstance(figure.value, (int,)) and not isinstance(figure.value, bool) or figure.unit in ("", None):
                    why = _A_COUNT if isinstance(figure.value, int) else _NOT_BUDGETED
                elif test.kind == "diagonal" and key == "model_error_range_um":
                    why = _PREDICTED
                elif test.kind in _NO_U and not test.uncertainty:
                    why = _NO_U[test.kind]
                else:
                    why = _NOT_BUDGETED if budget else _NO_BUDGET
            check = checks.get(key) if key is not None else None
            rows.append({"test_id": test.id, "kind": test.kind, "label": figure.label, "key": key,
                         "value": figure.value, "unit": figure.unit, "U": U,
                         "why": None if why is None else gettext(why),
                         "limit": None if check is None else check.limit,
                         "result": None if check is None else check.result})
    return rows


def _standards(results: CampaignResults) -> list[str]:
    """The methods and standards with their editions, one line each, as the tests name them."""
    return sorted({t.method for t in results.tests if t.method})


def certificate_context(results: CampaignResults, language: str) -> dict[str, Any]:
    """The certificate layer's texts in ``language``, for the templates.

    Parameters
    ----------
    results : CampaignResults
        A campaign with the certificate's fields (:func:`check_certificate` passed).
    language : str
        ISO 639-1 code with a catalog (``en``, ``de``).

    Returns
    -------
    dict
        ``language``, ``number``, ``issue_date``, ``performance_date``, ``location``,
        ``laboratory``, ``customer``, ``item``, ``replaces``, ``signatories``, ``methods``,
        ``deviations``, ``figures`` (:func:`figure_rows` with the numbers written in the language),
        ``conditions``, ``traceability``, ``decision``, ``statements``, ``coverage``.
    """
    check_certificate(results)
    tr = translations(language).gettext
    lab = results.issuer["laboratory"]
    cert = results.issuer["certificate"]
    instrument = results.instrument

    def number(value: Any, digits: int = 3) -> str:
        return format_decimal_for(value, digits, language)

    figures = []
    for row in figure_rows(results, tr):
        digits = 0 if isinstance(row["value"], int) else 3
        figures.append({**row, "value_text": number(row["value"], digits),
                        "U_text": "" if row["U"] is None else number(row["U"]),
                        "limit_text": "" if row["limit"] is None else number(row["limit"]),
                        "result_text": "" if row["result"] is None else tr(row["result"])})
    conditions = []
    for test in results.tests:
        if test.environment:
            conditions.append({"test_id": test.id, "sensors": [
                {"name": tr(name), "mean": number(e.get("mean"), e.get("digits", 2)),
                 "min": number(e.get("min"), e.get("digits", 2)), "max": number(e.get("max"), e.get("digits", 2)),
                 "unit": e.get("unit", "")} for name, e in test.environment.items()]})
        else:
            conditions.append({"test_id": test.id, "sensors": [],
                               "words": tr("no air or material sensors were recorded with this test's data")})
    traceability = tr(
        "The measurements are traceable to the International System of Units (SI) through the {instrument}, "
        "serial {serial}, calibrated by {body} on {date}, certificate {certificate}."
    ).format(instrument=instrument.get("name", ""), serial=instrument.get("serial", ""),
             body=instrument.get("calibrated_by", ""), certificate=instrument.get("certificate", ""),
             date=format_date_for(instrument["calibrated"], language) if instrument.get("calibrated") else "")
    if instrument.get("vacuum_wavelength_nm") is not None:
        traceability += " " + tr("The laser's vacuum wavelength is {wavelength} nm.").format(
            wavelength=format_decimal_for(instrument["vacuum_wavelength_nm"], 5, language))
    rule = {"simple": tr("simple acceptance: a figure conforms when its value is within the limit (ILAC-G8:09/2019, "
                         "4.2.1; the measurement uncertainty is stated beside it but not taken into account)"),
            "guard-band": tr("guarded acceptance (ISO 14253-1, ILAC-G8:09/2019 4.2.2): a figure conforms when its "
                             "value plus U is within the limit, does not conform when its value minus U exceeds "
                             "it, and is inconclusive between")}[results.decision_rule]
    assessed = any(t.checks for t in results.tests)
    decision = None
    if assessed:
        decision = {"rule": rule, "source": cert.get("tolerance_source", ""), "verdict": tr(results.verdict)}
    return {
        "language": language,
        "title": tr("Calibration certificate"),
        "number": cert["number"],
        "issue_date": format_date_for(cert["issue_date"], language),
        "performance_date": format_date_for(results.campaign["date"], language),
        "location": tr(_LOCATIONS[cert["location"]]),
        "laboratory": {"name": lab["name"], "address": lab["address"], "country": lab["country"],
                       "accreditation": lab.get("accreditation")},
        "customer": {"name": results.campaign.get("customer", ""), "address": results.campaign.get("customer_address", "")},
        "item": {"name": results.machine.get("name", ""), "serial": results.machine.get("serial"),
                 "manufacturer": results.machine.get("manufacturer", ""), "condition": results.machine.get("condition", "")},
        "replaces": cert.get("replaces"),
        "signatories": list(results.issuer.get("signatories", [])),
        "methods": _standards(results),
        "deviations": cert.get("deviations") or tr("none"),
        "figures": figures,
        "conditions": conditions,
        "traceability": traceability,
        "decision": decision,
        "statements": [tr(s) for s in _STATEMENTS],
        "coverage": tr("U is the expanded uncertainty for k = {k}, a coverage probability of about {p} %.").format(
            k=COVERAGE_FACTOR, p=round(COVERAGE_PROBABILITY * 100)),
    }



_NO_TOLERANCE = _("no tolerance given")
_NUMBER_TEXT = __import__("re").compile(r"^[-+]?\d+\.\d+$")


def localised_rows(rows: list[dict[str, str]], language: str) -> list[dict[str, str]]:
    """The report's verdict rows (:func:`axiscal.report.html.verdict_rows`) written in ``language``.

    Parameters
    ----------
    rows : list of dict
    language : str

    Returns
    -------
    list of dict
        The numbers with the language's decimal sign, the words translated.
    """
    from babel.numbers import get_decimal_symbol

    if not isinstance(rows, list) or not all(isinstance(row, dict) for row in rows):
        raise AxiscalError("rows must be the report's verdict rows (a list of dicts)")
    tr = translations(language).gettext
    point = get_decimal_symbol(language)
    out = []
    for row in rows:
        row = dict(row)
        for key in ("value", "U", "limit", "before", "before_U", "change"):
            if _NUMBER_TEXT.match(row.get(key, "")):
                row[key] = row[key].replace(".", point)
        if row.get("figure") == _NO_TOLERANCE:
            row["figure"] = tr(_NO_TOLERANCE)
        out.append(row)
    return out


#: words shown through the catalogs that the code hands over as data (verdicts, sensors), for the extraction
_DATA_WORDS = (_("pass"), _("fail"), _("inconclusive"), _("not assessed"), _("air temperature"), _("air pressure"),
               _("relative humidity"), _("material temperature"), _("none"))


def certificate_environment(language: str):
    """The report's template environment speaking ``language``: its catalog installed, numbers written its way.

    Parameters
    ----------
    language : str

    Returns
    -------
    jinja2.Environment
    """
    from axiscal.report.html import template_environment

    env = template_environment()
    env.install_gettext_translations(translations(language), newstyle=True)
    env.globals["fmt"] = lambda value, digits=3: format_decimal_for(value, digits, language)
    return env


def render_certificate_html(results: CampaignResults, *, language: str,
                            compare: dict[str, Any] | None = None) -> str:
    """The certificate page: the report's page in ``language`` with the certificate layer.

    Parameters
    ----------
    results : CampaignResults
        With the certificate's fields (:func:`check_certificate` passed).
    language : str
    compare : mapping, keyword-only
        Another campaign's results, as for the report.

    Returns
    -------
    str
        The HTML text. The page carries no history (calibration intervals stay off a certificate).
    """
    from axiscal.report.html import check_compare, page_context

    check_certificate(results)
    env = certificate_environment(language)
    if compare is not None:
        check_compare(compare)
    context = page_context(results, compare=compare, generated=results.issuer["certificate"]["issue_date"])
    context["verdict_rows"] = localised_rows(context["verdict_rows"], language)
    return env.get_template("report/certificate.html.j2").render(
        **context, cert=certificate_context(results, language))
