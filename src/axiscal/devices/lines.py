"""A line-oriented conversation over a link: send a line, read the lines that come back, with a time limit.

The serial controllers (grbl, Marlin) answer each line with ``ok`` (or an error) and interleave
status reports and keep-alives; :class:`LineChannel` keeps the partial last line and hands whole lines
to the driver, raising ``OSError`` when nothing at all arrives for a given silence.
"""

from __future__ import annotations

import errno
import time
from collections import deque

__all__ = ["LineChannel"]


class LineChannel:
    """Lines over a link (:mod:`axiscal.devices.links`).

    Parameters
    ----------
    link : a link
    where : str
        The device, named in errors.
    """

    def __init__(self, link, where: str):
        self.link = link
        self.where = where
        self._tail = b""
        self._lines: deque[str] = deque()
        self.last_heard = time.monotonic()

    def send(self, text: str | bytes) -> None:
        data = text if isinstance(text, bytes) else text.encode("ascii") + b"\n"
        self.link.write(data)

    def next_line(self, timeout_s: float) -> str | None:
        """The next whole line (without its end), or None when none came within ``timeout_s``."""
        deadline = time.monotonic() + timeout_s
        while not self._lines:
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                return None
            data = self.link.read(min(remaining, 0.05))
            if not data:
                continue
            self.last_heard = time.monotonic()
            parts = (self._tail + data).replace(b"\r\n", b"\n").replace(b"\r", b"\n").split(b"\n")
            self._tail = parts.pop()
            if len(self._tail) > 4096:
                self._tail = b""
            for part in parts:
                text = part.decode("ascii", "replace").strip()
                if text:
                    self._lines.append(text)
        return self._lines.popleft()

    def silent_for(self) -> float:
        """Seconds since the device last sent anything."""
        return time.monotonic() - self.last_heard

    def require_heard(self, silence_s: float) -> None:
        """Raise OSError when the device has said nothing for ``silence_s`` seconds."""
        if self.silent_for() >= silence_s:
            raise OSError(errno.ETIMEDOUT, f"{self.where} has not answered for {silence_s:g} s")

    def close(self) -> None:
        self.link.close()
