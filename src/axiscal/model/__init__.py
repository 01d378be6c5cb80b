"""The machine model: per-axis error tables, the homogeneous-transformation chain, the machine, diagonal tests and the volumetric map (paper 000)."""

from __future__ import annotations

from axiscal.model.diagonal import (
    MEASURES,
    DiagonalResult,
    diagonal_check,
    diagonal_positions,
)
from axiscal.model.kinematics import (
    ChainLink,
    error_matrix,
    link_matrix,
    reference_volumetric_error,
    translation_matrix,
    volumetric_error,
)
from axiscal.model.machine import (
    SQUARENESS_PLACEMENTS,
    Axis,
    Machine,
    axis_positions_from_grid,
    load_machine,
    machine_from_dict,
    parse_chain,
    positions_from_points,
)
from axiscal.model.plot import (
    plot_diagonal,
    plot_diagonal_experiment,
    plot_error_tables,
    plot_volumetric,
)
from axiscal.model.tables import INTERPOLATIONS, ErrorTable, read_error_table

__all__ = [
    "INTERPOLATIONS",
    "ErrorTable",
    "read_error_table",
    "ChainLink",
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
    "axis_positions_from_grid",
    "positions_from_points",
    "MEASURES",
    "DiagonalResult",
    "diagonal_positions",
    "diagonal_check",
    "plot_error_tables",
    "plot_volumetric",
    "plot_diagonal",
    "plot_diagonal_experiment",
]
