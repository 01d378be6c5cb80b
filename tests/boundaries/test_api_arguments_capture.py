"""Every public callable of the capture room refuses bad arguments with AxiscalError naming them.

The same table harness as the other rooms (api_cases.CaseTable). The result objects a capture
returns (a Capture and its stops, the files written, a simulated recording) are made by the room
itself and are exempt.
"""

from __future__ import annotations

import numpy as np

from api_cases import EXAMPLES, CaseTable, api

from axiscal.model import load_machine

ROOMS = ("capture",)
NAN, INF = float("nan"), float("inf")
TABLE = CaseTable(ROOMS)
bad = TABLE.bad
ca = api("capture")
C = "capture"
PLAN = EXAMPLES / "capture" / "plan_x.csv"
RECORDING = EXAMPLES / "capture" / "recording_x.csv"
PROGRAM = EXAMPLES / "capture" / "x.ngc"
MACHINE = EXAMPLES / "xz_module" / "machine.toml"
NEVER = EXAMPLES / "no such folder" / "run.csv"
STEPS = ca.plan_steps(PLAN)
T = np.arange(5.0)

bad(C, "detect_stops", "time_s", lambda: ca.detect_stops(np.array([0.0, NAN]), np.zeros(2), stability_m=1e-6, window_s=0.5),
    lambda: ca.detect_stops("t", np.zeros(2), stability_m=1e-6, window_s=0.5))
bad(C, "detect_stops", "one length", lambda: ca.detect_stops(T, np.zeros(3), stability_m=1e-6, window_s=0.5))
bad(C, "detect_stops", "stability_m", lambda: ca.detect_stops(T, T, stability_m=-1.0, window_s=0.5),
    lambda: ca.detect_stops(T, T, stability_m=INF, window_s=0.5))
bad(C, "detect_stops", "window_s", lambda: ca.detect_stops(T, T, stability_m=1e-6, window_s=0.0))
bad(C, "StopDetector", "stability_m", lambda: ca.StopDetector(stability_m=NAN, window_s=0.5))
bad(C, "StopDetector", "channels", lambda: ca.StopDetector(stability_m=1e-6, window_s=0.5, channels="air_temperature_c"))
bad(C, "Recording", "reading_m", lambda: ca.Recording(T, np.zeros(3)))
bad(C, "Recording", "time_s", lambda: ca.Recording(np.array([0.0, INF]), np.zeros(2)))
bad(C, "Recording", "channels", lambda: ca.Recording(T, T, {"air_temperature_c": np.zeros(2)}), lambda: ca.Recording(T, T, None))
bad(C, "read_recording", "path", lambda: ca.read_recording(None))
bad(C, "read_recording", "unknown unit", lambda: ca.read_recording(RECORDING, unit="furlong"))
bad(C, "read_recording", "no column", lambda: ca.read_recording(RECORDING, channel="laser_um"))
bad(C, "environment_columns", "names", lambda: ca.environment_columns(None))
bad(C, "plan_steps", "plan", lambda: ca.plan_steps(None), lambda: ca.plan_steps(5))
bad(C, "PlanSteps", "run", lambda: ca.PlanSteps(np.arange(2), np.arange(3), np.array(["+", "-"]), np.zeros(2), np.zeros(2)))
bad(C, "PlanSteps", "direction", lambda: ca.PlanSteps(np.arange(2), np.arange(2), np.array(["+", "up"]), np.zeros(2), np.zeros(2)))
bad(C, "StepMatcher", "steps", lambda: ca.StepMatcher(None, tolerance_m=1e-3, offset_m=0.0))
bad(C, "StepMatcher", "tolerance_m", lambda: ca.StepMatcher(STEPS, tolerance_m=0.0, offset_m=0.0))
bad(C, "StepMatcher", "start", lambda: ca.StepMatcher(STEPS, tolerance_m=1e-3, offset_m=0.0, start=-1))
bad(C, "CaptureSettings", "stability_m", lambda: ca.CaptureSettings(stability_m=0.0))
bad(C, "CaptureSettings", "window_s", lambda: ca.CaptureSettings(window_s=NAN))
bad(C, "CaptureSettings", "offset_m", lambda: ca.CaptureSettings(offset_m=INF), lambda: ca.CaptureSettings(offset_m="0"),
    lambda: ca.CaptureSettings(offset_m=1e300))
bad(C, "CaptureSettings", "window_s", lambda: ca.CaptureSettings(window_s=1e300))  # an OverflowError in the run's wait
bad(C, "CaptureSettings", "stability_m", lambda: ca.CaptureSettings(stability_m=1e300))
bad(C, "CaptureSettings", "tolerance_m", lambda: ca.CaptureSettings(tolerance_m=1e300), lambda: ca.CaptureSettings(tolerance_m=0.0))
bad(C, "capture", "settings", lambda: ca.capture(PLAN, RECORDING, settings={"window_s": 0.5}))
bad(C, "capture", "recording", lambda: ca.capture(PLAN, 5), lambda: ca.capture(PLAN, None))
bad(C, "capture", "plan", lambda: ca.capture(None, RECORDING))
bad(C, "capture", "window_s", lambda: ca.capture(PLAN, RECORDING, settings=ca.CaptureSettings(window_s=1e300)))
bad(C, "capture_run", "recording", lambda: ca.capture_run(PLAN, 5))
bad(C, "capture_to_file", "output", lambda: ca.capture_to_file(PLAN, RECORDING, None))
bad(C, "capture_to_file", "resume", lambda: ca.capture_to_file(PLAN, RECORDING, NEVER, resume="yes"))
bad(C, "partial_path", "output", lambda: ca.partial_path(None))
bad(C, "VirtualAxis", "acceleration_m_s2", lambda: ca.VirtualAxis(acceleration_m_s2=0.0))
bad(C, "VirtualAxis", "noise_m", lambda: ca.VirtualAxis(noise_m=-1e-9), lambda: ca.VirtualAxis(noise_m=NAN))
bad(C, "simulate_motions", "machine", lambda: ca.simulate_motions([], None, axis="X"))
bad(C, "simulate_motions", "axis", lambda: ca.simulate_motions([], load_machine(MACHINE), axis="Q"))
bad(C, "simulate_capture", "not a linear axis", lambda: ca.simulate_capture(PROGRAM, MACHINE, axis="Y"))
bad(C, "simulate_capture", "rate_hz", lambda: ca.simulate_capture(PROGRAM, MACHINE, axis="X", rate_hz=-1.0))
bad(C, "simulate_capture", "controller", lambda: ca.simulate_capture(PROGRAM, MACHINE, axis="X", compensation=PROGRAM))
bad(C, "simulate_capture", "never moves", lambda: ca.simulate_capture(PROGRAM, MACHINE, axis="Z"))
bad(C, "simulate_motions", "never moves", lambda: ca.simulate_motions(ca.plan_motions(STEPS, axis="Z"), load_machine(MACHINE), axis="X"))
bad(C, "write_recording", "simulated", lambda: ca.write_recording(None, NEVER))
bad(C, "plan_motions", "dwell_s", lambda: ca.plan_motions(STEPS, dwell_s=-1.0))
bad(C, "plan_motions", "feed_mm_per_min", lambda: ca.plan_motions(STEPS, feed_mm_per_min=0.0))
bad(C, "open_capture_source", "unknown source", lambda: ca.open_capture_source("udp:1.2.3.4:5"))
bad(C, "open_capture_source", "needs the plan", lambda: ca.open_capture_source("sim"))
bad(C, "measure_axis", "folder", lambda: ca.measure_axis(None, MACHINE, axis="X", start_m=0.0, end_m=0.19, targets=5))
bad(C, "measure_axis", "targets", lambda: ca.measure_axis(NEVER.parent, MACHINE, axis="X", start_m=0.0, end_m=0.19, targets=2))
bad(C, "CaptureBoard", "steps", lambda: ca.CaptureBoard(None))
bad(C, "CaptureBoard", "source", lambda: ca.CaptureBoard(STEPS, None))
# the driven run: a controller and an instrument of axiscal.devices (or anything with their methods)
class _Source:
    """Anything with read and close is a source."""

    channels = ("reading_mm",)

    def read(self, timeout_s):
        raise AssertionError("a bad argument is refused before anything is read")

    def close(self):
        pass


SIM_CONTROLLER = ca.sim_machine().controller()
bad(C, "DriveSettings", "axis", lambda: ca.DriveSettings(axis="XY"), lambda: ca.DriveSettings(axis=3))
bad(C, "DriveSettings", "feed", lambda: ca.DriveSettings(feed_m_per_s=0.0), lambda: ca.DriveSettings(feed_m_per_s=NAN),
    lambda: ca.DriveSettings(feed_m_per_s=1e300), lambda: ca.DriveSettings(feed_m_per_s=1e6 / 60e3))
bad(C, "DriveSettings", "dwell", lambda: ca.DriveSettings(dwell_s=-1.0), lambda: ca.DriveSettings(dwell_s=1e300))
bad(C, "InstrumentReader", "source", lambda: ca.InstrumentReader(None), lambda: ca.InstrumentReader("umd:/dev/ttyACM0"))
bad(C, "planned_moves", "steps", lambda: ca.planned_moves(None))
bad(C, "planned_moves", "start", lambda: ca.planned_moves(STEPS, start=-1), lambda: ca.planned_moves(STEPS, start=10**6))
bad(C, "drive_plan", "steps", lambda: ca.drive_plan(PLAN, SIM_CONTROLLER, None))
bad(C, "drive_plan", "controller", lambda: ca.drive_plan(STEPS, "sim", None))
bad(C, "drive_plan", "source", lambda: ca.drive_plan(STEPS, SIM_CONTROLLER, None))
bad(C, "drive_plan", "drive", lambda: ca.drive_plan(STEPS, SIM_CONTROLLER, _Source(), drive={"axis": "X"}))
bad(C, "drive_plan", "settings", lambda: ca.drive_plan(STEPS, SIM_CONTROLLER, _Source(), settings=0.5))
bad(C, "dry_run", "controller", lambda: ca.dry_run(PLAN, None))
bad(C, "dry_run", "beyond the soft limits", lambda: ca.dry_run(PLAN, ca.SimMachine("X", (0.0, 0.01), np.zeros(2) + [0, 1],
                                                                                      np.zeros(2)).controller()))
bad(C, "open_run_devices", "controller", lambda: ca.open_run_devices(None, "sim"))
bad(C, "open_run_devices", "source", lambda: ca.open_run_devices("sim", 5))
bad(C, "open_run_devices", "unknown instrument", lambda: ca.open_run_devices("sim", "laser:/dev/ttyUSB0"))
bad(C, "open_run_devices", "unknown controller", lambda: ca.open_run_devices("fanuc:1.2.3.4", "sim"))
bad(C, "open_run_devices", "machine", lambda: ca.open_run_devices("sim", "sim", machine="xz"))
bad(C, "run_to_file", "output", lambda: ca.run_to_file(PLAN, SIM_CONTROLLER, None, None))
bad(C, "run_to_file", "controller", lambda: ca.run_to_file(PLAN, None, None, NEVER))
bad(C, "sim_machine", "axis", lambda: ca.sim_machine(axis="Q"), lambda: ca.sim_machine(axis=None))
bad(C, "sim_machine", "machine", lambda: ca.sim_machine(machine=5))
bad(C, "pass_moves", "steps", lambda: ca.pass_moves(None), lambda: ca.pass_moves(PLAN))
bad(C, "fly_plan", "controller", lambda: ca.fly_plan(PLAN, None, _Source(), NEVER))
bad(C, "fly_plan", "source", lambda: ca.fly_plan(PLAN, SIM_CONTROLLER, None, NEVER))
bad(C, "fly_plan", "window_s", lambda: ca.fly_plan(PLAN, SIM_CONTROLLER, _Source(), NEVER, window_s=0.0))
bad(C, "fly_plan", "drive", lambda: ca.fly_plan(PLAN, SIM_CONTROLLER, _Source(), NEVER, drive="fast"))

T4 = np.arange(6.0)
FLY = ca.FlyRecording(T4, T4 * 1e-3, T4, T4 * 1e-3)
bad(C, "FlyRecording", "reading_m", lambda: ca.FlyRecording(T4, np.zeros(3), T4, T4))
bad(C, "FlyRecording", "position_m", lambda: ca.FlyRecording(T4, T4, T4, np.zeros(2)))
bad(C, "FlyRecording", "increase", lambda: ca.FlyRecording(T4, T4, T4[::-1].copy(), T4))
bad(C, "read_fly_recording", "position_mm", lambda: ca.read_fly_recording(RECORDING))
bad(C, "read_fly_recording", "path", lambda: ca.read_fly_recording(None))
bad(C, "read_fly_recording", "unknown unit", lambda: ca.read_fly_recording(RECORDING, unit="furlong"))
bad(C, "estimate_delay", "recording", lambda: ca.estimate_delay(None), lambda: ca.estimate_delay(RECORDING))
bad(C, "estimate_delay", "max_delay_s", lambda: ca.estimate_delay(FLY, max_delay_s=0.0), lambda: ca.estimate_delay(FLY, max_delay_s=NAN))
bad(C, "on_the_fly", "recording", lambda: ca.on_the_fly(PLAN, None), lambda: ca.on_the_fly(PLAN, 5))
bad(C, "on_the_fly", "plan", lambda: ca.on_the_fly(None, FLY))
bad(C, "least_dwell_s", "window_s", lambda: ca.least_dwell_s(0.0), lambda: ca.least_dwell_s(NAN), lambda: ca.least_dwell_s("0.5"))
bad(C, "least_dwell_s", "settle_s", lambda: ca.least_dwell_s(0.5, settle_s=-1.0), lambda: ca.least_dwell_s(0.5, settle_s=INF))
bad(C, "on_the_fly", "window_s", lambda: ca.on_the_fly(PLAN, FLY, window_s=0.0), lambda: ca.on_the_fly(PLAN, FLY, window_s=INF))
bad(C, "on_the_fly", "delay_s", lambda: ca.on_the_fly(PLAN, FLY, delay_s=NAN), lambda: ca.on_the_fly(PLAN, FLY, delay_s="8"))
bad(C, "on_the_fly", "offset_m", lambda: ca.on_the_fly(PLAN, FLY, delay_s=0.0, offset_m=INF))
bad(C, "on_the_fly_run", "recording", lambda: ca.on_the_fly_run(PLAN, None))
bad(C, "on_the_fly_to_file", "output", lambda: ca.on_the_fly_to_file(PLAN, FLY, None))
bad(C, "plot_on_the_fly", "result", lambda: ca.plot_on_the_fly(NEVER.with_suffix(".png"), None))
bad(C, "simulate_motions", "position_delay_s", lambda: ca.simulate_motions([], load_machine(MACHINE), axis="X", position_delay_s=NAN))
bad(C, "simulate_motions", "continuous", lambda: ca.simulate_motions([], load_machine(MACHINE), axis="X", continuous="yes"))

EXEMPT = {C: {"OnTheFly", "Capture", "CaptureFiles", "CaptureProgress", "CapturedStop", "Stop", "StopReading", "SimulatedRecording",
              "AxisMeasurement", "DryRun", "SimMachine", "FlyFiles"}}

test_bad_arguments_raise_axiscal_error_naming_them, test_every_public_callable_has_a_bad_argument_case = TABLE.tests(EXEMPT)
