"""Flatness line files declared: ``[[lines]]`` with their ends and readings (docs/flatness.md)."""

from __future__ import annotations

from pydantic import Field

from axiscal.io.formats.base import Bool, FormatModel, Name, Number, Numbers, Pair

__all__ = ["ANGLE_KEYS", "FlatnessLineEntry", "FlatnessFile"]

#: the keys a line's level readings may stand under, one per unit
ANGLE_KEYS = ("angle_arcsec", "angle_urad", "angle_um_per_m")


class FlatnessLineEntry(FormatModel):
    """One ``[[lines]]`` entry: a measured line of the surface.

    Attributes
    ----------
    name : str
    from_mm, to_mm : list of 2 float
        The line's ends on the surface, mm.
    foot_mm : float or None
        Foot spacing of a level (default: the file's).
    gravity : bool or None
    profile : str or None
        A profile CSV beside the file.
    position_mm, deviation_um : list of float or None
        A profile written in the file.
    angle_arcsec, angle_urad, angle_um_per_m : list of float or None
        Level readings, one per foot step.
    """

    name: Name = Field(description="the line's name (unique)")
    from_mm: Pair = Field(description="start of the line on the surface [x, y], mm")
    to_mm: Pair = Field(description="end of the line on the surface [x, y], mm")
    foot_mm: Number | None = Field(None, description="foot spacing of the level (default: foot_mm at the top)")
    gravity: Bool | None = Field(None, description="readings are against gravity (default: gravity at the top)")
    profile: Name | None = Field(None, description="profile CSV beside this file (position_mm, deviation_um)")
    position_mm: Numbers | None = Field(None, description="positions along the line, with deviation_um")
    deviation_um: Numbers | None = Field(None, description="deviations at position_mm")
    angle_arcsec: Numbers | None = Field(None, description="level readings, arcsec")
    angle_urad: Numbers | None = Field(None, description="level readings, urad")
    angle_um_per_m: Numbers | None = Field(None, description="level readings, um/m")


class FlatnessFile(FormatModel):
    """A flatness lines file (TOML).

    Attributes
    ----------
    title : str or None
    foot_mm : float or None
    gravity : bool or None
    lines : list of FlatnessLineEntry
    """

    title: Name | None = Field(None, description="the surface's name in the report")
    foot_mm: Number | None = Field(None, description="foot spacing of the level for every line, mm")
    gravity: Bool | None = Field(None, description="level readings against gravity, for every line (default false)")
    lines: list[FlatnessLineEntry] = Field(default_factory=list, description="the measured lines, [[lines]]")
