"""The statistics per target that every positioning estimator starts from: unidirectional means and standard uncertainties, the bidirectional mean and the reversal value (ISO 230-2 clause 2), and the warnings a run's shape calls for."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from axiscal.io.arguments import check_instance

from axiscal.positioning.run import PositioningRun

__all__ = [
    "LONG_AXIS_M",
    "ONE_DIRECTION_WARNING",
    "NO_S_WARNING",
    "TargetStatistics",
    "target_statistics",
]


#: travel above which ISO 230-2 tests with one run each way (no R, no A), metres
LONG_AXIS_M = 2.0
ONE_DIRECTION_WARNING = (
    "one-direction test ({direction} only): the reversal value B and the bidirectional figures A, E, M and R"
    " do not apply (n/a)"
)
NO_S_WARNING = (
    "only one run per direction: the standard uncertainty s cannot be estimated, "
    "so s, the repeatabilities R and the accuracies A are not given (NaN / null)"
)


@dataclass(frozen=True)
class TargetStatistics:
    """Per-target estimators shared by every standard (ISO 230-2, 3.2-3.3), metres.

    Attributes
    ----------
    targets : ndarray, shape (m,), metres
        Target positions P_i.
    mean_up, mean_down : ndarray, shape (m,), metres
        Mean unidirectional positional deviations x̄_i↑, x̄_i↓.
    s_up, s_down : ndarray, shape (m,), metres
        Estimators of the unidirectional standard uncertainty s_i↑, s_i↓ (n - 1 in the
        denominator); NaN when there is one run per direction.
    mean : ndarray, shape (m,), metres
        Mean bidirectional positional deviation x̄_i = (x̄_i↑ + x̄_i↓) / 2.
    reversal : ndarray, shape (m,), metres
        Reversal value B_i = x̄_i↑ - x̄_i↓.
    runs : int
        Number of runs n in each direction.
    """

    targets: np.ndarray
    mean_up: np.ndarray
    mean_down: np.ndarray
    s_up: np.ndarray
    s_down: np.ndarray
    mean: np.ndarray
    reversal: np.ndarray
    runs: int


def _readonly(*arrays: np.ndarray) -> None:
    for a in arrays:
        a.setflags(write=False)


def target_statistics(run: PositioningRun) -> TargetStatistics:
    """Unidirectional means, s (n - 1 in the denominator), bidirectional mean and B_i per target.

    ISO 230-2 mean unidirectional and bidirectional positional deviations, reversal value
    ``B_i = mean_up - mean_down`` and the estimator of the unidirectional standard uncertainty
    ``s_i`` (n - 1 in the denominator). With one run s is NaN; for a unidirectional test the
    values of the direction not tested, the bidirectional mean and B_i are NaN.

    Parameters
    ----------
    run : PositioningRun
        Deviations per target, metres, shape (m, n) per direction.

    Returns
    -------
    TargetStatistics
        Arrays of shape (m,), metres (read-only).

    Examples
    --------
    >>> from axiscal.units import UM
    >>> from axiscal.positioning.run import paper003_table4_run
    >>> st = target_statistics(paper003_table4_run())
    >>> (st.mean_up / UM).round(3).tolist(), (st.s_up / UM).round(3).tolist()
    ([0.733, 1.6], [0.643, 0.458])
    """
    check_instance("run", run, PositioningRun)
    missing = np.full((run.targets.size, run.runs), np.nan)
    up = missing if run.deviations_up is None else run.deviations_up
    down = missing if run.deviations_down is None else run.deviations_down
    mean_up = up.mean(axis=1)
    mean_down = down.mean(axis=1)
    if run.runs >= 2:
        s_up = up.std(axis=1, ddof=1)
        s_down = down.std(axis=1, ddof=1)
    else:
        s_up = np.full(run.targets.size, np.nan)
        s_down = np.full(run.targets.size, np.nan)
    mean = 0.5 * (mean_up + mean_down)
    reversal = mean_up - mean_down
    _readonly(mean_up, mean_down, s_up, s_down, mean, reversal)
    return TargetStatistics(run.targets, mean_up, mean_down, s_up, s_down, mean, reversal, run.runs)


def _warnings(run: PositioningRun) -> tuple[str, ...]:
    notes = []
    if not run.bidirectional:
        notes.append(ONE_DIRECTION_WARNING.format(direction=run.directions[0]))
    if run.runs >= 2:
        return tuple(notes)
    if not run.rotary and run.targets[-1] - run.targets[0] > LONG_AXIS_M:
        return (NO_S_WARNING + " (one run each way is what ISO 230-2 asks for on axes longer than 2000 mm)", *notes)
    return (NO_S_WARNING, *notes)
