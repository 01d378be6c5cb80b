"""The one tabular reader and writer (CSV with units in column names), TOML and JSON files, atomic writes."""

from __future__ import annotations

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
]

# instrument importers (axiscal.io.importers)
from axiscal.io.importers import (  # noqa: E402
    ColumnMap,
    ImportedReadings,
    RtxCapture,
    import_readings,
    read_column_map,
    read_rtx,
    write_positioning_csv,
    write_rtx,
    write_rtx_csv,
)

__all__ += [
    "ColumnMap",
    "ImportedReadings",
    "RtxCapture",
    "import_readings",
    "read_column_map",
    "read_rtx",
    "write_positioning_csv",
    "write_rtx",
    "write_rtx_csv",
]
