"""From raw sensor frames to the error of the functional point (paper 000), the calibration runs of the sensors and the diagonal they explain, the virtual instrument that simulates them, and a whole campaign simulated on it."""

from __future__ import annotations

from axiscal.measurement.campaign_sim import (
    AIR,
    DIAGONAL_LOADS_KG,
    PRISM_DEVIATION_RAD,
    REPEATABILITY_M,
    REVERSAL_M,
    STRAIGHTEDGE_M,
    VACUUM_WAVELENGTH_NM,
    SimulatedCampaign,
    campaign_toml,
    diagonal_readings,
    laser_run,
    probe_readings,
    squareness_runs,
    write_campaign,
)
from axiscal.measurement.display import (
    display_factor,
    display_name,
    to_display,
)
from axiscal.measurement.faults import (
    FAULT_TEXT,
    Fault,
    fault_legend,
    fault_text,
    mark_malformed,
)
from axiscal.measurement.frames import (
    RECORD_KIND,
    CsvOutput,
    columns_csv,
    drop_cut_line,
    is_live_record,
    numeric_columns,
    read_frames,
    read_frames_table,
    write_data_csv,
)
from axiscal.measurement.system import load_system
from axiscal.measurement.offline import MeasureResult, measure_file
from axiscal.measurement.calibrate import calibrate_mirror, calibrate_sensitivity, calibration_text
from axiscal.measurement.simulate import MAX_SIMULATED_FRAMES, simulate_frames, simulate_laser
from axiscal.measurement.experiment import DiagonalExperiment, DiagonalReport, diagonal_experiment, run_diagonal_experiment
from axiscal.measurement.pipeline import (
    MeasurementSystem,
    diagonal_errors,
    spatial_error,
)
from axiscal.measurement.virtual import (
    INTERFEROMETER_BEAM_M,
    NOISE,
    PATHS,
    QD_FOCAL_M,
    REFERENCE_NOISE,
    ROLL_FOCAL_M,
    SQUARENESS_EB0Z_RAD,
    STROKE_M,
    TOOL_M,
    Z_ORIGIN_M,
    Truth,
    VirtualModule,
)

from axiscal.measurement.sensor_diagonal import STOP_TOLERANCE_M, SensorDiagonal, sensor_diagonal
from axiscal.measurement.sensor_runs import SENSOR_RUN_COLUMNS, SensorRuns, calibrate_sensor_runs

__all__ = [
    "display_name",
    "display_factor",
    "to_display",
    "Fault",
    "FAULT_TEXT",
    "fault_text",
    "fault_legend",
    "mark_malformed",
    "RECORD_KIND",
    "MAX_SIMULATED_FRAMES",
    "load_system",
    "is_live_record",
    "drop_cut_line",
    "numeric_columns",
    "read_frames_table",
    "read_frames",
    "columns_csv",
    "write_data_csv",
    "CsvOutput",
    "MeasureResult",
    "measure_file",
    "calibrate_sensitivity",
    "calibrate_mirror",
    "calibration_text",
    "simulate_frames",
    "simulate_laser",
    "DiagonalReport",
    "run_diagonal_experiment",
    "MeasurementSystem",
    "spatial_error",
    "diagonal_errors",
    "STROKE_M",
    "SQUARENESS_EB0Z_RAD",
    "TOOL_M",
    "Z_ORIGIN_M",
    "PATHS",
    "INTERFEROMETER_BEAM_M",
    "QD_FOCAL_M",
    "ROLL_FOCAL_M",
    "NOISE",
    "REFERENCE_NOISE",
    "Truth",
    "VirtualModule",
    "DiagonalExperiment",
    "diagonal_experiment",
    "AIR",
    "DIAGONAL_LOADS_KG",
    "PRISM_DEVIATION_RAD",
    "REPEATABILITY_M",
    "REVERSAL_M",
    "STRAIGHTEDGE_M",
    "VACUUM_WAVELENGTH_NM",
    "SimulatedCampaign",
    "campaign_toml",
    "diagonal_readings",
    "laser_run",
    "probe_readings",
    "squareness_runs",
    "write_campaign",
    "SENSOR_RUN_COLUMNS",
    "SensorRuns",
    "calibrate_sensor_runs",
    "SensorDiagonal",
    "sensor_diagonal",
    "STOP_TOLERANCE_M",
]
