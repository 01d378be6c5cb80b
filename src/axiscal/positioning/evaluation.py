"""Positioning accuracy and repeatability of a numerically controlled axis from a bidirectional test.

Implements the estimators ISO 230-2:2014 defines for a test of 5 runs each way (adopted
unchanged as GB/T 17421.2-2016), with the coverage factor k = 2 of the 1997, 2006 and 2014
editions or k = 3 of the 1988 edition (``edition="1988"``, the "3 sigma" figures JIS B 0182
term 346 also uses), and VDI/DGQ 3441 (1977) positional uncertainty. Paper 003 Table 4 applies these estimators to three
runs. See docs/positioning.md for every symbol, the sign convention and how the editions differ.

Deviation convention (ISO 230-2): ``x_ij = P_ij - P_i``, actual position reached minus target.
The API is in metres; files and JSON carry micrometres in their names.

This module is the top of the positioning estimators: the run (:mod:`axiscal.positioning.run`), the
statistics per target (:mod:`axiscal.positioning.statistics`) and VDI/DGQ 3441
(:mod:`axiscal.positioning.vdi3441`) sit below it, and their names are importable from here.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_choice, check_instance
from axiscal.positioning.run import TURN, PositioningRun, covers_circle, paper003_table4_run, require_finite
from axiscal.positioning.statistics import (
    LONG_AXIS_M,
    NO_S_WARNING,
    ONE_DIRECTION_WARNING,
    TargetStatistics,
    _readonly,
    _warnings,
    target_statistics,
)
from axiscal.positioning.vdi3441 import VDI_SYMBOLS, Vdi3441Result, vdi3441

__all__ = [
    "ISO_EDITIONS",
    "LONG_AXIS_M",
    "NO_S_WARNING",
    "ONE_DIRECTION_WARNING",
    "BIDIRECTIONAL_SYMBOLS",
    "PositioningRun",
    "TargetStatistics",
    "Iso230Result",
    "ISO_SYMBOLS",
    "VDI_SYMBOLS",
    "Vdi3441Result",
    "target_statistics",
    "iso230_2",
    "vdi3441",
    "STANDARDS",
    "iso_edition",
    "paper003_table4_run",
    "TURN",
    "covers_circle",
    "require_finite",
]


#: ISO 230-2 editions this module evaluates, and their coverage factor k
ISO_EDITIONS: dict[str, int] = {"2014": 2, "2006": 2, "1997": 2, "1988": 3}


#: ISO 230-2 figures that need both directions: NaN (null, "n/a") for a unidirectional test
BIDIRECTIONAL_SYMBOLS = ("A", "B", "B_mean", "E", "M", "R")


@dataclass(frozen=True)
class Iso230Result:
    """ISO 230-2 figures of one axis (metres) and the per-target values they come from.

    Per target (shape (m,)): ``stats`` holds the unidirectional means, s and the reversal value
    B_i; ``repeatability_up``/``_down`` are R_i up/down = 2 k s_i, ``repeatability`` is
    R_i = max(k s_up + k s_down + |B_i|, R_i up, R_i down).

    Axis figures: accuracy ``A`` (and ``A_up``, ``A_down``), reversal value ``B`` = max |B_i|,
    mean reversal value ``B_mean``, systematic positional deviation ``E`` (``E_up``, ``E_down``),
    range of the mean bidirectional positional deviation ``M``, repeatability ``R`` (``R_up``,
    ``R_down``), and ``S_up``/``S_down`` = the largest unidirectional s_i over the axis (so that
    R_up = 2 k S_up). Figures that need s are NaN when there is one run; ``warnings`` says so.

    Attributes
    ----------
    edition : str
        The ISO 230-2 edition (a key of :data:`ISO_EDITIONS`).
    coverage : int
        Coverage factor k (2, or 3 for 1988).
    stats : TargetStatistics
        Per-target means, s and B_i, metres.
    repeatability_up, repeatability_down, repeatability : ndarray, shape (m,), metres
        R_i↑, R_i↓ and R_i.
    A, A_up, A_down, B, B_mean, E, E_up, E_down, M, R, R_up, R_down, S_up, S_down : float, metres
        The axis figures (:data:`ISO_SYMBOLS`).
    warnings : tuple of str
        What the reader should know (e.g. one run: no s).
    """

    edition: str
    coverage: int
    stats: TargetStatistics
    repeatability_up: np.ndarray
    repeatability_down: np.ndarray
    repeatability: np.ndarray
    A: float
    A_up: float
    A_down: float
    B: float
    B_mean: float
    E: float
    E_up: float
    E_down: float
    M: float
    R: float
    R_up: float
    R_down: float
    S_up: float
    S_down: float
    warnings: tuple[str, ...] = field(default=())

    @property
    def standard(self) -> str:
        """The standard's name as ``--standard`` spells it, e.g. ``"iso230-2:2014"``."""
        return f"iso230-2:{self.edition}"

    def figures(self) -> dict[str, float]:
        """The axis figures by their symbol (:data:`ISO_SYMBOLS`), metres."""
        return {name: getattr(self, name) for name in ISO_SYMBOLS}


ISO_SYMBOLS = ("A", "A_up", "A_down", "B", "B_mean", "E", "E_up", "E_down", "M", "R", "R_up", "R_down", "S_up", "S_down")


def _spread(*arrays: np.ndarray) -> float:
    """max - min over the arrays, NaN if any value is NaN (a figure that does not apply)."""
    values = np.concatenate(arrays)
    return float(values.max() - values.min())


def iso230_2(run: PositioningRun, *, edition: str = "2014") -> Iso230Result:
    """Evaluate a bidirectional positioning test to ISO 230-2.

    Parameters
    ----------
    run : PositioningRun
        Deviations per target, metres.
    edition : {"2014", "2006", "1997", "1988"}, keyword-only
        Edition of ISO 230-2 (default "2014", which GB/T 17421.2-2016 adopts unchanged). The
        1997, 2006 and 2014 editions use the coverage factor k = 2 (A from mean +- 2 s, R_i up =
        4 s); the 1988 edition uses k = 3 (mean +- 3 s, R_i up = 6 s). All other definitions are
        the same.

    Returns
    -------
    Iso230Result
        Axis figures in metres (radians for a rotary axis); figures needing s are NaN (with a
        warning) for one run; for a unidirectional test the figures of the direction tested are
        given and those of the other direction, B and the bidirectional figures
        (:data:`BIDIRECTIONAL_SYMBOLS`) are NaN, with a warning.

    Raises
    ------
    AxiscalError
        For an edition not in :data:`ISO_EDITIONS`.

    Examples
    --------
    >>> from axiscal.units import UM
    >>> result = iso230_2(paper003_table4_run())
    >>> round(result.B / UM, 3), round(result.R / UM, 3)
    (1.5, 8.451)
    """
    check_instance("run", run, PositioningRun)
    if not isinstance(edition, str) or edition not in ISO_EDITIONS:
        raise AxiscalError(f"unknown ISO 230-2 edition {edition!r}; use one of {', '.join(ISO_EDITIONS)}")
    k = ISO_EDITIONS[edition]
    st = target_statistics(run)
    r_up = 2 * k * st.s_up
    r_down = 2 * k * st.s_down
    r_bi = np.maximum(np.maximum(k * st.s_up + k * st.s_down + np.abs(st.reversal), r_up), r_down)
    _readonly(r_up, r_down, r_bi)
    hi_up, lo_up = st.mean_up + k * st.s_up, st.mean_up - k * st.s_up
    hi_down, lo_down = st.mean_down + k * st.s_down, st.mean_down - k * st.s_down
    return Iso230Result(
        edition=edition,
        coverage=k,
        stats=st,
        repeatability_up=r_up,
        repeatability_down=r_down,
        repeatability=r_bi,
        A=float(np.concatenate([hi_up, hi_down]).max() - np.concatenate([lo_up, lo_down]).min()),
        A_up=float(hi_up.max() - lo_up.min()),
        A_down=float(hi_down.max() - lo_down.min()),
        B=float(np.abs(st.reversal).max()),
        B_mean=float(st.reversal.mean()),
        E=_spread(st.mean_up, st.mean_down),
        E_up=float(np.ptp(st.mean_up)),
        E_down=float(np.ptp(st.mean_down)),
        M=float(np.ptp(st.mean)),
        R=float(r_bi.max()),
        R_up=float(r_up.max()),
        R_down=float(r_down.max()),
        S_up=float(st.s_up.max()),
        S_down=float(st.s_down.max()),
        warnings=_warnings(run),
    )


#: names accepted by :func:`axiscal.positioning.report.evaluate_positioning_file` and ``--standard``
STANDARDS = ("iso230-2:2014", "iso230-2:2006", "iso230-2:1997", "iso230-2:1988", "jis-b6192", "vdi3441")


def iso_edition(standard: str) -> str:
    """The ISO 230-2 edition a standard's name evaluates with ("jis-b6192" -> "1988").

    Parameters
    ----------
    standard : str
        One of :data:`STANDARDS` other than ``"vdi3441"``.

    Returns
    -------
    str
        A key of :data:`ISO_EDITIONS`.

    Raises
    ------
    AxiscalError
        For a name that is not an ISO 230-2 edition or ``"jis-b6192"``.

    Examples
    --------
    >>> iso_edition("jis-b6192"), iso_edition("iso230-2:1997")
    ('1988', '1997')
    """
    if not isinstance(standard, str):
        check_choice("standard", standard, STANDARDS)
    if standard == "jis-b6192":
        return "1988"
    prefix = "iso230-2:"
    if standard.startswith(prefix) and standard[len(prefix):] in ISO_EDITIONS:
        return standard[len(prefix):]
    raise AxiscalError(f"unknown standard '{standard}'; use one of {', '.join(STANDARDS)}")
