"""Pre-compensation: part programs and points corrected through the machine model, and a 3D grid out.

Every control obeys its program: command each point where the machine must be sent for the tool to
land on the nominal point (:func:`precompensate_points`, the machine model's inverse), rewrite a
part program that way with straight moves cut and arcs linearised where the error varies along
them (:func:`precompensate_program`), and write the correction on a regular grid for controls and
tools that interpolate a 3D table (:func:`correction_grid`), and the model as a TwinCAT CNC / ISG kernel
volumetric table or axis lists (:func:`export_isg`).
"""

from __future__ import annotations

from axiscal.precompensation.grid import (
    GRID_COLUMNS,
    CorrectionGrid,
    correction_grid,
    export_correction_grid,
    write_correction_grid,
)
from axiscal.precompensation.isg import (
    ISG_KINDS,
    IsgExport,
    export_isg,
    isg_axis_tables,
    isg_volumetric_table,
    parse_axis_numbers,
)
from axiscal.precompensation.points import PrecompensatedPoints, precompensate_points
from axiscal.precompensation.program import (
    Precompensation,
    precompensate_program,
    rewrite_program,
)
from axiscal.precompensation.streaming import precompensate_file

__all__ = [
    "GRID_COLUMNS",
    "CorrectionGrid",
    "correction_grid",
    "export_correction_grid",
    "write_correction_grid",
    "ISG_KINDS",
    "IsgExport",
    "export_isg",
    "isg_axis_tables",
    "isg_volumetric_table",
    "parse_axis_numbers",
    "PrecompensatedPoints",
    "precompensate_points",
    "Precompensation",
    "precompensate_file",
    "precompensate_program",
    "rewrite_program",
]
