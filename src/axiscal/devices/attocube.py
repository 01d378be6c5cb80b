"""Attocube IDS3010 displacement sensor, read over its JSON-RPC 2.0 interface on TCP.

Source: the IDS3010 JSON-RPC API documentation (attocube systems). The sensor listens on TCP port 9090;
a request is one JSON object, no line end needed::

    {"jsonrpc": "2.0", "method": "com.attocube.ids.displacement.getAxesDisplacement", "params": [], "id": 7}

and the reply, ended by ``\\r\\n``, carries ``"result": [warning, d0, d1, d2]``: displacements of the three
axes in picometres; a non-zero warning means the values are no reading. An ``"error"`` member is a
refusal of the request. Each reply is time-stamped with the host's clock when it arrives.
"""

from __future__ import annotations

import json

from axiscal.devices.base import PolledSource

__all__ = ["AttocubeSource", "ATTOCUBE_PORT", "ATTOCUBE_METHOD"]

#: the IDS3010's JSON-RPC port
ATTOCUBE_PORT = 9090
#: the method that returns the three displacements
ATTOCUBE_METHOD = "com.attocube.ids.displacement.getAxesDisplacement"


class AttocubeSource(PolledSource):
    """One axis of an Attocube IDS3010.

    Parameters
    ----------
    link : TcpLink
    channel : int
        1, 2 or 3.
    description : str
    """

    terminator = b"\n"
    resolution_m = 1e-12

    def __init__(self, link, channel: int, description: str):
        super().__init__(link, description)
        self.channel = channel
        self._id = 0

    def _next_request(self) -> bytes:
        self._id += 1
        return json.dumps({"jsonrpc": "2.0", "method": ATTOCUBE_METHOD, "params": [], "id": self._id}).encode()

    def _parse(self, reply: bytes):
        try:
            message = json.loads(reply.decode("utf-8"))
        except (UnicodeDecodeError, ValueError):
            return None, f"not a JSON-RPC reply: {reply[:40]!r}"
        if not isinstance(message, dict):
            return None, f"not a JSON-RPC reply: {reply[:40]!r}"
        if "error" in message:
            error = message["error"]
            text = error.get("message", error) if isinstance(error, dict) else error
            return None, f"the sensor refused the request: {str(text)[:80]}"
        result = message.get("result")
        if not (isinstance(result, list) and len(result) >= 4
                and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in result[:4])):
            return None, f"a reply without [warning, d0, d1, d2]: {reply[:60]!r}"
        if result[0] != 0:
            return None, f"the sensor warns ({result[0]}): no reading"
        value = float(result[self.channel]) * 1e-12
        if value != value or abs(value) > 1e3:
            return None, f"not a displacement: {result[self.channel]!r} pm"
        return value, None
