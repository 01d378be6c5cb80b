"""Positioning accuracy and repeatability of a numerically controlled axis from a bidirectional test.

Implements the estimators ISO 230-2:2014 defines for a test of 5 runs each way (adopted
unchanged as GB/T 17421.2-2016), with the coverage factor k = 2 of the 1997, 2006 and 2014
editions or k = 3 of the 1988 edition (``edition="1988"``, the "3 sigma" figures JIS B 0182
term 346 also uses), and VDI/DGQ 3441 (1977) positional uncertainty. Paper 003 Table 4 applies these estimators to three
runs. See docs/positioning.md for every symbol, the sign convention and how the editions differ.

Deviation convention (ISO 230-2): ``x_ij = P_ij - P_i``, actual position reached minus target.
The API is in metres; files and JSON carry micrometres in their names.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_choice, check_instance
from axiscal.units import MM, UM

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

#: one revolution, radians
TURN = 2.0 * np.pi

# largest magnitude of a target or deviation a run holds (metres or radians): beyond it a value
# has no physical meaning and the figures would overflow
_LIMIT = 1e6

#: ISO 230-2 editions this module evaluates, and their coverage factor k
ISO_EDITIONS: dict[str, int] = {"2014": 2, "2006": 2, "1997": 2, "1988": 3}

#: travel above which ISO 230-2 tests with one run each way (no R, no A), metres
LONG_AXIS_M = 2.0

#: ISO 230-2 figures that need both directions: NaN (null, "n/a") for a unidirectional test
BIDIRECTIONAL_SYMBOLS = ("A", "B", "B_mean", "E", "M", "R")

ONE_DIRECTION_WARNING = (
    "one-direction test ({direction} only): the reversal value B and the bidirectional figures A, E, M and R"
    " do not apply (n/a)"
)

NO_S_WARNING = (
    "only one run per direction: the standard uncertainty s cannot be estimated, "
    "so s, the repeatabilities R and the accuracies A are not given (NaN / null)"
)


@dataclass(frozen=True)
class PositioningRun:
    """Deviations of a positioning test, checked and arranged per target.

    A bidirectional test holds both arrays; a unidirectional test (ISO 230-2 figures for one
    direction only) holds one of them and None for the other. A rotary axis (``rotary=True``)
    holds its targets and deviations in radians, a linear axis in metres.

    Attributes
    ----------
    targets : ndarray, shape (m,), metres (radians for a rotary axis)
        Target positions P_i, strictly increasing.
    deviations_up : ndarray, shape (m, n), metres (radians), or None
        ``x_ij`` for the approach in the positive direction (run j = 0..n-1); None for a test in
        the - direction only.
    deviations_down : ndarray, shape (m, n), metres (radians), or None
        ``x_ij`` for the approach in the negative direction; None for a test in the + direction only.
    source : str
        Where the data came from (a file name), for messages.
    rotary : bool
        True for a rotary axis: targets and deviations in radians.

    Raises
    ------
    AxiscalError
        Fewer than 2 targets, arrays of the wrong shape, unequal run counts per direction, no
        direction at all, a non-finite value, or targets that do not strictly increase.

    Examples
    --------
    >>> import numpy as np
    >>> PositioningRun(np.array([0.0, 0.1]), np.zeros((2, 5)), np.zeros((2, 5))).runs
    5
    >>> PositioningRun(np.array([0.0, 0.1]), np.zeros((2, 3)), None).directions
    ('+',)
    """

    targets: np.ndarray
    deviations_up: np.ndarray | None
    deviations_down: np.ndarray | None
    source: str = "<data>"
    rotary: bool = False

    def __post_init__(self) -> None:
        check_instance("source", self.source, str)
        check_instance("rotary", self.rotary, (bool, np.bool_))
        targets = np.array(check_array("targets", self.targets, finite=False, unit=""), dtype=float)
        if self.deviations_up is None and self.deviations_down is None:
            raise AxiscalError(f"{self.source}: no deviations in either direction")
        up = None if self.deviations_up is None else np.array(
            check_array("deviations_up", self.deviations_up, finite=False, unit=""), dtype=float)
        down = None if self.deviations_down is None else np.array(
            check_array("deviations_down", self.deviations_down, finite=False, unit=""), dtype=float)
        given = [a for a in (up, down) if a is not None]
        if targets.ndim != 1 or targets.size < 2:
            raise AxiscalError(f"{self.source}: at least 2 target positions are needed, got {targets.size}")
        if any(a.ndim != 2 or a.shape[0] != targets.size for a in given):
            shapes = " and ".join(str(a.shape) for a in given)
            raise AxiscalError(
                f"{self.source}: deviations must have shape (targets, runs) = ({targets.size}, n) for each direction,"
                f" got {shapes}"
            )
        if up is not None and down is not None and up.shape[1] != down.shape[1]:
            raise AxiscalError(
                f"{self.source}: unequal run counts: {up.shape[1]} runs in + direction, {down.shape[1]} in - direction"
            )
        if given[0].shape[1] < 1:
            raise AxiscalError(f"{self.source}: no runs")
        if not (np.all(np.isfinite(targets)) and all(np.all(np.isfinite(a)) for a in given)):
            raise AxiscalError(f"{self.source}: targets and deviations must be finite numbers (found NaN or infinity)")
        for name, value in (("targets", targets), ("deviations_up", up), ("deviations_down", down)):
            if value is not None and value.size and np.abs(value).max() > _LIMIT:
                raise AxiscalError(
                    f"{self.source}: {name} holds {np.abs(value).max():g}, beyond any physical value (more than {_LIMIT:g})"
                )
        if np.any(np.diff(targets) <= 0):
            raise AxiscalError(f"{self.source}: target positions must be strictly increasing")
        for name, value in (("targets", targets), ("deviations_up", up), ("deviations_down", down)):
            if value is not None:
                value.setflags(write=False)
            object.__setattr__(self, name, value)

    @property
    def runs(self) -> int:
        """Number of runs n in each direction."""
        present = self.deviations_up if self.deviations_up is not None else self.deviations_down
        return int(present.shape[1])

    @property
    def directions(self) -> tuple[str, ...]:
        """The directions tested: ``("+", "-")``, ``("+",)`` or ``("-",)``."""
        return tuple(d for d, a in (("+", self.deviations_up), ("-", self.deviations_down)) if a is not None)

    @property
    def bidirectional(self) -> bool:
        """True when both directions were tested."""
        return len(self.directions) == 2


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


def require_finite(**values: float | None) -> None:
    """Refuse a NaN or infinite number given for an option, naming the option by its keyword.

    Parameters
    ----------
    **values : float or None
        Keyword -> value; None (an option not given) and non-numbers are passed over.

    Returns
    -------
    None
        When every number is finite.

    Raises
    ------
    AxiscalError
        ``"<keyword> must be a finite number, got nan"`` for the first value that is not finite.

    Examples
    --------
    >>> require_finite(start_m=0.0, end_m=None)
    >>> require_finite(end_m=float("inf"))
    Traceback (most recent call last):
    axiscal.errors.AxiscalError: end_m must be a finite number, got inf
    """
    for name, value in values.items():
        if isinstance(value, (int, float, np.floating)) and not isinstance(value, bool) and not np.isfinite(value):
            raise AxiscalError(f"{name} must be a finite number, got {value}")


def covers_circle(targets: np.ndarray) -> bool:
    """Whether the targets of a rotary axis (radians, in [0, 2 pi), increasing) go round the circle.

    The circle counts as covered when the gap from the last target round to the first is no
    more than twice the largest spacing between neighbouring targets (0, 30, ..., 330 deg covers
    it; 0..90 deg does not).

    Parameters
    ----------
    targets : ndarray, shape (m,), radians
        Target positions, increasing, within one turn.

    Returns
    -------
    bool

    Examples
    --------
    >>> import numpy as np
    >>> covers_circle(np.radians(np.arange(0, 360, 30))), covers_circle(np.radians([0, 45, 90]))
    (True, False)
    """
    targets = check_array("targets_rad", targets, ndim=1, min_len=2)
    wrap = targets[0] + TURN - targets[-1]
    return bool(wrap <= 2.0 * float(np.diff(targets).max()) * (1 + 1e-9))


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


def paper003_table4_run() -> PositioningRun:
    """The three runs at two targets printed in paper 003, Table 4, as a run to try the estimators on.

    Targets 0 and 20 mm; per target the column marked "up" is the + approach, the one marked
    "down" the - approach (three runs each). See docs/positioning.md for how the table reads.

    Returns
    -------
    PositioningRun
        Shape (2, 3) per direction, metres; ``source`` is "paper 003, Table 4".

    Examples
    --------
    >>> from axiscal.units import UM
    >>> round(float(iso230_2(paper003_table4_run()).repeatability[0]) / UM, 3)  # R_1 as printed
    8.451
    """
    up = np.array([[0.0, 1.2, 1.0], [1.7, 2.0, 1.1]]) * UM
    down = np.array([[3.6, -0.2, 3.3], [4.1, 1.9, 2.2]]) * UM
    return PositioningRun(np.array([0.0, 20.0]) * MM, up, down, source="paper 003, Table 4")
