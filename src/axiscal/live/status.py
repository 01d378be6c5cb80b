"""What a live source is doing: its state, connections and last problem, for the dashboard and the progress line.

Every source of :mod:`axiscal.live.sources` keeps one :class:`SourceStatus` as ``source.status``.
"""

from __future__ import annotations

from dataclasses import dataclass, field

__all__ = ["SourceStatus"]


@dataclass
class SourceStatus:
    """What a source is doing, for the dashboard and the progress line.

    Attributes
    ----------
    description : str
        What the source is (``"sim (1000 Hz, diagonal)"``, a file, an address).
    state : str
        One of ``"connecting"``, ``"streaming"``, ``"retrying"``, ``"finished"``.
    connections, retries : int
        Connections made and retries after a failure.
    message : str
        The last problem, if any.
    attempt_times : list of float
        Monotonic times of the connection attempts.
    """

    description: str
    state: str = "connecting"
    connections: int = 0
    retries: int = 0
    message: str = ""
    attempt_times: list[float] = field(default_factory=list)
