"""axiscal: measure, model and compensate the geometric errors of machine axes.

The Python API works in SI units (metres, radians, kelvin, pascals). Files and the command line
use the units people use, spelled out in names (``position_mm``, ``EXX_um``, ``--pressure-pa``).

The names below are the stated public API; each lives in its room (``axiscal.model``,
``axiscal.positioning``, ...) and is imported from there on first use, so ``import axiscal``
stays cheap.

Examples
--------
>>> import numpy as np, axiscal
>>> axiscal.refractive_index(20.0, 101325.0, 50.0, 632.99137)  # doctest: +ELLIPSIS
1.000271...
"""

from __future__ import annotations

import importlib
from typing import Any

from axiscal.errors import AxiscalError
from axiscal.version import __version__ as __version__

#: public name -> the module that defines it
_PUBLIC: dict[str, str] = {
    # the machine model (paper 000, ISO 230-1)
    "load_machine": "axiscal.model.machine",
    "Machine": "axiscal.model.machine",
    "ErrorTable": "axiscal.model.tables",
    "read_error_table": "axiscal.model.tables",
    "diagonal_check": "axiscal.model.diagonal",
    "diagonal_test": "axiscal.model.diagonal",
    "volumetric_map": "axiscal.model.volumetric",
    "inverse_commands": "axiscal.model.inverse",
    # instruments (paper 003, Ciddor/Edlen, paper 002)
    "refractive_index": "axiscal.instruments.air",
    "length_from_fringes": "axiscal.instruments.interferometer",
    "compensated_length": "axiscal.instruments.interferometer",
    "pentaprism_deviation": "axiscal.instruments.optics",
    # positioning (ISO 230-2, VDI/DGQ 3441)
    "PositioningRun": "axiscal.positioning.evaluation",
    "read_positioning_run": "axiscal.positioning.reader",
    "iso230_2": "axiscal.positioning.evaluation",
    "vdi3441": "axiscal.positioning.evaluation",
    "target_statistics": "axiscal.positioning.evaluation",
    "plan_test": "axiscal.positioning.plan",
    "plan_step_cycle": "axiscal.positioning.step_cycle",
    "evaluate_positioning_file": "axiscal.positioning.report",
    # straightness and error separation (paper 001)
    "reference_line": "axiscal.straightness.reference",
    "separate": "axiscal.straightness.separation",
    "reversal": "axiscal.straightness.separation",
    "ProbeReadings": "axiscal.straightness.separation",
    "read_profile": "axiscal.straightness.files",
    "evaluate_straightness_file": "axiscal.straightness.files",
    "separate_file": "axiscal.straightness.files",
    # squareness (papers 002, 004)
    "squareness": "axiscal.squareness.evaluation",
    "squareness_from_slopes": "axiscal.squareness.evaluation",
    "prism_reversal": "axiscal.squareness.evaluation",
    "squareness_from_files": "axiscal.squareness.evaluation",
    # circular tests (ISO 230-4)
    "evaluate_ballbar_file": "axiscal.circular.report",
    # compensation tables
    "error_curve": "axiscal.compensation.curve",
    "linuxcnc_table": "axiscal.compensation.linuxcnc",
    "fanuc_table": "axiscal.compensation.fanuc",
    "siemens_table": "axiscal.compensation.siemens",
    "heidenhain_table": "axiscal.compensation.heidenhain",
    "compensation_table": "axiscal.compensation.formats",
    "skew_correction": "axiscal.compensation.skew",
    "backlash_setting": "axiscal.compensation.backlash",
    # data in from instruments
    "import_readings": "axiscal.io.importers.readings",
    "read_rtx": "axiscal.io.importers.rtx",
    # uncertainty (ISO 230-2 Annex A, GUM, GUM Supplement 1)
    "read_budget": "axiscal.uncertainty.budget",
    "positioning_uncertainty": "axiscal.uncertainty.positioning",
    "volumetric_monte_carlo": "axiscal.uncertainty.volumetric",
    "volumetric_uncertainty_map": "axiscal.uncertainty.volumetric_map",
    # identification of error tables from artefacts (ball plate, step gauge, ballbar, multilateration, R-test)
    "identify": "axiscal.identification.solve",
    "read_artefact": "axiscal.identification.files",
    # measurement from raw sensor frames (paper 000)
    "MeasurementSystem": "axiscal.measurement.pipeline",
    "VirtualModule": "axiscal.measurement.virtual",
    "measure_file": "axiscal.measurement.offline",
    # dynamics, periodic errors (ISO 230-2 Annexes B and C), on-the-fly capture
    "axis_dynamics": "axiscal.dynamics.analysis",
    "periodic_error": "axiscal.dynamics.periodic",
    "on_the_fly_run": "axiscal.capture.on_the_fly",
    # campaigns and the report
    "load_campaign": "axiscal.campaign.config",
    "run_campaign": "axiscal.campaign.runner",
    "report_campaign": "axiscal.report.writer",
}

__all__ = ["AxiscalError", "__version__", *_PUBLIC]


def __getattr__(name: str) -> Any:
    module = _PUBLIC.get(name)
    if module is None:
        raise AttributeError(f"module 'axiscal' has no attribute '{name}'")
    value = getattr(importlib.import_module(module), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_PUBLIC))
