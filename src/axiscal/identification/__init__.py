"""Identification of a machine's error tables from artefacts: ball plate, step gauge, ballbar network, multilateration and the R-test.

The measurement equation of each artefact (docs/identification.md) is written on the volumetric
error of the machine model (:meth:`axiscal.model.Machine.volumetric_error`); the error motions are
polynomial or spline error functions of each axis' position (Kunzmann, Trapet and Waeldele, CIRP
Annals 1990; MSLNZ ls_cmm_error_map), fitted by least squares with a rank analysis that names the
combinations the artefacts cannot separate, and their covariance.
"""

from __future__ import annotations

from axiscal.identification.artefacts import (
    ARTEFACT_KINDS,
    MISFIT_M,
    Artefact,
    BallbarNetwork,
    BallPlate,
    Multilateration,
    RTest,
    StepGauge,
    axis_positions,
)
from axiscal.identification.basis import MODEL_KINDS, ErrorModel, parse_model
from axiscal.identification.files import identify_files, read_artefact, write_artefact, write_identification, write_machine_folder
from axiscal.identification.maps import map_difference
from axiscal.identification.parameters import ParameterSet, Term
from axiscal.identification.result import Combination, Identification, Undetermined
from axiscal.identification.solve import RANK_TOLERANCE, identify

__all__ = [
    "ARTEFACT_KINDS",
    "MISFIT_M",
    "MODEL_KINDS",
    "RANK_TOLERANCE",
    "Artefact",
    "BallPlate",
    "StepGauge",
    "BallbarNetwork",
    "Multilateration",
    "RTest",
    "axis_positions",
    "ErrorModel",
    "parse_model",
    "ParameterSet",
    "Term",
    "Combination",
    "Undetermined",
    "Identification",
    "identify",
    "identify_files",
    "map_difference",
    "read_artefact",
    "write_artefact",
    "write_identification",
    "write_machine_folder",
]
