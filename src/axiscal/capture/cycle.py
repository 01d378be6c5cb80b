"""One axis measured on the virtual machine as an engineer measures a real one: plan, program, run, capture.

:func:`measure_axis` plans an ISO 230-2 test (:func:`axiscal.positioning.plan.plan_test`),
writes its cycle CSV and its program in a controller's dialect, runs the program on the virtual
machine with the controller's compensation loaded or not (:func:`axiscal.capture.virtual.simulate_capture`),
records the laser, and captures the run from the recording (:func:`axiscal.capture.run.capture_to_file`)
-- the files each step leaves are those the commands ``axiscal plan``, ``axiscal simulate capture``
and ``axiscal capture`` write, so every step can be repeated by hand.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from axiscal.capture.files import CaptureFiles, capture_to_file
from axiscal.capture.run import CaptureSettings
from axiscal.capture.virtual import SimulatedRecording, VirtualAxis, simulate_capture
from axiscal.io.arguments import check_path
from axiscal.io.gcode import dialect as find_dialect
from axiscal.model.machine import Machine
from axiscal.positioning.plan import plan_test, write_plan

__all__ = ["AxisMeasurement", "measure_axis"]


@dataclass(frozen=True)
class AxisMeasurement:
    """The files and results of one axis measured on the virtual machine.

    Attributes
    ----------
    plan_csv, program, recording, run_csv : Path
        The cycle CSV, the program, the laser recording and the captured run.
    simulated : SimulatedRecording
        What the virtual machine did (with the truth).
    captured : CaptureFiles
        The capture.
    """

    plan_csv: Path
    program: Path
    recording: Path
    run_csv: Path
    simulated: SimulatedRecording
    captured: CaptureFiles


def measure_axis(
    folder: str | Path,
    machine: Machine | str | Path,
    *,
    axis: str,
    start_m: float,
    end_m: float,
    targets: int,
    runs: int = 5,
    seed: int = 0,
    run_seed: int | None = None,
    dialect: str = "linuxcnc",
    dwell_s: float = 1.0,
    compensation: str | Path | None = None,
    controller: str | None = None,
    rate_hz: float = 200.0,
    name: str | None = None,
    spec: VirtualAxis | None = None,
    wavelength_nm: float | None = None,
    settings: CaptureSettings | None = None,
) -> AxisMeasurement:
    """Plan, program, run on the virtual machine and capture a positioning test of one axis.

    Parameters
    ----------
    folder : str or Path
        Where the files go: ``plan_<name>.csv`` (and its sidecar), ``<name>`` + the dialect's
        extension, ``recording_<name>.csv``, ``positioning_<name>.csv`` (and sidecars).
    machine : Machine, str or Path
        The virtual machine's model.
    axis : str, keyword-only
        The axis measured.
    start_m, end_m, targets, runs, seed : keyword-only
        The plan (:func:`axiscal.positioning.plan.plan_test`): metres, a count, runs each way, its seed.
    run_seed : int, optional, keyword-only
        Seed of the virtual machine's scatter and noise (default ``seed``): a second run of the same
        plan takes another.
    dialect : str, keyword-only
        The program's dialect (default linuxcnc).
    dwell_s : float, keyword-only
        Dwell at each target, seconds (default 1).
    compensation, controller : keyword-only
        A compensation file loaded into the virtual controller, and whose it is.
    rate_hz : float, keyword-only
        The laser's sample rate (default 200 Hz).
    name : str, optional, keyword-only
        The files' stem (default the axis letter in lower case).
    spec : VirtualAxis, optional, keyword-only
        The virtual axis' motion, reversal, settling and noise.
    wavelength_nm : float, optional, keyword-only
        The laser's vacuum wavelength (default He-Ne).
    settings : CaptureSettings, optional, keyword-only
        The capture's stability, window, tolerance and offset.

    Returns
    -------
    AxisMeasurement

    Raises
    ------
    AxiscalError
        As the plan, the program's reader, the virtual machine and the capture refuse.
    """
    folder = check_path("folder", folder)
    name = name or axis.lower()
    plan = plan_test(start_m, end_m, targets, runs=runs, seed=seed)
    plan_csv = folder / f"plan_{name}.csv"
    program = folder / f"{name}{find_dialect(dialect).extension}"
    write_plan(plan, plan_csv, gcode_path=program, axis=axis, dwell_s=dwell_s, dialect=dialect)
    recording = folder / f"recording_{name}.csv"
    extra = {} if wavelength_nm is None else {"wavelength_nm": wavelength_nm}
    simulated = simulate_capture(program, machine, recording, axis=axis, dialect=dialect, compensation=compensation,
                                 controller=controller, rate_hz=rate_hz, seed=seed if run_seed is None else run_seed,
                                 spec=spec, **extra)
    run_csv = folder / f"positioning_{name}.csv"
    captured = capture_to_file(plan_csv, recording, run_csv, settings=settings)
    return AxisMeasurement(plan_csv, program, recording, run_csv, simulated, captured)
