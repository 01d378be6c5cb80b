"""A capture written to files: the partial file as it goes, resume, the run and its sidecar at the end.

A capture to a file appends every stop to ``RUN.csv.partial`` as it is taken (flushed to disk), so
a stream that dies leaves every stop before it; a resumed capture reads that file (each row checked
against the plan's step: its target, run and direction) and goes on from the step after its last,
with the stops of the source that come after it (a partial file that holds no stop yet, left by a
capture stopped before its first, is started afresh); the run itself is written atomically at the
end, with a JSON sidecar holding the plan's seed, the source, the settings and, per stop, its start
time and the standard deviation of the reading over its window; the partial file is removed last.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.capture.recording import Recording, environment_columns
from axiscal.capture.run import Capture, StopReading, capture
from axiscal.capture.steps import PlanSteps, plan_steps
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_instance, check_path
from axiscal.io.jsonio import named_from, write_sidecar
from axiscal.io.tabular import read_csv, write_csv
from axiscal.positioning.plan import PositioningTestPlan
from axiscal.positioning.reader import DIRECTIONS
from axiscal.units import MM, UM

__all__ = ["PARTIAL_COLUMNS", "CaptureFiles", "capture_to_file", "partial_path"]

#: columns of the partial file, before the environment columns
PARTIAL_COLUMNS = ("step", "target_mm", "run", "direction", "deviation_um", "position_mm", "start_s", "window_std_um", "samples")


def partial_path(output: str | Path) -> Path:
    """The partial file of a capture to ``output``: ``RUN.csv.partial`` beside it.

    Parameters
    ----------
    output : str or Path
        The run CSV the capture writes.

    Returns
    -------
    Path
    """
    output = check_path("output", output)
    return output.with_name(output.name + ".partial")


class _PartialWriter:
    """Appends each stop to the partial file and flushes it to disk."""

    def __init__(self, path: Path, steps: PlanSteps, environment: tuple[str, ...]):
        self.path = path
        self.steps = steps
        self.environment = environment
        fresh = not path.exists() or path.stat().st_size == 0
        try:
            path.parent.mkdir(parents=True, exist_ok=True)
            self._file = open(path, "a", encoding="utf-8", newline="\n")
        except OSError as exc:
            raise AxiscalError(f"cannot write the partial capture ({exc.strerror or exc})", path=path) from None
        if fresh:
            self._write(",".join(PARTIAL_COLUMNS + environment))

    def _write(self, line: str) -> None:
        try:
            self._file.write(line + "\n")
            self._file.flush()
            os.fsync(self._file.fileno())
        except OSError as exc:
            raise AxiscalError(f"cannot write the partial capture ({exc.strerror or exc})", path=self.path) from None

    def add(self, r: StopReading) -> None:
        s = self.steps
        cells = [str(int(s.step[r.index])), f"{s.target_m[r.index] / MM:.6f}", str(int(s.run[r.index])), s.direction[r.index],
                 f"{r.deviation_m / UM:.5f}", f"{(s.target_m[r.index] + r.deviation_m) / MM:.8f}", f"{r.start_s:.6f}",
                 f"{r.window_std_m / UM:.5f}", str(r.samples)]
        cells += [f"{r.channels[n]:.6g}" if n in r.channels else "" for n in self.environment]
        self._write(",".join(cells))

    def close(self) -> None:
        self._file.close()


def _partial_rows(path: Path) -> int | None:
    """Stops a partial file holds, None where it is not a partial capture's table (damaged, or another file)."""
    try:
        if not path.read_bytes().strip():
            return 0  # emptied before its header reached the disk
        table = read_csv(path, min_rows=0)
        table.require(*PARTIAL_COLUMNS)
    except (AxiscalError, OSError):
        return None
    return len(table)


def _read_partial(path: Path, steps: PlanSteps) -> tuple[list[StopReading], tuple[str, ...] | None]:
    """The stops a partial file holds, each row checked against the plan's step (None: no stop, no sensors)."""
    if not path.is_file():
        raise AxiscalError("nothing to resume: no partial capture here", path=path)
    if _partial_rows(path) == 0:
        return [], None  # interrupted before its first stop: the capture starts from the plan's first step
    table = read_csv(path, min_rows=0)
    table.require(*PARTIAL_COLUMNS)
    environment = environment_columns(table.header)
    number = table.numeric("step")
    target = table.numeric("target_mm") * MM
    run = table.numeric("run")
    direction = table.text("direction")
    deviation = table.numeric("deviation_um") * UM
    start = table.numeric("start_s")
    std = table.numeric("window_std_um") * UM
    samples = table.numeric("samples")
    env = {n: table.numeric_or_missing(n) for n in environment}
    index_of = {int(s): k for k, s in enumerate(steps.step)}
    readings: list[StopReading] = []
    last = -1
    for row in range(len(table)):
        k = index_of.get(int(number[row])) if number[row] == int(number[row]) else None
        where = {"path": path, "line": table.line_of(row)}
        if k is None or not np.isfinite(steps.target_m[k]) or k <= last:
            raise AxiscalError(f"step {number[row]:g} is not the plan's next step with a target: this partial capture is"
                               f" not of the plan {steps.source}", **where)
        # the row is the plan's step: its target, run and direction (else the deviations belong to another plan)
        problems = []
        if abs(target[row] - steps.target_m[k]) > 1e-9:  # the partial writes targets to 1e-6 mm
            problems.append(f"target {target[row] / MM:.6g} mm, not {steps.target_m[k] / MM:.6g} mm")
        if run[row] != steps.run[k]:
            problems.append(f"run {run[row]:g}, not {int(steps.run[k])}")
        if DIRECTIONS.get(direction[row]) != steps.direction[k]:
            problems.append(f"direction '{direction[row]}', not '{steps.direction[k]}'")
        if problems:
            raise AxiscalError(f"step {int(steps.step[k])} has {' and '.join(problems)} in the plan {steps.source}:"
                               " this partial capture is not of that plan", **where)
        if not (samples[row] >= 1 and samples[row] == int(samples[row])):
            raise AxiscalError(f"samples {samples[row]:g} is not a count of samples", **where)
        readings.append(StopReading(k, float(deviation[row]), float(start[row]), float(std[row]), int(samples[row]),
                                    {n: float(env[n][row]) for n in environment if np.isfinite(env[n][row])}))
        last = k
    return readings, environment


@dataclass(frozen=True)
class CaptureFiles:
    """What :func:`capture_to_file` wrote.

    Attributes
    ----------
    capture : Capture
    run_csv, sidecar : Path
        The run and its JSON sidecar.
    """

    capture: Capture
    run_csv: Path
    sidecar: Path


def capture_to_file(
    plan: PositioningTestPlan | str | Path,
    recording: Recording | str | Path | Any,
    output: str | Path,
    *,
    resume: bool = False,
    engine: Any = None,
    **options: Any,
) -> CaptureFiles:
    """Capture a run into ``output`` (``axiscal capture``): partial file as it goes, the run atomically at the end.

    Parameters
    ----------
    plan, recording :
        As :func:`capture` takes them.
    output : str or Path
        The run CSV to write; ``OUTPUT.partial`` holds the stops as they are taken.
    resume : bool, keyword-only
        Continue the partial capture ``OUTPUT.partial`` with this recording or source: the rest of
        the run, or a source that reaches back over the partial (its stops up to the partial's last
        are passed over, see :func:`capture`).
    engine : callable, optional, keyword-only
        What takes the readings, called as ``engine(steps, recording, resumed=..., on_stop=..., **options)``:
        :func:`~axiscal.capture.run.capture` (default), or a driven run (:func:`axiscal.capture.drive.drive_plan`).
    **options
        ``settings``, ``unit``, ``channel``, ``environment``, ``progress``, ``timeout_s`` and
        ``on_stop`` (called after each stop is written to the partial file) of :func:`capture`.

    Returns
    -------
    CaptureFiles

    Raises
    ------
    AxiscalError
        As :func:`capture` (the partial file then keeps every stop taken before); for a partial
        file holding stops left from an interrupted capture when ``resume`` is not given (one
        holding none is started afresh), or none when it is; for a row of the partial file that is
        not the plan's step it names (target, run or direction), naming the file and the line.
    """
    output = check_path("output", output)
    check_instance("resume", resume, bool)
    steps = plan_steps(plan)
    partial = partial_path(output)
    resumed: list[StopReading] = []
    environment: tuple[str, ...] | None = None
    if resume:
        resumed, environment = _read_partial(partial, steps)
    elif partial.exists() and _partial_rows(partial) != 0:
        raise AxiscalError("resume=True continues the partial capture an interrupted run left here (or delete it)",
                           path=partial)
    if not resumed and partial.exists():
        _remove(partial)  # it holds no stop (a capture killed before its first): start it afresh
    writer: _PartialWriter | None = None

    observe = options.pop("on_stop", None)

    def on_stop(reading: StopReading) -> None:
        nonlocal writer
        if writer is None:  # a resumed partial goes on in its own columns
            writer = _PartialWriter(partial, steps, environment if resumed else tuple(reading.channels))
        writer.add(reading)
        if observe is not None:
            observe(reading)

    try:
        result = (capture if engine is None else engine)(steps, recording, resumed=resumed, on_stop=on_stop, **options)
    finally:
        if writer is not None:
            writer.close()
    if environment is not None and set(environment) != set(result.environment):
        raise AxiscalError("the partial capture and the recording carry different sensors", path=partial)
    write_csv(output, result.columns(), fmt={"target_mm": "{:.6f}", "deviation_um": "{:.5f}",
                                              **{n: "{:.6g}" for n in result.environment}})
    sidecar = write_sidecar(
        output,
        kind="positioning run (captured)",
        units={"deviation_um": "um, (reading - offset) - target" + (
            "; the raw reading, compensated for the air when read" if result.environment else "")},
        sources=[named_from(s, output) for s in (steps.source, result.source) if s and not s.startswith("<")
                 and Path(s).is_file()],
        standard="ISO 230-2",
        plan=named_from(steps.source, output) if Path(steps.source).is_file() else steps.source,
        plan_seed=steps.seed,
        source=named_from(result.source, output) if Path(result.source).is_file() else result.source,
        settings=result.settings.as_dict(),
        recording_header=dict(result.header),
        stops=[{"step": int(steps.step[r.index]), "start_s": r.start_s, "window_std_um": r.window_std_m / UM,
                "samples": r.samples} for r in result.readings],
    )
    try:
        partial.unlink(missing_ok=True)
    except OSError:
        pass
    return CaptureFiles(result, output, sidecar)


def _remove(path: Path) -> None:
    try:
        path.unlink()
    except OSError as exc:
        raise AxiscalError(f"cannot remove the partial capture that holds no stop ({exc.strerror or exc})", path=path) from None
