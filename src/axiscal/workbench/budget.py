"""The visit's uncertainty budget: the New visit form's fields written as the campaign's budget file, and
remembered per instrument so that the instrument's next visit is prefilled with them.

The form names each number as the budget file does (docs/uncertainty.md), with its section in front
where two sections share a key (``air_temperature_u_K``, ``machine_temperature_u_K``): the laser's
certificate (``length_U_ppm``, expanded, k = 2), the air sensors' and the material sensor's standard
uncertainties, the expansion coefficient and its uncertainty, the misalignment's bound, the
environmental variation error. A form that gives any of them writes ``budget.toml`` beside
``campaign.toml`` (and in ``as-left/``, whose campaign names it too), read back by the library's own
reader before it is written; the campaign's evaluation then states U (k = 2) beside every figure the
budget covers and holds each figure against its tolerance under the campaign's decision rule. Nothing
here computes an uncertainty.

The budgets are remembered in ``budgets.json`` in the workbench's data folder, one per instrument (by
its serial, or by its name when it has none).
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_mapping, check_path
from axiscal.io.atomic import write_text
from axiscal.io.formats.budget import BUDGET_KEYS, BUDGET_WORDS

__all__ = ["BUDGET_FILE", "BUDGETS_FILE", "BUDGET_FIELDS", "budget_tables", "write_budget", "remember_budget",
           "budget_defaults", "decision_of"]

#: the campaign's budget file, in the visit's folder (and in its as-left folder)
BUDGET_FILE = "budget.toml"
#: the budgets remembered per instrument, in the data folder
BUDGETS_FILE = "budgets.json"
#: the New visit form's budget fields -> (section, key) of the budget file, in the file's units
BUDGET_FIELDS: dict[str, tuple[str, str]] = {
    "length_U_ppm": ("instrument", "length_U_ppm"),
    "air_temperature_u_K": ("air", "temperature_u_K"),
    "air_pressure_u_Pa": ("air", "pressure_u_Pa"),
    "air_humidity_u_percent": ("air", "humidity_u_percent"),
    "machine_temperature_C": ("machine", "temperature_C"),
    "machine_temperature_u_K": ("machine", "temperature_u_K"),
    "expansion_per_K": ("machine", "expansion_per_K"),
    "expansion_u_per_K": ("machine", "expansion_u_per_K"),
    "misalignment_urad": ("setup", "misalignment_urad"),
    "eve_um": ("setup", "eve_um"),
}
#: what is remembered of a visit's budget: its numbers and the decision rule
_REMEMBERED = (*BUDGET_FIELDS, "decision_rule")


def _number(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)


def budget_tables(form: dict[str, Any]) -> dict[str, dict[str, float]]:
    """The budget file's tables from the New visit form's values; empty when the form gives no budget.

    Parameters
    ----------
    form : dict
        The checked New visit form as JSON values (a budget number left empty is None); its
        ``wavelength_nm`` goes into ``[instrument]`` with a budget, for the air's sensitivities.

    Returns
    -------
    dict
        Section -> key -> value, in the order of the budget format; ``{}`` without a budget number.

    Examples
    --------
    >>> budget_tables({"length_U_ppm": 0.5, "wavelength_nm": 632.99137, "eve_um": None})
    {'instrument': {'length_U_ppm': 0.5, 'wavelength_nm': 632.99137}}
    """
    check_mapping("form", form, what="the New visit form's values (a mapping)")
    given = {field: float(form[field]) for field in BUDGET_FIELDS if _number(form.get(field))}
    if not given:
        return {}
    tables: dict[str, dict[str, float]] = {}
    for section, keys in BUDGET_KEYS.items():
        for key in keys:
            field = next((f for f, place in BUDGET_FIELDS.items() if place == (section, key)), None)
            if field in given:
                tables.setdefault(section, {})[key] = given[field]
            elif (section, key) == ("instrument", "wavelength_nm") and _number(form.get("wavelength_nm")):
                tables.setdefault(section, {})[key] = float(form["wavelength_nm"])
    return tables


def _budget_text(tables: dict[str, dict[str, float]]) -> str:
    from axiscal.io.templates import render_template

    rows = [(section, [(key, repr(value), BUDGET_WORDS[section][key]) for key, value in table.items()])
            for section, table in tables.items()]
    return render_template("workbench/budget.toml.j2", keep_trailing_newline=True, tables=rows)


def write_budget(folder: Path, form: dict[str, Any]) -> Path | None:
    """Write the visit's ``budget.toml`` (in ``folder`` and ``folder/as-left``) from its New visit form.

    The text is read back by :func:`axiscal.uncertainty.budget_from_dict`, the reader every campaign
    uses, before it is written. A form without a budget removes an earlier ``budget.toml`` of the
    visit, which its campaign no longer names.

    Parameters
    ----------
    folder : Path
        The visit's folder.
    form : dict
        The checked New visit form as JSON values.

    Returns
    -------
    Path or None
        The budget file, or None without a budget.

    Raises
    ------
    AxiscalError
        For a budget the library refuses (naming the key), or a file that cannot be written.
    """
    from axiscal.io.text_files import parse_toml
    from axiscal.uncertainty.budget import budget_from_dict

    folder = check_path("folder", folder)
    tables = budget_tables(form)
    targets = (folder / BUDGET_FILE, folder / "as-left" / BUDGET_FILE)
    if not tables:
        for path in targets:
            path.unlink(missing_ok=True)
        return None
    text = _budget_text(tables)
    budget_from_dict(parse_toml(text, path=BUDGET_FILE), source=BUDGET_FILE, text=text)
    for path in targets:
        write_text(path, text)
    return targets[0]


def _key(instrument: Any, serial: Any) -> str | None:
    """The instrument a budget belongs to: its serial, or its name when it has none."""
    serial = serial.strip() if isinstance(serial, str) else ""
    instrument = instrument.strip() if isinstance(instrument, str) else ""
    if serial:
        return "serial:" + serial.casefold()
    return "name:" + instrument.casefold() if instrument else None


def _remembered(data: Path) -> dict[str, Any]:
    try:
        kept = json.loads((data / BUDGETS_FILE).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return {}
    return kept if isinstance(kept, dict) else {}


def remember_budget(data: Path, form: dict[str, Any]) -> None:
    """Keep a visit's budget as its instrument's, for the instrument's next visit (none given: nothing kept).

    Parameters
    ----------
    data : Path
        The workbench's data folder.
    form : dict
        The checked New visit form as JSON values.

    Returns
    -------
    None
    """
    data = check_path("data", data)
    check_mapping("form", form, what="the New visit form's values (a mapping)")
    key = _key(form.get("instrument"), form.get("instrument_serial"))
    if key is None or not budget_tables(form):
        return
    kept = _remembered(data)
    kept[key] = {"instrument": form.get("instrument"), "serial": form.get("instrument_serial") or "",
                 "date": str(form.get("date") or ""),
                 "budget": {name: form[name] for name in _REMEMBERED if form.get(name) is not None}}
    write_text(data / BUDGETS_FILE, json.dumps(kept, indent=1, ensure_ascii=False) + "\n")


def budget_defaults(data: Path, instrument: Any, serial: Any = "") -> dict[str, Any]:
    """The budget an instrument's last visit stated, to prefill its next New visit form.

    Parameters
    ----------
    data : Path
        The workbench's data folder.
    instrument : str
        The instrument's name.
    serial : str
        Its serial (the budget is the serial's when one is given).

    Returns
    -------
    dict
        ``{"fields": {form field: value}, "date": the visit's date}``; ``{}`` when the instrument has
        no budget remembered (or the file is damaged).
    """
    from axiscal.uncertainty.decision import DECISION_RULES

    data = check_path("data", data)
    for name, value in (("instrument", instrument), ("serial", serial)):
        if not isinstance(value, str):
            raise AxiscalError(f"{name} must be the instrument's {name} (a str), not {value!r}"[:200])
    key = _key(instrument, serial)
    entry = _remembered(data).get(key) if key is not None else None
    if not isinstance(entry, dict) or not isinstance(entry.get("budget"), dict):
        return {}
    fields = {name: value for name, value in entry["budget"].items()
              if (name in BUDGET_FIELDS and _number(value)) or (name == "decision_rule" and value in DECISION_RULES)}
    if not fields:
        return {}
    return {"fields": fields, "date": entry.get("date") if isinstance(entry.get("date"), str) else ""}


def decision_of(campaign: Any) -> dict[str, Any]:
    """How Results states a campaign's decision rule and budget, as the report states them.

    Parameters
    ----------
    campaign : axiscal.campaign.Campaign
        The loaded campaign of a phase.

    Returns
    -------
    dict
        ``decision_rule`` (``"simple"`` or ``"guard-band"``), ``decision`` (the report's sentence,
        :func:`axiscal.report.decision_statement`) and ``budget`` (True when the campaign states one,
        so that its figures carry U).
    """
    from axiscal.campaign import Campaign
    from axiscal.io.arguments import check_instance
    from axiscal.report import decision_statement

    check_instance("campaign", campaign, Campaign)
    return {"decision_rule": campaign.decision_rule, "decision": decision_statement(campaign.decision_rule),
            "budget": campaign.budget is not None}
