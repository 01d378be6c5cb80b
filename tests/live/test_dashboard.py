"""The dashboard served by a process of its own: the same state as in the loop's process, over HTTP and the WebSocket."""

from __future__ import annotations

import json
import os
import socket
import time

import httpx
import numpy as np
import pytest
from websockets.sync.client import connect

from axiscal.errors import AxiscalError
from axiscal.live.dashboard import BACKLOG_BYTES, DashboardProcess, _Feed
from axiscal.live.pipeline import Pipeline
from axiscal.live.protocol import FrameBatch
from axiscal.live.session import LiveSession
from axiscal.live.state import LiveState
from axiscal.measurement.display import to_display
from axiscal.measurement.virtual import VirtualModule


@pytest.fixture(scope="module")
def module():
    return VirtualModule(seed=0)


def batches(module, pipeline, count: int, size: int):
    """``count`` processed batches of the virtual module's frames, ``size`` frames each, one faulty frame in the second."""
    system = module.measurement_system()
    out = []
    for k in range(count):
        t = (np.arange(size) + k * size) / 1000.0
        frames, _ = module.frames(t)
        batch = FrameBatch.from_frames(frames, system.channels)
        if k == 1:
            batch.values[3, 0] = np.nan
        fault, results = pipeline.process(batch)
        out.append((batch, fault, to_display(results)))
    return out


def wait_for(client: httpx.Client, frames: int) -> dict:
    deadline = time.monotonic() + 20.0
    while time.monotonic() < deadline:
        shown = client.get("/api/state").json()
        if shown["frames"] >= frames:
            return shown
        time.sleep(0.05)
    raise AssertionError(f"the dashboard's process did not fold {frames} frames in 20 s")


def test_the_process_shows_what_a_state_in_the_loops_process_would(module):
    system = module.measurement_system()
    pipeline = Pipeline(system, None)
    fed, direct = LiveState(system), LiveState(system)
    processed = batches(module, pipeline, 5, 200)
    with DashboardProcess(fed, port=0, update_hz=20.0, title="twin") as dashboard:
        dashboard.start()
        fed.extra = {"source": {"state": "streaming"}}
        for batch, fault, shown in processed:
            fed.update(batch, fault, shown)
            direct.update(batch, fault, shown)
        with httpx.Client(base_url=dashboard.url) as client:
            served = wait_for(client, 1000)
            config = client.get("/api/config").json()
    expected = direct.snapshot()
    assert fed.frames == 1000 and fed.faults == 1 == expected["faults"]  # the loop's state counts, the process folds
    assert config == {"title": "twin", "channels": list(system.channels), "axes": list(system.axes), "update_hz": 20.0}
    assert served["title"] == "twin" and served["source"] == {"state": "streaming"}
    for name in ("frames", "faults", "t_s", "last_fault", "last_fault_text", "sensors"):
        assert served[name] == expected[name], name
    for name, value in expected["latest"].items():
        assert served["latest"][name] == pytest.approx(value, rel=1e-12, abs=1e-12), name
    for letter, axis in expected["axes"].items():
        for name, values in axis["errors"].items():
            np.testing.assert_allclose(np.array(served["axes"][letter]["errors"][name], dtype=float), np.array(values, dtype=float),
                                       rtol=0, atol=1e-9, equal_nan=True)
    for name, values in expected["history"].items():
        np.testing.assert_allclose(np.array(served["history"][name], dtype=float), np.array(values, dtype=float), rtol=0, atol=1e-9,
                                   equal_nan=True)


def test_the_websocket_streams_states_and_the_process_ends_with_stop(module):
    system = module.measurement_system()
    pipeline = Pipeline(system, None)
    state = LiveState(system)
    dashboard = DashboardProcess(state, port=0, update_hz=20.0).start()
    try:
        host = f"127.0.0.1:{dashboard.port}"
        with connect(f"ws://{host}/ws", max_size=None, additional_headers={"Origin": f"http://{host}"}) as client:
            versions = []
            for batch, fault, shown in batches(module, pipeline, 3, 100):
                state.update(batch, fault, shown)
                versions.append(json.loads(client.recv(timeout=10))["version"])
            deadline = time.monotonic() + 10
            while json.loads(client.recv(timeout=10))["frames"] < 300 and time.monotonic() < deadline:
                pass
        with httpx.Client(base_url=dashboard.url) as client:
            assert client.get("/", headers={"host": "evil.example"}).status_code == 403
    finally:
        dashboard.stop()
    assert versions == sorted(versions) and len(set(versions)) == 3
    assert dashboard._process.returncode == 0
    state.update(*batches(module, pipeline, 1, 10)[0])  # after stop the state keeps its batches again
    assert state.snapshot()["frames"] == 310
    with pytest.raises(httpx.ConnectError):
        httpx.get(dashboard.url, timeout=2)
    dashboard.stop()  # twice is harmless


def test_a_reader_that_never_reads_leaves_batches_out_and_the_loop_never_waits(module):
    system = module.measurement_system()
    pipeline = Pipeline(system, None)
    batch, fault, shown = batches(module, pipeline, 1, 2000)[0]
    read_end, write_end = os.pipe()
    os.set_blocking(write_end, False)
    feed = _Feed(write_end)
    try:
        start = time.monotonic()
        for _ in range(60):  # about 45 MB: more than the pipe and the backlog hold
            feed.batch(batch, fault, shown)
        elapsed = time.monotonic() - start
        kept = len(feed.backlog)
    finally:
        os.close(read_end)
        feed.close()
    feed.batch(batch, fault, shown)  # after close: nothing written, no error
    assert feed.left_out > 0 and feed.left_out % 2000 == 0
    assert BACKLOG_BYTES < kept <= BACKLOG_BYTES + 2 * len(batch) * 8 * (1 + len(system.channels) + len(shown) + 2)
    assert elapsed < 10.0  # it returned: a blocking write would never have


def test_a_port_in_use_and_bad_settings_are_one_error(module):
    state = LiveState(module.measurement_system())
    with socket.create_server(("127.0.0.1", 0)) as holder:
        with pytest.raises(AxiscalError, match=r"the dashboard cannot listen on 127\.0\.0\.1:\d+ \(.*\); choose another port or host"):
            DashboardProcess(state, port=holder.getsockname()[1]).start()
    assert state._feed is None
    for settings, message in [
        ({"port": 70000}, "port"),
        ({"host": " "}, "host must be an address"),
        ({"update_hz": 0.0}, "update_hz: the update rate must be 0.1 to 60"),
        ({"title": 3}, "title must be a str"),
        ({"allowed_hosts": ["monitor.lan:80"]}, "without port or scheme"),
    ]:
        with pytest.raises(AxiscalError, match=message):
            DashboardProcess(state, **settings)
    with pytest.raises(AxiscalError, match="state"):
        DashboardProcess({"frames": 0})


def test_a_live_session_serves_its_dashboard_from_its_own_process():
    with LiveSession(rate_hz=1000.0, port=0, update_hz=20.0) as session:
        assert isinstance(session.server, DashboardProcess)
        summary = session.run(duration_s=1.5)
        with httpx.Client(base_url=session.url) as client:
            shown = wait_for(client, summary.frames)
        process = session.server._process
    assert process.returncode == 0
    assert shown["frames"] == summary.frames == session.state.frames
    assert shown["title"].startswith("axiscal live: sim") and shown["source"]["state"] in ("streaming", "finished")
    assert shown["latency_ms"] is None or shown["latency_ms"]["p99"] >= 0


def test_the_process_runs_at_normal_priority_whatever_the_loops(module):
    from axiscal.live.priority import raise_priority, restore_priority

    state = LiveState(module.measurement_system())
    priority = raise_priority()  # as axiscal live does before it starts the dashboard
    try:
        with DashboardProcess(state, port=0).start() as dashboard:
            pid = dashboard._process.pid
            policy, nice = os.sched_getscheduler(pid), os.getpriority(os.PRIO_PROCESS, pid)
    finally:
        restore_priority(priority)
    assert policy == os.SCHED_OTHER and nice >= 0
