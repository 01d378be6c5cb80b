"""Capture: the readings of a positioning test taken from a stream or a recording, stop by stop.

:func:`detect_stops` finds where a reading held still; :func:`capture_run` walks a plan's steps
through a recording or a live source and returns the positioning run; :func:`capture_to_file` is
``axiscal capture`` (a partial file as it goes, resume, the run written atomically);
:func:`simulate_capture` runs a program on the virtual machine and records what a laser reads;
:func:`measure_axis` does plan, program, run and capture for one axis of the virtual machine;
:func:`on_the_fly_run` takes the readings as the axis passes the targets without stopping, from a
recording that carries the machine's position stream beside the laser's reading.
"""

from __future__ import annotations

from axiscal.capture.stops import (
    SETTLE_S,
    Stop,
    StopDetector,
    detect_stops,
    least_dwell_s,
)
from axiscal.capture.recording import (
    ENVIRONMENT_COLUMNS,
    READING_UNITS,
    Recording,
    environment_columns,
    read_recording,
)
from axiscal.capture.steps import (
    CapturedStop,
    PlanSteps,
    StepMatcher,
    plan_steps,
)
from axiscal.capture.run import (
    Capture,
    CaptureProgress,
    CaptureSettings,
    StopReading,
    capture,
    capture_run,
)
from axiscal.capture.files import (
    CaptureFiles,
    PARTIAL_COLUMNS,
    capture_to_file,
    partial_path,
)
from axiscal.capture.virtual import (
    SimulatedRecording,
    VirtualAxis,
    simulate_capture,
    simulate_motions,
    write_recording,
)
from axiscal.capture.sources import (
    open_capture_source,
    plan_motions,
)
from axiscal.capture.cycle import (
    AxisMeasurement,
    measure_axis,
)
from axiscal.capture.board import (
    CaptureBoard,
)
from axiscal.capture.on_the_fly import (
    FlyRecording,
    OnTheFly,
    estimate_delay,
    on_the_fly,
    on_the_fly_run,
    on_the_fly_to_file,
    read_fly_recording,
)
from axiscal.capture.on_the_fly_plot import plot_on_the_fly

from axiscal.capture.drive import DriveSettings, InstrumentReader, drive_plan, planned_moves
from axiscal.capture.fly_drive import FlyFiles, fly_plan, pass_moves
from axiscal.capture.connected import DryRun, SimMachine, dry_run, open_run_devices, run_to_file, sim_machine
from axiscal.capture.fly_drive import (
    FLY_AGREEMENT_M,
    FLY_SPEED_LIMIT_M_S,
)

__all__ = [
    "FlyFiles",
    "fly_plan",
    "pass_moves",
    "DriveSettings",
    "InstrumentReader",
    "drive_plan",
    "planned_moves",
    "DryRun",
    "SimMachine",
    "dry_run",
    "open_run_devices",
    "run_to_file",
    "sim_machine",
    "SETTLE_S",
    "Stop",
    "StopDetector",
    "detect_stops",
    "least_dwell_s",
    "ENVIRONMENT_COLUMNS",
    "READING_UNITS",
    "Recording",
    "environment_columns",
    "read_recording",
    "CapturedStop",
    "PlanSteps",
    "StepMatcher",
    "plan_steps",
    "Capture",
    "CaptureProgress",
    "CaptureSettings",
    "StopReading",
    "capture",
    "capture_run",
    "CaptureFiles",
    "PARTIAL_COLUMNS",
    "capture_to_file",
    "partial_path",
    "SimulatedRecording",
    "VirtualAxis",
    "simulate_capture",
    "simulate_motions",
    "write_recording",
    "open_capture_source",
    "plan_motions",
    "AxisMeasurement",
    "measure_axis",
    "CaptureBoard",
    "FlyRecording",
    "OnTheFly",
    "estimate_delay",
    "on_the_fly",
    "on_the_fly_run",
    "on_the_fly_to_file",
    "read_fly_recording",
    "plot_on_the_fly",
    "FLY_AGREEMENT_M",
    "FLY_SPEED_LIMIT_M_S",
]
