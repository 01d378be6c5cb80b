"""Controller compensation tables: the shared error curve, one module per controller and the one call that picks the controller."""

from __future__ import annotations

from axiscal.compensation.curve import DIRECTIONS, ErrorCurve, error_curve, residuals
from axiscal.compensation.fanuc import MAX_AXIS_NUMBER, FanucTable, fanuc_table
from axiscal.compensation.formats import (
    FORMAT_OPTIONS,
    FORMATS,
    CompensationResult,
    compensation_table,
)
from axiscal.compensation.heidenhain import (
    HEIDENHAIN_MAX_ENTRIES,
    HeidenhainTable,
    heidenhain_table,
)
from axiscal.compensation.linuxcnc import (
    LINUXCNC_MAX_ENTRIES,
    LinuxcncTable,
    linuxcnc_table,
    parse_linuxcnc,
)
from axiscal.compensation.siemens import SiemensTable, siemens_table

__all__ = [
    "DIRECTIONS",
    "ErrorCurve",
    "error_curve",
    "residuals",
    "LINUXCNC_MAX_ENTRIES",
    "LinuxcncTable",
    "linuxcnc_table",
    "parse_linuxcnc",
    "MAX_AXIS_NUMBER",
    "FanucTable",
    "fanuc_table",
    "SiemensTable",
    "siemens_table",
    "HEIDENHAIN_MAX_ENTRIES",
    "HeidenhainTable",
    "heidenhain_table",
    "FORMATS",
    "FORMAT_OPTIONS",
    "CompensationResult",
    "compensation_table",
]
