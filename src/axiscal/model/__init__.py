"""The machine model: per-axis error tables, the homogeneous-transformation chain, the machine, diagonal tests, the volumetric map and compensated commands (paper 000)."""

from __future__ import annotations

from axiscal.model.diagonal import (
    DEFAULT_STEPS,
    MAX_DIAGONAL_STEPS,
    MEASURES,
    DiagonalResult,
    diagonal_check,
    diagonal_positions,
    diagonal_test,
)
from axiscal.model.inputs import (
    READING_TOLERANCE_M,
    check_travel,
    parse_point,
    read_interferometer,
    read_points,
    read_targets,
)
from axiscal.model.inverse import InverseResult, inverse_commands
from axiscal.model.kinematics import (
    ChainLink,
    RotaryLink,
    error_matrix,
    link_matrix,
    pose_error,
    reference_volumetric_error,
    translation_matrix,
    volumetric_error,
)
from axiscal.model.axes import SQUARENESS_PLACEMENTS, Axis, parse_chain
from axiscal.model.chain import Machine
from axiscal.model.machine_file import as_machine, load_machine, machine_from_dict
from axiscal.model.positions import (
    AXIS_UNITS,
    MAX_GRID_POINTS,
    MAX_MACHINE_SIZE_MM,
    axis_positions_from_grid,
    positions_from_points,
)
from axiscal.model.output import (
    SIGN_CONVENTION,
    TableResult,
    render_template,
    table_text,
    write_table,
)
from axiscal.model.plot import (
    plot_diagonal,
    plot_diagonal_experiment,
    plot_error_tables,
    plot_volumetric,
)
from axiscal.model.tables import (
    INTERPOLATIONS,
    MAX_ANGLE_ERROR_RAD,
    MAX_TRANSLATION_ERROR_M,
    ErrorTable,
    read_error_table,
)
from axiscal.model.volumetric import VolumetricMap, volumetric_map

__all__ = [
    "INTERPOLATIONS",
    "MAX_ANGLE_ERROR_RAD",
    "MAX_TRANSLATION_ERROR_M",
    "MAX_DIAGONAL_STEPS",
    "AXIS_UNITS",
    "MAX_GRID_POINTS",
    "MAX_MACHINE_SIZE_MM",
    "ErrorTable",
    "read_error_table",
    "ChainLink",
    "RotaryLink",
    "pose_error",
    "volumetric_error",
    "translation_matrix",
    "error_matrix",
    "link_matrix",
    "reference_volumetric_error",
    "SQUARENESS_PLACEMENTS",
    "Axis",
    "parse_chain",
    "Machine",
    "machine_from_dict",
    "load_machine",
    "as_machine",
    "axis_positions_from_grid",
    "positions_from_points",
    "READING_TOLERANCE_M",
    "read_points",
    "check_travel",
    "parse_point",
    "read_targets",
    "read_interferometer",
    "SIGN_CONVENTION",
    "table_text",
    "write_table",
    "TableResult",
    "render_template",
    "VolumetricMap",
    "volumetric_map",
    "MEASURES",
    "DEFAULT_STEPS",
    "DiagonalResult",
    "diagonal_positions",
    "diagonal_check",
    "diagonal_test",
    "InverseResult",
    "inverse_commands",
    "plot_error_tables",
    "plot_volumetric",
    "plot_diagonal",
    "plot_diagonal_experiment",
]
