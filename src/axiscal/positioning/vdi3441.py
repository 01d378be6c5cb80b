"""Positional uncertainty of an axis to VDI/DGQ 3441 (1977), from the same statistics per target as ISO 230-2."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_instance

from axiscal.positioning.run import PositioningRun
from axiscal.positioning.statistics import TargetStatistics, _readonly, _warnings, target_statistics

__all__ = [
    "VDI_SYMBOLS",
    "Vdi3441Result",
    "vdi3441",
]


VDI_SYMBOLS = ("P", "Pa", "Ps_max", "Ps_mean", "U_max", "U_mean")


@dataclass(frozen=True)
class Vdi3441Result:
    """VDI/DGQ 3441 figures of one axis (metres) and the per-target values they come from.

    Per target (shape (m,)): reversal span ``U_j = |mean_up - mean_down|``, mean standard
    deviation ``s_mean_j = (s_up + s_down) / 2`` and positional scatter ``Ps_j = 6 s_mean_j``.
    Axis: ``Pa`` = range of the bidirectional means, ``P`` = max(mean + (U + Ps)/2) -
    min(mean - (U + Ps)/2), ``Ps_max``, ``Ps_mean``, ``U_max``, ``U_mean``.

    Attributes
    ----------
    stats : TargetStatistics
        Per-target means, s and B_i, metres.
    reversal_span, s_mean, scatter : ndarray, shape (m,), metres
        U_j, s_mean_j and Ps_j.
    P, Pa, Ps_max, Ps_mean, U_max, U_mean : float, metres
        The axis figures (:data:`VDI_SYMBOLS`).
    warnings : tuple of str
        What the reader should know (e.g. one run: no s).
    """

    stats: TargetStatistics
    reversal_span: np.ndarray
    s_mean: np.ndarray
    scatter: np.ndarray
    P: float
    Pa: float
    Ps_max: float
    Ps_mean: float
    U_max: float
    U_mean: float
    warnings: tuple[str, ...] = field(default=())

    @property
    def standard(self) -> str:
        """``"vdi3441"``."""
        return "vdi3441"

    def figures(self) -> dict[str, float]:
        """The axis figures by their symbol (:data:`VDI_SYMBOLS`), metres."""
        return {name: getattr(self, name) for name in VDI_SYMBOLS}


def vdi3441(run: PositioningRun) -> Vdi3441Result:
    """Evaluate a bidirectional positioning test to VDI/DGQ 3441.

    ``U_j = |mean_up_j - mean_down_j|``, ``s_mean_j = (s_up_j + s_down_j) / 2``,
    ``Ps_j = 6 s_mean_j``, ``Pa = max mean_j - min mean_j`` (bidirectional means),
    ``P = max(mean_j + (U_j + Ps_j) / 2) - min(mean_j - (U_j + Ps_j) / 2)``.

    Parameters
    ----------
    run : PositioningRun
        Deviations per target, metres.

    Returns
    -------
    Vdi3441Result
        Axis figures in metres; with one run the scatter and P are NaN (with a warning).

    Raises
    ------
    AxiscalError
        For a unidirectional test: VDI/DGQ 3441 defines its figures from both directions.

    Examples
    --------
    >>> from axiscal.units import UM
    >>> from axiscal.positioning.run import paper003_table4_run
    >>> result = vdi3441(paper003_table4_run())
    >>> round(result.Pa / UM, 3), round(result.P / UM, 3)
    (0.683, 9.767)
    """
    check_instance("run", run, PositioningRun)
    if not run.bidirectional:
        raise AxiscalError(
            f"{run.source}: VDI/DGQ 3441 evaluates a bidirectional test; this one goes in the {run.directions[0]}"
            " direction only (evaluate it to ISO 230-2)"
        )
    st = target_statistics(run)
    u = np.abs(st.reversal)
    s_mean = 0.5 * (st.s_up + st.s_down)
    ps = 6.0 * s_mean
    half = 0.5 * (u + ps)
    _readonly(u, s_mean, ps)
    return Vdi3441Result(
        stats=st,
        reversal_span=u,
        s_mean=s_mean,
        scatter=ps,
        P=float((st.mean + half).max() - (st.mean - half).min()),
        Pa=float(np.ptp(st.mean)),
        Ps_max=float(ps.max()),
        Ps_mean=float(ps.mean()),
        U_max=float(u.max()),
        U_mean=float(u.mean()),
        warnings=_warnings(run),
    )
