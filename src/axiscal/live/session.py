"""One live run set up from what a user names: machine, source, record, dashboard (what ``axiscal live`` does).

:class:`LiveSession` checks the settings, builds the measurement system (a machine TOML or the
built-in virtual module of paper 000), opens the source, the record (plain CSV with its JSON
sidecar, :mod:`axiscal.live.recorder`) and the dashboard (served by a process of its own,
:mod:`axiscal.live.dashboard`), and runs the
:class:`~axiscal.live.pipeline.Pipeline` until the duration has passed, a replay is finished or
it is stopped.
"""

from __future__ import annotations

import math
import os
import threading
import time
from collections.abc import Callable, Sequence
from datetime import datetime, timezone
from pathlib import Path

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_count, check_number, check_path, is_real
from axiscal.io.arguments import check_instance
from axiscal.io.jsonio import sidecar_path
from axiscal.live.pipeline import Pipeline, RunSummary, _check_run
from axiscal.live.priority import Priority, raise_priority, restore_priority
from axiscal.live.recorder import Recorder
from axiscal.live.sources import MAX_RATE_HZ, open_source, parse_source, rtx_parts
from axiscal.live.state import UPDATE_HZ_RANGE, LiveState, result_columns
from axiscal.measurement.pipeline import MeasurementSystem
from axiscal.measurement.virtual import PATHS, VirtualModule

__all__ = ["build_system", "check_record_target", "LiveSession"]


def build_system(machine: str | Path | None, source_kind: str, *, seed: int = 0, load_kg: float = 0.0):
    """The measurement system of a live run and a maker of the virtual module (built once, on first call).

    Parameters
    ----------
    machine : str or Path, optional
        Machine TOML with sensor sections; None: the built-in virtual module.
    source_kind : str
        ``"sim"``, ``"replay"``, ``"tcp"`` or ``"serial"`` (:func:`~axiscal.live.sources.parse_source`).
    seed : int
        Seed of the virtual module.
    load_kg : float
        Mass on the virtual module's Z slide, kg.

    Returns
    -------
    system : MeasurementSystem
    module : callable
        Returns the (one) :class:`~axiscal.measurement.virtual.VirtualModule` of the sim source.

    Raises
    ------
    AxiscalError
        If the machine file is wrong, or the sim source cannot feed the machine's channels.
    """
    if machine is not None:
        check_path("machine", machine)
    if not isinstance(source_kind, str) or source_kind not in _SOURCE_KINDS:
        raise AxiscalError(f"unknown source_kind {source_kind!r}; use one of {', '.join(_SOURCE_KINDS)}")
    seed = check_count("seed", seed, minimum=0)
    load_kg = check_number("load_kg", load_kg, nonnegative=True)
    built: list[VirtualModule] = []

    def module() -> VirtualModule:
        if not built:
            built.append(VirtualModule(seed=seed, load_kg=load_kg))
        return built[0]

    if machine is None:
        return module().measurement_system(), module
    system = MeasurementSystem.from_toml(machine)
    if source_kind == "sim":
        simulated = set(module().measurement_system().channels)
        unknown = [name for name in system.channels if name not in simulated]
        if unknown:
            raise AxiscalError(
                f"the sim source cannot feed channel(s) {', '.join(unknown)}: it emits the virtual module's channels; "
                "with this machine use a source replay:FILE or tcp:HOST:PORT",
                path=machine,
            )
    return system, module


_SOURCE_KINDS = ("sim", "replay", "rtx", "tcp", "serial")


def _finite(value: float) -> bool:
    return is_real(value) and math.isfinite(value)


def _shown(value: object) -> str:
    """A number as ``:g`` shows it; anything else as its repr."""
    return f"{value:g}" if is_real(value) else repr(value)


def _check(rate_hz: float, duration_s: float | None, port: int, update_hz: float, load_kg: float, path: str, seed: int) -> None:
    """Refuse a bad setting before anything is built or allocated (every number must be finite)."""
    if not (_finite(rate_hz) and 0 < rate_hz <= MAX_RATE_HZ):
        raise AxiscalError(f"rate_hz must be a positive number of frames per second up to {MAX_RATE_HZ:g}, got {_shown(rate_hz)}")
    if duration_s is not None and not (_finite(duration_s) and duration_s > 0):
        raise AxiscalError(f"duration_s must be positive seconds, got {_shown(duration_s)}")
    if not isinstance(port, int) or isinstance(port, bool) or not 0 <= port <= 65535:
        raise AxiscalError(f"port must be 0-65535, got {port}")
    low, high = UPDATE_HZ_RANGE
    if not (_finite(update_hz) and low <= update_hz <= high):
        raise AxiscalError(f"update_hz must be {low:g} to {high:g} refreshes per second, got {_shown(update_hz)}")
    if not (_finite(load_kg) and load_kg >= 0):
        raise AxiscalError(f"load_kg must be a finite mass of 0 kg or more, got {_shown(load_kg)}")
    if not isinstance(seed, int) or isinstance(seed, bool) or seed < 0:
        raise AxiscalError(f"seed must not be negative, got {seed!r}" if isinstance(seed, int) else f"seed must be a whole number, not {seed!r}")
    if not isinstance(path, str) or path not in PATHS:
        raise AxiscalError(f"unknown path '{path}'; use one of {', '.join(PATHS)}")


def _identity(path: str | Path) -> tuple[int, int] | None:
    """(st_dev, st_ino) of an existing file, None when there is none: a hard link or another name of
    the same file has the same identity."""
    try:
        info = os.stat(path)
    except OSError:
        return None
    return info.st_dev, info.st_ino


def check_record_target(record: str | Path, inputs: Sequence[str | Path], *, force: bool = False) -> None:
    """Refuse a record that would overwrite an input, or an existing file without ``force``.

    Files are compared by (st_dev, st_ino), so another path, a symbolic link or a hard link to an
    input is recognised. The record's JSON sidecar is checked the same way.

    Parameters
    ----------
    record : str or Path
        The record file to be written.
    inputs : sequence of str or Path
        Files the run reads (the replayed file, the machine TOML).
    force : bool
        Replace an existing record (never an input).

    Returns
    -------
    None
        Returns only when the record may be written.

    Raises
    ------
    AxiscalError
        If the record or its sidecar is one of the inputs, or the record exists and ``force`` is
        not given.
    """
    record = check_path("record", record)
    if isinstance(inputs, (str, bytes)) or not isinstance(inputs, (tuple, list, set, frozenset)):
        raise AxiscalError(f"inputs must be a sequence of the files the run reads, not {inputs!r}")
    inputs = [check_path("inputs", name) for name in inputs]
    check_instance("force", force, bool)
    used = {identity for identity in map(_identity, inputs) if identity is not None}
    for target in (Path(record), sidecar_path(record)):
        if _identity(target) in used:
            raise AxiscalError(f"record would overwrite {target.name}, a file this run reads; record to another file", path=record)
    if not force and Path(record).exists():
        raise AxiscalError("the record file exists; choose another file, or give force=True to replace it", path=record)


class LiveSession:
    """Everything of one live run: system, source, state, record, pipeline and (optionally) the dashboard.

    Parameters
    ----------
    machine : str or Path, optional
        Machine TOML with ``[axes.<L>.sensors]`` (default: the built-in virtual module).
    source : str
        ``sim``, ``replay:FILE``, ``rtx:FILE:UNIT:CHANNEL``, ``tcp:HOST:PORT`` or ``serial:DEVICE[:BAUD]``.
    rate_hz : float
        Frames per second of the sim source, Hz.
    path : str
        Motion of the sim source (:data:`~axiscal.measurement.virtual.PATHS`).
    seed : int
        Seed of the virtual module.
    load_kg : float
        Mass on the virtual module's Z slide, kg.
    pace : bool
        Replay a file at its ``t_s`` pace (False: as fast as possible).
    record : str or Path, optional
        Record every frame and result here (plus a JSON sidecar); an existing file is refused
        unless ``force`` (:func:`check_record_target`).
    server : bool
        Serve the dashboard (from a process of its own, :class:`~axiscal.live.dashboard.DashboardProcess`,
        fed the batches through a pipe: ``state`` then counts frames and faults, the process folds them).
    port : int
        Dashboard port (0: any free port).
    update_hz : float
        Dashboard refreshes per second.
    duration_s : float, optional
        Only checked here; passed to :meth:`run`.
    force : bool
        Replace an existing record file (never a file the run reads).
    bind : str
        Address the dashboard listens on (default loopback; ``0.0.0.0`` exposes it to the network).
    allowed_hosts : sequence of str
        Host names the dashboard answers besides the loopback names (DNS-rebinding guard).
    realtime : bool
        (``axiscal live`` gives True.) Raise the calling thread's scheduling priority for the run (:mod:`axiscal.live.priority`:
        real-time where the system allows it, else a lower nice value; :attr:`priority` says which
        and why), so frames are recorded on time while other work keeps the cores busy. Threads
        the session starts inherit it; :meth:`close` restores it. A replay without ``pace`` runs
        as fast as it can and so is never raised.

    Attributes
    ----------
    priority : Priority or None
        What the run's thread was given (None when not raised).

    Raises
    ------
    AxiscalError
        For a bad setting, a record that names a file the run reads or (without ``force``) an
        existing file, or a record or source that
        cannot be opened. Whatever was opened is closed again.
    """

    def __init__(
        self,
        *,
        machine: str | Path | None = None,
        source: str = "sim",
        rate_hz: float = 1000.0,
        path: str = "diagonal",
        seed: int = 0,
        load_kg: float = 0.0,
        pace: bool = True,
        record: str | Path | None = None,
        server: bool = True,
        port: int = 8765,
        update_hz: float = 10.0,
        duration_s: float | None = None,
        force: bool = False,
        bind: str = "127.0.0.1",
        allowed_hosts: Sequence[str] = (),
        realtime: bool = False,
    ):
        _check(rate_hz, duration_s, port, update_hz, load_kg, path, seed)
        for name, flag in (("pace", pace), ("server", server), ("force", force), ("realtime", realtime)):
            check_instance(name, flag, bool)
        if isinstance(allowed_hosts, str) or not isinstance(allowed_hosts, (tuple, list, set, frozenset)):
            raise AxiscalError(f"allowed_hosts must be a sequence of host names, not {allowed_hosts!r}")
        if not isinstance(bind, str) or not bind.strip():
            raise AxiscalError(f"bind must be an address to listen on, not {bind!r}")
        kind, argument = parse_source(source)
        if record is not None:
            read = {"replay": argument, "rtx": rtx_parts(argument)[0]}.get(kind)
            check_record_target(record, [name for name in (read, machine) if name], force=force)
        self.system, module = build_system(machine, kind, seed=seed, load_kg=load_kg)
        self.source = open_source(source, self.system.channels, virtual_module=module, rate_hz=rate_hz, path=path, pace=pace)
        self.state = LiveState(self.system)
        self.recorder: Recorder | None = None
        self.server = None
        # before any thread starts (they inherit it); a replay as fast as possible is a batch job, never raised
        self.priority: Priority | None = raise_priority() if realtime and (pace or kind in ("sim", "tcp", "serial")) else None
        try:
            if server:  # before the record: a port in use leaves no record file behind
                from axiscal.live.dashboard import DashboardProcess

                title = f"axiscal live: {self.source.status.description}"
                self.server = DashboardProcess(self.state, port=port, host=bind, update_hz=update_hz, title=title, allowed_hosts=allowed_hosts).start()
            if record is not None:
                try:
                    Path(record).parent.mkdir(parents=True, exist_ok=True)
                except OSError as exc:
                    raise AxiscalError(f"cannot create the record's folder ({exc.strerror or exc})", path=record) from None
                self.recorder = Recorder(
                    record,
                    self.system.channels,
                    result_columns(tuple(self.system.axes)),
                    metadata={
                        "source": self.source.status.description,
                        "machine": str(machine) if machine else f"built-in virtual module (seed {seed}, load {load_kg:g} kg)",
                        "started": datetime.now(timezone.utc).isoformat(timespec="seconds"),
                    },
                    overwrite=force,
                )
            self.pipeline = Pipeline(self.system, self.source, recorder=self.recorder, state=self.state)
            self.pipeline.priority = "" if self.priority is None else self.priority.text
        except BaseException:
            self.close()
            raise

    @property
    def url(self) -> str | None:
        """The dashboard's address (None without a server)."""
        return None if self.server is None else self.server.url

    def run(
        self,
        *,
        stop: threading.Event | None = None,
        duration_s: float | None = None,
        progress: Callable[[RunSummary], None] | None = None,
        progress_interval_s: float = 1.0,
    ) -> RunSummary:
        """Run until ``stop``, ``duration_s`` or the end of a finite source; with a dashboard keep serving until ``stop`` or ``duration_s``.

        Parameters
        ----------
        stop : threading.Event, optional
            Set it to end the run cleanly.
        duration_s : float, optional
            Wall time of the run, s.
        progress : callable, optional
            Called with the running summary every ``progress_interval_s``.
        progress_interval_s : float
            Seconds between progress calls.

        Returns
        -------
        RunSummary
            The final summary; with a record, after every frame was made durable.
        """
        _check_run(stop, duration_s, progress, progress_interval_s)
        stop = stop or threading.Event()
        start = time.monotonic()
        try:
            summary = self.pipeline.run(stop=stop, duration_s=duration_s, progress=progress, progress_interval_s=progress_interval_s)
            if self.server is not None and not stop.is_set():
                remaining = None if duration_s is None else duration_s - (time.monotonic() - start)
                while not stop.is_set() and (remaining is None or remaining > 0):
                    stop.wait(0.2 if remaining is None else min(0.2, remaining))
                    remaining = None if duration_s is None else duration_s - (time.monotonic() - start)
        except KeyboardInterrupt:
            summary = self.pipeline.summary(time.monotonic() - start)
        if self.recorder is not None:
            self.recorder.close()
            summary = self.pipeline.summary(summary.elapsed_s)
        return summary

    def close(self) -> None:
        """Stop the server, close the record and the source (safe to call twice)."""
        if self.server is not None:
            self.server.stop()
            self.server = None
        if self.recorder is not None:
            self.recorder.close()
        self.source.close()
        if self.priority is not None:
            restore_priority(self.priority)
            self.priority = None

    def __enter__(self) -> "LiveSession":
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
