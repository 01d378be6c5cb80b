"""``axiscal run``: the plan driven on a controller, read by an instrument, written as ``axiscal capture`` writes.

:func:`run_to_file` opens the controller and the instrument from their specs (``linuxcnc:HOST``,
``umd:/dev/ttyACM0`` ...), drives every step (:func:`axiscal.capture.drive.drive_plan`), and writes the run
CSV, its sidecar and the partial file (fsync'd per stop, resumable) exactly as a capture does. With
``--controller sim`` the virtual controller moves the built-in XZ module's X axis (its model's error, a
reversal and the compensation given), and ``sim:KIND`` instruments read its carriage.
:func:`dry_run` lists the moves and checks them against the controller's soft limits without moving.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.capture.drive import DriveSettings, _check_device, _check_limits, drive_plan, planned_moves
from axiscal.capture.files import CaptureFiles, capture_to_file, partial_path
from axiscal.capture.recording import environment_columns
from axiscal.capture.run import CaptureSettings
from axiscal.capture.steps import PlanSteps, plan_steps
from axiscal.devices.controllers import open_controller
from axiscal.devices.instruments import InstrumentOptions, is_instrument_spec, open_instrument
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_instance, check_path

__all__ = ["SimMachine", "sim_machine", "open_run_devices", "run_to_file", "dry_run", "DryRun"]


@dataclass(frozen=True)
class SimMachine:
    """What the virtual controller moves: the error along the axis and its reversal (SI units).

    Attributes
    ----------
    axis : str
    travel_m : tuple of float
    positions_m, error_m : ndarray
        The axis's error table (positions and the error there), interpolated.
    reversal_m : float
        Reversal error (an axis approached from below stops short by half of it).
    compensation : object or None
        A :class:`~axiscal.compensation.readback.ControllerCompensation` loaded in the controller.
    """

    axis: str
    travel_m: tuple[float, float]
    positions_m: np.ndarray
    error_m: np.ndarray
    reversal_m: float = 4e-6
    compensation: Any = None
    extra: dict = field(default_factory=dict)

    def carriage(self, motor_m: float, direction: float) -> float:
        """Where the carriage is for a motor position and the direction of the last move, metres."""
        return motor_m + float(np.interp(motor_m, self.positions_m, self.error_m)) - direction * self.reversal_m / 2

    def controller(self):
        """A fresh virtual controller of this machine."""
        from axiscal.devices.sim import SimController

        comp = self.compensation

        def correction(commanded: float, direction: str) -> float:
            return float(np.asarray(comp.correction(np.array([commanded]), direction))[0])

        return SimController(carriage=self.carriage, travel_m=self.travel_m, correction=None if comp is None else correction,
                             axis=self.axis)


def sim_machine(*, compensation: Any = None, machine: str | Path | None = None, axis: str = "X") -> SimMachine:
    """The machine the virtual controller moves: an axis of a model (the built-in XZ module's X by default).

    Parameters
    ----------
    compensation : ControllerCompensation, optional, keyword-only
        Loaded in the controller.
    machine : str or Path, optional, keyword-only
        A machine.toml (default: the built-in XZ module).
    axis : str, keyword-only

    Returns
    -------
    SimMachine
    """
    from axiscal.model.machine import load_machine

    check_instance("axis", axis, str)
    if machine is not None:
        machine = check_path("machine", machine)
    path = Path(str(resources.files("axiscal") / "data" / "xz_module" / "machine.toml")) if machine is None else Path(machine)
    model = load_machine(path)
    axis = axis.upper()
    if axis not in model.letters or axis not in "XYZ":
        raise AxiscalError(f"axis {axis!r} is not a linear axis of the machine ({', '.join(model.letters)})")
    start, end = model.travel_m(axis)
    grid = np.linspace(start, end, 201)
    positions = {letter: np.zeros_like(grid) for letter in model.letters}
    positions[axis] = grid
    error = np.asarray(model.volumetric_error(positions))[:, "XYZ".index(axis)]
    return SimMachine(axis, (float(start), float(end)), grid, error, compensation=compensation)


class _Follower:
    """The virtual controller's carriage at a simulated instrument's sample times (seconds from its start).

    The first sample anchors the instrument's time to the monotonic clock; each later one is read at its
    own moment, so a sample written late (in a burst) still reads where the carriage was when it was due.
    """

    def __init__(self, controller):
        self.controller = controller
        self.began: float | None = None

    def __call__(self, t: float) -> float:
        import time

        if self.began is None:
            self.began = time.monotonic() - t
        return self.controller.carriage_at(self.began + t)


def open_run_devices(controller: str, source: str, *, options: InstrumentOptions | None = None, ini: str | Path | None = None,
                     machine: SimMachine | None = None, seed: int = 0) -> tuple[Any, Any]:
    """Open the controller and the instrument of a run.

    Parameters
    ----------
    controller : str
        A controller spec (:func:`axiscal.devices.controllers.open_controller`).
    source : str
        An instrument spec (:func:`axiscal.devices.instruments.open_instrument`); ``sim`` is ``sim:umd``.
    options : InstrumentOptions, keyword-only
    ini : str or Path, keyword-only
        LinuxCNC's INI file.
    machine : SimMachine, keyword-only
        What ``--controller sim`` moves (default :func:`sim_machine`).
    seed : int, keyword-only
        Noise seed of a simulated instrument.

    Returns
    -------
    tuple of (controller, source)

    Raises
    ------
    AxiscalError
        For a spec either opener refuses, or a simulated instrument without the virtual controller.
    """
    check_instance("controller", controller, str, what="a controller spec such as 'linuxcnc:127.0.0.1' or 'sim'")
    check_instance("source", source, str, what="an instrument spec such as 'umd:/dev/ttyACM0' or 'sim:umd'")
    if machine is not None:
        check_instance("machine", machine, SimMachine)
    source = "sim:umd" if source.strip().lower() == "sim" else source
    if not is_instrument_spec(source):
        raise AxiscalError(f"unknown instrument '{source}'; use umd:PORT[@BAUD], sylvac:PORT, mahr:PORT, touchdro:PORT,"
                           " attocube:HOST[:PORT] or sim:KIND")
    sim = machine if machine is not None else None
    made = open_controller(controller, ini=ini, sim=lambda: (sim or sim_machine()).controller())
    position = _Follower(made) if hasattr(made, "carriage_at") else None
    if source.lower().startswith("sim:") and position is None:
        made.close()
        raise AxiscalError(f"the simulated instrument '{source}' reads the virtual controller's axis: its controller must be 'sim'")
    try:
        instrument = open_instrument(source, options, position=position, seed=seed)
    except BaseException:
        made.close()
        raise
    return made, instrument


@dataclass(frozen=True)
class DryRun:
    """The moves of a run, checked against the soft limits, nothing moved.

    Attributes
    ----------
    moves : list of tuple
        (step number, position in metres, whether a reading is taken).
    limits : tuple of float or None
        The controller's soft limits, metres, where it tells them.
    """

    moves: list
    limits: tuple[float, float] | None


def dry_run(plan: str | Path | PlanSteps, controller, *, axis: str = "X", resume_from: int = 0) -> DryRun:
    """The moves a run would make, checked against the controller's soft limits; nothing moves.

    Parameters
    ----------
    plan : str, Path or PlanSteps
    controller : a controller
    axis : str, keyword-only
    resume_from : int, keyword-only
        The first step not yet taken (0-based).

    Returns
    -------
    DryRun

    Raises
    ------
    AxiscalError
        For a move beyond the soft limits (naming its step).
    """
    steps = plan if isinstance(plan, PlanSteps) else plan_steps(plan)
    _check_device("controller", controller, ("limits",), "a controller")
    check_instance("axis", axis, str)
    moves = planned_moves(steps, start=resume_from)
    limits = controller.limits(axis.upper())
    _check_limits(steps, moves, limits, controller.description)
    return DryRun([(int(steps.step[k]), position, reading) for k, position, reading in moves], limits)


def run_to_file(
    plan: str | Path | PlanSteps,
    controller,
    source,
    output: str | Path,
    *,
    drive: DriveSettings | None = None,
    settings: CaptureSettings | None = None,
    resume: bool = False,
    progress: Callable | None = None,
    on_stop: Callable | None = None,
    on_fault: Callable[[str], None] | None = None,
    before_move: Callable[[], None] | None = None,
) -> CaptureFiles:
    """Drive the plan on the controller, read the instrument, and write the run as ``axiscal capture`` does.

    Parameters
    ----------
    plan : str, Path or PlanSteps
        The plan's cycle CSV (``axiscal plan``).
    controller, source :
        An open controller and instrument (:func:`open_run_devices`).
    output : str or Path
        The run CSV; ``OUTPUT.partial`` holds the stops as they are taken.
    drive : DriveSettings, keyword-only
        Axis, feed, dwell.
    settings : CaptureSettings, keyword-only
        Stability, window and offset of the readings.
    resume : bool, keyword-only
        Continue the partial run: the axis is first driven to where the first missing step's approach begins.
    progress, on_stop, on_fault, before_move : callable, keyword-only
        As :func:`axiscal.capture.drive.drive_plan` takes them.

    Returns
    -------
    CaptureFiles

    Raises
    ------
    AxiscalError
        As :func:`~axiscal.capture.drive.drive_plan` (the partial file keeps every step taken); on
        Ctrl-C, one line naming the partial file and ``--resume``.
    """
    output = check_path("output", output)
    steps = plan if isinstance(plan, PlanSteps) else plan_steps(plan)
    _check_device("controller", controller, ("check_ready", "limits", "move_to", "stop"), "a controller")
    _check_device("source", source, ("read", "close"), "an instrument or live source")
    environment = environment_columns(tuple(source.channels))

    def engine(steps_, source_, *, resumed, on_stop):
        return drive_plan(steps_, controller, source_, drive=drive, settings=settings, environment=environment, resumed=resumed,
                          on_stop=on_stop, progress=progress, on_fault=on_fault, before_move=before_move)

    try:
        return capture_to_file(steps, source, output, resume=resume, engine=engine, on_stop=on_stop)
    except KeyboardInterrupt:
        partial = partial_path(output)
        kept = max(0, sum(1 for _ in open(partial, encoding="utf-8")) - 1) if partial.is_file() else 0
        raise AxiscalError(f"interrupted: the controller was stopped; {partial} keeps {kept} step(s): go on with the same"
                           " run and resume=True") from None
