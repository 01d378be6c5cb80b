"""A machine with 1 to 3 linear and up to 3 rotary axes: its kinematic chain, error tables, squareness and location errors (paper 000 §3; ISO 230-1, ISO 230-7).

The names a user of the machine model imports, in one place: the model (:class:`Machine`, in
:mod:`axiscal.model.chain`), its axes and chain notation (:mod:`axiscal.model.axes`), its TOML
description (:func:`load_machine`, in :mod:`axiscal.model.machine_file`) and the positions of its
axes (:mod:`axiscal.model.positions`). Chain notation as ISO 10791 / ISO 230-1 use it:
workpiece-side axes, ``F`` (the frame), tool-side axes; ``"XFYZ"``: the table moves X, the column
carries Y and Z. The volumetric error is the tool point relative to the workpiece.
"""

from __future__ import annotations

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

__all__ = [
    "SQUARENESS_PLACEMENTS",
    "Axis",
    "parse_chain",
    "Machine",
    "as_machine",
    "load_machine",
    "machine_from_dict",
    "AXIS_UNITS",
    "MAX_GRID_POINTS",
    "MAX_MACHINE_SIZE_MM",
    "axis_positions_from_grid",
    "positions_from_points",
]
