"""Live capture: the plan walked through a TCP stream in the line protocol, as it arrives."""

from __future__ import annotations

import socket
import threading

import numpy as np
import pytest

from axiscal.capture import capture, capture_to_file, plan_steps
from axiscal.capture.sources import open_capture_source, plan_motions
from axiscal.capture.virtual import simulate_motions
from axiscal.errors import AxiscalError
from axiscal.live.protocol import encode_lines, header_line
from axiscal.model.machine import load_machine
from axiscal.positioning.plan import plan_test
from axiscal.report.demo import builtin_example
from axiscal.units import MM


@pytest.fixture(scope="module")
def simulated():
    plan = plan_test(0.0, 0.19, 5, runs=1, seed=3)
    machine = load_machine(builtin_example() / "machine.toml")
    return plan, simulate_motions(plan_motions(plan_steps(plan), dwell_s=1.2), machine, axis="X", rate_hz=500.0, seed=2)


def serve(recording, names=("reading_mm", "air_temperature_c", "pressure_pa", "humidity_pct")):
    """A loopback server that sends the recording at once and keeps the connection open (the laser goes on)."""
    listener = socket.create_server(("127.0.0.1", 0))
    stop = threading.Event()
    values = np.column_stack([recording.reading_m / MM] + [recording.channels[n] for n in names[1:]])

    def run():
        connection, _ = listener.accept()
        connection.sendall(header_line(names) + encode_lines(recording.time_s, values))
        stop.wait(30)
        connection.close()
        listener.close()

    threading.Thread(target=run, daemon=True).start()
    return listener.getsockname()[1], stop


def test_a_tcp_stream_captures_the_same_run_as_its_recording(simulated, tmp_path):
    plan, sim = simulated
    port, stop = serve(sim.recording)
    source = open_capture_source(f"tcp:127.0.0.1:{port}")
    seen = []
    try:
        live = capture_to_file(plan, source, tmp_path / "live.csv", progress=seen.append, timeout_s=20.0).capture
    finally:
        stop.set()
        source.close()
    offline = capture(plan, sim.recording)
    assert len(live.readings) == len(offline.readings) == plan.readings
    # every stop but the last is taken when the axis moves on; the last once it held two windows
    live_dev = np.array([r.deviation_m for r in live.readings])
    offline_dev = np.array([r.deviation_m for r in offline.readings])
    assert live_dev[:-1] == pytest.approx(offline_dev[:-1], abs=1e-9)
    assert live_dev[-1] == pytest.approx(offline_dev[-1], abs=0.05e-6)
    assert live.environment == ("air_temperature_c", "pressure_pa", "humidity_pct")
    assert seen and seen[-1].total == plan.readings and np.isfinite(seen[-1].reading_m)


def test_a_stream_that_stops_short_leaves_the_stops_before(simulated, tmp_path):
    plan, sim = simulated
    rec = sim.recording
    cut = int(np.searchsorted(rec.time_s, sim.dwells[3, 1] + 0.2))
    short = type(rec)(rec.time_s[:cut], rec.reading_m[:cut], {k: v[:cut] for k, v in rec.channels.items()}, "short")
    port, stop = serve(short)
    source = open_capture_source(f"tcp:127.0.0.1:{port}")
    try:
        with pytest.raises(AxiscalError, match="the recording ends before it"):
            capture_to_file(plan, source, tmp_path / "run.csv", timeout_s=3.0)
    finally:
        stop.set()
        source.close()
    assert len((tmp_path / "run.csv.partial").read_text().splitlines()) == 1 + 4


def test_the_sim_source_runs_the_plan(simulated):
    plan, _ = simulated
    source = open_capture_source("sim", steps=plan_steps(plan), rate_hz=200.0, pace=False)
    assert capture(plan, source).run.runs == 1
    with pytest.raises(AxiscalError, match="needs the plan"):
        open_capture_source("sim")


def test_the_capture_board_shows_the_plan_the_target_and_the_stops(simulated):
    import httpx

    from axiscal.capture.board import CaptureBoard
    from axiscal.live.server import LiveServer, create_board_app

    plan, sim = simulated
    board = CaptureBoard(plan_steps(plan), "sim")
    server = LiveServer(create_board_app(board.snapshot, page="capture.html"), port=0).start()
    with server, httpx.Client(base_url=server.url) as client:
        assert "axiscal capture" in client.get("/").text
        captured = capture(plan, sim.recording, on_stop=board.stop)
        state = client.get("/api/state").json()
        assert [p["step"] for p in state["plan"]] == [int(plan_steps(plan).step[r.index]) for r in captured.readings]
        assert [t["deviation_um"] for t in state["taken"]] == pytest.approx([r.deviation_m * 1e6 for r in captured.readings])
        assert client.get("/api/state", headers={"host": "evil.example"}).status_code == 403


def test_the_dashboard_goes_with_a_live_source(tmp_path, capsys):
    from axiscal.cli.main import main

    assert main(["capture", "plan.csv", "--from", "rec.csv", "-o", str(tmp_path / "r.csv"), "--dashboard"]) == 2
    assert "goes with --source" in capsys.readouterr().err
