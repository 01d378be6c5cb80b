"""TouchDRO adapters: glass and magnetic scales read as raw counts, streamed as ``;``-terminated tokens.

Source: the TouchDRO adapter protocol (touchdro.com, "Adapter communication protocol"). The adapter
sends, with no line end needed, tokens ``X1234;Y-567;Z0;W89;`` (the axis letter, either case, then the
signed count since power on), and ``T<rpm>;`` (tachometer) and ``P0;`` / ``P1;`` (probe), which are not
lengths and are passed over. A count becomes a length with the scale's counts per millimetre
(``--counts-per-mm``: 200 for a 5 µm scale, 1000 for a 1 µm scale). The adapter streams on its own
(Bluetooth serial at its set rate, 115200 by default here); a sample's time is the host's clock.
"""

from __future__ import annotations

import math
import time

from axiscal.devices.base import InstrumentSource, Samples

__all__ = ["TouchDroSource", "TOUCHDRO_AXES"]

#: the axis letters of a TouchDRO adapter
TOUCHDRO_AXES = ("X", "Y", "Z", "W")


class TouchDroSource(InstrumentSource):
    """One axis of a TouchDRO adapter.

    Parameters
    ----------
    link : a link
    axis : str
        ``X``, ``Y``, ``Z`` or ``W``.
    counts_per_mm : float
        The scale's counts per millimetre.
    description : str
    """

    def __init__(self, link, axis: str, counts_per_mm: float, description: str):
        super().__init__(link, description)
        self.axis = axis.upper().encode()
        self.counts_per_mm = counts_per_mm
        self.resolution_m = 1e-3 / counts_per_mm
        self._tail = b""
        self._t0 = time.monotonic()

    def _decode(self, data: bytes) -> Samples:
        tokens = (self._tail + data).split(b";")
        self._tail = tokens.pop()
        if len(self._tail) > 64:
            t = time.monotonic() - self._t0
            self._fault(t, f"not a TouchDRO token: {self._tail[:20]!r}...")
            self._tail = b""
        t_out, rows, bad = [], [], []
        for raw in tokens:
            token = raw.strip(b"\r\n\t ")
            if not token:
                continue
            letter = token[:1].upper()
            if letter != self.axis:
                if letter not in b"XYZWTP":
                    self._fault(time.monotonic() - self._t0, f"not a TouchDRO token: {token[:20]!r}")
                continue
            body = token[1:]
            t = time.monotonic() - self._t0
            try:
                count = int(body)
            except ValueError:
                self._fault(t, f"not a count: {token[:20]!r}")
                t_out.append(t)
                rows.append([math.nan] + [math.nan] * (len(self.channels) - 1))
                bad.append(True)
                continue
            t_out.append(t)
            rows.append([count / self.counts_per_mm] + [math.nan] * (len(self.channels) - 1))
            bad.append(False)
        return Samples.of(t_out, rows, bad, len(self.channels))
