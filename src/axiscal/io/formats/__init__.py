"""One declared model per file format people write by hand (pydantic v2).

Each model is the single source of truth of its format: the reader validates the parsed TOML into
it (one error naming file, line, key path and what was expected; an unknown key answered with the
nearest valid name), the formats pages' key tables are generated from it, and so is the JSON Schema
that ``axiscal schema NAME`` prints for editors (docs/schemas/).
"""

from __future__ import annotations

from axiscal.io.formats.base import FormatModel, key_path, line_of, read_format, validate_data
from axiscal.io.formats.budget import BudgetFile, BudgetTables
from axiscal.io.formats.campaign import CampaignFile, UncertaintyTable
from axiscal.io.formats.catalogue import FORMATS, json_schema, key_table

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
