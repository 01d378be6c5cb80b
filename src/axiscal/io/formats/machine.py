"""machine.toml declared: the chain, the functional point, the axes and their error tables,
squareness and location errors (docs/formats.md)."""

from __future__ import annotations

from typing import Annotated, Any, Literal

from annotated_types import Ge, Le, Len
from pydantic import AllowInfNan, Field, Strict, StringConstraints

from axiscal.io.formats.base import Bool, FileName, FormatModel, Number, Text

__all__ = ["INTERPOLATIONS", "SQUARENESS_PLACEMENTS", "MAX_MACHINE_SIZE_MM", "MachineAxis", "MachineFile"]

#: how an error table is read between its rows
INTERPOLATIONS = ("linear", "cubic")
#: where the squareness errors are placed in the chain (docs/conventions.md)
SQUARENESS_PLACEMENTS = ("relative", "guideway")
#: largest length accepted in a machine file (tool, workpiece, origins), mm
MAX_MACHINE_SIZE_MM = 1.0e5

_Length = Annotated[float, Strict(), AllowInfNan(False), Ge(-MAX_MACHINE_SIZE_MM), Le(MAX_MACHINE_SIZE_MM)]
#: three finite numbers in mm, each within +-100 000 mm
PointMm = Annotated[list[_Length], Len(3, 3)]
_SQUARENESS_KEY = r"^(EC0Y|EB0Z|EA0Z)_(urad|mrad|arcsec)(_u)?$"
_LOCATION_KEY = r"^E[XYZABC]0[ABC]_(nm|um|mm|urad|mrad|arcsec)$"


class MachineAxis(FormatModel):
    """``[axes.<L>]``: one axis of the chain.

    Attributes
    ----------
    errors : str
        The axis' error table (CSV), relative to the machine file.
    origin_mm : list of 3 float or None
    interpolation : str or None
    hold_ends, periodic : bool or None
    sensors : dict or None
        The 6-DOF sensor geometry, read by ``MeasurementSystem.from_toml`` (docs/formats.md).
    """

    errors: FileName = Field(description="the error table (CSV), relative to this file, inside its folder")
    origin_mm: PointMm | None = Field(None, description="origin of this carriage's frame at position 0, in its parent's frame (default 0)")
    interpolation: Literal[INTERPOLATIONS] | None = Field(None, description="between rows (default: the file's)")  # type: ignore[valid-type]
    hold_ends: Bool | None = Field(None, description="hold end values outside the table (default: the file's)")
    periodic: Bool | None = Field(None, description="rotary axes only: the table repeats every 360 degrees (default true)")
    sensors: dict[str, Any] | None = Field(None, description="6-DOF sensor geometry of this axis (measurement)")


class MachineFile(FormatModel):
    """A machine description (TOML, docs/formats.md).

    Attributes
    ----------
    name : str or None
    chain : str
        Workpiece-side axes, ``F`` (the frame), tool-side axes: ``"FXZ"``, ``"CAFXYZ"``.
    tool_mm, workpiece_mm : list of 3 float or None
    interpolation : str or None
    hold_ends : bool or None
    squareness_placement : str or None
    axes : dict of str to MachineAxis
    squareness, location : dict of str to float, or None
        Terms with their unit in the key (``EB0Z_arcsec``, ``EX0C_um``).
    """

    name: Text | None = Field(None, description="the machine's name")
    chain: Annotated[str, Strict(), StringConstraints(pattern=r"\S")] = Field(
        description="workpiece-side axes, F (frame), tool-side axes, e.g. FXZ")
    tool_mm: PointMm | None = Field(None, description="functional point in the frame of the last tool-side carriage")
    workpiece_mm: PointMm | None = Field(None, description="point of the workpiece frame the error is measured from (default 0)")
    interpolation: Literal[INTERPOLATIONS] | None = Field(None, description="between table rows, for every axis (default linear)")  # type: ignore[valid-type]
    hold_ends: Bool | None = Field(None, description="hold end values outside the tables (default false)")
    squareness_placement: Literal[SQUARENESS_PLACEMENTS] | None = Field(  # type: ignore[valid-type]
        None, description="relative keeps the measured included angles; guideway (docs/conventions.md)")
    axes: dict[str, MachineAxis] | None = Field(
        None, description="one [axes.<L>] per axis of the chain",
        json_schema_extra={"propertyNames": {"pattern": "^[XYZABC]$"}})
    squareness: dict[str, Number] | None = Field(
        None, description="EC0Y, EB0Z, EA0Z with a unit _urad, _mrad or _arcsec; at most 0.01 rad",
        json_schema_extra={"propertyNames": {"pattern": _SQUARENESS_KEY}})
    location: dict[str, Number] | None = Field(
        None, description="location errors of rotary axes (EX0C_um, EA0C_urad ...); at most 10 mm or 0.01 rad",
        json_schema_extra={"propertyNames": {"pattern": _LOCATION_KEY}})
