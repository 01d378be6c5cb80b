"""The laboratory's details remembered between visits, and the next certificate number proposed.

A visit whose New visit form states a certificate (its number, the laboratory, the signatory) leaves
``laboratory.json`` in the workbench's data folder: the next visit's form is prefilled from it, with
the number after the last one (``AX-2026-0042`` -> ``AX-2026-0043``).
"""

from __future__ import annotations

import json
import re
from pathlib import Path
from typing import Any

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_mapping, check_path
from axiscal.io.atomic import write_text

__all__ = ["LABORATORY_FILE", "REMEMBERED", "next_number", "remember_laboratory", "laboratory_defaults"]

#: the file in the data folder
LABORATORY_FILE = "laboratory.json"
#: the fields of the New visit form that are the laboratory's, not the visit's
REMEMBERED = ("lab_name", "lab_address", "lab_country", "lab_accreditation", "signatory_name", "signatory_role",
              "location", "language", "tolerance_source", "instrument", "instrument_serial", "certificate",
              "instrument_calibrated", "instrument_calibrated_by")


def next_number(number: str) -> str:
    """The certificate number after ``number``: its last run of digits counted up, its width kept.

    Parameters
    ----------
    number : str

    Returns
    -------
    str
        ``"AX-2026-0043"`` after ``"AX-2026-0042"``; ``number + "-2"`` when it ends without digits.

    Examples
    --------
    >>> next_number("AX-2026-0042"), next_number("K-99"), next_number("lab")
    ('AX-2026-0043', 'K-100', 'lab-2')
    """
    if not isinstance(number, str) or not number.strip():
        raise AxiscalError(f"number must be a certificate number (a non-empty str), not {number!r}"[:200])
    match = re.search(r"(\d+)(\D*)$", number)
    if match is None:
        return f"{number}-2"
    digits = match.group(1)
    return number[: match.start(1)] + str(int(digits) + 1).zfill(len(digits)) + match.group(2)


def remember_laboratory(data: Path, form: dict[str, Any]) -> None:
    """Keep the laboratory's fields of a visit that states a certificate (``form`` as JSON values).

    Parameters
    ----------
    data : Path
        The workbench's data folder.
    form : dict
        The checked New visit form, dumped as JSON values.

    Returns
    -------
    None
    """
    data = check_path("data", data)
    check_mapping("form", form, what="the New visit form's values (a mapping)")
    if not form.get("certificate_number"):
        return
    kept = {key: form.get(key) for key in REMEMBERED} | {"last_number": form["certificate_number"]}
    write_text(data / LABORATORY_FILE, json.dumps(kept, indent=1) + "\n")


def laboratory_defaults(data: Path) -> dict[str, Any]:
    """What the next New visit form is prefilled with: the laboratory, the signatory, the next number.

    Parameters
    ----------
    data : Path
        The workbench's data folder.

    Returns
    -------
    dict
        Form field -> value; empty when no visit has stated a certificate (or the file is damaged).
    """
    data = check_path("data", data)
    try:
        kept = json.loads((data / LABORATORY_FILE).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return {}
    if not isinstance(kept, dict):
        return {}
    out = {key: kept[key] for key in REMEMBERED if isinstance(kept.get(key), str) and kept[key]}
    if isinstance(kept.get("last_number"), str) and kept["last_number"]:
        out["certificate_number"] = next_number(kept["last_number"])
    return out
