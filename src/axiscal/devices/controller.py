"""What a machine controller does for a run: say it is ready, tell its limits, move one axis and say when done.

Every driver (LinuxCNC, grbl, Marlin, Klipper, Moonraker, the virtual machine) has this interface, so
``axiscal run`` drives them alike:

- ``check_ready(axis)``: one line (an :class:`~axiscal.errors.AxiscalError`) when the machine is not
  homed, in e-stop, in alarm or in error; the run never homes a machine;
- ``limits(axis) -> (low_m, high_m) or None``: its soft limits where it can tell them;
- ``move_to(axis, position_m, feed_m_per_s)``: an absolute move of that axis alone, returning once the
  controller reports it done; a controller that stops answering ends the move within
  :data:`SILENCE_S` seconds with one line;
- ``position(axis) -> metres``: where it says the axis is;
- ``stop()``: feed hold and abort (Ctrl-C), ``close()``.

Positions are metres in the API; each driver speaks its controller's unit (mm) on the wire.
"""

from __future__ import annotations

from abc import ABC, abstractmethod

import threading
import time
from dataclasses import dataclass

from axiscal.errors import AxiscalError

__all__ = ["SILENCE_S", "Controller", "ControllerStatus", "Heartbeat", "move_words"]

#: longest silence of a controller before a run stops, seconds (the run has stopped within 2 s of its last answer)
SILENCE_S = 1.5


def move_words(axis: str, position_m: float, feed_m_per_s: float, *, places: int = 4, feed_places: int = 1) -> str:
    """The words of an absolute move as a control reads them: ``X12.3456 F1000``, bounded, never an exponent.

    Parameters
    ----------
    axis : str
        The axis letter.
    position_m : float, metres
        Within +/-99999.999 mm (:data:`axiscal.io.gcode.writer.MAX_POSITION_MM`).
    feed_m_per_s : float, m/s
        At most 100 000 mm/min (:data:`axiscal.io.gcode.writer.MAX_FEED_MM_MIN`).
    places, feed_places : int, keyword-only
        Decimals of the position (mm) and of the feed (mm/min) the controller is sent.

    Returns
    -------
    str

    Raises
    ------
    AxiscalError
        For a position or a feed a control's word cannot hold (nothing is sent).

    Examples
    --------
    >>> move_words("X", 0.0123456, 1000 / 60e3)
    'X12.3456 F1000'
    """
    from axiscal.io.gcode.writer import feed_word, position_word

    return (f"{axis}{position_word(f'the {axis} position in mm', position_m * 1e3, places)}"
            f" F{feed_word(feed_m_per_s * 60e3, feed_places)}")


@dataclass
class ControllerStatus:
    """What a controller is doing, for a status light.

    Attributes
    ----------
    description : str
    state : str
        ``"connected"``, ``"moving"``, ``"idle"``, ``"lost"`` or ``"closed"``.
    position_m : float, metres
        The last position it reported for the axis driven (NaN before any).
    message : str
    """

    description: str
    state: str = "connected"
    position_m: float = float("nan")
    message: str = ""


class Controller(ABC):
    """Base of the controller drivers (see the module's text for the interface).

    Attributes
    ----------
    description : str
        The controller and its address.
    status : ControllerStatus
    """

    description = "controller"

    def __init__(self) -> None:
        self.status = ControllerStatus(self.description)

    @abstractmethod
    def check_ready(self, axis: str) -> None:
        """Refuse, in one line, a machine that is not homed, in e-stop, alarm or error."""

    def limits(self, axis: str) -> tuple[float, float] | None:
        return None

    @abstractmethod
    def move_to(self, axis: str, position_m: float, feed_m_per_s: float) -> None:
        """An absolute move of ``axis`` alone, returning once the controller reports it done."""

    @abstractmethod
    def position(self, axis: str) -> float:
        """Where the controller says ``axis`` is, metres."""

    def stop(self) -> None:
        """Feed hold and abort what runs (Ctrl-C)."""

    def close(self) -> None:
        self.status.state = "closed"

    def lost(self, what: str) -> AxiscalError:
        """The one line for a controller that stopped answering."""
        self.status.state = "lost"
        self.status.message = what
        return AxiscalError(f"{self.description}: {what}: the run stopped (the partial run is kept; resume=True goes on)")


class Heartbeat:
    """Asks a controller something every ``period_s`` on a second channel while a move runs.

    ``ask()`` must return within :data:`SILENCE_S` or raise ``OSError``; when it fails, or no answer has
    come for ``SILENCE_S``, ``failed`` is set and ``on_fail`` is called (which unblocks the move).

    Parameters
    ----------
    ask : callable
        Returns the axis position (metres) or raises OSError.
    on_fail : callable
        Called once, with the reason, from the heartbeat's thread.
    period_s : float
    """

    def __init__(self, ask, on_fail, *, period_s: float = 0.2):
        self.ask, self.on_fail, self.period_s = ask, on_fail, period_s
        self.failed: str | None = None
        self.last_answer = time.monotonic()
        self.position_m = float("nan")
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, name="controller-heartbeat", daemon=True)

    def __enter__(self) -> "Heartbeat":
        self.last_answer = time.monotonic()
        self._thread.start()
        return self

    def __exit__(self, *exc) -> None:
        self._stop.set()
        self._thread.join(timeout=SILENCE_S + 1)

    def _run(self) -> None:
        while not self._stop.wait(self.period_s):
            try:
                self.position_m = self.ask()
                self.last_answer = time.monotonic()
            except OSError as exc:
                reason = f"no answer ({exc.strerror or exc})"
            else:
                continue
            if time.monotonic() - self.last_answer >= SILENCE_S or "closed" in reason:
                self.failed = reason
                self.on_fail(reason)
                return
