"""One declared model per file format people write by hand (pydantic v2).

Each model is the single source of truth of its format: the reader validates the parsed TOML into
it (one error naming file, line, key path and what was expected; an unknown key answered with the
nearest valid name), the formats pages' key tables are generated from it, and so is the JSON Schema
that ``axiscal schema NAME`` prints for editors (docs/schemas/).
"""

from __future__ import annotations

import importlib
from typing import Any

#: each name and the module that holds it: loaded on first use, so that a command reading one format
#: does not build every format's model (the campaign's alone takes a noticeable part of a second)
_HOME = {
    "FormatModel": "base", "key_path": "base", "line_of": "base", "read_format": "base", "validate_data": "base",
    "BudgetFile": "budget", "BudgetTables": "budget",
    "CampaignFile": "campaign", "UncertaintyTable": "campaign",
    "FORMATS": "catalogue", "json_schema": "catalogue", "key_table": "catalogue",
}


def __getattr__(name: str) -> Any:
    home = _HOME.get(name)
    if home is None:
        raise AttributeError(f"module 'axiscal.io.formats' has no attribute {name!r}")
    value = getattr(importlib.import_module(f"axiscal.io.formats.{home}"), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_HOME))


__all__ = [
    "FormatModel",
    "key_path",
    "line_of",
    "read_format",
    "validate_data",
    "BudgetFile",
    "BudgetTables",
    "CampaignFile",
    "UncertaintyTable",
    "FORMATS",
    "json_schema",
    "key_table",
]
