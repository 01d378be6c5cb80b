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


def serve(recording, names=("reading_mm", "air_temperature_c", "pressure_pa", "humidity_pct"), chunk=None):
    """A loopback server that sends the recording (at once, or ``chunk`` samples every 20 ms as a laser
    streams them) and keeps the connection open (the laser goes on)."""
    listener = socket.create_server(("127.0.0.1", 0))
    stop = threading.Event()
    values = np.column_stack([recording.reading_m / MM] + [recording.channels[n] for n in names[1:]])

    def run():
        connection, _ = listener.accept()
        connection.sendall(header_line(names))
        size = chunk or len(values)
        for k in range(0, len(values), size):
            connection.sendall(encode_lines(recording.time_s[k : k + size], values[k : k + size]))
            if chunk:
                stop.wait(0.02)
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


def cut(recording, end_s, start_s=-np.inf, source="cut"):
    """The part of a recording between two times."""
    keep = (recording.time_s >= start_s) & (recording.time_s < end_s)
    return type(recording)(recording.time_s[keep], recording.reading_m[keep], {k: v[keep] for k, v in recording.channels.items()},
                           source)


def test_a_resumed_stream_takes_the_last_stop_not_the_standstill_it_starts_with(simulated, tmp_path):
    # the partial holds every stop but the last; the stream starts with the axis standing (at the
    # datum, the last step's target): that standstill is not the last stop, nor any stop the partial holds
    plan, sim = simulated
    out = tmp_path / "run.csv"
    with pytest.raises(AxiscalError, match="the recording ends before it"):
        capture_to_file(plan, cut(sim.recording, sim.dwells[-1, 0] - 0.5), out)
    assert len((tmp_path / "run.csv.partial").read_text().splitlines()) == 1 + plan.readings - 1
    port, stop = serve(sim.recording)
    source = open_capture_source(f"tcp:127.0.0.1:{port}")
    try:
        resumed = capture_to_file(plan, source, out, resume=True, timeout_s=20.0).capture
    finally:
        stop.set()
        source.close()
    whole = capture(plan, sim.recording)
    got, want = [r.deviation_m for r in resumed.readings], [r.deviation_m for r in whole.readings]
    assert got[:-1] == pytest.approx(want[:-1], abs=1e-9) and got[-1] == pytest.approx(want[-1], abs=0.05e-6)


def test_a_resumed_stream_that_starts_at_the_last_target_has_not_captured_it(simulated, tmp_path):
    # the stream starts with the axis already standing at the last target: that is not a stop it came to
    plan, sim = simulated
    out = tmp_path / "run.csv"
    with pytest.raises(AxiscalError, match="the recording ends before it"):
        capture_to_file(plan, cut(sim.recording, sim.dwells[-1, 0] - 0.5), out)
    arrive, leave, _ = sim.dwells[-1]
    tail = cut(sim.recording, np.inf, start_s=(arrive + leave) / 2)
    rest = cut(sim.recording, np.inf, start_s=sim.recording.time_s[-1] - 1.0)  # standing still at the end
    n, span = rest.time_s.size, rest.time_s[-1] - rest.time_s[0] + 1 / 500.0
    standing = type(tail)(  # the stream goes on for 5 s more, batch after batch
        np.concatenate([tail.time_s] + [rest.time_s + span * (k + 1) for k in range(5)]),
        np.concatenate([tail.reading_m] + [rest.reading_m] * 5),
        {k: np.concatenate([v] + [rest.channels[k]] * 5) for k, v in tail.channels.items()}, "standing")
    assert n > 100 and np.all(np.diff(standing.time_s) > 0)
    port, stop = serve(standing, chunk=250)
    source = open_capture_source(f"tcp:127.0.0.1:{port}")
    try:
        with pytest.raises(AxiscalError, match=r"step \d+ \(target 0.000 mm, run 1, -\): the recording ends before it"):
            capture_to_file(plan, source, out, resume=True, timeout_s=1.5)
    finally:
        stop.set()
        source.close()
    assert len((tmp_path / "run.csv.partial").read_text().splitlines()) == 1 + plan.readings - 1


def test_the_sim_source_resumed_goes_on_after_the_partial(tmp_path):
    # the sim replays the plan from its first step: a resume passes over the stops the partial holds
    from importlib import resources
    from pathlib import Path

    plan = plan_test(0.0, 0.19, 5, runs=2, seed=4)
    steps = plan_steps(plan)
    machine = load_machine(Path(str(resources.files("axiscal") / "data" / "xz_module" / "machine.toml")))  # the sim's
    replay = simulate_motions(plan_motions(steps), machine, axis="X", rate_hz=200.0, seed=0)
    whole = capture(plan, open_capture_source("sim", steps=steps, rate_hz=200.0, pace=False))
    out = tmp_path / "run.csv"
    for taken in (3, plan.readings - 1):  # partway, and all but the last stop
        (tmp_path / "run.csv.partial").unlink(missing_ok=True)
        with pytest.raises(AxiscalError, match="the recording ends before it"):
            capture_to_file(plan, cut(replay.recording, replay.dwells[taken, 0]), out)
        assert len((tmp_path / "run.csv.partial").read_text().splitlines()) == 1 + taken
        source = open_capture_source("sim", steps=steps, rate_hz=200.0, pace=False)
        resumed = capture_to_file(plan, source, out, resume=True).capture
        assert [r.index for r in resumed.readings] == [r.index for r in whole.readings]
        got, want = [r.deviation_m for r in resumed.readings], [r.deviation_m for r in whole.readings]
        assert got[:-1] == pytest.approx(want[:-1], abs=1e-9) and got[-1] == pytest.approx(want[-1], abs=0.05e-6)


def test_a_host_timestamped_stream_whose_axis_stands_at_the_start(simulated, tmp_path):
    # uneven time stamps (the host's clock): the first whole window does not begin at sample 0, yet the
    # standstill the stream starts with is passed over, as in the same recording read from a file
    plan, sim = simulated
    rng = np.random.default_rng(5)
    rec = sim.recording
    t = np.cumsum(rng.uniform(1.0, 3.0, int(rec.time_s[-1] * 500))) * 1e-3
    t = t[t <= rec.time_s[-1]]
    uneven = type(rec)(t, np.interp(t, rec.time_s, rec.reading_m), {k: np.interp(t, rec.time_s, v) for k, v in rec.channels.items()},
                       "host")
    port, stop = serve(uneven)
    source = open_capture_source(f"tcp:127.0.0.1:{port}")
    try:
        live = capture_to_file(plan, source, tmp_path / "live.csv", timeout_s=20.0).capture
    finally:
        stop.set()
        source.close()
    offline = capture(plan, uneven)
    assert len(live.readings) == len(offline.readings) == plan.readings
    live_dev, offline_dev = [r.deviation_m for r in live.readings], [r.deviation_m for r in offline.readings]
    assert live_dev[:-1] == pytest.approx(offline_dev[:-1], abs=1e-9) and live_dev[-1] == pytest.approx(offline_dev[-1], abs=0.05e-6)
