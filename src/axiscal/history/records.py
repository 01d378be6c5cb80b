"""What the history keeps of a results.json: the machine, the campaign and one row per figure.

No standard clause: the rows of ISO/IEC 17025 7.5 technical records, read from an axiscal
results.json (schema ``axiscal-results/1``, docs/campaign.md). A figure is named
``KIND.AXIS.FIGURE`` (``positioning.X.E``, ``squareness.XZ.squareness_arcsec``); a test without an
axis, or a second test of the same kind and axis, uses its test id in place of the axis
(``diagonal.diagonal-0kg.diagonal_error_um``). Each figure is held against its tolerance again
under the campaign's decision rule, so that the history knows the result of every figure.
"""

from __future__ import annotations

import datetime as _dt
import hashlib
import json
import math
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from axiscal.campaign.results import SCHEMA, VERDICTS, Check
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_mapping, check_path, is_real
from axiscal.io.jsonio import json_line

__all__ = ["FigureRecord", "CampaignRecord", "campaign_record", "read_results"]

# a tolerance key whose figure is stored under another name in the test's figures
_TOLERANCE_FIGURES = {"diagonal_um": "diagonal_error_um"}
# unit suffixes of figure names, longest first
_UNITS = ("arcsec", "urad", "deg", "um", "mm", "nm")


@dataclass(frozen=True)
class FigureRecord:
    """One figure of one test, as the history stores it.

    Attributes
    ----------
    key : str
        ``KIND.AXIS.FIGURE``, e.g. ``positioning.X.E``.
    test_id, kind, axis, name : str
        The test's id and kind, its axis (or plane; ``""`` when none) and the figure's key in the
        test's figures.
    value : float or None
        The figure in ``unit`` (None when the results file gives none).
    unit : str
        ``"um"``, ``"arcsec"`` ... or ``""`` when neither its name nor its test says it.
    tolerance : float or None
        The limit held against the figure's magnitude, in ``unit``.
    U : float or None
        Expanded uncertainty (k = 2) in ``unit``.
    result : str
        ``"pass"``, ``"fail"``, ``"inconclusive"`` or ``"not assessed"`` (no tolerance).
    """

    key: str
    test_id: str
    kind: str
    axis: str
    name: str
    value: float | None
    unit: str
    tolerance: float | None
    U: float | None
    result: str


@dataclass(frozen=True)
class CampaignRecord:
    """A campaign as the history stores it.

    Attributes
    ----------
    machine, serial : str
        The machine's name and serial (``""`` when the results file has none).
    title : str
    date : datetime.date
        The campaign's date.
    verdict, decision_rule, software_version : str
        From the results file.
    sha256 : str
        SHA-256 of the results file's bytes: the same file is stored once.
    source : str
        Where the file was read from.
    figures : tuple of FigureRecord
    """

    machine: str
    serial: str
    title: str
    date: _dt.date
    verdict: str
    decision_rule: str
    software_version: str
    sha256: str
    source: str
    figures: tuple[FigureRecord, ...]


def _unit(name: str, test_unit: Any, tolerance_key: str | None) -> str:
    for unit in _UNITS:
        if name.endswith("_" + unit):
            return unit
    if tolerance_key is not None and "_" in tolerance_key:
        return tolerance_key.rsplit("_", 1)[1]
    return test_unit if isinstance(test_unit, str) and test_unit in _UNITS else ""


def _number(value: Any) -> float | None:
    if value is None or not is_real(value):
        return None
    value = float(value)
    return value if math.isfinite(value) else None


def campaign_record(payload: Mapping[str, Any], *, sha256: str, source: str = "") -> CampaignRecord:
    """The record of a parsed results.json.

    Parameters
    ----------
    payload : mapping
        A results.json object, schema ``axiscal-results/1``.
    sha256 : str, keyword-only
        The hash of the file's bytes (64 hexadecimal digits).
    source : str, keyword-only
        Where it came from, kept with the campaign.

    Returns
    -------
    CampaignRecord
        Its figures: every number at the top of each test's figures, in file order.

    Raises
    ------
    AxiscalError
        For a payload of another schema, without a machine name or a campaign date, or whose
        tests are not a list of objects (the message names the key; see :func:`read_results` for
        the line).
    """
    check_mapping("payload", payload, what="a results.json object")
    if not isinstance(sha256, str) or len(sha256) != 64:
        raise AxiscalError(f"sha256 must be 64 hexadecimal digits, not {sha256!r}")
    if payload.get("schema") != SCHEMA:
        raise AxiscalError(f"not an axiscal results file (schema must be {SCHEMA!r}, not {payload.get('schema')!r})")
    tables = payload.get("campaign")
    tables = tables if isinstance(tables, Mapping) else {}
    campaign = tables.get("campaign") if isinstance(tables.get("campaign"), Mapping) else {}
    machine = tables.get("machine") if isinstance(tables.get("machine"), Mapping) else {}
    name = machine.get("name")
    if not isinstance(name, str) or not name.strip():
        raise AxiscalError("campaign.machine.name must name the machine (a non-empty text)")
    serial = machine.get("serial", "")
    serial = "" if serial is None else str(serial)
    date_text = campaign.get("date")
    try:
        date = _dt.date.fromisoformat(str(date_text)[:10])
    except ValueError:
        raise AxiscalError(f"campaign.campaign.date must be a date (YYYY-MM-DD), not {date_text!r}") from None
    verdict = payload.get("verdict")
    if verdict not in VERDICTS:
        raise AxiscalError(f"verdict must be one of {', '.join(VERDICTS)}, not {verdict!r}")
    rule = payload.get("decision_rule", "simple")
    if rule not in ("simple", "guard-band"):
        raise AxiscalError(f"decision_rule must be 'simple' or 'guard-band', not {rule!r}")
    software = payload.get("software")
    version = str(software.get("version", "")) if isinstance(software, Mapping) else ""
    tests = payload.get("tests", [])
    if not isinstance(tests, list) or not all(isinstance(t, Mapping) for t in tests):
        raise AxiscalError("tests must be a list of objects")
    figures = _figures(tests, rule)
    title = campaign.get("title", "")
    return CampaignRecord(name.strip(), serial.strip(), "" if title is None else str(title), date, verdict, rule,
                          version, sha256, source, tuple(figures))


def _figures(tests: list[Mapping[str, Any]], rule: str) -> list[FigureRecord]:
    places: dict[tuple[str, str], int] = {}
    for test in tests:
        place = (str(test.get("kind", "")), str(test.get("axis") or test.get("axes") or ""))
        places[place] = places.get(place, 0) + 1
    out: list[FigureRecord] = []
    for index, test in enumerate(tests):
        test_id = str(test.get("id", f"test-{index + 1}"))
        kind = str(test.get("kind", ""))
        axis = str(test.get("axis") or test.get("axes") or "")
        where = axis if axis and places[(kind, axis)] == 1 else test_id
        values = test.get("figures")
        values = values if isinstance(values, Mapping) else {}
        tolerances = test.get("tolerances")
        tolerances = tolerances if isinstance(tolerances, Mapping) else {}
        uncertainty = test.get("uncertainty")
        uncertainty = uncertainty if isinstance(uncertainty, Mapping) else {}
        limits: dict[str, tuple[str, float]] = {}
        for key, limit in tolerances.items():
            figure = _TOLERANCE_FIGURES.get(key, key if key in values else str(key).rsplit("_", 1)[0])
            if figure in values and _number(limit) is not None and _number(limit) >= 0:
                limits[figure] = (str(key), float(limit))
        for name, value in values.items():
            if isinstance(value, bool) or not (value is None or is_real(value)):
                continue
            tolerance_key, limit = limits.get(name, (None, None))
            number = _number(value)
            U = _number(uncertainty.get(name))
            U = U if U is not None and U >= 0 else None
            result = "not assessed"
            if limit is not None:
                result = Check(name, tolerance_key or name, float("nan") if number is None else number, limit,
                               "", U, rule).result
            # a count (runs, frames, a coverage factor) is an integer and has no unit
            unit = "" if isinstance(value, int) and tolerance_key is None else _unit(
                str(name), values.get("unit"), tolerance_key)
            out.append(FigureRecord(f"{kind}.{where}.{name}", test_id, kind, axis, str(name), number,
                                    unit, limit, U, result))
    return out


def read_results(path: str | Path) -> CampaignRecord:
    """Read a results.json into the record the history stores.

    Parameters
    ----------
    path : str or Path
        An axiscal results.json.

    Returns
    -------
    CampaignRecord

    Raises
    ------
    AxiscalError
        For a missing or unreadable file, malformed JSON, or a file that is not an axiscal results
        file with a machine name and a campaign date; the message names the file and the line.
    """
    path = check_path("path", path)
    try:
        data = path.read_bytes()
    except OSError as exc:
        raise AxiscalError(f"cannot read the results file: {exc.strerror or exc}", path=path) from None
    try:
        text = data.decode("utf-8")
        payload = json.loads(text)
    except UnicodeDecodeError:
        raise AxiscalError("not a results.json: the file is not UTF-8 text", path=path) from None
    except json.JSONDecodeError as exc:
        raise AxiscalError(f"malformed JSON: {exc.msg}", path=path, line=exc.lineno) from None
    except RecursionError:
        raise AxiscalError("malformed JSON: nested too deeply", path=path) from None
    if not isinstance(payload, dict):
        raise AxiscalError("not an axiscal results file (the JSON is not an object)", path=path, line=1)
    try:
        return campaign_record(payload, sha256=hashlib.sha256(data).hexdigest(), source=str(path))
    except AxiscalError as exc:
        first = exc.message.split(" ", 1)[0].split(".")
        keys = ["schema"] if "schema" in exc.message else [k for k in first if k.isidentifier()]
        raise exc.located(path=path, line=json_line(text, *keys) if keys else None) from None
