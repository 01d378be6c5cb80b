"""A positioning test's deviations, checked and arranged per target (ISO 230-2 clause 2.11: actual position reached minus target).

The API is in metres (radians for a rotary axis); files and JSON carry micrometres in their names.
The estimators built on it are :mod:`axiscal.positioning.evaluation` (ISO 230-2) and
:mod:`axiscal.positioning.vdi3441` (VDI/DGQ 3441).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_instance
from axiscal.units import MM, UM

__all__ = [
    "TURN",
    "PositioningRun",
    "require_finite",
    "covers_circle",
    "paper003_table4_run",
]


#: one revolution, radians
TURN = 2.0 * np.pi
# largest magnitude of a target or deviation a run holds (metres or radians): beyond it a value
# has no physical meaning and the figures would overflow
_LIMIT = 1e6


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
    >>> from axiscal.positioning.evaluation import iso230_2
    >>> round(float(iso230_2(paper003_table4_run()).repeatability[0]) / UM, 3)  # R_1 as printed
    8.451
    """
    up = np.array([[0.0, 1.2, 1.0], [1.7, 2.0, 1.1]]) * UM
    down = np.array([[3.6, -0.2, 3.3], [4.1, 1.9, 2.2]]) * UM
    return PositioningRun(np.array([0.0, 20.0]) * MM, up, down, source="paper 003, Table 4")
