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
    axis_positions,
    BallbarNetwork,
    BallPlate,
    Multilateration,
    r_test_positions,
    RTest,
    StepGauge,
)
from axiscal.identification.basis import (
    MAX_MODEL_ORDER,
    MODEL_KINDS,
    ErrorModel,
    parse_model,
)
from axiscal.identification.files import (
    ARTEFACT_KEYS,
    read_artefact,
    write_artefact,
)
from axiscal.identification.output import (
    report_html,
    write_identification,
    write_machine_folder,
)
from axiscal.identification.maps import (
    map_difference,
)
from axiscal.identification.parameters import (
    STEP,
    ParameterSet,
    Term,
)
from axiscal.identification.plot import (
    motions_figure,
    plot_motions,
    plot_residuals,
    residuals_figure,
)
from axiscal.identification.result import (
    Combination,
    Identification,
    Undetermined,
)
from axiscal.identification.simulate import (
    plate_grid,
    simulate_ball_plate,
    simulate_ballbar,
    simulate_multilateration,
    simulate_r_test,
    simulate_step_gauge,
)
from axiscal.identification.solve import (
    RANK_TOLERANCE,
    identify,
    identify_files,
)

__all__ = [
    "MISFIT_M",
    "Artefact",
    "BallPlate",
    "StepGauge",
    "BallbarNetwork",
    "Multilateration",
    "RTest",
    "axis_positions",
    "r_test_positions",
    "ARTEFACT_KINDS",
    "MODEL_KINDS",
    "MAX_MODEL_ORDER",
    "ErrorModel",
    "parse_model",
    "identify_files",
    "read_artefact",
    "write_artefact",
    "write_machine_folder",
    "write_identification",
    "report_html",
    "ARTEFACT_KEYS",
    "map_difference",
    "Term",
    "ParameterSet",
    "STEP",
    "plot_residuals",
    "plot_motions",
    "residuals_figure",
    "motions_figure",
    "Combination",
    "Undetermined",
    "Identification",
    "simulate_ball_plate",
    "simulate_step_gauge",
    "simulate_ballbar",
    "simulate_multilateration",
    "simulate_r_test",
    "plate_grid",
    "identify",
    "RANK_TOLERANCE",
]
