"""The values the command line's options offer, without importing the library that defines them.

``--help`` and a mistyped option must answer at once, so the command modules take their choices
and defaults from here; each name below has the library constant it mirrors beside it, and
tests/cli/test_choices.py checks that every value equals the library's.
"""

from __future__ import annotations

__all__ = [
    "BACKLASH_CONTROLLERS", "BACKLASH_METHODS", "BK7_INDEX", "CONTROLLERS", "CYCLES", "DB_ENVIRONMENT",
    "DIALECT_NAMES", "DIRECTIONS", "EVALUATIONS", "FIRMWARES", "FLEET_SCHEDULER_TIMEOUT_S", "FORMATS", "HENE_WAVELENGTH_NM", "IMPORT_UNITS",
    "MEASURES", "MODEL_KINDS", "PAPER_004_SQUARENESS_ARCMIN", "PATHS", "PLANES", "READING_UNITS", "REFERENCES",
    "SAG_CONTROLLERS", "SAG_REFERENCES", "SCREWMAP_CONTROLLERS", "SEPARATION_METHODS", "SKEW_CONVENTIONS",
    "SQUARENESS_REFERENCES", "STANDARDS", "UNCERTAINTY_SCHEDULER_TIMEOUT_S", "AIR_METHODS", "MIRRORED",
    "DECISION_RULES", "SCHEMA_FORMATS",
]

AIR_METHODS = ("ciddor", "edlen", "edlen1966", "shopfloor")
SCHEMA_FORMATS = ('campaign', 'machine', 'budget', 'artefact', 'flatness', 'import-map')
DECISION_RULES = ('simple', 'guard-band')
BACKLASH_CONTROLLERS = ("linuxcnc", "fanuc", "siemens", "heidenhain", "twincat", "grblhal", "marlin", "rrf")
BACKLASH_METHODS = ("mean", "max", "target")
BK7_INDEX = 1.5168
HENE_WAVELENGTH_NM = 632.991
IMPORT_UNITS = ("nm", "um", "mm", "m", "in")
CONTROLLERS = ("linuxcnc", "fanuc", "siemens", "heidenhain")
CYCLES = ("linear", "pilgrim")
DB_ENVIRONMENT = "AXISCAL_DB"
DIALECT_NAMES = ("linuxcnc", "grbl", "fanuc", "sinumerik", "heidenhain", "marlin", "klipper")
DIRECTIONS = ("ccw", "cw")
EVALUATIONS = ("least-squares", "moody")
FIRMWARES = ("klipper", "marlin", "rrf")
FLEET_SCHEDULER_TIMEOUT_S = 10.0
FORMATS = ("linuxcnc", "fanuc", "siemens", "heidenhain")
MEASURES = ("projection", "length")
MODEL_KINDS = ("poly", "spline")
PAPER_004_SQUARENESS_ARCMIN = (8.05, 27.1, -16.6)
PATHS = ("diagonal", "raster", "back-and-forth")
PLANES = ("XY", "YX", "XZ", "ZX", "YZ", "ZY")
READING_UNITS = ("nm", "um", "mm", "m", "in")
REFERENCES = ("least-squares", "end-points", "minimum-zone")
SAG_CONTROLLERS = ("siemens", "heidenhain")
SAG_REFERENCES = ("none", "least-squares", "end-points")
SCREWMAP_CONTROLLERS = ("twincat", "mach4")
SEPARATION_METHODS = ("stp", "strp", "fstrp", "gtp", "frequency", "combined", "reversal")
SKEW_CONVENTIONS = ("included-angle", "iso")
SQUARENESS_REFERENCES = ("least-squares", "end-points")
STANDARDS = ("iso230-2:2014", "iso230-2:2006", "iso230-2:1997", "iso230-2:1988", "jis-b6192", "vdi3441")
UNCERTAINTY_SCHEDULER_TIMEOUT_S = 10.0

#: name here -> the library constant it mirrors ("module:NAME"); keys of a mapping are compared as a tuple
MIRRORED: dict[str, str] = {
    "DECISION_RULES": "axiscal.uncertainty.decision:DECISION_RULES",
    "SCHEMA_FORMATS": "axiscal.io.formats.catalogue:FORMAT_FILES",
    "AIR_METHODS": "axiscal.instruments.air:METHODS",
    "BACKLASH_CONTROLLERS": "axiscal.compensation.backlash:BACKLASH_CONTROLLERS",
    "BACKLASH_METHODS": "axiscal.compensation.backlash:BACKLASH_METHODS",
    "BK7_INDEX": "axiscal.instruments.optics:BK7_INDEX",
    "IMPORT_UNITS": "axiscal.io.importers:IMPORT_UNITS",
    "HENE_WAVELENGTH_NM": "axiscal.instruments.interferometer:HENE_WAVELENGTH_NM",
    "CONTROLLERS": "axiscal.compensation.readback:CONTROLLERS",
    "CYCLES": "axiscal.positioning.plan:CYCLES",
    "DB_ENVIRONMENT": "axiscal.history.database:DB_ENVIRONMENT",
    "DIALECT_NAMES": "axiscal.io.gcode:DIALECT_NAMES",
    "DIRECTIONS": "axiscal.circular.evaluation:DIRECTIONS",
    "EVALUATIONS": "axiscal.flatness.surface:EVALUATIONS",
    "FIRMWARES": "axiscal.compensation.skew:FIRMWARES",
    "FLEET_SCHEDULER_TIMEOUT_S": "axiscal.fleet.runner:SCHEDULER_TIMEOUT_S",
    "FORMATS": "axiscal.compensation.formats:FORMATS",
    "MEASURES": "axiscal.model.diagonal:MEASURES",
    "MODEL_KINDS": "axiscal.identification.basis:MODEL_KINDS",
    "PAPER_004_SQUARENESS_ARCMIN": "axiscal.squareness.cmm:PAPER_004_SQUARENESS_ARCMIN",
    "PATHS": "axiscal.measurement.virtual:PATHS",
    "PLANES": "axiscal.circular.evaluation:PLANES",
    "READING_UNITS": "axiscal.capture.recording:READING_UNITS",
    "REFERENCES": "axiscal.straightness.reference:REFERENCES",
    "SAG_CONTROLLERS": "axiscal.compensation.sag:SAG_CONTROLLERS",
    "SAG_REFERENCES": "axiscal.compensation.sag:SAG_REFERENCES",
    "SCREWMAP_CONTROLLERS": "axiscal.compensation.screwmaps:SCREWMAP_CONTROLLERS",
    "SEPARATION_METHODS": "axiscal.straightness.files:SEPARATION_METHODS",
    "SKEW_CONVENTIONS": "axiscal.compensation.skew:SKEW_CONVENTIONS",
    "SQUARENESS_REFERENCES": "axiscal.squareness.evaluation:SQUARENESS_REFERENCES",
    "STANDARDS": "axiscal.positioning.evaluation:STANDARDS",
    "UNCERTAINTY_SCHEDULER_TIMEOUT_S": "axiscal.uncertainty.volumetric:SCHEDULER_TIMEOUT_S",
}
