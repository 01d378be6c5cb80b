"""Sylvac (and Bowers) gauges with the Opto RS interface: dial indicators, probes, calipers.

Source: the Sylvac / Bowers Opto RS manual. The cable is a duplex RS-232 link at 4800 baud, 7 data bits,
even parity, 2 stop bits (``7E2``). The computer sends ``?\\r``; the gauge answers its display,
``[+|-| ]int.frac\\r``, in the display's unit (mm, or inch on an inch instrument: say ``--unit in``).
``ERR<n>\\r`` is no reading (0 sensor, 1 command, 2 parity, 3 range). Other commands (``OUT1`` continuous
output, ``MM`` / ``IN`` units, ``ID?`` identity) are not used: axiscal asks for each reading.
The gauge's resolution is the last digit of its reply (0.001 mm = 1 µm); a gauge flickers by one count
at rest, so its default stop stability is two counts.
"""

from __future__ import annotations

import re

from axiscal.devices.base import PolledSource
from axiscal.devices.links import SerialFraming

__all__ = ["SYLVAC_FRAMING", "SYLVAC_ERRORS", "SylvacSource", "parse_decimal_reply"]

#: the Opto RS framing
SYLVAC_FRAMING = SerialFraming(4800, 7, "E", 2)
#: meaning of ERR<n>
SYLVAC_ERRORS = {0: "sensor error", 1: "command error", 2: "parity error", 3: "out of range"}
_REPLY = re.compile(rb"^([+\- ]?)\s*(\d{1,9})(?:\.(\d{1,9}))?$")
_UNITS = {"mm": 1e-3, "in": 25.4e-3}


def parse_decimal_reply(text: bytes, factor_m: float) -> tuple[float, float] | None:
    """A gauge's decimal reply as (metres, resolution in metres), or None when it is not one.

    Parameters
    ----------
    text : bytes
        ``+12.345``, ``-0.0010``, `` 3.2`` ...
    factor_m : float
        Metres per display unit.

    Returns
    -------
    tuple of float, or None
    """
    m = _REPLY.match(text.strip())
    if m is None:
        return None
    sign = -1.0 if m.group(1) == b"-" else 1.0
    frac = m.group(3) or b""
    value = float(m.group(2) + (b"." + frac if frac else b""))
    return sign * value * factor_m, 10.0 ** -len(frac) * factor_m


class SylvacSource(PolledSource):
    """A Sylvac Opto RS gauge on a serial port, asked ``?`` for each reading.

    Parameters
    ----------
    link : SerialLink
        Opened with :data:`SYLVAC_FRAMING`.
    unit : str
        ``"mm"`` or ``"in"``: the gauge's display unit.
    description : str
    """

    request = b"?\r"
    terminator = b"\r"

    def __init__(self, link, unit: str, description: str):
        super().__init__(link, description)
        self.factor_m = _UNITS[unit]

    def _parse(self, reply: bytes):
        if reply.upper().startswith(b"ERR"):
            code = reply[3:].strip()
            meaning = SYLVAC_ERRORS.get(int(code), "error") if code.isdigit() else "error"
            return None, f"the gauge answered {reply.decode('ascii', 'replace')} ({meaning}): no reading"
        parsed = parse_decimal_reply(reply, self.factor_m)
        if parsed is None:
            return None, f"not a reading: {reply[:40]!r}"
        value, resolution = parsed
        self.resolution_m = resolution
        return value, None
