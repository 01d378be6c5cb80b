"""The plan's steps a capture walks, and which stop belongs to which step.

A plan (:func:`axiscal.positioning.plan.plan_test`, or its cycle CSV as ``axiscal plan`` writes
it: ``step, run, direction, target_mm, move_to_mm``) lists every commanded move in order; a
row with a target is reached in its direction from the row before (a row that says otherwise
is refused, naming it: it would be driven one way and labelled the other). A step
with a target needs one stop there; an overrun step (no target) is passed over. The steps are
walked in order, each stop of the axis taken in turn:

- a stop within ``tolerance`` of the next target is that step's reading, provided the axis came
  to it moving in the step's direction (``+``: from below, ``-``: from above);
- a stop at the end of an overrun move the axis has not yet passed is passed over;
- a stop the axis was already at when the recording began (before the program) is passed over;
- anything else is refused in one line naming the step, its target, run and direction: a stop
  elsewhere (an extra stop), a step without a stop before the axis stopped at a later step's
  target (a missing stop), the other side, and a recording that ends before the last step.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from axiscal.capture.stops import Stop
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_count, check_instance, check_number
from axiscal.io.jsonio import read_json, sidecar_path
from axiscal.io.tabular import read_csv
from axiscal.positioning.plan import PositioningTestPlan
from axiscal.positioning.reader import DIRECTIONS
from axiscal.units import MM

__all__ = ["PlanSteps", "CapturedStop", "StepMatcher", "plan_steps"]

#: how each direction of a step comes to its target, in words
_APPROACH = {"+": "moving in the + direction (from below)", "-": "moving in the - direction (from above)"}


def _mm(value_m: float, decimals: int) -> str:
    """A position in mm for a message: fixed decimals, exponent form where that would be a long number."""
    value = value_m / MM
    return f"{value:.{decimals}f}" if abs(value) < 1e6 else f"{value:.{decimals}e}"


@dataclass(frozen=True)
class PlanSteps:
    """The moves of a plan, in order.

    Attributes
    ----------
    step : ndarray of int, shape (k,)
        Step numbers (1-based, as the cycle CSV numbers them).
    run : ndarray of int, shape (k,)
        Run of each step.
    direction : ndarray of str, shape (k,)
        ``"+"`` or ``"-"``.
    target_m : ndarray, shape (k,), metres
        Target of each step, NaN for an overrun move (no reading).
    move_to_m : ndarray, shape (k,), metres
        Where each move ends.
    seed : int or None
        The plan's seed, where known.
    source : str
        The plan file (or ``"<plan>"``).
    """

    step: np.ndarray
    run: np.ndarray
    direction: np.ndarray
    target_m: np.ndarray
    move_to_m: np.ndarray
    seed: int | None = None
    source: str = "<plan>"

    def __post_init__(self) -> None:
        n = check_array("step", self.step, ndim=1, min_len=1, unit="").size
        for name in ("run", "target_m", "move_to_m"):
            values = check_array(name, getattr(self, name), ndim=1, finite=name != "target_m", unit="")
            if values.size != n:
                raise AxiscalError(f"{name} must hold one value per step ({n}), not {values.size}")
        if len(self.direction) != n or not all(d in ("+", "-") for d in self.direction):
            raise AxiscalError(f"direction must hold '+' or '-' for each of the {n} steps")

    @property
    def readings(self) -> int:
        """Steps with a target (one reading each)."""
        return int(np.isfinite(self.target_m).sum())

    def describe(self, k: int) -> str:
        """Step ``k`` (0-based index) in words: ``step 7 (target 120.523 mm, run 1, +)``."""
        target = self.target_m[k]
        where = f"target {_mm(target, 3)} mm" if np.isfinite(target) else f"overrun to {_mm(self.move_to_m[k], 3)} mm"
        return f"step {int(self.step[k])} ({where}, run {int(self.run[k])}, {self.direction[k]})"


def _contrary_direction(move_to: np.ndarray, target: np.ndarray, directions: np.ndarray) -> tuple[int, str] | None:
    """The first step with a target whose direction is not the one the axis reaches it in (and that one), or None.

    The axis reaches step k moving from step k - 1's position to its own: ``+`` upwards, ``-``
    downwards. A step where the axis does not move keeps the direction of the move before it; the
    first step's is not known (the axis stands wherever it stood). An overrun step's direction is
    the side of the target it goes to (the pilgrim cycle's ``-`` overrun below the next target is
    reached moving up): only the steps read are held to it.
    """
    came = None
    for k in range(1, move_to.size):
        if move_to[k] != move_to[k - 1]:
            came = "+" if move_to[k] > move_to[k - 1] else "-"
        if came is not None and np.isfinite(target[k]) and directions[k] != came:
            return k, came
    return None


def plan_steps(plan: PositioningTestPlan | str | Path) -> PlanSteps:
    """The steps of a plan object or of a plan's cycle CSV (with its JSON sidecar's seed, if there is one).

    Parameters
    ----------
    plan : PositioningTestPlan, str or Path
        The plan, or its cycle CSV.

    Returns
    -------
    PlanSteps

    Raises
    ------
    AxiscalError
        Naming the file and line: a missing column, a direction that is not ``+``/``-`` or is not
        the one the axis reaches the step in (from the step before), step numbers that do not
        increase, a target that is not where its move ends, or no target at all.
    """
    if isinstance(plan, PlanSteps):
        return plan
    if isinstance(plan, PositioningTestPlan):
        k = plan.moves.size
        return PlanSteps(np.arange(1, k + 1), plan.move_run.copy(), plan.move_direction.astype(str),
                         plan.move_target.copy(), plan.moves.copy(), plan.seed, "<plan>")
    check_instance("plan", plan, (str, Path), what="a PositioningTestPlan or the path of a plan's cycle CSV")
    table = read_csv(plan, min_rows=1)
    table.require("step", "run", "direction", "target_mm", "move_to_mm")
    step = table.numeric("step")
    run = table.numeric("run")
    move_to = table.numeric("move_to_mm") * MM
    target = table.numeric_or_missing("target_mm") * MM
    directions = []
    for k, text in enumerate(table.text("direction")):
        if text.strip() not in DIRECTIONS:
            raise AxiscalError(f"direction '{text}' is not + or -", path=table.path, line=table.line_of(k))
        directions.append(DIRECTIONS[text.strip()])
    for name, values in (("step", step), ("run", run)):
        bad = np.flatnonzero(values != np.round(values))
        if bad.size:
            raise AxiscalError(f"{name} {values[bad[0]]:g} is not a whole number", path=table.path, line=table.line_of(int(bad[0])))
    back = np.flatnonzero(np.diff(step) <= 0)
    if back.size:
        raise AxiscalError("step numbers must increase", path=table.path, line=table.line_of(int(back[0]) + 1))
    cells = table.text("target_mm")
    for k, cell in enumerate(cells):
        if cell.strip() and not np.isfinite(target[k]):
            raise AxiscalError(f"target_mm '{cell}' is not a number", path=table.path, line=table.line_of(k))
    off = np.flatnonzero(np.isfinite(target) & (np.abs(target - move_to) > 0.5e-6))
    if off.size:
        raise AxiscalError("a step's target is not where its move ends (target_mm differs from move_to_mm)",
                           path=table.path, line=table.line_of(int(off[0])))
    if not np.isfinite(target).any():
        raise AxiscalError("the plan has no step with a target: nothing to capture", path=table.path)
    contrary = _contrary_direction(move_to, target, np.array(directions))
    if contrary is not None:
        k, came = contrary
        raise AxiscalError(f"step {int(step[k])} (target {_mm(target[k], 3)} mm, run {int(run[k])}, {directions[k]}): the axis reaches it"
                           f" {_APPROACH[came]}, from {_mm(move_to[k - 1], 3)} mm: its direction must be {came}",
                           path=table.path, line=table.line_of(k))
    seed = None
    side = sidecar_path(plan)
    if side.is_file():
        try:
            meta = read_json(side)
        except AxiscalError:
            meta = {}
        value = meta.get("seed") if isinstance(meta, dict) else None
        seed = int(value) if isinstance(value, int) and not isinstance(value, bool) else None
    return PlanSteps(step.astype(int), run.astype(int), np.array(directions), target, move_to, seed, str(plan))


@dataclass(frozen=True)
class CapturedStop:
    """The reading taken at one step.

    Attributes
    ----------
    index : int
        The step's index in the plan (0-based).
    stop : Stop
        The stop it was taken from.
    position_m : float, metres
        The reading less the offset (the stop's value - offset).
    deviation_m : float, metres
        ``position - target``.
    """

    index: int
    stop: Stop
    position_m: float
    deviation_m: float


class StepMatcher:
    """Walk the plan's steps, taking each stop of the axis in turn (see the module's description).

    Parameters
    ----------
    steps : PlanSteps
    tolerance_m : float, metres
        How far from a target a stop may be and still be that target's.
    offset_m : float, metres
        The reading at the datum (subtracted from every stop's value).
    start : int
        Index of the first step still to capture (after a resumed partial capture).
    locate : callable, optional
        Gives the file and line of a stop, for messages: ``locate(stop) -> (path, line)``.
    """

    def __init__(self, steps: PlanSteps, *, tolerance_m: float, offset_m: float, start: int = 0, locate=None):
        self.steps = check_instance("steps", steps, PlanSteps)
        self.tolerance_m = check_number("tolerance_m", tolerance_m, positive=True, unit="m")
        self.offset_m = check_number("offset_m", offset_m, unit="m")
        start = check_count("start", start, minimum=0)
        if locate is not None and not callable(locate):
            raise AxiscalError(f"locate must be a function of a stop, not {locate!r}")
        self._targets = np.flatnonzero(np.isfinite(steps.target_m))
        self._passed = start  # every step before this index has been taken or passed
        self._locate = locate or (lambda stop: (None, None))

    @property
    def next_index(self) -> int | None:
        """Index of the next step that needs a stop, None when every one has been taken."""
        later = self._targets[self._targets >= self._passed]
        return int(later[0]) if later.size else None

    @property
    def taken(self) -> int:
        """Steps with a target taken so far (including those of a resumed capture)."""
        return int((self._targets < self._passed).sum())

    @property
    def done(self) -> bool:
        """True once every step with a target has its stop."""
        return self.next_index is None

    def _refuse(self, stop: Stop, message: str) -> AxiscalError:
        path, line = self._locate(stop)
        return AxiscalError(message, path=path, line=line)

    def take(self, stop: Stop) -> CapturedStop | None:
        """The captured step for ``stop``, or None where the stop is passed over.

        Raises
        ------
        AxiscalError
            For a stop that is not the next target's (elsewhere, at a later step's target, or
            approached from the other side), or a stop after the last step.
        """
        k = self.next_index
        position = stop.value_m - self.offset_m
        if stop.first_index == 0:
            return None  # the axis stood there before the recording began: not a stop of the program
        if k is None:
            raise self._refuse(stop, f"a stop at {_mm(position, 4)} mm after the plan's last step")
        steps, tol = self.steps, self.tolerance_m
        if abs(position - steps.target_m[k]) <= tol:
            if stop.approach != steps.direction[k]:
                raise self._refuse(stop, f"{steps.describe(k)}: the axis came to the target {_APPROACH[stop.approach]},"
                                         f" not {_APPROACH[steps.direction[k]]}")
            self._passed = k + 1
            return CapturedStop(k, stop, position, position - float(steps.target_m[k]))
        overruns = [j for j in range(self._passed, k) if abs(position - steps.move_to_m[j]) <= tol]
        if overruns:
            self._passed = overruns[0] + 1  # at the end of an overrun move: passed over
            return None
        later = [int(j) for j in self._targets[self._targets > k] if abs(position - steps.target_m[j]) <= tol]
        if later:
            raise self._refuse(stop, f"{steps.describe(k)}: no stop there: the axis went on and stopped at"
                                     f" {_mm(position, 4)} mm, the target of step {int(steps.step[later[0]])}")
        raise self._refuse(stop, f"{steps.describe(k)}: the axis stopped at {_mm(position, 4)} mm, not within"
                                 f" {tol / MM:g} mm of the target")

    def missing(self, source: str | None) -> AxiscalError:
        """The error for a recording that ended before every step had its stop."""
        k = self.next_index
        assert k is not None
        return AxiscalError(
            f"{self.steps.describe(k)}: the recording ends before it ({self.taken} of {len(self._targets)} stops taken)",
            path=source,
        )
