"""The one tabular reader and writer (CSV with units in column names), TOML and JSON files, atomic
writes, JSON sidecars, the importers of instrument exports, the checks of the arguments public
functions share (:mod:`axiscal.io.arguments`), the lazy entry to matplotlib for plots
(:mod:`axiscal.io.figures`), and G-code: every control's dialect, its reader and its writer
(:mod:`axiscal.io.gcode`)."""

from __future__ import annotations

from axiscal.io.arguments import (
    check_array,
    check_broadcast,
    check_choice,
    check_count,
    check_instance,
    type_name,
    check_integer,
    check_mapping,
    check_number,
    check_optional_number,
    check_path,
    check_same_length,
    is_real,
    render_checked,
    unit_words,
)
from axiscal.io.atomic import atomic_write, remove_stale_temporaries, write_text
from axiscal.io.folders import atomic_folder, stale_temporaries
from axiscal.io.jsonio import (
    dumps,
    read_json,
    json_line,
    sidecar_path,
    to_plain,
    write_json,
    write_sidecar,
)
from axiscal.io.lines import Lines
from axiscal.io.tabular import (
    CsvTable,
    parse_csv,
    read_csv,
    read_text,
    read_toml,
    parse_toml,
    write_csv,
)

__all__ = [
    "check_array",
    "check_broadcast",
    "check_choice",
    "check_count",
    "check_instance",
    "check_integer",
    "check_mapping",
    "check_number",
    "check_optional_number",
    "check_path",
    "check_same_length",
    "is_real",
    "render_checked",
    "unit_words",
    "type_name",
    "atomic_write",
    "remove_stale_temporaries",
    "write_text",
    "atomic_folder",
    "stale_temporaries",
    "dumps",
    "read_json",
    "json_line",
    "sidecar_path",
    "to_plain",
    "write_json",
    "write_sidecar",
    "Lines",
    "CsvTable",
    "parse_csv",
    "read_csv",
    "read_text",
    "read_toml",
    "parse_toml",
    "write_csv",
]

# instrument importers (axiscal.io.importers), which read through the names above
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
