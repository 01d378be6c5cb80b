"""The one tabular reader and writer (CSV with units in column names), TOML and JSON files, atomic writes."""

from __future__ import annotations

from axiscal.io.lines import Lines
from axiscal.io.tabular import (
    CsvTable,
    parse_csv,
    read_csv,
    read_text,
    read_toml,
    write_csv,
)

__all__ = [
    "CsvTable",
    "read_csv",
    "read_text",
    "parse_csv",
    "write_csv",
    "read_toml",
    "Lines",
]
