"""Importers of instrument files: a column map for any CSV or text export, and Renishaw's ``.rtx`` dynamic capture."""

from __future__ import annotations

from axiscal.io.importers.columnmap import (
    IMPORT_UNITS,
    INCH,
    POSITIONING_COLUMNS,
    ColumnMap,
    column_map,
    read_column_map,
)
from axiscal.io.importers.readings import (
    ImportedReadings,
    import_readings,
    positioning_csv,
    write_positioning_csv,
)
from axiscal.io.importers.rtx import (
    RTX_DATA,
    RTX_EOF,
    RTX_FIELDS,
    RTX_HEADER,
    RTX_TRAILERS,
    RtxCapture,
    read_rtx,
    rtx_csv,
    write_rtx,
    write_rtx_csv,
)

__all__ = [
    "INCH",
    "IMPORT_UNITS",
    "POSITIONING_COLUMNS",
    "ColumnMap",
    "ImportedReadings",
    "column_map",
    "read_column_map",
    "import_readings",
    "positioning_csv",
    "write_positioning_csv",
    "RTX_HEADER",
    "RTX_DATA",
    "RTX_EOF",
    "RTX_TRAILERS",
    "RTX_FIELDS",
    "RtxCapture",
    "read_rtx",
    "write_rtx",
    "rtx_csv",
    "write_rtx_csv",
]
