"""Mahr Millimar amplifiers and compact gauges on their RS-232 port.

Source: the Mahr Millimar interface description. The computer sends ``?\\r``; the instrument answers its
display and unit, ``xxx.xxx<unit>\\r\\n`` (``mm``, ``um`` / ``µm`` or ``in``), e.g. ``+0012.345mm``.
A reply without a number is no reading. Default 9600 8N1 (set the instrument's port to match, or give
``mahr:PORT@BAUD``).
"""

from __future__ import annotations

import re

from axiscal.devices.base import PolledSource
from axiscal.devices.sylvac import parse_decimal_reply

__all__ = ["MahrSource", "MAHR_UNITS"]

#: metres per unit of a Millimar reply
MAHR_UNITS = {"mm": 1e-3, "um": 1e-6, "µm": 1e-6, "in": 25.4e-3, "inch": 25.4e-3}
_REPLY = re.compile(r"^\s*([+\- ]?\s*\d+(?:\.\d+)?)\s*([a-zA-Zµ]+)\s*$")


class MahrSource(PolledSource):
    """A Mahr Millimar on a serial port, asked ``?`` for each reading.

    Parameters
    ----------
    link : SerialLink
    description : str
    """

    request = b"?\r"
    terminator = b"\n"

    def _parse(self, reply: bytes):
        text = reply.decode("utf-8", "replace").strip()
        m = _REPLY.match(text)
        if m is None or m.group(2).lower() not in MAHR_UNITS:
            return None, f"not a reading: {text[:40]!r}"
        parsed = parse_decimal_reply(m.group(1).replace(" ", "").encode(), MAHR_UNITS[m.group(2).lower()])
        if parsed is None:
            return None, f"not a reading: {text[:40]!r}"
        value, resolution = parsed
        self.resolution_m = resolution
        return value, None
