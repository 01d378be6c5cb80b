"""The one adapter between the workbench and the machine: connect, run a plan, pause, resume, abort.

Everything the workbench needs to run a positioning plan goes through this module, so that the
page never speaks to an instrument or a controller itself. Its implementation drives the virtual
machine (``sim`` instrument and ``sim`` controller): the plan's program is run on an axis of a machine
model (the visit's; the built-in XZ module's X by default; :func:`axiscal.capture.virtual.simulate_motions`, with the controller's
compensation loaded for an as-left run), the laser's samples are streamed at the pace of the
machine's clock (``speed`` times faster when asked), and the capture is
:func:`axiscal.capture.files.capture_to_file` fed by that stream: the stops are those its
:class:`~axiscal.capture.stops.StopDetector` finds, each written to the partial file as it is
taken, so a connection that breaks leaves every stop before it and :meth:`PlanRun` with
``resume=True`` goes on from the next. A step whose stop does not come (the reading never held still
over its dwell) ends the run when its dwell is over, not at the program's end, its stops kept alike.

Instrument and controller specs are those of the controller-driven run (``sim``, ``umd:PORT``,
``sylvac:PORT``; ``sim``, ``linuxcnc:HOST``, ``grbl:PORT`` ...). With both ``sim`` the virtual
machine above runs (faster than real time when asked); any other pair is driven for real by
:func:`axiscal.capture.connected.run_to_file` (the devices of ``axiscal run``): the controller moves the
axis to each step and the instrument is read over the dwell, the page's pause holding the machine
between two steps and its abort stopping the controller. A compensation the page wrote is loaded by
the virtual controller itself; a real controller loads it as ``axiscal cycle`` says (LinuxCNC: its
``COMP_FILE``, then a restart and homing).

What the rest of the workbench uses, and all that another implementation has to give:
:func:`~axiscal.workbench.connection.connect` (a :class:`~axiscal.workbench.connection.Connection`: the two
lights, the reading, the position, what the devices told) and
:class:`PlanRun` -- made with the plan, the output, the specs, the compensation text and its
controller, ``resume``, ``speed``, ``dwell_s`` and ``seed``; then ``start``, ``pause``, ``resume``,
``abort``, ``wait``; ``state`` (``ready``, ``running``, ``paused``, ``done``, ``aborted``,
``broken``, ``failed``) with ``message`` and ``resumable``; ``stops`` and ``total``; ``samples_since`` (the trace);
``snapshot`` (what the page shows); ``result`` (the capture's files).
"""

from __future__ import annotations

import math
import threading
import time
from collections.abc import Callable
from importlib import resources
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.capture.files import CaptureFiles, capture_to_file, partial_path
from axiscal.capture.recording import ENVIRONMENT_COLUMNS
from axiscal.capture.run import CaptureProgress, CaptureSettings, StopReading
from axiscal.capture.sources import plan_motions
from axiscal.capture.steps import plan_steps
from axiscal.capture.stops import least_dwell_s
from axiscal.capture.virtual import simulate_motions
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_count, check_instance, check_number, check_path
from axiscal.live.protocol import FrameBatch
from axiscal.live.sources import SourceStatus
from axiscal.units import MM, UM
from axiscal.workbench.connection import SIM_RATE_HZ, check_spec, is_virtual

__all__ = ["PlanRun", "DevicePlanRun"]

_CHANNELS = ("reading_mm",) + ENVIRONMENT_COLUMNS[:3]
#: the machine the virtual machine runs when none is named: the built-in XZ module
_BUILT_IN = Path(str(resources.files("axiscal") / "data" / "xz_module" / "machine.toml"))


def _checked_axis(axis: Any) -> str:
    if not isinstance(axis, str) or axis not in ("X", "Y", "Z"):
        raise AxiscalError(f"axis must be a linear axis letter (X, Y or Z), not {axis!r}")
    return axis


def _checked_partial(output: Path, resume: bool) -> Path:
    """The partial file of a run to ``output``: there to resume, or not there for a new run."""
    partial = partial_path(output)
    if resume and not partial.is_file():
        raise AxiscalError("nothing to resume: no partial capture here", path=partial)
    if not resume and partial.exists():
        raise AxiscalError("a broken run left its stops here: resume it (or delete the file)", path=partial)
    return partial


def _partial_stops(partial: Path) -> list[dict[str, Any]]:
    """The stops a broken run's partial file holds, as the page lists them."""
    from axiscal.io.tabular import read_csv

    table = read_csv(partial, min_rows=1)
    return [{name: float(table.numeric(name)[row]) for name in ("step", "target_mm", "deviation_um", "start_s")}
            | {"run": int(table.numeric("run")[row]), "direction": table.text("direction")[row]} for row in range(len(table))]


class _SimLaser:
    """The virtual machine's laser streamed at its clock's pace times ``speed``; pausable, and cut on request."""

    def __init__(self, time_s: np.ndarray, values: np.ndarray, *, start_s: float, speed: float,
                 tap: Callable[[np.ndarray, np.ndarray], None], watch: Callable[[float], float] | None = None):
        self.channels = _CHANNELS
        self._t = time_s
        self._values = values
        self._next = int(np.searchsorted(time_s, start_s))
        self._first = self._next
        self._watch = watch
        self._speed = speed
        self._tap = tap
        self._sim_at_resume = float(time_s[self._next]) if self._next < len(time_s) else 0.0
        self._wall_at_resume: float | None = None
        self.paused = False
        self.stopped = False
        self.cut = False
        self.finished = self._next >= len(time_s)
        self.status = SourceStatus(f"sim (virtual laser, {SIM_RATE_HZ:g} Hz)", state="streaming", connections=1)

    def sim_now(self) -> float:
        if self._wall_at_resume is None or self.paused or self.stopped:
            return self._sim_at_resume
        return self._sim_at_resume + (time.monotonic() - self._wall_at_resume) * self._speed

    def pause(self) -> None:
        if not self.paused:
            self._sim_at_resume = self.sim_now()
            self.paused = True

    def resume(self) -> None:
        if self.paused:
            self._wall_at_resume = time.monotonic()
            self.paused = False

    def read(self, timeout_s: float) -> FrameBatch:
        if self.cut:
            self.status.state = "retrying"
            raise AxiscalError("the connection to the instrument was lost: the stops taken are kept; resume to go on")
        # the watch raises when the clock of the samples taken in so far is past its deadline, else names the
        # deadline: a batch ends at the first sample beyond it, so the step is judged there however late the read
        deadline = math.inf
        if self._watch is not None:
            deadline = self._watch(float(self._t[self._next - 1]) if self._next > self._first else -math.inf)
        if self.stopped or self.finished:
            self.finished = True
            return FrameBatch(np.empty(0), np.empty((0, len(self.channels))), np.zeros(0, bool))
        if self._wall_at_resume is None:
            self._wall_at_resume = time.monotonic()
        if self.paused:
            time.sleep(min(timeout_s, 0.02))
            return FrameBatch(np.empty(0), np.empty((0, len(self.channels))), np.zeros(0, bool))
        now = self.sim_now()
        stop = int(np.searchsorted(self._t, now, side="right"))
        if math.isfinite(deadline):
            stop = min(stop, int(np.searchsorted(self._t, deadline, side="right")) + 1)
        if stop <= self._next:
            time.sleep(min(timeout_s, 0.005))
            return FrameBatch(np.empty(0), np.empty((0, len(self.channels))), np.zeros(0, bool))
        t = self._t[self._next:stop]
        values = self._values[self._next:stop]
        self._next = stop
        self.finished = stop >= len(self._t)
        self._tap(t, values[:, 0])
        return FrameBatch(t.copy(), values.copy(), np.zeros(t.size, bool))

    def close(self) -> None:
        # the machine's clock stops where the run did: at the last sample taken, not wherever the wall clock
        # (times speed) has got to by the time the run is closed (50 ms late at speed 200 is 10 s of its clock)
        if not self.stopped:
            self._sim_at_resume = float(self._t[self._next - 1]) if self._next > self._first else self.sim_now()
            self.stopped = True


class PlanRun:
    """A plan run on the machine and captured stop by stop into a positioning run, in a thread.

    Parameters
    ----------
    plan_csv : str or Path
        The plan's cycle CSV (``axiscal plan`` writes it).
    output : str or Path
        The run CSV; ``OUTPUT.partial`` holds the stops as they are taken.
    instrument, controller : str, keyword-only
        Specs (``sim``).
    compensation : str, optional, keyword-only
        Text of a compensation file loaded into the controller (an as-left run).
    controller_kind : str, keyword-only
        Whose file ``compensation`` is (``linuxcnc``, ``fanuc``, ``siemens``, ``heidenhain``).
    resume : bool, keyword-only
        Go on from the partial file a broken run left.
    speed : float, keyword-only
        How many times faster than real time the virtual machine runs (default 1).
    dwell_s : float, keyword-only
        Dwell at each target, seconds.
    seed : int, keyword-only
        Seed of the virtual machine's scatter and noise.
    settings : CaptureSettings, optional, keyword-only
        Stop detection and matching.
    axis : str, keyword-only
        The linear axis the plan moves (default X).
    machine : str or Path, optional, keyword-only
        The machine description the virtual machine runs (default the built-in XZ module).
    ini : str or Path, optional, keyword-only
        LinuxCNC's INI file: a plan beyond its soft limits is refused before any move (a LinuxCNC's run only).

    Raises
    ------
    AxiscalError
        For a spec not driven, a bad number, a plan that cannot be read, a compensation the
        controller refuses, a partial file left without ``resume`` (or none with it).
    """

    def __new__(cls, *args: Any, **kwargs: Any) -> "PlanRun":
        instrument, controller = kwargs.get("instrument", "sim"), kwargs.get("controller", "sim")
        if cls is PlanRun and isinstance(instrument, str) and isinstance(controller, str) and not is_virtual(instrument, controller):
            return super().__new__(DevicePlanRun)
        return super().__new__(cls)

    def __init__(self, plan_csv: str | Path, output: str | Path, *, instrument: str = "sim", controller: str = "sim",
                 compensation: str | None = None, controller_kind: str = "linuxcnc", resume: bool = False,
                 speed: float = 1.0, dwell_s: float = 1.0, seed: int = 0, settings: CaptureSettings | None = None,
                 axis: str = "X", machine: str | Path | None = None, ini: str | Path | None = None):
        from axiscal.compensation.readback import read_compensation
        from axiscal.model.machine import load_machine

        self.instrument = check_spec("instrument", instrument)
        self.controller = check_spec("controller", controller)
        if ini is not None:
            raise AxiscalError("an INI file is LinuxCNC's: the virtual machine takes none")
        self.plan_csv = check_path("plan_csv", plan_csv)
        self.output = check_path("output", output)
        check_instance("resume", resume, bool)
        speed = check_number("speed", speed, positive=True, high=1000.0)
        dwell_s = check_number("dwell_s", dwell_s, positive=True, high=600.0, unit="s")
        seed = check_count("seed", seed, minimum=0)
        self.settings = CaptureSettings() if settings is None else check_instance("settings", settings, CaptureSettings)
        self.steps = plan_steps(self.plan_csv)
        partial = _checked_partial(self.output, resume)
        loaded = None
        if compensation is not None:
            check_instance("compensation", compensation, str, what="the compensation file's text")
            # a FANUC table is zero at its reference position, the first target (compensation_table's default)
            reference = float(np.nanmin(self.steps.target_m)) if controller_kind == "fanuc" else 0.0
            loaded = read_compensation(compensation, controller_kind, reference_position_m=reference)
        self.axis = _checked_axis(axis)
        model = load_machine(_BUILT_IN if machine is None else check_path("machine", machine))
        simulated = simulate_motions(plan_motions(self.steps, axis=self.axis, dwell_s=dwell_s), model, axis=self.axis,
                                     compensation=loaded, rate_hz=SIM_RATE_HZ, seed=seed)
        rec = simulated.recording
        self._dwells = simulated.dwells
        values = np.column_stack([rec.reading_m / MM] + [rec.channels[n] for n in _CHANNELS[1:]])
        self.total = self.steps.readings
        self.stops: list[dict[str, Any]] = []
        if resume:
            self.stops = _partial_stops(partial)
        taken = len(self.stops)
        start_s = float(self._dwells[taken - 1, 1]) if taken else 0.0
        self._lock = threading.Lock()
        self._trace_t: list[np.ndarray] = []
        self._trace_x: list[np.ndarray] = []
        self._trace_n = 0
        self._dwell_s = dwell_s
        self.source = _SimLaser(rec.time_s, values, start_s=start_s, speed=speed, tap=self._tap, watch=self._watch)
        self._end_s = float(rec.time_s[-1])
        self._resume = resume
        self.state = "ready"
        self.message = ""
        self.result: CaptureFiles | None = None
        self.progress: CaptureProgress | None = None
        self._started = math.nan
        self._thread = threading.Thread(target=self._run, name="axiscal-workbench-run", daemon=True)

    # -- the trace -------------------------------------------------------------------------------
    def _tap(self, t: np.ndarray, reading_mm: np.ndarray) -> None:
        with self._lock:
            self._trace_t.append(t.copy())
            self._trace_x.append(reading_mm.copy())
            self._trace_n += t.size

    def samples_since(self, index: int) -> tuple[np.ndarray, np.ndarray, int]:
        """The trace's samples from ``index`` on: times (s), readings (mm), and the index after them.

        Parameters
        ----------
        index : int
            The first sample wanted (0: all).

        Returns
        -------
        time_s, reading_mm : ndarray, shape (n,)
        next : int
        """
        with self._lock:
            if len(self._trace_t) > 1:
                self._trace_t = [np.concatenate(self._trace_t)]
                self._trace_x = [np.concatenate(self._trace_x)]
            total = self._trace_n
            if not self._trace_t or index >= total:
                return np.empty(0), np.empty(0), total
            return self._trace_t[0][index:total], self._trace_x[0][index:total], total

    # -- control ---------------------------------------------------------------------------------
    def start(self) -> "PlanRun":
        """Start the run in its thread."""
        if self.state != "ready":
            raise AxiscalError(f"the run is {self.state}: it cannot start again")
        self.state = "running"
        self._started = time.monotonic()
        self._thread.start()
        return self

    def pause(self) -> None:
        """Hold the machine (feed hold) until :meth:`resume`."""
        if self.state == "running":
            self._hold()
            self.state = "paused"

    def resume(self) -> None:
        """Go on after :meth:`pause`."""
        if self.state == "paused":
            self._release()
            self.state = "running"

    def abort(self) -> None:
        """Stop the run; the stops taken stay in the partial file."""
        if self.state in ("running", "paused", "ready"):
            self.state = "aborted"
            self.message = "aborted: the stops taken are kept; resume to go on"
            self._stop_machine()

    # how the virtual machine holds, goes on and stops (the devices' run has its own)
    def _hold(self) -> None:
        self.source.pause()

    def _release(self) -> None:
        self.source.resume()

    def _stop_machine(self) -> None:
        self.source.cut = True

    def cut_connection(self) -> None:
        """Break the instrument's connection now (what a pulled cable does)."""
        self.source.cut = True

    def wait(self, timeout_s: float | None = None) -> str:
        """Wait for the run's thread to end; return the state."""
        if self._thread.is_alive():
            self._thread.join(timeout_s)
        return self.state

    def _on_stop(self, reading: StopReading) -> None:
        s = self.steps
        k = reading.index
        self.stops = self.stops + [{"step": int(s.step[k]), "target_mm": float(s.target_m[k] / MM), "run": int(s.run[k]),
                                    "direction": str(s.direction[k]), "deviation_um": reading.deviation_m / UM,
                                    "start_s": reading.start_s}]

    def _on_progress(self, progress: CaptureProgress) -> None:
        self.progress = progress

    def _watch(self, now_s: float) -> float:
        """The awaited step's deadline, seconds of the machine's clock; raises once ``now_s`` is past it.

        The detector gives a stop a window after the axis has left it; the clock at ``now_s`` (every
        sample up to it taken in) past the awaited step's dwell by two windows means the step cannot
        be taken: the run ends there, not at the program's end, the stops taken before kept in the
        partial file for a resume.
        """
        taken = len(self.stops)
        if taken >= self.total:
            return math.inf
        deadline = float(self._dwells[taken, 1]) + 2.0 * self.settings.window_s
        if now_s <= deadline:
            return deadline
        k = int(np.flatnonzero(np.isfinite(self.steps.target_m))[taken])
        w = self.settings
        kept = f"the {taken} stops taken before it are kept: resume to go on" if taken else "no stop was taken before it"
        least = least_dwell_s(w.window_s)
        why = (f"the least dwell is {least:g} s" if self._dwell_s < least else
               "the machine did not settle: check the set-up, or lengthen the dwell")
        raise AxiscalError(f"{self.steps.describe(k)}: no stop over its {self._dwell_s:g} s dwell: the reading did not hold"
                           f" within {w.stability_m / UM:g} µm for a whole {w.window_s:g} s window ({why}); {kept}")

    def _run(self) -> None:
        try:
            self.result = capture_to_file(self.plan_csv, self.source, self.output, resume=self._resume,
                                          settings=self.settings, channel="reading_mm", on_stop=self._on_stop,
                                          progress=self._on_progress)
            self.state = "done"
        except AxiscalError as exc:
            if self.state != "aborted":
                self.state = "broken" if self.source.cut else "failed"
                self.message = str(exc)
        except Exception as exc:  # the thread must report, never die silently
            self.state = "failed"
            self.message = f"the run stopped: {exc}"
        finally:
            self.source.pause()  # the machine's clock stops where the run ended: the page shows it there

    # -- what the page shows ---------------------------------------------------------------------
    def snapshot(self) -> dict[str, Any]:
        """The run as the page shows it (JSON-able; mm, um, s).

        Returns
        -------
        dict
            ``state``, ``message``, ``taken``, ``total``, ``remaining_s``, ``reading_mm``,
            ``position_mm``, ``target_mm``, ``step``, ``still``, ``stops``, ``lights``, ``run_csv``,
            ``resumable``.
        """
        p = self.progress
        sim_now = self.source.sim_now()
        taken = len(self.stops)
        speed = self.source._speed
        remaining = max(self._end_s - sim_now, 0.0) / speed if self.state in ("running", "paused", "ready") else 0.0
        k = int(np.searchsorted(self._dwells[:, 1], sim_now))
        position = float(self._dwells[min(k, len(self._dwells) - 1), 2]) / MM
        lost = self.state == "broken"
        return {
            "state": self.state, "message": self.message, "taken": taken, "total": self.total,
            "remaining_s": remaining, "sim_time_s": sim_now,
            "reading_mm": None if p is None or math.isnan(p.reading_m) else p.reading_m / MM,
            "target_mm": None if p is None or math.isnan(p.target_m) else p.target_m / MM,
            "step": None if p is None else p.step, "still": bool(p.still) if p is not None else False,
            "position_mm": position, "stops": self.stops,
            "lights": {"instrument": "lost" if lost else "ok", "controller": "ok"},
            "run_csv": str(self.output) if self.state == "done" else None,
            "resumable": self.resumable,
        }

    @property
    def resumable(self) -> bool:
        """Whether the run has ended short (broken, aborted, failed at a step) with stops in its partial file."""
        return self.state in ("broken", "aborted", "failed") and partial_path(self.output).is_file()


class DevicePlanRun(PlanRun):
    """A plan driven on real devices (``axiscal run``'s), with the interface of :class:`PlanRun`.

    Made by :class:`PlanRun` for any pair of specs but ``sim``/``sim``. The controller moves the axis
    to each step; the reading is the mean over the last window of the dwell; pause holds the machine
    before its next move, abort stops the controller (the partial file keeps every step taken) and
    ``resume=True`` goes on from it. ``speed`` does not apply (a machine runs at its own pace).

    Parameters
    ----------
    plan_csv, output, instrument, controller, compensation, controller_kind, resume, speed, dwell_s, seed, settings, axis, machine, ini :
        As :class:`PlanRun` takes them; ``ini`` is given to the controller as ``axiscal run --ini`` gives it.
    """

    def __init__(self, plan_csv: str | Path, output: str | Path, *, instrument: str = "sim", controller: str = "sim",
                 compensation: str | None = None, controller_kind: str = "linuxcnc", resume: bool = False,
                 speed: float = 1.0, dwell_s: float = 1.0, seed: int = 0, settings: CaptureSettings | None = None,
                 axis: str = "X", machine: str | Path | None = None, ini: str | Path | None = None):
        from axiscal.capture.connected import open_run_devices, sim_machine

        self.instrument = check_spec("instrument", instrument)
        self.controller = check_spec("controller", controller)
        self.plan_csv = check_path("plan_csv", plan_csv)
        self.output = check_path("output", output)
        check_instance("resume", resume, bool)
        check_number("speed", speed, positive=True, high=1000.0)
        self.dwell_s = check_number("dwell_s", dwell_s, positive=True, high=600.0, unit="s")
        seed = check_count("seed", seed, minimum=0)
        self.settings = CaptureSettings() if settings is None else check_instance("settings", settings, CaptureSettings)
        self.steps = plan_steps(self.plan_csv)
        partial = _checked_partial(self.output, resume)
        self.compensation_note = "" if compensation is None else (
            "the controller must have loaded the compensation written (axiscal cycle says how)")
        self.total = self.steps.readings
        self.stops = []
        if resume:
            self.stops = _partial_stops(partial)
        self._resume = resume
        self._lock = threading.Lock()
        self._trace_t: list[np.ndarray] = []
        self._trace_x: list[np.ndarray] = []
        self._trace_n = 0
        self.axis = _checked_axis(axis)
        # the virtual controller moves the run's axis of the visit's machine (the XZ module's X when none is named)
        virtual = self.controller.lower() == "sim"
        moved = sim_machine(machine=None if machine is None else check_path("machine", machine), axis=self.axis) if virtual else None
        ini = None if ini is None else check_path("ini", ini)
        self._device, self._instrument = open_run_devices(self.controller, self.instrument, seed=seed, machine=moved, ini=ini)
        original = self._instrument.read

        def tapped(timeout_s: float):
            batch = original(timeout_s)
            if len(batch):
                self._tap(np.asarray(batch.t_s), np.asarray(batch.values[:, 0]))
            return batch

        self._instrument.read = tapped
        self._held = threading.Event()
        self._held.set()
        self._aborted = False
        self.state = "ready"
        self.message = self.compensation_note
        self.result = None
        self.progress = None
        self._started = math.nan
        self._thread = threading.Thread(target=self._run, name="axiscal-workbench-device-run", daemon=True)

    def _before_move(self) -> None:
        while not self._held.wait(0.1):
            if self._aborted:
                break
        if self._aborted:
            raise AxiscalError("aborted: the stops taken are kept; resume to go on")

    def _hold(self) -> None:  # the machine holds before its next move
        self._held.clear()

    def _release(self) -> None:
        self._held.set()

    def _stop_machine(self) -> None:
        self._aborted = True
        self._held.set()
        self._device.stop()

    def cut_connection(self) -> None:
        """Break the instrument's connection now (what a pulled cable does)."""
        self._instrument.close()

    def _run(self) -> None:
        from axiscal.capture.connected import run_to_file
        from axiscal.capture.drive import DriveSettings

        try:
            self.result = run_to_file(self.plan_csv, self._device, self._instrument, self.output,
                                      drive=DriveSettings(axis=self.axis, dwell_s=float(self.dwell_s)), settings=self.settings,
                                      resume=self._resume, progress=self._on_progress, on_stop=self._on_stop,
                                      before_move=self._before_move)
            self.state = "done"
        except AxiscalError as exc:
            if self.state != "aborted":
                self.state = "broken" if getattr(self._instrument, "finished", False) else "failed"
                self.message = str(exc)
        except Exception as exc:  # the thread must report, never die silently
            self.state = "failed"
            self.message = f"the run stopped: {exc}"
        finally:
            self._instrument.close()
            self._device.close()

    def snapshot(self) -> dict[str, Any]:
        """The run as the page shows it (as :meth:`PlanRun.snapshot`).

        Returns
        -------
        dict
        """
        p = self.progress
        taken = len(self.stops)
        elapsed = time.monotonic() - self._started if math.isfinite(self._started) else 0.0
        remaining = elapsed / taken * (self.total - taken) if taken and self.state in ("running", "paused") else 0.0
        position = getattr(getattr(self._device, "status", None), "position_m", math.nan)
        lost = self.state == "broken"
        return {
            "state": self.state, "message": self.message, "taken": taken, "total": self.total,
            "remaining_s": remaining, "sim_time_s": elapsed,
            "reading_mm": None if p is None or math.isnan(p.reading_m) else p.reading_m / MM,
            "target_mm": None if p is None or math.isnan(p.target_m) else p.target_m / MM,
            "step": None if p is None else p.step, "still": bool(p.still) if p is not None else False,
            "position_mm": None if not math.isfinite(position) else position / MM, "stops": self.stops,
            "lights": {"instrument": "lost" if lost else "ok",
                       "controller": "lost" if getattr(self._device.status, "state", "") == "lost" else "ok"},
            "run_csv": str(self.output) if self.state == "done" else None,
            "resumable": self.resumable,
        }
