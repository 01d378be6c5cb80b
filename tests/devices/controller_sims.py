"""Protocol simulators of grbl 1.1, Marlin, Klipper's API socket and Moonraker, written from their documents.

No simulator of these firmwares installs from the package registries here, so each is simulated from
its public interface documentation (grbl 1.1 wiki "Interface" and "Commands"; Marlin's G-code reference;
Klipper's API_Server.html; Moonraker's printer API): the states, the ``ok`` semantics (grbl's ``ok`` is
"buffered", ``G4 P0.01`` answers once the planner is empty; Marlin's ``M400`` answers after the moves,
with ``echo:busy: processing`` keep-alives), alarms and error replies, homing and soft limits. An axis
moves at the feed asked, in real time. ``silent`` makes a simulator stop answering (a cable pulled).
"""

from __future__ import annotations

import json
import os
import re
import select
import socketserver
import threading
import time
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from urllib.parse import parse_qs, urlsplit


class Axis:
    """Positions (mm) moving toward their targets at a feed, in real time."""

    def __init__(self, travel_mm=(0.0, 200.0)):
        self.travel = travel_mm
        self._lock = threading.Lock()
        self._start = {"X": 0.0, "Y": 0.0, "Z": 0.0}
        self._end = dict(self._start)
        self._t0 = time.monotonic()
        self._duration = 0.0
        self.homed = True

    def _at(self, now):
        f = 1.0 if self._duration == 0 else min(1.0, (now - self._t0) / self._duration)
        return {k: self._start[k] + (self._end[k] - self._start[k]) * f for k in self._start}

    def position(self):
        with self._lock:
            return self._at(time.monotonic())

    def moving(self):
        with self._lock:
            return time.monotonic() - self._t0 < self._duration

    def move(self, target: dict, feed_mm_min: float) -> float:
        with self._lock:
            now = time.monotonic()
            here = self._at(now)
            end = {**here, **target}
            distance = max(abs(end[k] - here[k]) for k in here)
            self._start, self._end, self._t0 = here, end, now
            self._duration = distance / (feed_mm_min / 60.0) if feed_mm_min > 0 else 0.0
            return self._duration

    def halt(self):
        with self._lock:
            here = self._at(time.monotonic())
            self._start = self._end = here
            self._duration = 0.0

    def x_m(self) -> float:
        return self.position()["X"] * 1e-3


_WORD = re.compile(r"([A-Z])\s*(-?\d+(?:\.\d*)?)")


def _words(line: str) -> dict[str, float]:
    return {k: float(v) for k, v in _WORD.findall(line.upper())}


class _PtyDevice(threading.Thread):
    """A serial device on a pty's master: bytes in, lines out."""

    def __init__(self, fd: int):
        super().__init__(daemon=True)
        self.fd = fd
        self.stop_event = threading.Event()
        self.silent = False
        self.received: list[str] = []

    def write(self, text: str) -> None:
        if self.silent:
            return
        data = text.encode()
        while data and not self.stop_event.is_set():
            try:
                data = data[os.write(self.fd, data):]
            except BlockingIOError:
                time.sleep(0.001)
            except OSError:
                return

    def stop(self):
        self.stop_event.set()
        self.join(timeout=5)


class GrblSim(_PtyDevice):
    """grbl 1.1h."""

    def __init__(self, fd: int, axis: Axis, *, soft_limits: bool = True, homed: bool = True):
        super().__init__(fd)
        self.axis = axis
        self.soft = soft_limits
        self.state = "Idle" if homed else "Alarm"
        self.queue_until = 0.0

    def banner(self):
        self.write("\r\nGrbl 1.1h ['$' for help]\r\n")

    def _status(self):
        p = self.axis.position()
        state = self.state if self.state == "Alarm" else ("Run" if self.axis.moving() else "Idle")
        self.write(f"<{state}|MPos:{p['X']:.3f},{p['Y']:.3f},{p['Z']:.3f}|FS:0,0>\r\n")

    def _line(self, line: str):
        self.received.append(line)
        if line == "$$":
            travel = self.axis.travel[1]
            for k, v in ((20, 1 if self.soft else 0), (23, 7), (130, travel), (131, travel), (132, 100.0)):
                self.write(f"${k}={v:g}\r\n")
            self.write("ok\r\n")
            return
        if self.state == "Alarm":
            self.write("error:9\r\n")
            return
        words = _words(line)
        if "G" in words and words["G"] == 4:
            # answered once the planner is empty: wait here, as grbl holds its reply
            while self.axis.moving() and not self.stop_event.is_set():
                time.sleep(0.005)
                self._realtime_pending()
            self.write("ok\r\n")
            return
        if "X" in words or "Y" in words or "Z" in words:
            target = {k: words[k] for k in "XYZ" if k in words}
            if self.soft and any(not self.axis.travel[0] <= v <= self.axis.travel[1] for v in target.values()):
                self.state = "Alarm"
                self.write("ALARM:2\r\n")
                return
            self.axis.move(target, words.get("F", 1000.0))
        if line.startswith("$") or line.upper().startswith("G") or not line:
            self.write("ok\r\n")
            return
        self.write("error:20\r\n")

    def _realtime_pending(self):
        try:
            if select.select([self.fd], [], [], 0)[0]:
                self._feed(os.read(self.fd, 4096), nested=True)
        except OSError:
            pass

    def _feed(self, data: bytes, nested: bool = False):
        for byte in data:
            ch = chr(byte)
            if ch == "?":
                self._status()
            elif ch == "!":
                self.axis.halt()
            elif byte == 0x18:
                self.axis.halt()
                self.state = "Alarm"
                self.banner()
            elif ch == "~":
                pass
            elif nested:
                self._pending += ch  # a line typed while the planner drains: kept for later
            else:
                self._pending += ch
        if nested:
            return
        while "\n" in self._pending:
            line, self._pending = self._pending.split("\n", 1)
            self._line(line.strip())

    def run(self):
        self._pending = ""
        self.banner()
        while not self.stop_event.is_set():
            try:
                ready = select.select([self.fd], [], [], 0.05)[0]
                if not ready:
                    continue
                data = os.read(self.fd, 4096)
            except OSError:
                return
            if self.silent:
                continue
            self._feed(data)


class MarlinSim(_PtyDevice):
    """Marlin 2.x."""

    def __init__(self, fd: int, axis: Axis, *, homed: bool = True):
        super().__init__(fd)
        self.axis = axis
        self.homed = homed
        self.keepalive_s = 2.0

    def _line(self, line: str):
        self.received.append(line)
        word = line.split()[0].upper() if line.split() else ""
        words = _words(line)
        if word == "M113":
            self.keepalive_s = words.get("S", 2.0)
        elif word == "M114":
            p = self.axis.position()
            self.write(f"X:{p['X']:.2f} Y:{p['Y']:.2f} Z:{p['Z']:.2f} E:0.00 Count X:{int(p['X'] * 80)} Y:0 Z:0\n")
        elif word == "M211":
            lo, hi = self.axis.travel
            self.write(f"echo:Soft endstops: On   Min:  X{lo:.2f} Y{lo:.2f} Z{lo:.2f}   Max:  X{hi:.2f} Y{hi:.2f} Z{hi:.2f}\n")
        elif word in ("G0", "G1"):
            if not self.homed:
                self.write("echo:Home XYZ first\n")
            else:
                target = {k: min(max(words[k], self.axis.travel[0]), self.axis.travel[1]) for k in "XYZ" if k in words}
                self.axis.move(target, words.get("F", 1000.0))
        elif word == "M400":
            last = time.monotonic()
            while self.axis.moving() and not self.stop_event.is_set():
                if time.monotonic() - last >= self.keepalive_s:
                    self.write("echo:busy: processing\n")
                    last = time.monotonic()
                time.sleep(0.01)
        elif word == "M410":
            self.axis.halt()
        self.write("ok\n")

    def run(self):
        pending = ""
        self.write("start\necho:Marlin 2.1.2\n")
        while not self.stop_event.is_set():
            try:
                if not select.select([self.fd], [], [], 0.05)[0]:
                    continue
                data = os.read(self.fd, 4096)
            except OSError:
                return
            if self.silent:
                continue
            pending += data.decode(errors="replace")
            while "\n" in pending:
                line, pending = pending.split("\n", 1)
                if line.strip():
                    self._line(line.strip())


class _Toolhead:
    """Klipper's toolhead, shared by the API socket and Moonraker."""

    def __init__(self, axis: Axis, homed: bool = True):
        self.axis = axis
        self.homed_axes = "xyz" if homed else ""
        self.silent = False
        self.shutdown = False

    def script(self, script: str) -> dict:
        for line in script.splitlines():
            words = _words(line)
            head = line.split()[0].upper() if line.split() else ""
            if head in ("G0", "G1"):
                target = {k: words[k] for k in "XYZ" if k in words}
                if any(k.lower() not in self.homed_axes for k in target):
                    return {"error": {"error": "WebRequestError", "message": "Must home axis first: 0.000 0.000 0.000 [0.000]"}}
                if any(not self.axis.travel[0] <= v <= self.axis.travel[1] for v in target.values()):
                    return {"error": {"error": "WebRequestError", "message": "Move out of range: %.3f 0.000 0.000 [0.000]" % list(target.values())[0]}}
                self.axis.move(target, words.get("F", 1000.0))
            elif head == "M400":
                while self.axis.moving():
                    time.sleep(0.005)
        return {"result": {}}

    def query(self) -> dict:
        p = self.axis.position()
        lo, hi = self.axis.travel
        return {"result": {"eventtime": time.monotonic(), "status": {"toolhead": {
            "position": [p["X"], p["Y"], p["Z"], 0.0], "homed_axes": self.homed_axes,
            "axis_minimum": [lo, lo, lo, 0.0], "axis_maximum": [hi, hi, hi, 0.0]}}}}

    def call(self, method: str, params: dict) -> dict:
        if method == "gcode/script":
            return self.script(params.get("script", ""))
        if method == "objects/query":
            return self.query()
        if method == "emergency_stop":
            self.axis.halt()
            self.shutdown = True
            return {"result": {}}
        return {"error": {"error": "WebRequestError", "message": f"No registered endpoint '{method}'"}}


class KlipperSim:
    """Klipper's API server on a Unix socket."""

    def __init__(self, path: str, axis: Axis, *, homed: bool = True):
        self.toolhead = _Toolhead(axis, homed)
        self.path = path
        toolhead = self.toolhead

        class Handler(socketserver.BaseRequestHandler):
            def handle(self):
                buffer = b""
                while True:
                    try:
                        data = self.request.recv(4096)
                    except OSError:
                        return
                    if not data:
                        return
                    buffer += data
                    while b"\x03" in buffer:
                        raw, buffer = buffer.split(b"\x03", 1)
                        request = json.loads(raw)
                        if toolhead.silent:
                            continue
                        reply = toolhead.call(request["method"], request.get("params", {}))
                        reply["id"] = request["id"]
                        if toolhead.silent:
                            continue
                        try:
                            self.request.sendall(json.dumps(reply).encode() + b"\x03")
                        except OSError:
                            return

        self.server = socketserver.ThreadingUnixStreamServer(path, Handler)
        self.server.daemon_threads = True
        threading.Thread(target=self.server.serve_forever, daemon=True).start()

    def stop(self):
        self.server.shutdown()
        self.server.server_close()


class MoonrakerSim:
    """Moonraker's HTTP API on 127.0.0.1 (any free port)."""

    def __init__(self, axis: Axis, *, homed: bool = True):
        self.toolhead = _Toolhead(axis, homed)
        toolhead = self.toolhead

        class Handler(BaseHTTPRequestHandler):
            def log_message(self, *args):
                pass

            def _reply(self, message: dict):
                if toolhead.silent:
                    time.sleep(10)
                    return
                status = 400 if "error" in message else 200
                body = json.dumps(message).encode()
                self.send_response(status)
                self.send_header("Content-Type", "application/json")
                self.send_header("Content-Length", str(len(body)))
                self.end_headers()
                self.wfile.write(body)

            def do_GET(self):
                url = urlsplit(self.path)
                if url.path == "/printer/objects/query":
                    self._reply(toolhead.query())
                else:
                    self._reply({"error": {"code": 404, "message": "Not Found"}})

            def do_POST(self):
                url = urlsplit(self.path)
                length = int(self.headers.get("Content-Length", 0) or 0)
                body = json.loads(self.rfile.read(length) or b"{}") if length else {}
                if url.path == "/printer/gcode/script":
                    script = body.get("script") or parse_qs(url.query).get("script", [""])[0]
                    reply = toolhead.script(script)
                    self._reply({"result": "ok"} if "result" in reply else reply)
                elif url.path == "/printer/emergency_stop":
                    self._reply(toolhead.call("emergency_stop", {}))
                else:
                    self._reply({"error": {"code": 404, "message": "Not Found"}})

        self.server = ThreadingHTTPServer(("127.0.0.1", 0), Handler)
        self.server.daemon_threads = True
        self.url = f"http://127.0.0.1:{self.server.server_address[1]}"
        threading.Thread(target=self.server.serve_forever, daemon=True).start()

    def stop(self):
        self.server.shutdown()
        self.server.server_close()
