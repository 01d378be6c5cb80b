"""Test planning for ISO 230-2 positioning tests: uneven target positions and the test cycle.

ISO 230-2 asks for at least five target positions per metre (and at least five in all), spaced
unevenly so that periodic errors of the screw or the scale are sampled rather than hit at the same
phase every time: ``P_i = (i - 1) p + r_i`` with ``p`` the even interval and ``r_i`` a different
offset at each target. Here ``r_i`` is drawn uniformly from [-p/4, p/4] by NumPy's seeded
generator (``np.random.default_rng(seed)``), rounded to 1 um, and is 0 at the two end targets so
the whole travel is covered. Each target is approached from both sides with an overrun beyond the
end targets; the linear cycle runs through all targets up then down, once per run; the pilgrim
(step) cycle makes all runs at one target before moving to the next. See docs/positioning.md.

The cycle CSV is plain (header first) with an empty ``deviation_um`` column: type each reading in
and the file is a run file for :func:`axiscal.positioning.reader.read_positioning_run`. What the plan
was made from (cycle, runs, overrun, seed) goes into the JSON sidecar beside it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_instance, check_integer, check_number, check_path, is_real
from axiscal.io.atomic import write_text
from axiscal.io.gcode import ProgramWriter, dialect as gcode_dialect
from axiscal.io.gcode.writer import MAX_DWELL_S, MAX_FEED_MM_MIN, MAX_POSITION_MM
from axiscal.io.jsonio import write_sidecar
from axiscal.positioning.evaluation import require_finite
from axiscal.units import MM, UM

#: largest plan accepted (checked before anything is allocated)
MAX_TARGETS = 10_000
MAX_RUNS = 100
#: every position of a plan, overruns included, is within this of zero, metres: what a control's
#: position word holds (five whole digits of millimetres, :data:`axiscal.io.gcode.writer.MAX_POSITION_MM`)
MAX_POSITION_M = MAX_POSITION_MM * MM
#: the longest overrun (and a step cycle's longest period), metres
MAX_OVERRUN_M = 1.0

__all__ = [
    "MAX_TARGETS",
    "MAX_RUNS",
    "MAX_POSITION_M",
    "MAX_OVERRUN_M",
    "CYCLES",
    "TARGETS_PER_METRE",
    "PositioningTestPlan",
    "minimum_targets",
    "plan_targets",
    "plan_test",
    "PLAN_COLUMNS",
    "cycle_csv",
    "gcode_program",
    "write_plan",
]

CYCLES = ("linear", "pilgrim")
#: ISO 230-2: at least this many targets per metre of travel (and at least this many in all)
TARGETS_PER_METRE = 5
#: columns of the cycle CSV; ``deviation_um`` is empty, for the readings to be typed in
PLAN_COLUMNS = ("step", "run", "direction", "target_mm", "move_to_mm", "deviation_um")


@dataclass(frozen=True)
class PositioningTestPlan:
    """A planned positioning test.

    Attributes
    ----------
    targets : ndarray, shape (m,), metres
        Target positions, strictly increasing, first = start, last = end.
    moves : ndarray, shape (k,), metres
        Every commanded position in order, overrun moves included.
    move_run : ndarray of int, shape (k,)
        Run number (1-based) each move belongs to.
    move_direction : ndarray of str, shape (k,)
        "+" or "-": the direction of the move.
    move_target : ndarray, shape (k,), metres
        The target a move stops at for a reading, NaN for overrun moves (no reading).
    cycle : str
        "linear" or "pilgrim".
    runs : int
        Runs in each direction.
    overrun : float, metres
        Travel beyond a target before approaching it.
    seed : int
        The seed actually used (drawn from the operating system's entropy when none was given),
        so the plan can be made again.
    """

    targets: np.ndarray
    moves: np.ndarray
    move_run: np.ndarray
    move_direction: np.ndarray
    move_target: np.ndarray
    cycle: str
    runs: int
    overrun: float
    seed: int

    def __post_init__(self) -> None:
        overrun = check_number("overrun", self.overrun, positive=True, high=MAX_OVERRUN_M, unit="metres")
        reach = float(np.max(np.abs(self.moves))) if np.size(self.moves) else 0.0
        if not reach <= MAX_POSITION_M:
            raise AxiscalError(f"the plan's moves reach {reach / MM:.10g} mm (the overrun of {overrun / MM:g} mm included): a plan"
                               f" stays within +/-{MAX_POSITION_MM:.3f} mm, the range of a control's position word")

    @property
    def readings(self) -> int:
        """Number of moves that end at a target (one reading each)."""
        return int(np.isfinite(self.move_target).sum())

    @property
    def description(self) -> str:
        """The plan in one phrase: cycle, targets, runs, overrun (mm) and seed (a step cycle: its even step, no seed)."""
        if self.cycle == "step":
            spacing = (self.targets[-1] - self.targets[0]) / max(self.targets.size - 1, 1)
            return (
                f"ISO 230-2 step cycle (Annexes B and C), {self.targets.size} targets every {spacing / MM:.4g} mm,"
                f" {self.runs} runs each way, overrun {self.overrun / MM:g} mm"
            )
        return (
            f"ISO 230-2 {self.cycle} cycle, {self.targets.size} targets, {self.runs} runs each way,"
            f" overrun {self.overrun / MM:g} mm, seed {self.seed}"
        )


def minimum_targets(length_m: float) -> int:
    """Fewest targets ISO 230-2 accepts over ``length_m``: 5 per metre, at least 5.

    Parameters
    ----------
    length_m : float, metres
        The measured travel.

    Returns
    -------
    int

    Examples
    --------
    >>> minimum_targets(0.8), minimum_targets(2.1)
    (5, 11)
    """
    length_m = check_number("length_m", length_m, nonnegative=True)
    return max(TARGETS_PER_METRE, math.ceil(TARGETS_PER_METRE * length_m - 1e-9))


def plan_targets(start_m: float, end_m: float, count: int, *, seed: int | None = None) -> np.ndarray:
    """Uneven ISO 230-2 target positions from ``start_m`` to ``end_m``.

    Parameters
    ----------
    start_m, end_m : float, metres
        First and last target (end > start).
    count : int
        Number of targets, at least :func:`minimum_targets` of the length.
    seed : int, optional, keyword-only
        Seed of ``np.random.default_rng``; the same seed gives the same targets.

    Returns
    -------
    ndarray, shape (count,), metres
        ``P_i = start + i p + r_i``, ``r_i`` uniform in [-p/4, p/4] rounded to 1 um, r = 0 at both ends.

    Raises
    ------
    AxiscalError
        If the end is not beyond the start, either is beyond :data:`MAX_POSITION_M`, or ``count``
        is below :func:`minimum_targets`.

    Examples
    --------
    >>> from axiscal.units import MM
    >>> (plan_targets(0.0, 0.4, 5, seed=1) / MM).round(3).tolist()
    [0.0, 122.523, 182.208, 322.432, 400.0]
    """
    require_finite(start_m=start_m, end_m=end_m)
    start_m = check_number("start_m", start_m)
    end_m = check_number("end_m", end_m)
    count = check_integer("count", count)
    if seed is not None:
        seed = check_integer("seed", seed)
    for name, value in (("start_m", start_m), ("end_m", end_m)):
        if abs(value) > MAX_POSITION_M:
            raise AxiscalError(f"{name} must be within +/-{MAX_POSITION_M:g} metres (a control's position word), not {value:.10g}")
    if end_m <= start_m:
        raise AxiscalError(f"the end ({end_m / MM:g} mm) must be beyond the start ({start_m / MM:g} mm)")
    need = minimum_targets(end_m - start_m)
    if count > MAX_TARGETS:
        raise AxiscalError(f"{count} targets: a plan holds at most {MAX_TARGETS}")
    if seed is not None and not 0 <= seed < 2**63:
        raise AxiscalError(f"the seed must be a whole number from 0 to 2**63 - 1, got {seed}")
    if count < need:
        raise AxiscalError(
            f"{count} targets over {(end_m - start_m) / MM:g} mm: ISO 230-2 needs at least {need}"
            f" (5 per metre, at least 5)"
        )
    pitch = (end_m - start_m) / (count - 1)
    rng = np.random.default_rng(seed)
    offsets = rng.uniform(-0.25 * pitch, 0.25 * pitch, size=count)
    offsets[0] = offsets[-1] = 0.0
    targets = start_m + pitch * np.arange(count) + offsets
    targets = np.round(targets / UM) * UM
    targets[0], targets[-1] = start_m, end_m
    return targets


def plan_test(
    start_m: float,
    end_m: float,
    count: int,
    *,
    runs: int = 5,
    overrun_m: float = 5e-3,
    seed: int | None = None,
    cycle: str = "linear",
) -> PositioningTestPlan:
    """Targets and test cycle of an ISO 230-2 bidirectional positioning test.

    Parameters
    ----------
    start_m, end_m, count :
        See :func:`plan_targets`.
    seed : int, optional, keyword-only
        Seed of the target offsets (see :func:`plan_targets`). Default: a fresh seed, drawn from the
        operating system's entropy and recorded in the plan (and in the CSV and G-code headers).
    runs : int, keyword-only
        Runs in each direction (default 5, as ISO 230-2 asks; 1 is accepted for axes over 2 m).
    overrun_m : float, metres, keyword-only
        How far the axis travels beyond a target before approaching it from that side (> 0).
    cycle : {"linear", "pilgrim"}, keyword-only
        "linear" (default): per run, every target up from ``start - overrun``, then to
        ``end + overrun`` and every target down.
        "pilgrim": per target, ``runs`` approaches from below, each from ``target - overrun``;
        then, going down, ``runs`` approaches from above, each from ``target + overrun``.

    Returns
    -------
    PositioningTestPlan
        Targets and every move of the cycle, metres.

    Raises
    ------
    AxiscalError
        For an unknown cycle, fewer than 1 run, an overrun that is not positive or beyond
        :data:`MAX_OVERRUN_M`, a move beyond :data:`MAX_POSITION_M`, or targets
        :func:`plan_targets` refuses.

    Examples
    --------
    >>> plan = plan_test(0.0, 0.8, 17, runs=5, seed=1)
    >>> plan.readings, plan.moves.size
    (170, 180)
    """
    if not isinstance(cycle, str) or cycle not in CYCLES:
        raise AxiscalError(f"unknown cycle {cycle!r}; use one of {', '.join(CYCLES)}")
    runs = check_integer("runs", runs)
    if not is_real(overrun_m):
        check_number("overrun_m", overrun_m)
    if runs < 1:
        raise AxiscalError(f"runs must be at least 1, got {runs}")
    if runs > MAX_RUNS:
        raise AxiscalError(f"{runs} runs: a plan holds at most {MAX_RUNS} runs in each direction")
    require_finite(overrun_m=overrun_m)
    if overrun_m <= 0:
        raise AxiscalError(f"the overrun must be positive, got {overrun_m / MM:g} mm")
    if overrun_m > MAX_OVERRUN_M:
        raise AxiscalError(f"overrun_m must be at most {MAX_OVERRUN_M:g} metres, not {overrun_m:.10g}")
    if seed is None:
        seed = int(np.random.SeedSequence().generate_state(1)[0])
    targets = plan_targets(start_m, end_m, count, seed=seed)
    moves: list[tuple[float, int, str, float]] = []
    nan = math.nan
    if cycle == "linear":
        for run in range(1, runs + 1):
            moves.append((targets[0] - overrun_m, run, "-", nan))
            moves.extend((t, run, "+", t) for t in targets)
            moves.append((targets[-1] + overrun_m, run, "+", nan))
            moves.extend((t, run, "-", t) for t in targets[::-1])
    else:
        for t in targets:
            for run in range(1, runs + 1):
                moves.append((t - overrun_m, run, "-", nan))
                moves.append((t, run, "+", t))
        for t in targets[::-1]:
            for run in range(1, runs + 1):
                moves.append((t + overrun_m, run, "+", nan))
                moves.append((t, run, "-", t))
    pos = np.array([m[0] for m in moves])
    return PositioningTestPlan(
        targets=targets,
        moves=pos,
        move_run=np.array([m[1] for m in moves], dtype=int),
        move_direction=np.array([m[2] for m in moves]),
        move_target=np.array([m[3] for m in moves]),
        cycle=cycle,
        runs=runs,
        overrun=overrun_m,
        seed=seed,
    )


def cycle_csv(plan: PositioningTestPlan) -> str:
    """The test cycle as plain CSV: ``step, run, direction, target_mm, move_to_mm, deviation_um``.

    Parameters
    ----------
    plan : PositioningTestPlan
        The plan (see :func:`plan_test`).

    Returns
    -------
    str
        The header line, then one row per move. ``target_mm`` (mm, 1 um resolution) is empty for
        overrun moves, where no reading is taken; ``deviation_um`` is empty everywhere, for the
        deviations (actual - target, um) to be typed in at the rows with a target. Filled in, the
        file is read by :func:`axiscal.positioning.reader.read_positioning_run` as it is.

    Examples
    --------
    >>> plan = plan_test(0.0, 0.4, 5, runs=1, seed=1)
    >>> cycle_csv(plan).splitlines()[:3]
    ['step,run,direction,target_mm,move_to_mm,deviation_um', '1,1,-,,-5.000,', '2,1,+,0.000,0.000,']
    """
    check_instance("plan", plan, PositioningTestPlan)
    lines = [",".join(PLAN_COLUMNS)]
    for k in range(plan.moves.size):
        target = plan.move_target[k]
        cell = "" if math.isnan(target) else f"{target / MM:.3f}"
        lines.append(f"{k + 1},{plan.move_run[k]},{plan.move_direction[k]},{cell},{plan.moves[k] / MM:.3f},")
    return "\n".join(lines) + "\n"


def gcode_program(
    plan: PositioningTestPlan,
    *,
    dialect: str = "linuxcnc",
    axis: str = "X",
    dwell_s: float = 2.0,
    feed_mm_per_min: float = 2000.0,
    program_name: str = "AXISCAL",
    on_the_fly: bool = False,
) -> str:
    """The test cycle as a G-code program in a control's dialect, with a dwell at each target.

    Millimetres, absolute, feed per minute (each dialect's own words: ``G21 G90 G94`` on LinuxCNC
    and Grbl, ``G71 G90 G94`` on SINUMERIK, ``BEGIN PGM ... MM`` on HEIDENHAIN ...), feed moves to
    every position of the cycle, and after every move that ends at a target the dialect's dwell:
    ``G4 P<s>`` (LinuxCNC, Grbl), ``G04 X<s>`` (FANUC), ``G4 F<s>`` (SINUMERIK), ``G4 P<ms>``
    (Marlin, Klipper), ``CYCL DEF 9.0 DWELL TIME`` / ``CYCL DEF 9.1 DWELL <s>`` (HEIDENHAIN).
    Each dialect's start, end and comments are its own (see :mod:`axiscal.io.gcode.dialects`);
    :func:`axiscal.io.gcode.program_motions` reads the program back.

    Parameters
    ----------
    plan : PositioningTestPlan
        The plan (see :func:`plan_test`).
    dialect : str, keyword-only
        One of :data:`axiscal.io.gcode.DIALECT_NAMES` (default "linuxcnc").
    axis : str, keyword-only
        One axis letter of the dialect (default "X").
    dwell_s : float, keyword-only
        Dwell at each target, seconds (>= 0, default 2); written to the dialect's resolution
        (1 ms).
    feed_mm_per_min : float, keyword-only
        Feed of the moves, mm/min (> 0, default 2000).
    program_name : str, keyword-only
        The program's name where the dialect writes one (HEIDENHAIN's ``BEGIN PGM name MM``).
    on_the_fly : bool, keyword-only
        A program for an on-the-fly capture (:mod:`axiscal.capture.on_the_fly`): no dwell, and
        a last move past the last target by the overrun, so that the axis passes every target
        without stopping at it (run it in the control's path mode). Default False.

    Returns
    -------
    str
        The program, one block a line.

    Raises
    ------
    AxiscalError
        For an unknown dialect, an axis that is not one of the dialect's letters, a dwell outside
        0 to 3600 s or a feed outside 0 to 100 000 mm/min (the bounds of the program's words).

    Examples
    --------
    >>> program = gcode_program(plan_test(0.0, 0.4, 5, runs=1, seed=1), axis="z", dwell_s=1)
    >>> program.splitlines()[4:7]
    ['G1 Z-5.000 F2000', 'G1 Z0.000', 'G4 P1']
    >>> program = gcode_program(plan_test(0.0, 0.4, 5, runs=1, seed=1), dialect="sinumerik", dwell_s=1.5)
    >>> program.splitlines()[2:6]
    ['G71 G90 G94', 'G1 X-5.000 F2000', 'G1 X0.000', 'G4 F1.5']
    """
    check_instance("plan", plan, PositioningTestPlan)
    spec = gcode_dialect(dialect)
    if not isinstance(axis, str) or axis.upper() not in spec.axes:
        raise AxiscalError(f"axis must be one letter of {spec.controller}'s axes ({', '.join(spec.axes)}), got {axis!r}")
    require_finite(dwell_s=dwell_s, feed_mm_per_min=feed_mm_per_min)
    dwell_s = check_number("dwell_s", dwell_s)
    feed_mm_per_min = check_number("feed_mm_per_min", feed_mm_per_min, unit="mm/min")
    if not 0 <= dwell_s <= MAX_DWELL_S:
        raise AxiscalError(f"dwell_s must be from 0 to {MAX_DWELL_S:g} s, not {dwell_s:.10g}")
    if not 0 < feed_mm_per_min <= MAX_FEED_MM_MIN:
        raise AxiscalError(f"feed_mm_per_min must be above 0 and at most {MAX_FEED_MM_MIN:g} mm/min, not {feed_mm_per_min:.10g}")
    axis = axis.upper()
    feed = feed_mm_per_min * MM / 60.0
    if not isinstance(on_the_fly, bool):
        raise AxiscalError(f"on_the_fly must be True or False, not {on_the_fly!r}")
    writer = ProgramWriter(spec, name=program_name, comments=(
        f"axiscal plan: {plan.description}",
        "on the fly: the axis passes every target without stopping (path mode); the last move runs past the last target"
        if on_the_fly else "a dwell follows every move that ends at a target: take the reading there",
    ))
    for k in range(plan.moves.size):
        writer.move({axis: float(plan.moves[k])}, feed_m_per_s=feed)
        if not math.isnan(plan.move_target[k]) and not on_the_fly:
            writer.dwell(dwell_s)
    if on_the_fly:
        last = 1.0 if plan.move_direction[-1] == "+" else -1.0
        writer.move({axis: float(plan.moves[-1] + last * plan.overrun)}, feed_m_per_s=feed)
    return writer.text()


def write_plan(
    plan: PositioningTestPlan,
    csv_path: str | Path | None = None,
    *,
    gcode_path: str | Path | None = None,
    dialect: str = "linuxcnc",
    axis: str = "X",
    dwell_s: float = 2.0,
    feed_mm_per_min: float = 2000.0,
    on_the_fly: bool = False,
) -> list[Path]:
    """Write the cycle CSV with its JSON sidecar, and the G-code program, each atomically.

    Parameters
    ----------
    plan : PositioningTestPlan
        The plan (see :func:`plan_test`).
    csv_path : str or Path, optional
        The cycle CSV (:func:`cycle_csv`); its sidecar ``NAME.json`` records the plan (cycle,
        targets in mm, runs, overrun in mm, seed). None writes no CSV.
    gcode_path : str or Path, optional, keyword-only
        The G-code program (:func:`gcode_program`). None writes none.
    dialect, axis, dwell_s, feed_mm_per_min, on_the_fly : keyword-only
        Passed to :func:`gcode_program` (the control's dialect, axis letter, dwell in seconds, feed
        in mm/min, a program for an on-the-fly capture); the program's name, where the dialect
        writes one, is the file's stem.

    Returns
    -------
    list of Path
        The files written: CSV, sidecar, G-code (those asked for).

    Raises
    ------
    AxiscalError
        For a G-code option :func:`gcode_program` refuses (checked before anything is written),
        or a file that cannot be written (naming it).

    Examples
    --------
    >>> plan = plan_test(0.0, 0.8, 17, seed=1)
    >>> write_plan(plan, "cycle.csv", gcode_path="cycle.ngc")  # doctest: +SKIP
    [PosixPath('cycle.csv'), PosixPath('cycle.json'), PosixPath('cycle.ngc')]
    """
    check_instance("plan", plan, PositioningTestPlan)
    if csv_path is not None:
        check_path("csv_path", csv_path)
    if gcode_path is not None:
        check_path("gcode_path", gcode_path)
    program = None if gcode_path is None else gcode_program(
        plan, dialect=dialect, axis=axis, dwell_s=dwell_s, feed_mm_per_min=feed_mm_per_min,
        program_name=Path(gcode_path).stem, on_the_fly=on_the_fly)
    written: list[Path] = []
    if csv_path is not None:
        written.append(write_text(csv_path, cycle_csv(plan)))
        written.append(
            write_sidecar(
                csv_path,
                kind="positioning test plan",
                units={"deviation_um": "um, actual - target: to be typed in at every row with a target_mm"},
                standard="ISO 230-2",
                description=plan.description,
                cycle=plan.cycle,
                target_mm=plan.targets / MM,
                runs=plan.runs,
                overrun_mm=plan.overrun / MM,
                seed=plan.seed,
                readings=plan.readings,
            )
        )
    if program is not None:
        written.append(write_text(gcode_path, program))
    return written
