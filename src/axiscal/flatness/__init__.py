"""Flatness: a surface joined from measured lines (Union Jack or grid), its closure errors and its flatness (ISO 230-1)."""

from __future__ import annotations

from axiscal.flatness.files import FlatnessEvaluation, FlatnessLines, evaluate_flatness, read_flatness_lines
from axiscal.flatness.moody import moody_union_jack
from axiscal.flatness.plot import plot_flatness
from axiscal.flatness.surface import (
    EVALUATIONS,
    Closure,
    FlatnessLine,
    FlatnessSurface,
    FlatnessZone,
    flatness_zone,
    line_from_angles,
    surface_from_lines,
)

__all__ = [
    "EVALUATIONS",
    "FlatnessLine",
    "line_from_angles",
    "Closure",
    "FlatnessZone",
    "flatness_zone",
    "FlatnessSurface",
    "surface_from_lines",
    "moody_union_jack",
    "FlatnessLines",
    "read_flatness_lines",
    "FlatnessEvaluation",
    "evaluate_flatness",
    "plot_flatness",
]
