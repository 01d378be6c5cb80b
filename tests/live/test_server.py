"""The dashboard server: page and assets from the package, state over the WebSocket, a slow client never slows the pipeline."""

from __future__ import annotations

import base64
import json
import os
import socket
import threading
import time

import httpx
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from websockets.sync.client import connect

from axiscal.errors import AxiscalError
from axiscal.live.pipeline import Pipeline
from axiscal.live.protocol import FrameBatch
from axiscal.live.recorder import Recorder, read_record
from axiscal.live.server import LiveServer, create_app
from axiscal.live.sources import SimSource
from axiscal.live.state import LiveState, axis_error_columns, result_columns
from axiscal.measurement.display import to_display


def _fed_state(module, system, recorder=None):
    state = LiveState(system)
    pipeline = Pipeline(system, SimSource(module, system.channels, rate_hz=20000.0), state=state, recorder=recorder)
    deadline = time.monotonic() + 5.0
    while pipeline.frames < 2000 and time.monotonic() < deadline:
        pipeline.step(0.02)
    return state, pipeline


def test_page_assets_config_and_state_are_served_without_internet(module, system):
    state, _ = _fed_state(module, system)
    server = LiveServer(create_app(state, update_hz=20.0), port=0).start()
    with server, httpx.Client(base_url=server.url) as client:
        page = client.get("/")
        assert page.status_code == 200 and "axiscal live" in page.text
        assert "http" not in page.text.replace("http-equiv", "")
        for asset in ("app.js", "plot.js", "style.css"):
            response = client.get(f"/static/{asset}")
            assert response.status_code == 200 and len(response.text) > 500
            assert "https://" not in response.text and "http://" not in response.text
        config = client.get("/api/config").json()
        assert config["channels"] == list(system.channels) and config["axes"] == ["X", "Z"]
        with connect(f"ws://127.0.0.1:{server.port}/ws") as websocket:
            first = json.loads(websocket.recv(timeout=5.0))
            second = json.loads(websocket.recv(timeout=5.0))
        assert second["version"] > first["version"]
        assert second["frames"] >= 2000
        latest = second["latest"]
        assert {"ex_um", "ey_um", "ez_um", "e_um", "px_mm", "py_mm", "pz_mm", "t_s"} <= set(latest)
        assert [s["name"] for s in second["sensors"]] == list(system.channels)
        assert all(s["state"] == "ok" for s in second["sensors"])
        profile = second["axes"]["X"]
        assert set(profile["errors"]) == set(axis_error_columns("X"))
        assert np.isfinite([v for v in profile["errors"]["EXX_um"] if v is not None]).all()
        assert client.get("/api/state").json()["frames"] >= 2000


def test_snapshot_latest_is_the_last_good_frame_the_pipeline_recorded(tmp_path, module, system):
    recorder = Recorder(tmp_path / "r.csv", system.channels, result_columns(system.axes))
    state, pipeline = _fed_state(module, system, recorder)
    recorder.close()
    snapshot = state.snapshot()
    record = read_record(tmp_path / "r.csv")
    assert snapshot["frames"] == pipeline.frames == len(record)
    row = int(np.flatnonzero(np.abs(record.columns["t_s"] - snapshot["latest"]["t_s"]) < 1e-7)[-1])
    assert row == len(record) - 1
    for name in ("ex_um", "ey_um", "ez_um", "e_um", "px_mm", "py_mm", "pz_mm", "x_mm", "EXX_um", "ECZ_urad"):
        assert snapshot["latest"][name] == pytest.approx(record.columns[name][row], rel=1e-8, abs=1e-9), name
    assert len([t for t in snapshot["history"]["t_s"] if t is not None]) >= 2


def _silent_websocket(port: int) -> socket.socket:
    """A client that completes the WebSocket handshake and then never reads anything."""
    sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4096)
    sock.connect(("127.0.0.1", port))
    key = base64.b64encode(os.urandom(16)).decode()
    request = (
        f"GET /ws HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
        f"Sec-WebSocket-Key: {key}\r\nSec-WebSocket-Version: 13\r\n\r\n"
    )
    sock.sendall(request.encode())
    return sock


def test_a_client_that_does_not_read_neither_slows_the_pipeline_nor_queues_states(module, system):
    rate = 2000.0
    state = LiveState(system, bins=2000, history_points=4000)  # large states fill the socket buffers fast
    pipeline = Pipeline(system, SimSource(module, system.channels, rate_hz=rate), state=state)
    app = create_app(state, update_hz=50.0)
    server = LiveServer(app, port=0).start()
    stop = threading.Event()
    runner = threading.Thread(target=pipeline.run, kwargs={"stop": stop, "duration_s": 10.0})
    silent = _silent_websocket(server.port)
    start = time.monotonic()
    runner.start()
    try:
        received = 0
        with connect(f"ws://127.0.0.1:{server.port}/ws", max_size=None) as reader:
            # 2.5 s, and on a loaded machine on until 60 states were sent (the silent client's buffer holds about 15)
            while time.monotonic() - start < 2.5 or (app.state.broadcaster.version < 60 and time.monotonic() - start < 8.0):
                latest = json.loads(reader.recv(timeout=5.0))
                newest = app.state.broadcaster.version
                received += 1
            clients = list(app.state.broadcaster.clients)
        frames = pipeline.frames
        due = rate * (time.monotonic() - pipeline.source.clock_offset_s)  # frames the sim source had made due by now
        deadline = time.monotonic() + 2.0
        while len(app.state.broadcaster.clients) > 1 and time.monotonic() < deadline:
            time.sleep(0.01)
        remaining = list(app.state.broadcaster.clients)
    finally:
        stop.set()
        runner.join(timeout=5)
        server.stop()
        silent.close()
    slow, fast = sorted(clients, key=lambda c: c.sent)
    # generous margins: a busy 2-core machine may hold any thread back for a while, but a pipeline that
    # waited for the silent client would stop for good, and a queue for the reader would grow by the second
    assert frames >= due - 0.5 * rate
    assert received >= 10
    assert newest - latest["version"] <= 10
    assert slow.sent < fast.sent / 2
    assert newest - slow.version > 20
    assert remaining == [slow]  # a client that left is forgotten


def test_server_refuses_a_port_in_use(module, system):
    state = LiveState(system)
    holder = socket.socket()
    holder.bind(("127.0.0.1", 0))
    holder.listen(1)
    try:
        with pytest.raises(AxiscalError, match="cannot listen"):
            LiveServer(create_app(state), port=holder.getsockname()[1]).start()
    finally:
        holder.close()


def test_faulty_frames_leave_a_gap_in_the_history_and_keep_the_last_good_values(module, system):
    state = LiveState(system, history_s=2.0, history_points=200)  # one history sample per 10 ms
    t = np.arange(1000) / 1000.0
    frames, _ = module.frames(t)
    frames["x_psd_y_um"][600:] = np.nan  # the PSD drops out at 0.6 s and stays out
    batch = FrameBatch.from_frames(frames, system.channels)
    results = to_display(system.process(batch.frames(system.channels)))
    state.update(batch, results["fault"], results)
    snapshot = state.snapshot()
    history_t = np.array(snapshot["history"]["t_s"], dtype=float)
    history_e = np.array([np.nan if v is None else v for v in snapshot["history"]["e_um"]])
    assert history_t[0] < 0.01 and history_t[-1] > 0.98 and np.all(np.diff(history_t) < 0.0201)  # one frame per 10 ms slot; faulty frames keep their time
    assert np.isfinite(history_e[history_t < 0.6]).all() and np.isnan(history_e[history_t >= 0.6]).all()
    assert snapshot["t_s"] == pytest.approx(0.999) and snapshot["latest"]["t_s"] == pytest.approx(0.599)
    assert snapshot["latest"]["e_um"] == pytest.approx(results["e_um"][599], rel=1e-12)
    assert snapshot["faults"] == 400 and snapshot["last_fault_text"] == "missing channel"
    psd = next(s for s in snapshot["sensors"] if s["name"] == "x_psd_y_um")
    assert psd["state"] == "missing" and psd["missing"] == 400 and psd["value"] is None


def _handshake_status(port: int, host: str, origin: str | None = None) -> int:
    """The HTTP status the real server answers a WebSocket handshake with (101: accepted)."""
    with socket.create_connection(("127.0.0.1", port), timeout=5.0) as sock:
        key = base64.b64encode(os.urandom(16)).decode()
        request = (
            f"GET /ws HTTP/1.1\r\nHost: {host}\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
            f"Sec-WebSocket-Key: {key}\r\nSec-WebSocket-Version: 13\r\n" + (f"Origin: {origin}\r\n" if origin else "") + "\r\n"
        )
        sock.sendall(request.encode())
        return int(sock.recv(4096).split(b" ", 2)[1])


def test_only_loopback_hosts_and_the_dashboards_own_origin_are_answered(module, system):
    """DNS rebinding (a foreign Host reaching 127.0.0.1) and cross-site pages (a foreign Origin) get 403, on the real uvicorn server."""
    state, _ = _fed_state(module, system)
    server = LiveServer(create_app(state, update_hz=20.0, allowed_hosts=["monitor.lan"]), port=0).start()
    port = server.port
    with server, httpx.Client(base_url=server.url) as client:
        for host in (f"127.0.0.1:{port}", f"localhost:{port}", f"LocalHost:{port}", f"[::1]:{port}", f"monitor.lan:{port}", "127.0.0.1"):
            assert client.get("/api/state", headers={"Host": host}).status_code == 200, host
            assert _handshake_status(port, host) == 101, host
        for host in (f"evil.example:{port}", f"127.0.0.1.evil.example:{port}", f"localhost.:{port}", "", f"monitor.lan.evil:{port}"):
            assert client.get("/", headers={"Host": host}).status_code in (400, 403), host
            assert client.get("/api/state", headers={"Host": host}).status_code in (400, 403), host
            assert _handshake_status(port, host) in (400, 403), host
        own = f"127.0.0.1:{port}"
        assert _handshake_status(port, own, origin=f"http://{own}") == 101
        for origin in ("http://evil.example", f"http://localhost:{port}", f"http://127.0.0.1:{port + 1}", f"https://{own}", "null"):
            assert _handshake_status(port, own, origin=origin) == 403, origin
            assert client.get("/api/state", headers={"Origin": origin}).status_code == 403, origin
        response = client.get("/api/state", headers={"Host": f"evil.example:{port}"})
        assert "frames" not in response.text
    with pytest.raises(AxiscalError, match="without port"):
        create_app(state, allowed_hosts=["monitor.lan:8765"])


def _reference_history(t, e_um, slot_s):
    """Plain reference: per slot of the stream clock, the faulty frame (NaN) if there is one, else the largest e_um."""
    out = {}
    for time_s, value in zip(t, e_um):
        slot = int(np.floor(time_s / slot_s))
        severity = np.inf if np.isnan(value) else value
        if slot not in out or severity > out[slot][0]:
            out[slot] = (severity, time_s, value)
    return [out[k] for k in sorted(out)]


@pytest.fixture(scope="module")
def processed(module, system):
    t = np.arange(400) / 1000.0
    frames, _ = module.frames(t)
    batch = FrameBatch.from_frames(frames, system.channels)
    return batch, to_display(system.process(batch.frames(system.channels)))


@settings(max_examples=40, deadline=None)
@given(faulty=st.lists(st.integers(0, 399), max_size=6), cuts=st.lists(st.integers(1, 399), max_size=6))
def test_the_history_keeps_the_worst_frame_of_each_slot_however_the_batches_fall(system, processed, faulty, cuts):
    """A faulty frame in the middle of a 50 ms slot shows (as a gap), and otherwise the slot's largest error, whatever the batches."""
    batch, results = processed
    results = {name: value.copy() for name, value in results.items()}
    fault = results["fault"].astype(np.int64)
    for k in faulty:
        fault[k] |= 1
        for name in results:
            if name not in ("t_s", "fault"):
                results[name][k] = np.nan
    state = LiveState(system, history_s=20.0, history_points=400)  # 50 ms slots
    bounds = sorted({0, 400, *cuts})
    for a, b in zip(bounds, bounds[1:]):
        part = FrameBatch(batch.t_s[a:b], batch.values[a:b], batch.malformed[a:b])
        state.update(part, fault[a:b], {name: value[a:b] for name, value in results.items()})
    history = state.snapshot()["history"]
    shown_e = [np.nan if v is None else v for v in history["e_um"]]
    expected = _reference_history(batch.t_s, results["e_um"], 0.05)
    kept = [(t, e) for t, e in zip(history["t_s"], shown_e) if t is not None]
    assert len(kept) == len(expected) == 8
    for (t, e), (_, t_ref, e_ref) in zip(kept, expected):
        assert t == pytest.approx(t_ref, abs=1e-6)
        assert (np.isnan(e) and np.isnan(e_ref)) or e == pytest.approx(e_ref, rel=1e-5, abs=1e-6)
    for k in faulty:  # every faulty frame's slot is a gap on the chart
        slot = int(np.floor(batch.t_s[k] / 0.05))
        assert np.isnan(kept[slot][1])


def test_the_state_folds_batches_together_and_shows_them_all_when_read(module, system):
    """update() only keeps a batch: the summaries take them at once, when FOLD_S has passed or a reader asks."""
    batch, results = _processed_frames(module, system, 30)
    state = LiveState(system)
    for k in range(3):
        part = slice(10 * k, 10 * (k + 1))
        state.update(FrameBatch(batch.t_s[part], batch.values[part], batch.malformed[part]), results["fault"][part], {n: v[part] for n, v in results.items()})
    assert state.frames == 0  # kept, not folded yet
    snapshot = state.snapshot()
    assert snapshot["frames"] == 30 == state.frames and snapshot["t_s"] == pytest.approx(batch.t_s[-1])
    whole = LiveState(system)
    whole.update(batch, results["fault"], results)
    assert whole.snapshot()["axes"] == snapshot["axes"] and whole.snapshot()["history"] == snapshot["history"]


def test_a_clock_that_goes_back_between_kept_batches_starts_the_history_afresh(module, system):
    batch, results = _processed_frames(module, system, 200)
    state = LiveState(system, history_s=2.0, history_points=200)
    state.update(batch, results["fault"], results)
    again = slice(0, 50)  # a new connection: its clock starts at 0 again, before the first batch was folded
    state.update(FrameBatch(batch.t_s[again], batch.values[again], batch.malformed[again]), results["fault"][again], {n: v[again] for n, v in results.items()})
    history = state.snapshot()["history"]["t_s"]
    assert max(history) < 0.05 and state.frames == 250


def _processed_frames(module, system, n):
    frames, _ = module.frames(np.arange(n) / 1000.0)
    batch = FrameBatch.from_frames(frames, system.channels)
    return batch, to_display(system.process(batch.frames(system.channels)))
