"""The Digital Calibration Certificate (PTB's DCC, XML schema 3.2.0 with D-SI 2.1.0), written and read back.

:func:`dcc_xml` writes the certificate of a campaign as a DCC from the same results the report
shows: administrativeData from the campaign's ``[laboratory]``, ``[certificate]``,
``[[signatory]]``, ``[campaign]``, ``[machine]`` and ``[instrument]`` tables; one measurementResult
per test with its method (usedMethods), the instrument (measuringEquipments), the air and material
conditions as measured (influenceConditions: mean, min, max) and every figure of results.json: each
number an ``si:real`` with its D-SI unit and, where the campaign's budget gives one,
``si:expandedUnc`` (k = 2, coverage probability 0.95), each list of numbers (per-target deviations,
profiles) an ``si:realListXMLList``, each text a ``dcc:noQuantity``, and the conformity of each
toleranced figure with its limit. The volumetric error of the machine model is one more
measurementResult.

Each quantity carries the figure's key path in results.json in its ``refType``
(``axiscal_figure:targets/mean_up_um``), so :func:`read_dcc` gives back a results.json object that
``axiscal report --compare`` takes as it takes an earlier visit's results.json.

The schema version lives in :data:`SCHEMA_VERSION` only.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from collections.abc import Iterator, Mapping
from pathlib import Path
from typing import Any
from urllib.parse import quote, unquote

from axiscal.campaign.results import SCHEMA, CampaignResults, TestResult, results_payload
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_mapping, check_path
from axiscal.report.certificate import COVERAGE_FACTOR, COVERAGE_PROBABILITY
from axiscal.report.i18n import translations
from axiscal.version import __version__

__all__ = ["SCHEMA_VERSION", "DCC_NS", "SI_NS", "dsi_unit", "dcc_xml", "read_dcc", "dcc_summary"]

#: the DCC schema this module writes (the root's ``schemaVersion``)
SCHEMA_VERSION = "3.2.0"
DCC_NS = "https://ptb.de/dcc"
SI_NS = "https://ptb.de/si"
_XSI = "http://www.w3.org/2001/XMLSchema-instance"
_SCHEMA_LOCATION = f"{DCC_NS} {DCC_NS}/v{SCHEMA_VERSION}/dcc.xsd"
#: the refType of a quantity that holds a figure of results.json; its key path follows the colon
FIGURE_REF = "axiscal_figure:"
#: the refType of a measurementResult that holds a test; the test's id follows the colon
TEST_REF = "axiscal_test:"

ET.register_namespace("dcc", DCC_NS)
ET.register_namespace("si", SI_NS)
ET.register_namespace("xsi", _XSI)

#: unit suffixes of figure keys, longest first, and their D-SI units
_SUFFIX_UNITS = (
    ("_um_per_m", r"\micro\metre\metre\tothe{-1}"),
    ("_um_per_k", r"\micro\metre\kelvin\tothe{-1}"),
    ("_mm_min", r"\milli\metre\minute\tothe{-1}"),
    ("_mm_s", r"\milli\metre\second\tothe{-1}"),
    ("_per_k", r"\kelvin\tothe{-1}"),
    ("_um", r"\micro\metre"), ("_mm", r"\milli\metre"), ("_nm", r"\nano\metre"), ("_m", r"\metre"),
    ("_urad", r"\micro\radian"), ("_mrad", r"\milli\radian"), ("_rad", r"\radian"),
    ("_arcsec", r"\arcsecond"), ("_arcmin", r"\arcminute"), ("_deg", r"\degree"),
    ("_ms", r"\milli\second"), ("_s", r"\second"), ("_h", r"\hour"), ("_hz", r"\hertz"),
    ("_c", r"\degreecelsius"), ("_degc", r"\degreecelsius"), ("_k", r"\kelvin"), ("_pa", r"\pascal"),
    ("_percent", r"\percent"), ("_ppm", r"\micro\metre\metre\tothe{-1}"), ("_kg", r"\kilogram"),
    ("_urad_s", r"\micro\radian\second\tothe{-1}"),
)
_BY_LENGTH = sorted(_SUFFIX_UNITS, key=lambda item: -len(item[0]))
#: units as files spell them (a figure's ``unit``, a sensor's unit) and their D-SI units
_NAMED_UNITS = {"um": r"\micro\metre", "mm": r"\milli\metre", "arcsec": r"\arcsecond", "urad": r"\micro\radian",
                "deg": r"\degree", "degC": r"\degreecelsius", "Pa": r"\pascal", "%": r"\percent", "s": r"\second",
                "K": r"\kelvin", "": r"\one"}


def _(text: str) -> str:
    """Marks a message for the catalogs; :func:`_text` translates it into each language of the certificate."""
    return text


def dsi_unit(key: str, unit: str | None = None) -> str:
    """The D-SI unit of a figure of results.json.

    Parameters
    ----------
    key : str
        The figure's key: its suffix names the unit (``straightness_um`` -> ``\\micro\\metre``).
    unit : str, optional
        The unit its test states for keys without a suffix (positioning's ``A``, ``E`` ...: ``um`` or
        ``arcsec``).

    Returns
    -------
    str
        A D-SI unit string; ``\\one`` for a count or a ratio (a key with no unit suffix).
    """
    if not isinstance(key, str) or not key:
        raise AxiscalError(f"key must be a figure's key (a non-empty str), not {key!r}"[:200])
    if unit is not None and not isinstance(unit, str):
        raise AxiscalError(f"unit must be a unit as files spell it (a str) or None, not {unit!r}"[:200])
    lowered = key.lower()
    for suffix, dsi in _BY_LENGTH:
        if lowered.endswith(suffix):
            return dsi
    if unit is not None and unit in _NAMED_UNITS:
        return _NAMED_UNITS[unit]
    return r"\one"


def _path_unit(path: tuple[str, ...], unit: str | None) -> str:
    """The unit of the figure at ``path``: the innermost key that names one (``max_at_mm/X`` is in mm)."""
    for key in reversed(path):
        if key.startswith(_ROW):
            continue
        dsi = dsi_unit(key)
        if dsi != r"\one":
            return dsi
    return dsi_unit(path[-1], unit) if len(path) == 1 else r"\one"


def _q(tag: str) -> str:
    prefix, _, name = tag.partition(":")
    return f"{{{DCC_NS if prefix == 'dcc' else SI_NS}}}{name}"


def _sub(parent: ET.Element, tag: str, text: Any = None, **attrib: str) -> ET.Element:
    element = ET.SubElement(parent, _q(tag), {k.replace("_", ""): v for k, v in attrib.items()})
    if text is not None:
        element.text = str(text)
    return element


def _text(parent: ET.Element, tag: str, message: str, languages: list[str], *, translate: bool = True) -> ET.Element:
    """A dcc:textType element: the message in every language of the certificate (data is not translated)."""
    element = _sub(parent, tag)
    if not translate:
        _sub(element, "dcc:content", message)
        return element
    for language in languages:
        _sub(element, "dcc:content", translations(language).gettext(message), lang=language)
    return element


def _number(value: float | int) -> str:
    """A number as D-SI writes it, read back to the same value (Python's shortest round trip)."""
    return repr(int(value)) if isinstance(value, int) else repr(float(value))


def _is_number(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)


def _walk(figures: Mapping[str, Any], path: tuple[str, ...] = ()) -> Iterator[tuple[tuple[str, ...], Any]]:
    """Every leaf of a figures object with its key path (dicts descended, lists of lists split by row)."""
    for key, value in figures.items():
        here = (*path, str(key))
        if isinstance(value, Mapping):
            yield from _walk(value, here)
        elif isinstance(value, list) and value and all(isinstance(v, list) for v in value):
            for index, row in enumerate(value):
                yield (*here, _ROW + str(index)), row
        else:
            yield here, value


#: marks a row of a list of lists in a key path (a quoted key never holds it)
_ROW = "#"


def _key(path: tuple[str, ...]) -> str:
    return "/".join(part if part.startswith(_ROW) else quote(part, safe="") for part in path)


def _expanded(parent: ET.Element, U: float, *, lists: int = 0) -> None:
    if lists:
        unc = _sub(parent, "si:expandedUncXMLList")
        _sub(unc, "si:uncertaintyXMLList", " ".join([_number(U)] * lists))
        _sub(unc, "si:coverageFactorXMLList", str(COVERAGE_FACTOR))
        _sub(unc, "si:coverageProbabilityXMLList", str(COVERAGE_PROBABILITY))
        _sub(unc, "si:distributionXMLList", "normal")
        return
    unc = _sub(parent, "si:expandedUnc")
    _sub(unc, "si:uncertainty", _number(U))
    _sub(unc, "si:coverageFactor", str(COVERAGE_FACTOR))
    _sub(unc, "si:coverageProbability", str(COVERAGE_PROBABILITY))
    _sub(unc, "si:distribution", "normal")


def _quantity(parent: ET.Element, path: tuple[str, ...], value: Any, unit: str | None, U: float | None,
              check: Any, languages: list[str]) -> None:
    """One figure as a dcc:quantity (si:real, si:realListXMLList or dcc:noQuantity)."""
    key = _key(path)
    quantity = _sub(parent, "dcc:quantity", refType=FIGURE_REF + key)
    _text(quantity, "dcc:name", "/".join(path), languages, translate=False)
    if _is_number(value):
        real = _sub(quantity, "si:real")
        _sub(real, "si:label", key)
        _sub(real, "si:value", _number(value))
        _sub(real, "si:unit", _path_unit(path, unit))
        if U is not None:
            _expanded(real, U)
    elif isinstance(value, list) and value and all(_is_number(v) for v in value):
        real = _sub(quantity, "si:realListXMLList")
        _sub(real, "si:valueXMLList", " ".join(_number(v) for v in value))
        _sub(real, "si:unitXMLList", _path_unit(path, unit))
    else:
        # a text, a flag, an empty list or a value that could not be computed (null in results.json)
        content = _sub(_sub(quantity, "dcc:noQuantity"), "dcc:content")
        content.text = _json_text(value)
    if check is not None:
        meta = _sub(_sub(quantity, "dcc:measurementMetaData"), "dcc:metaData", refType="basic_conformity")
        _text(_sub(meta, "dcc:declaration"), "dcc:name", _("Conformity"), languages)
        _sub(meta, "dcc:conformity", "pass" if check.result == "pass" else
             "fail" if check.result == "fail" else "conditionalPass")
        data = _sub(meta, "dcc:data")
        limit = _sub(data, "dcc:quantity", refType="basic_acceptanceLimitUpper")
        _text(limit, "dcc:name", _("Upper acceptance limit"), languages)
        real = _sub(limit, "si:real")
        _sub(real, "si:value", _number(check.limit))
        _sub(real, "si:unit", _NAMED_UNITS.get(check.unit, dsi_unit("x_" + check.unit)))


def _json_text(value: Any) -> str:
    from axiscal.io.jsonio import dumps

    return dumps(value).strip()


def _influences(parent: ET.Element, environment: Mapping[str, Any], languages: list[str]) -> None:
    conditions = _sub(parent, "dcc:influenceConditions")
    for name, stats in environment.items():
        condition = _sub(conditions, "dcc:influenceCondition",
                         refType={"air temperature": "basic_temperature", "material temperature": "basic_temperature",
                                  "relative humidity": "basic_humidityRelative",
                                  "air pressure": "basic_pressure"}.get(name, "axiscal_condition"))
        _text(condition, "dcc:name", name, languages)
        data = _sub(condition, "dcc:data")
        unit = _NAMED_UNITS.get(stats.get("unit", ""), r"\one")
        for statistic, words in (("mean", _("Mean")), ("min", _("Minimum")), ("max", _("Maximum"))):
            if not _is_number(stats.get(statistic)):
                continue
            quantity = _sub(data, "dcc:quantity", refType=f"axiscal_{statistic}")
            _text(quantity, "dcc:name", words, languages)
            real = _sub(quantity, "si:real")
            _sub(real, "si:value", _number(stats[statistic]))
            _sub(real, "si:unit", unit)


def _equipment(parent: ET.Element, instrument: Mapping[str, Any], languages: list[str]) -> None:
    equipment = _sub(_sub(parent, "dcc:measuringEquipments"), "dcc:measuringEquipment")
    _text(equipment, "dcc:name", instrument.get("name", ""), languages, translate=False)
    ids = _sub(equipment, "dcc:identifications")
    for issuer, key, words in (("manufacturer", "serial", _("Serial number")),
                               ("other", "certificate", _("Calibration certificate"))):
        if instrument.get(key):
            identification = _sub(ids, "dcc:identification")
            _sub(identification, "dcc:issuer", issuer)
            _sub(identification, "dcc:value", instrument[key])
            _text(identification, "dcc:name", words, languages)


def _test_result(parent: ET.Element, test: TestResult, entry: Mapping[str, Any], instrument: Mapping[str, Any],
                 languages: list[str]) -> None:
    result = _sub(parent, "dcc:measurementResult", refType=TEST_REF + test.id)
    _text(result, "dcc:name", test.id, languages, translate=False)
    if test.method:
        method = _sub(_sub(result, "dcc:usedMethods"), "dcc:usedMethod")
        _text(method, "dcc:name", test.method, languages, translate=False)
        if isinstance(entry["figures"].get("standard"), str):
            _sub(method, "dcc:norm", entry["figures"]["standard"])
    if instrument:
        _equipment(result, instrument, languages)
    if test.environment:
        _influences(result, test.environment, languages)
    data = _result_data(result, test.id, languages)
    unit = entry["figures"].get("unit") if isinstance(entry["figures"].get("unit"), str) else None
    checks = {c.figure: c for c in test.checks}
    for path, value in _walk(entry["figures"]):
        figure = path[0] if len(path) == 1 else None
        U = test.uncertainty.get(figure) if figure is not None and _is_number(value) else None
        _quantity(data, path, value, unit, U, checks.get(figure) if figure is not None else None, languages)


def _result_data(parent: ET.Element, name: str, languages: list[str], *, translate: bool = False) -> ET.Element:
    """The ``dcc:data`` of a measurementResult's one ``dcc:result``, named."""
    result = _sub(_sub(parent, "dcc:results"), "dcc:result")
    _text(result, "dcc:name", name, languages, translate=translate)
    return _sub(result, "dcc:data")


def dcc_xml(results: CampaignResults) -> bytes:
    """The campaign's certificate as a DCC (schema :data:`SCHEMA_VERSION`).

    Parameters
    ----------
    results : CampaignResults
        With the certificate's fields (:func:`axiscal.report.certificate.check_certificate`).

    Returns
    -------
    bytes
        UTF-8 XML with its declaration.
    """
    from axiscal.report.certificate import check_certificate

    check_certificate(results)
    cert = results.issuer["certificate"]
    lab = results.issuer["laboratory"]
    languages = list(cert.get("languages", ["en"]))
    payload = results_payload(results)
    root = ET.Element(_q("dcc:digitalCalibrationCertificate"),
                      {"schemaVersion": SCHEMA_VERSION, f"{{{_XSI}}}schemaLocation": _SCHEMA_LOCATION})
    admin = _sub(root, "dcc:administrativeData")
    software = _sub(_sub(admin, "dcc:dccSoftware"), "dcc:software")
    _text(software, "dcc:name", "axiscal", languages, translate=False)
    _sub(software, "dcc:release", __version__)
    core = _sub(admin, "dcc:coreData")
    _sub(core, "dcc:countryCodeISO3166_1", lab["country"])
    for language in languages:
        _sub(core, "dcc:usedLangCodeISO639_1", language)
    _sub(core, "dcc:mandatoryLangCodeISO639_1", languages[0])
    _sub(core, "dcc:uniqueIdentifier", cert["number"])
    _sub(core, "dcc:beginPerformanceDate", results.campaign["date"])
    _sub(core, "dcc:endPerformanceDate", results.campaign["date"])
    _sub(core, "dcc:performanceLocation", cert["location"])
    _sub(core, "dcc:issueDate", cert["issue_date"])
    item = _sub(_sub(admin, "dcc:items"), "dcc:item")
    _text(item, "dcc:name", results.machine.get("name", ""), languages, translate=False)
    if results.machine.get("condition"):
        _text(item, "dcc:description", results.machine["condition"], languages, translate=False)
    _text(_sub(item, "dcc:manufacturer"), "dcc:name", results.machine.get("manufacturer", ""), languages,
          translate=False)
    ids = _sub(item, "dcc:identifications")
    identification = _sub(ids, "dcc:identification")
    _sub(identification, "dcc:issuer", "manufacturer")
    _sub(identification, "dcc:value", results.machine.get("serial") or results.machine.get("name", ""))
    _text(identification, "dcc:name", _("Serial number"), languages)
    contact = _sub(_sub(admin, "dcc:calibrationLaboratory"), "dcc:contact")
    _text(contact, "dcc:name", lab["name"], languages, translate=False)
    location = _sub(contact, "dcc:location")
    _sub(location, "dcc:countryCode", lab["country"])
    _text(location, "dcc:further", lab["address"], languages, translate=False)
    persons = _sub(admin, "dcc:respPersons")
    for index, signatory in enumerate(results.issuer.get("signatories", [])):
        person = _sub(persons, "dcc:respPerson")
        _text(_sub(person, "dcc:person"), "dcc:name", signatory["name"], languages, translate=False)
        _sub(person, "dcc:role", signatory["role"])
        if index == 0:
            _sub(person, "dcc:mainSigner", "true")
    customer = _sub(admin, "dcc:customer")
    _text(customer, "dcc:name", results.campaign.get("customer", ""), languages, translate=False)
    _text(_sub(customer, "dcc:location"), "dcc:further", results.campaign.get("customer_address", ""), languages,
          translate=False)
    _statements(admin, results, languages)
    measurements = _sub(root, "dcc:measurementResults")
    by_id = {entry["id"]: entry for entry in payload["tests"]}
    for test in results.tests:
        _test_result(measurements, test, by_id[test.id], results.instrument, languages)
    if payload.get("volumetric"):
        volumetric = _sub(measurements, "dcc:measurementResult", refType=TEST_REF + "volumetric")
        _text(volumetric, "dcc:name", _("Volumetric error of the working volume"), languages)
        data = _result_data(volumetric, _("Volumetric error of the working volume"), languages, translate=True)
        for path, value in _walk(payload["volumetric"]):
            _quantity(data, path, value, None, None, None, languages)
    ET.indent(root, space=" ")
    return ET.tostring(root, encoding="utf-8", xml_declaration=True) + b"\n"


def _statements(admin: ET.Element, results: CampaignResults, languages: list[str]) -> None:
    from axiscal.report.certificate import _STATEMENTS

    cert = results.issuer["certificate"]
    statements = _sub(admin, "dcc:statements")
    for text, reference in zip(_STATEMENTS, ("7.8.2.1 c", "7.8.2.2")):
        statement = _sub(statements, "dcc:statement")
        _sub(statement, "dcc:norm", "ISO/IEC 17025:2017")
        _sub(statement, "dcc:reference", reference)
        _text(statement, "dcc:declaration", text, languages)
    if cert.get("replaces"):
        statement = _sub(statements, "dcc:statement", refType="axiscal_replaces")
        declaration = _sub(statement, "dcc:declaration")
        for language in languages:
            _sub(declaration, "dcc:content", translations(language).gettext(
                "This certificate replaces certificate {number}.").format(number=cert["replaces"]), lang=language)
    if any(t.checks for t in results.tests):
        statement = _sub(statements, "dcc:statement", refType="basic_conformity")
        _sub(statement, "dcc:norm", "ILAC-G8:09/2019")
        declaration = _sub(statement, "dcc:declaration")
        for language in languages:
            tr = translations(language).gettext
            rule = tr("Decision rule") + ": " + (tr("simple acceptance") if results.decision_rule == "simple"
                                                 else tr("guarded acceptance (ISO 14253-1)"))
            _sub(declaration, "dcc:content", f"{rule}. {tr('Source of the limits')}: {cert.get('tolerance_source', '')}.",
                 lang=language)
        _sub(statement, "dcc:conformity", {"pass": "pass", "fail": "fail"}.get(results.verdict, "conditionalPass"))


def _local(tag: str) -> str:
    return tag.rpartition("}")[2]


def read_dcc(path: str | Path) -> dict[str, Any]:
    """A DCC written by axiscal, read back as a results.json object.

    Parameters
    ----------
    path : str or Path

    Returns
    -------
    dict
        Schema ``axiscal-results/1``: ``campaign`` (title, date, machine), ``tests`` (``id``,
        ``figures`` as in results.json, ``uncertainty`` with ``k``) and ``volumetric``; what
        ``report --compare`` and ``dcc show`` read.

    Raises
    ------
    AxiscalError
        For a file that is not XML, not a DCC, or holds no test written by axiscal.
    """
    path = check_path("path", path)
    try:
        root = ET.parse(path).getroot()
    except (ET.ParseError, OSError, ValueError, LookupError) as exc:  # LookupError: an encoding Python does not know
        raise AxiscalError(f"not a readable XML file: {exc}", path=path) from None
    if root.tag != _q("dcc:digitalCalibrationCertificate"):
        raise AxiscalError("not a Digital Calibration Certificate (root dcc:digitalCalibrationCertificate)", path=path)
    core = root.find(f"{_q('dcc:administrativeData')}/{_q('dcc:coreData')}")
    number = core.findtext(_q("dcc:uniqueIdentifier")) if core is not None else None
    date = core.findtext(_q("dcc:beginPerformanceDate")) if core is not None else None
    machine = root.findtext(f"{_q('dcc:administrativeData')}/{_q('dcc:items')}/{_q('dcc:item')}/{_q('dcc:name')}/"
                            f"{_q('dcc:content')}")
    tests = []
    volumetric = None
    for result in root.iter(_q("dcc:measurementResult")):
        ref = result.get("refType", "")
        if not ref.startswith(TEST_REF):
            continue
        figures: dict[str, Any] = {}
        uncertainty: dict[str, float] = {}
        for quantity in result.iter(_q("dcc:quantity")):
            qref = quantity.get("refType", "")
            if not qref.startswith(FIGURE_REF):
                continue
            keys = [part if part.startswith(_ROW) else unquote(part) for part in qref[len(FIGURE_REF):].split("/")]
            value, U = _quantity_value(quantity, path)
            try:
                _place(figures, keys, value)
            except ValueError as exc:
                raise AxiscalError(str(exc), path=path) from None
            if U is not None and len(keys) == 1:
                uncertainty[keys[0]] = U
        test_id = ref[len(TEST_REF):]
        try:
            figures = _lists(figures)
        except KeyError as exc:
            raise AxiscalError(f"test '{test_id[:80]}': row {exc} of a table of figures is missing", path=path) from None
        if test_id == "volumetric":
            volumetric = figures
            continue
        entry: dict[str, Any] = {"id": test_id, "figures": figures}
        if uncertainty:
            entry["uncertainty"] = {"k": COVERAGE_FACTOR, **uncertainty}
        tests.append(entry)
    if not tests:
        raise AxiscalError("this DCC holds no test written by axiscal (no measurementResult of refType "
                           f"'{TEST_REF}...')", path=path)
    out: dict[str, Any] = {"schema": SCHEMA, "source": "dcc", "certificate": number,
                           "campaign": {"campaign": {"title": f"certificate {number}", "date": date},
                                        "machine": {"name": machine}},
                           "tests": tests}
    if volumetric is not None:
        out["volumetric"] = volumetric
    return out


def _quantity_value(quantity: ET.Element, path: Path) -> tuple[Any, float | None]:
    try:
        return _read_quantity(quantity, path)
    except (ValueError, TypeError):
        raise AxiscalError(f"figure '{quantity.get('refType', '')[len(FIGURE_REF):][:80]}': its value is not a number "
                           "as D-SI writes one", path=path) from None


def _read_quantity(quantity: ET.Element, path: Path) -> tuple[Any, float | None]:
    import json

    real = quantity.find(_q("si:real"))
    if real is not None:
        text = real.findtext(_q("si:value")) or ""
        U = real.findtext(f"{_q('si:expandedUnc')}/{_q('si:uncertainty')}")
        value: Any = int(text) if text.lstrip("+-").isdigit() else float(text)
        return value, None if U is None else float(U)
    listed = quantity.find(_q("si:realListXMLList"))
    if listed is not None:
        return [int(v) if v.lstrip("+-").isdigit() else float(v)
                for v in (listed.findtext(_q("si:valueXMLList")) or "").split()], None
    content = quantity.findtext(f"{_q('dcc:noQuantity')}/{_q('dcc:content')}")
    try:
        return json.loads(content or "null"), None
    except (ValueError, RecursionError):
        raise AxiscalError(f"a figure's text is not the JSON value axiscal writes: {content[:80]!r}", path=path) from None


def _place(target: dict[str, Any], keys: list[str], value: Any) -> None:
    """Put ``value`` at ``keys`` in nested dicts (rows of a list of lists under their ``#n`` keys)."""
    here = target
    for key in keys[:-1]:
        here = here.setdefault(key, {})
        if not isinstance(here, dict):
            raise ValueError(f"figure '{'/'.join(keys)}' lies under a figure that is a value")
    here[keys[-1]] = value


def _lists(value: Any) -> Any:
    """Nested dicts with the ``#n`` rows of lists of lists made lists again."""
    if isinstance(value, dict):
        if value and all(k.startswith(_ROW) for k in value):
            return [_lists(value[f"{_ROW}{i}"]) for i in range(len(value))]
        return {k: _lists(v) for k, v in value.items()}
    return value


def dcc_summary(read: Mapping[str, Any]) -> str:
    """What ``axiscal dcc show`` prints: each test's figures, one a line, with U where stated.

    Parameters
    ----------
    read : mapping
        :func:`read_dcc`'s object.

    Returns
    -------
    str
    """
    from axiscal.report.html import format_number, template_environment

    check_mapping("read", read, ("tests",), what="what read_dcc returns (a results.json object)")
    if not isinstance(read["tests"], list) or not all(isinstance(t, Mapping) and "id" in t and isinstance(
            t.get("figures"), Mapping) for t in read["tests"]):
        raise AxiscalError("read['tests'] must be a list of tests with an id and figures, as read_dcc returns")
    tests = []
    for test in read["tests"]:
        uncertainty = test.get("uncertainty", {})
        rows = []
        for path, value in _walk(test["figures"]):
            key = "/".join(path)
            if _is_number(value):
                text = format_number(value, 6) if isinstance(value, float) else str(value)
            elif isinstance(value, list) and all(_is_number(v) for v in value):
                text = f"[{len(value)} values]"
            else:
                text = _json_text(value).replace("\n", " ")[:80]
            U = uncertainty.get(key) if len(path) == 1 else None
            rows.append({"key": key, "value": text, "U": None if U is None else format_number(U, 6)})
        tests.append({"id": test["id"], "rows": rows})
    width = max((len(r["key"]) for t in tests for r in t["rows"]), default=0)
    info = read.get("campaign", {})
    return template_environment().get_template("report/dcc_show.txt.j2").render(
        number=read.get("certificate"), machine=info.get("machine", {}).get("name"),
        date=info.get("campaign", {}).get("date"), tests=tests, width=width).rstrip() + "\n"
