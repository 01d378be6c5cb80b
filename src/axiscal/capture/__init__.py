"""Capture: the readings of a positioning test taken from a stream or a recording, stop by stop.

:func:`detect_stops` finds where a reading held still; :func:`capture_run` walks a plan's steps
through a recording or a live source and returns the positioning run; :func:`capture_to_file` is
``axiscal capture`` (a partial file as it goes, resume, the run written atomically);
:func:`simulate_capture` runs a program on the virtual machine and records what a laser reads.
"""

from axiscal.capture.recording import Recording, read_recording
from axiscal.capture.files import CaptureFiles, capture_to_file, partial_path
from axiscal.capture.run import Capture, CaptureSettings, StopReading, capture, capture_run
from axiscal.capture.steps import PlanSteps, plan_steps
from axiscal.capture.stops import Stop, StopDetector, detect_stops
from axiscal.capture.virtual import SimulatedRecording, VirtualAxis, simulate_capture, simulate_motions

__all__ = [
    "Capture",
    "CaptureFiles",
    "CaptureSettings",
    "PlanSteps",
    "Recording",
    "SimulatedRecording",
    "Stop",
    "StopDetector",
    "StopReading",
    "VirtualAxis",
    "capture",
    "capture_run",
    "capture_to_file",
    "detect_stops",
    "partial_path",
    "plan_steps",
    "read_recording",
    "simulate_capture",
    "simulate_motions",
]
