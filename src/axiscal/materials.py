"""Material constants used as defaults, each with its source.

Values are linear thermal expansion coefficients in 1/K at about 20 degC. The value of a real
machine's scale or workpiece should come from its maker; these are the usual textbook defaults
(ISO/TR 16015:2003, Table 2 gives the same ranges).
"""

from __future__ import annotations

__all__ = ["EXPANSION_PER_K", "STEEL_EXPANSION_PER_K"]

#: linear expansion coefficients, 1/K, at 20 degC
EXPANSION_PER_K: dict[str, float] = {
    "steel": 11.5e-6,
    "cast_iron": 10.5e-6,
    "aluminium": 23.0e-6,
    "granite": 7.0e-6,
    "glass_ceramic": 0.05e-6,
    "invar": 1.2e-6,
}
#: the default of every length normalised to 20 degC: a steel scale or lead screw
STEEL_EXPANSION_PER_K = EXPANSION_PER_K["steel"]
