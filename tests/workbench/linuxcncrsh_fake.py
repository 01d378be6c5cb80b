"""A LinuxCNC stand-in on a real TCP socket: linuxcncrsh's line protocol as axiscal's LinuxCNC controller speaks it.

It answers the hello, the session settings, the state queries (out of e-stop, on, every joint homed),
``get abs_act_pos`` (the axes at rest at ``position_mm``) and acknowledges every ``set mdi`` it is sent,
keeping the commands in ``moves`` so that a test can say none was sent.
"""

from __future__ import annotations

import socket
import threading

ANSWERS = {
    "set verbose on": "SET VERBOSE ACK",
    "set enable EMCTOO": "SET ENABLE ACK",
    "set set_wait done": "SET SET_WAIT ACK",
    "get estop": "ESTOP OFF",
    "get machine": "MACHINE ON",
    "get joint_homed": "JOINT_HOMED YES YES YES NO NO NO NO NO NO",
    "set mode mdi": "SET MODE ACK",
    "set linear_unit_conversion mm": "SET LINEAR_UNIT_CONVERSION ACK",
    "set abort": "SET ABORT ACK",
    "get error": "ERROR none",
}


class LinuxcncrshFake:
    """linuxcncrsh on 127.0.0.1 (a free port), each session served in a thread.

    Parameters
    ----------
    position_mm : tuple of float
        Where X, Y and Z are.
    """

    def __init__(self, position_mm: tuple[float, float, float] = (10.0, 0.0, 0.0)):
        self.position_mm = position_mm
        self.moves: list[str] = []
        self.server = socket.create_server(("127.0.0.1", 0))
        self.port = self.server.getsockname()[1]
        self._threads: list[threading.Thread] = []
        self._accepting = threading.Thread(target=self._accept, daemon=True)
        self._accepting.start()

    @property
    def spec(self) -> str:
        """The controller spec that names it."""
        return f"linuxcnc:127.0.0.1:{self.port}"

    def _accept(self) -> None:
        while True:
            try:
                conn, _ = self.server.accept()
            except OSError:
                return
            thread = threading.Thread(target=self._serve, args=(conn,), daemon=True)
            thread.start()
            self._threads.append(thread)

    def _answer(self, line: str) -> str:
        if line.startswith("hello "):
            return "HELLO ACK EMC 1.1"
        if line == "set echo off":
            return "set echo off"  # echoed once, as linuxcncrsh does
        if line.startswith("set mdi "):
            self.moves.append(line)
            return "SET MDI ACK"
        if line == "get abs_act_pos":
            return "ABS_ACT_POS " + " ".join(f"{v:.4f}" for v in (*self.position_mm, 0, 0, 0, 0, 0, 0))
        return ANSWERS.get(line, f"{line.split()[0].upper()} NAK")

    def _serve(self, conn: socket.socket) -> None:
        buffer = b""
        with conn:
            while True:
                try:
                    data = conn.recv(4096)
                except OSError:
                    return
                if not data:
                    return
                buffer += data
                while b"\n" in buffer:
                    raw, buffer = buffer.split(b"\n", 1)
                    line = raw.strip(b"\r ").decode("ascii")
                    if line:
                        conn.sendall(self._answer(line).encode("ascii") + b"\r\n")

    def close(self) -> None:
        """Stop accepting; the sessions end as their clients close them."""
        self.server.close()
