"""The step cycle for short-period (periodic) positioning errors: ISO 230-2:2014 Annexes B and C.

An ordinary ISO 230-2 test spaces its targets unevenly so that a periodic error of the screw or
the scale is sampled rather than hit at the same phase every time; it cannot tell that error's
amplitude and period. Annex C considers the periodic positioning error and Annex B describes the
step cycle: here, targets in equal steps of a fraction of the period (the screw's pitch, the
scale's grating period, a rack's tooth pitch) over one or a few periods, each approached from
both sides with an overrun as in the linear cycle. The run it gives is evaluated by
:func:`axiscal.dynamics.periodic.periodic_error`. As ISO 230-2 says of its step cycle, its
figures are not for acceptance unless agreed between supplier and user.
"""

from __future__ import annotations

import math

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_count, check_number
from axiscal.positioning.plan import MAX_OVERRUN_M, MAX_RUNS, MAX_TARGETS, PositioningTestPlan
from axiscal.units import UM

__all__ = ["plan_step_cycle"]


def plan_step_cycle(
    start_m: float,
    period_m: float,
    *,
    periods: int = 2,
    steps_per_period: int = 12,
    runs: int = 1,
    overrun_m: float = 1e-3,
) -> PositioningTestPlan:
    """A step cycle: evenly spaced targets over whole periods, approached from both sides.

    Parameters
    ----------
    start_m : float, metres
        First target.
    period_m : float, metres
        The period looked for (a screw's pitch; at most 1 m).
    periods : int, keyword-only
        Periods covered (default 2).
    steps_per_period : int, keyword-only
        Targets per period (default 12; at least 4).
    runs : int, keyword-only
        Runs in each direction (default 1).
    overrun_m : float, metres, keyword-only
        Travel beyond the end targets before approaching them (default 1 mm; at most 1 m).

    Returns
    -------
    PositioningTestPlan
        ``cycle = "step"``; targets ``start + i period / steps_per_period`` for ``i = 0 ..
        periods * steps_per_period`` rounded to 1 um; per run every target up from ``start -
        overrun``, then to ``end + overrun`` and every target down; ``seed`` 0 (nothing random).

    Raises
    ------
    AxiscalError
        For a period or overrun that is not positive or beyond 1 m, counts out of range, a step
        below 1 um, or a move beyond the range of a control's position word.

    Examples
    --------
    >>> plan = plan_step_cycle(0.1, 5e-3, periods=2, steps_per_period=4)
    >>> (plan.targets * 1e3).round(3).tolist()
    [100.0, 101.25, 102.5, 103.75, 105.0, 106.25, 107.5, 108.75, 110.0]
    >>> plan.readings, plan.moves.size
    (18, 20)
    """
    start_m = check_number("start_m", start_m)
    period_m = check_number("period_m", period_m, positive=True, high=MAX_OVERRUN_M)
    periods = check_count("periods", periods, minimum=1, maximum=1000)
    steps_per_period = check_count("steps_per_period", steps_per_period, minimum=4, maximum=1000)
    runs = check_count("runs", runs, minimum=1, maximum=MAX_RUNS)
    overrun_m = check_number("overrun_m", overrun_m, positive=True, high=MAX_OVERRUN_M)
    count = periods * steps_per_period + 1
    if count > MAX_TARGETS:
        raise AxiscalError(f"{count} targets: a plan holds at most {MAX_TARGETS}")
    step = period_m / steps_per_period
    if step < UM:
        raise AxiscalError(f"a step of {step / UM:g} um: the targets are written to 1 um, a step must be at least 1 um")
    targets = np.round((start_m + step * np.arange(count)) / UM) * UM
    moves: list[tuple[float, int, str, float]] = []
    for run in range(1, runs + 1):
        moves.append((targets[0] - overrun_m, run, "-", math.nan))
        moves.extend((t, run, "+", t) for t in targets)
        moves.append((targets[-1] + overrun_m, run, "+", math.nan))
        moves.extend((t, run, "-", t) for t in targets[::-1])
    return PositioningTestPlan(
        targets=targets,
        moves=np.array([m[0] for m in moves]),
        move_run=np.array([m[1] for m in moves], dtype=int),
        move_direction=np.array([m[2] for m in moves]),
        move_target=np.array([m[3] for m in moves]),
        cycle="step",
        runs=runs,
        overrun=overrun_m,
        seed=0,
    )


