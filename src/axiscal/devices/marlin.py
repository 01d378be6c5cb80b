"""Marlin firmware on a serial port (115200 8N1 by default; 250000 on many boards).

Source: the Marlin G-code reference (marlinfw.org/meta/gcode). Each line is answered ``ok`` once
taken; ``M400`` is answered once all moves have finished; while it waits Marlin sends ``echo:busy:
processing`` keep-alives, every ``M113`` seconds (set to 1 s here). ``M114`` answers ``X:.. Y:.. Z:..
E:.. Count ...``; ``M211`` reports the soft endstops (``Soft endstops: On Min: X0.00 ... Max: X200.00
...``). A move before homing is refused with ``echo:Home XYZ first`` where the firmware is built so;
``Error:`` lines and ``!!`` are errors. ``M410`` stops at once (Ctrl-C). A Marlin that sends nothing for
2 s while a move runs ends the run.
"""

from __future__ import annotations

import re
import time

from axiscal.devices.controller import SILENCE_S, Controller, move_words
from axiscal.devices.lines import LineChannel
from axiscal.errors import AxiscalError

__all__ = ["MarlinController"]

_POSITION = re.compile(r"([XYZE]):\s*(-?\d+(?:\.\d+)?)")
_ENDSTOP = re.compile(r"([XYZ])\s*:?\s*(-?\d+(?:\.\d+)?)")


class MarlinController(Controller):
    """A Marlin board.

    Parameters
    ----------
    link : a link
    where : str
    """

    def __init__(self, link, where: str):
        self.description = f"Marlin on {where}"
        super().__init__()
        self.io = LineChannel(link, self.description)
        self._pos: dict[str, float] = {}
        self._soft: dict[str, tuple[float, float]] = {}
        time.sleep(0.05)
        try:
            self._command("M113 S1", during="setting the keep-alive", timeout_s=3.0)
        except AxiscalError as exc:
            raise AxiscalError(f"{self.description}: no Marlin answers ({exc})") from None

    def _take(self, line: str) -> None:
        low = line.lower()
        if line.startswith("Error:") or line.startswith("!!"):
            raise AxiscalError(f"{self.description} reports an error: {line}")
        if "home" in low and "first" in low:
            raise AxiscalError(f"{self.description}: {line.removeprefix('echo:')}: home the machine first (axiscal run never homes)")
        if line.startswith("X:") and "Count" in line:
            head = line.split("Count")[0]
            self._pos = {k: float(v) for k, v in _POSITION.findall(head)}
        if "Soft endstops" in line and "Min:" in line and "Max:" in line:
            mins = dict(_ENDSTOP.findall(line.split("Min:")[1].split("Max:")[0]))
            maxs = dict(_ENDSTOP.findall(line.split("Max:")[1]))
            self._soft = {k: (float(mins[k]), float(maxs[k])) for k in mins if k in maxs}
            if "Off" in line.split("Min:")[0]:
                self._soft = {}

    def _command(self, text: str, *, during: str, timeout_s: float | None = None) -> None:
        self.io.send(text)
        self.io.last_heard = time.monotonic()
        began = time.monotonic()
        while True:
            line = self.io.next_line(0.05)
            if line is not None:
                if line == "ok" or line.startswith("ok "):
                    return
                self._take(line)
            silence = SILENCE_S if timeout_s is None else timeout_s
            if self.io.silent_for() >= silence or (timeout_s is not None and time.monotonic() - began > timeout_s):
                raise self.lost(f"no answer to {text.split()[0]} for {silence:g} s during {during}")

    def check_ready(self, axis: str) -> None:
        if axis.upper() not in "XYZ":
            raise AxiscalError(f"axis must be X, Y or Z, not {axis!r}")
        self._command("M114", during="asking the position")
        self.status.position_m = self.position(axis)

    def limits(self, axis: str) -> tuple[float, float] | None:
        self._command("M211", during="asking the soft endstops")
        if axis.upper() not in self._soft:
            return None
        low, high = self._soft[axis.upper()]
        return low * 1e-3, high * 1e-3

    def position(self, axis: str) -> float:
        self._command("M114", during="asking the position")
        return self._pos.get(axis.upper(), float("nan")) * 1e-3

    def move_to(self, axis: str, position_m: float, feed_m_per_s: float) -> None:
        axis = axis.upper()
        words = move_words(axis, position_m, feed_m_per_s)  # refused before anything is sent
        during = f"the move to {axis} {position_m * 1e3:.4f} mm"
        self.status.state = "moving"
        self._command("G90", during=during)
        self._command(f"G1 {words}", during=during)
        self._command("M400", during=during)
        self.status.state = "idle"
        self.status.position_m = position_m

    def stop(self) -> None:
        try:
            self.io.send("M410")
        except OSError:
            pass

    def close(self) -> None:
        self.io.close()
        super().close()
