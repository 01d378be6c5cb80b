"""Controller compensation tables: the shared error curve, one module per controller and the one call that picks the controller."""

from __future__ import annotations

from axiscal.compensation.curve import DIRECTIONS, ErrorCurve, error_curve, residuals
from axiscal.compensation.fanuc import MAX_AXIS_NUMBER, FanucTable, fanuc_table
from axiscal.compensation.formats import (
    FANUC_ROTARY_INCREMENT,
    FORMAT_OPTIONS,
    FORMATS,
    ROTARY_OPTIONS,
    CompensationResult,
    compensation_table,
)
from axiscal.compensation.heidenhain import (
    HEIDENHAIN_MAX_ENTRIES,
    HeidenhainTable,
    heidenhain_table,
)
from axiscal.compensation.isg import (
    ISG_ARGUMENTS,
    IsgTable,
    grid_values,
    parse_isg_csv,
    read_isg_csv,
    volcomp_list_text,
)
from axiscal.compensation.linuxcnc import (
    LINUXCNC_MAX_ENTRIES,
    LinuxcncTable,
    linuxcnc_table,
    parse_linuxcnc,
)
from axiscal.compensation.siemens import SiemensTable, siemens_table
from axiscal.compensation.formats import (
    MAX_CORRECTION_M,
    MAX_CORRECTION_RAD,
)
from axiscal.compensation.isg import (
    check_distinct_axis_numbers,
)

__all__ = [
    "DIRECTIONS",
    "ErrorCurve",
    "error_curve",
    "residuals",
    "ISG_ARGUMENTS",
    "IsgTable",
    "grid_values",
    "parse_isg_csv",
    "read_isg_csv",
    "volcomp_list_text",
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
    "ROTARY_OPTIONS",
    "FANUC_ROTARY_INCREMENT",
    "CompensationResult",
    "compensation_table",
    "MAX_CORRECTION_M",
    "MAX_CORRECTION_RAD",
    "check_distinct_axis_numbers",
]

# firmware skew correction (axiscal.compensation.skew)
from axiscal.compensation.skew import (  # noqa: E402
    FIRMWARES,
    MAX_SKEW_RAD,
    SKEW_CONVENTIONS,
    SKEW_PLANES,
    SkewCorrection,
    klipper_lengths,
    skew_correction,
    squareness_from_results,
)

__all__ += [
    "FIRMWARES",
    "SKEW_PLANES",
    "SKEW_CONVENTIONS",
    "MAX_SKEW_RAD",
    "SkewCorrection",
    "skew_correction",
    "klipper_lengths",
    "squareness_from_results",
]

# backlash parameters (axiscal.compensation.backlash)
from axiscal.compensation.backlash import (  # noqa: E402
    BACKLASH_CONTROLLERS,
    BACKLASH_METHODS,
    BacklashSetting,
    backlash_from_run,
    backlash_setting,
    reversal_backlash,
)

__all__ += [
    "BACKLASH_CONTROLLERS",
    "BACKLASH_METHODS",
    "BacklashSetting",
    "reversal_backlash",
    "backlash_setting",
    "backlash_from_run",
]

# lead-screw tables of open and PC-based controllers (axiscal.compensation.screwmaps)
from axiscal.compensation.screwmaps import (  # noqa: E402
    SCREWMAP_CONTROLLERS,
    TWINCAT_UNIT,
    Mach4ScrewMap,
    TwincatTable,
    mach4_screw_map,
    parse_twincat_table,
    screwmap_file,
    twincat_table,
)

__all__ += ["SCREWMAP_CONTROLLERS", "TWINCAT_UNIT", "Mach4ScrewMap", "TwincatTable", "mach4_screw_map", "screwmap_file",
            "twincat_table", "parse_twincat_table"]

# cross-axis (sag) tables (axiscal.compensation.sag)
from axiscal.compensation.sag import (  # noqa: E402
    SAG_CONTROLLERS,
    SAG_REFERENCES,
    SinumerikSagTable,
    heidenhain_sag_table,
    sag_table_file,
    sinumerik_sag_table,
)

__all__ += ["SAG_CONTROLLERS", "SAG_REFERENCES", "SinumerikSagTable", "heidenhain_sag_table", "sag_table_file",
            "sinumerik_sag_table"]

from axiscal.compensation.readback import (  # noqa: E402
    CONTROLLERS,
    ControllerCompensation,
    parse_fanuc_tape,
    parse_siemens,
    read_compensation,
)

__all__ += ["CONTROLLERS", "ControllerCompensation", "parse_fanuc_tape", "parse_siemens", "read_compensation"]
