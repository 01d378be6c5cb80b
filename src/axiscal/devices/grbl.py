"""grbl 1.1 and grblHAL, on a serial port (115200 8N1) or, for grblHAL, on TCP.

Source: the grbl 1.1 interface documentation (gnea/grbl wiki: "Grbl v1.1 Interface", "Grbl v1.1
Commands"). On reset grbl prints ``Grbl 1.1h ['$' for help]``. Each line sent is answered ``ok`` (parsed
and buffered, not done) or ``error:N``; the real-time ``?`` (no line end) is answered
``<Idle|MPos:0.000,0.000,0.000|FS:0,0>`` (states Idle, Run, Hold:n, Jog, Alarm, Door:n, Check, Home,
Sleep; ``WPos`` instead of ``MPos`` when so set, ``WCO`` the work offset); ``ALARM:N`` reports an alarm.
``G4 P0.01`` is answered ``ok`` only once the planner is empty: the move before it has ended.
``!`` holds the feed, ``~`` resumes, 0x18 resets. Soft limits: ``$20=1`` with ``$130..$132`` the travel
(mm); with the default homing direction (``$23=0``) machine positions run from ``-travel`` to 0.
While a move runs ``?`` is asked every 0.2 s: a grbl that stops answering ends the run within 2 s.
"""

from __future__ import annotations

import re
import time

from axiscal.devices.controller import SILENCE_S, Controller, move_words
from axiscal.devices.lines import LineChannel
from axiscal.errors import AxiscalError

__all__ = ["GrblController", "GRBL_ERRORS", "GRBL_ALARMS", "parse_status"]

#: grbl 1.1's error codes (the commonest; the wiki lists them all)
GRBL_ERRORS = {
    1: "G-code words consist of a letter and a value; the letter was not found",
    2: "numeric value format is not valid or missing an expected value",
    3: "grbl '$' system command was not recognized or supported",
    8: "grbl '$' command cannot be used unless grbl is IDLE",
    9: "G-code locked out during alarm or jog state",
    15: "jog target exceeds machine travel",
    20: "unsupported or invalid g-code command found in block",
    22: "feed rate has not yet been set or is undefined",
    33: "the motion command has an invalid target",
}
#: grbl 1.1's alarm codes
GRBL_ALARMS = {
    1: "hard limit triggered: position likely lost, re-homing recommended",
    2: "G-code motion target exceeds machine travel (soft limit)",
    3: "reset while in motion: position likely lost, re-homing recommended",
    6: "homing fail: reset during active homing cycle",
    8: "homing fail: cycle failed to clear limit switch when pulling off",
    9: "homing fail: could not find limit switch within search distance",
}
_STATUS = re.compile(r"^<([A-Za-z]+)(?::\d+)?\|(.*)>$")
_AXES = "XYZABC"


def parse_status(line: str) -> tuple[str, dict[str, list[float]]] | None:
    """A ``<State|MPos:...|...>`` report as (state, fields with numbers), or None.

    Parameters
    ----------
    line : str

    Returns
    -------
    tuple or None
    """
    m = _STATUS.match(line.strip())
    if m is None:
        return None
    fields: dict[str, list[float]] = {}
    for part in m.group(2).split("|"):
        name, _, values = part.partition(":")
        try:
            fields[name] = [float(v) for v in values.split(",") if v.strip()]
        except ValueError:
            continue
    return m.group(1), fields


class GrblController(Controller):
    """A grbl 1.1 or grblHAL board.

    Parameters
    ----------
    link : a link
        A serial port at 115200 8N1, or a TCP link to a grblHAL board.
    where : str
        Its port or address.
    """

    def __init__(self, link, where: str):
        self.description = f"grbl on {where}"
        super().__init__()
        self.io = LineChannel(link, self.description)
        self.banner = ""
        self._wco = [0.0] * 6
        self._pos = [float("nan")] * 6
        self.state = "?"
        deadline = time.monotonic() + 2.5
        self.io.send(b"\r\n")
        asked = 0.0
        while time.monotonic() < deadline:
            if time.monotonic() - asked > 0.5:
                self.io.send(b"?")
                asked = time.monotonic()
            line = self.io.next_line(0.1)
            if line is None:
                continue
            if line.startswith("Grbl") or line.startswith("GrblHAL"):
                self.banner = line
            if self._take(line) is not None:
                while self.io.next_line(0.15) is not None:  # what answered the wake-up line
                    pass
                break
        else:
            raise AxiscalError(f"{self.description}: no grbl answers (no banner, no status within 2.5 s): check the port and"
                               " the baud rate (115200)")

    # -- replies ------------------------------------------------------------------------------
    def _take(self, line: str) -> str | None:
        """Handle a status report or alarm line; return the state of a status report."""
        status = parse_status(line)
        if status is not None:
            state, fields = status
            self.state = state
            if "WCO" in fields:
                self._wco = (fields["WCO"] + [0.0] * 6)[:6]
            if "MPos" in fields:
                mpos = (fields["MPos"] + [0.0] * 6)[:6]
                self._pos = [m - w for m, w in zip(mpos, self._wco)]
            elif "WPos" in fields:
                self._pos = (fields["WPos"] + [0.0] * 6)[:6]
            return state
        if line.startswith("ALARM:"):
            code = line[6:].strip()
            self.state = "Alarm"
            meaning = GRBL_ALARMS.get(int(code), "alarm") if code.isdigit() else "alarm"
            raise AxiscalError(f"{self.description} is in alarm ({line}: {meaning}): clear it ($X or $H) and home first")
        return None

    def _error(self, line: str) -> str:
        code = line[6:].strip()
        return f"{line} ({GRBL_ERRORS.get(int(code), 'see the grbl error codes')})" if code.isdigit() else line

    def _command(self, text: str, *, during: str) -> None:
        """Send a line and wait for its ``ok``, asking ``?`` meanwhile; errors and alarms end it in one line."""
        self.io.send(text)
        asked = time.monotonic()
        self.io.last_heard = time.monotonic()
        while True:
            line = self.io.next_line(0.05)
            if line is not None:
                if line == "ok":
                    return
                if line.startswith("error:"):
                    raise AxiscalError(f"{self.description} refused {during}: {self._error(line)}")
                self._take(line)
                if self.state == "Alarm":
                    raise AxiscalError(f"{self.description} went into alarm during {during}")
            if time.monotonic() - asked >= 0.2:
                self.io.send(b"?")
                asked = time.monotonic()
            try:
                self.io.require_heard(SILENCE_S)
            except OSError as exc:
                raise self.lost(str(exc)) from None

    def _status(self) -> str:
        self.io.send(b"?")
        deadline = time.monotonic() + SILENCE_S
        while time.monotonic() < deadline:
            line = self.io.next_line(0.05)
            if line is None:
                continue
            state = self._take(line)
            if state is not None:
                return state
        raise self.lost(f"no status report within {SILENCE_S:g} s")

    # -- the controller's interface -----------------------------------------------------------
    def check_ready(self, axis: str) -> None:
        if axis.upper() not in _AXES:
            raise AxiscalError(f"axis must be one of {', '.join(_AXES)}, not {axis!r}")
        state = self._status()
        if state == "Alarm":
            raise AxiscalError(f"{self.description} is in alarm: home the machine ($H) first (axiscal run never homes)")
        if state not in ("Idle",):
            raise AxiscalError(f"{self.description} is {state}, not Idle: finish or reset what runs first")
        self.status.position_m = self.position(axis)

    def settings(self) -> dict[int, float]:
        """grbl's ``$$`` settings as it lists them: number -> value (``{20: 1.0, 130: 200.0, ...}``).

        Returns
        -------
        dict of int to float
            Empty when grbl listed none within the silence allowed.
        """
        self.io.send("$$")
        settings: dict[int, float] = {}
        deadline = time.monotonic() + SILENCE_S
        while time.monotonic() < deadline:
            line = self.io.next_line(0.05)
            if line is None:
                continue
            if line == "ok" and settings:
                break
            m = re.match(r"^\$(\d+)=([-\d.]+)", line)
            if m:
                settings[int(m.group(1))] = float(m.group(2))
        return settings

    def limits(self, axis: str) -> tuple[float, float] | None:
        settings = self.settings()
        index = _AXES.index(axis.upper())
        if settings.get(20, 0) != 1 or 130 + index not in settings:
            return None
        travel = settings[130 + index] * 1e-3
        positive = int(settings.get(23, 0)) >> index & 1
        mpos = (0.0, travel) if positive else (-travel, 0.0)
        offset = self._wco[index] * 1e-3
        return mpos[0] - offset, mpos[1] - offset

    def position(self, axis: str) -> float:
        self._status()
        return self._pos[_AXES.index(axis.upper())] * 1e-3

    def move_to(self, axis: str, position_m: float, feed_m_per_s: float) -> None:
        axis = axis.upper()
        words = move_words(axis, position_m, feed_m_per_s)  # refused before anything is sent
        self.status.state = "moving"
        self._command(f"G21 G90 G1 {words}",
                      during=f"the move to {axis} {position_m * 1e3:.4f} mm")
        self._command("G4 P0.01", during=f"the move to {axis} {position_m * 1e3:.4f} mm")  # ok once the planner is empty
        self.status.state = "idle"
        self.status.position_m = self._pos[_AXES.index(axis)] * 1e-3

    def stop(self) -> None:
        try:
            self.io.send(b"!")
            time.sleep(0.2)
            self.io.send(b"\x18")
        except OSError:
            pass

    def close(self) -> None:
        self.io.close()
        super().close()
