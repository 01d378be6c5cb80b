"""Live sources and the pipeline loop: sim pacing, replay, TCP on loopback with back-off, faults kept."""

from __future__ import annotations

import fcntl
import gc
import os
import socket
import struct
import sys
import termios
import threading
import time
import tty

import numpy as np
import pytest

from axiscal.errors import AxiscalError
from axiscal.live.pipeline import Pipeline
from axiscal.live.protocol import FrameBatch, encode_lines, header_line
from axiscal.live.recorder import Recorder, read_record
from axiscal.live.sources import (
    Backoff,
    ReplaySource,
    SerialSource,
    SimSource,
    TcpSource,
    open_source,
    parse_source,
)
from axiscal.live.state import LiveState, result_columns
from axiscal.measurement.faults import Fault


class LineServer:
    """A loopback acquisition box: accepts connections one after another and sends each its payload, then closes."""

    def __init__(self, payloads, *, port=0, pause_s=0.0):
        self.listener = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        self.listener.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        self.listener.bind(("127.0.0.1", port))
        self.listener.listen(1)
        self.listener.settimeout(5.0)
        self.port = self.listener.getsockname()[1]
        self.payloads = list(payloads)
        self.pause_s = pause_s
        self.thread = threading.Thread(target=self._serve, daemon=True)
        self.thread.start()

    def _serve(self):
        for payload in self.payloads:
            try:
                connection, _ = self.listener.accept()
            except OSError:
                return
            with connection:
                for k in range(0, len(payload), 997):
                    connection.sendall(payload[k : k + 997])
                time.sleep(self.pause_s)
        self.listener.close()

    def join(self):
        self.thread.join(timeout=10)
        self.listener.close()


def _drain(source, *, frames, timeout_s=5.0):
    batches = []
    deadline = time.monotonic() + timeout_s
    while sum(len(b) for b in batches) < frames and time.monotonic() < deadline:
        batch = source.read(0.02)
        if len(batch):
            batches.append(batch)
    return FrameBatch.concatenate(batches, len(source.channels))


def _frames(module, system, n, start=0):
    frames, _ = module.frames((start + np.arange(n)) / 1000.0)
    return FrameBatch.from_frames(frames, system.channels)


def test_sim_source_delivers_frames_at_the_rate_in_real_time(module, system):
    source = SimSource(module, system.channels, rate_hz=2000.0)
    start = time.monotonic()
    batch = _drain(source, frames=400)
    elapsed = time.monotonic() - start
    np.testing.assert_allclose(batch.t_s[:400], np.arange(400) / 2000.0)
    assert 0.19 < elapsed < 5.0  # never ahead of the clock; the upper bound only catches a hang
    assert source.clock_offset_s is not None and not source.finished


def test_replay_paced_follows_t_s_and_fast_replay_does_not_wait(tmp_path, module, system):
    batch = _frames(module, system, 300)
    path = tmp_path / "r.csv"
    with Recorder(path, system.channels, ()) as recorder:
        recorder.append(batch.t_s, batch.values, np.zeros(300, dtype=np.int64), {})
    paced = ReplaySource(path, system.channels, pace=True)
    start = time.monotonic()
    got = _drain(paced, frames=300)
    assert time.monotonic() - start > 0.25 and paced.finished
    np.testing.assert_allclose(got.values, batch.values, rtol=1e-8)
    fast = ReplaySource(path, system.channels, pace=False, max_batch=128)
    reads = [len(fast.read(10.0)) for _ in range(3)]  # no read waits for the file's clock: 128, 128, 44
    assert reads == [128, 128, 44] and fast.finished


def test_replay_needs_every_channel(tmp_path, system):
    path = tmp_path / "short.csv"
    path.write_text("t_s,x_scale_mm\n0,1\n")
    with pytest.raises(AxiscalError, match="lacks channel column"):
        ReplaySource(path, system.channels)


def test_tcp_source_reads_frames_and_reconnects_after_the_sender_drops(module, system):
    first, second = _frames(module, system, 200), _frames(module, system, 150, start=200)
    server = LineServer([header_line(system.channels) + encode_lines(first.t_s, first.values), encode_lines(second.t_s, second.values)])
    source = TcpSource("127.0.0.1", server.port, system.channels, backoff=Backoff(initial_s=0.01, maximum_s=0.05))
    got = _drain(source, frames=350)
    source.close()
    server.join()
    np.testing.assert_array_equal(got.t_s, np.concatenate([first.t_s, second.t_s]))
    np.testing.assert_array_equal(got.values, np.concatenate([first.values, second.values]))
    assert source.status.connections == 2 and source.status.retries >= 1


def test_back_off_doubles_between_failed_connects_up_to_the_cap_and_then_connects(module, system):
    probe = socket.socket()
    probe.bind(("127.0.0.1", 0))
    port = probe.getsockname()[1]
    probe.close()
    source = TcpSource("127.0.0.1", port, system.channels, backoff=Backoff(initial_s=0.02, factor=2.0, maximum_s=0.16))
    expected = [0.02, 0.04, 0.08, 0.16, 0.16]
    deadline = time.monotonic() + 10.0
    while len(source.status.attempt_times) <= len(expected) and time.monotonic() < deadline:
        assert len(source.read(0.01)) == 0
    assert source.status.state == "retrying"
    gaps = np.diff(source.status.attempt_times)
    assert len(gaps) >= len(expected)
    np.testing.assert_array_less(np.array(expected) - 0.002, gaps[: len(expected)])
    # a late wake-up on a busy machine only lengthens a gap; the cap still shows (uncapped, the last would be 0.32 s)
    np.testing.assert_array_less(gaps[: len(expected)], np.array(expected) + 0.15)
    batch = _frames(module, system, 20)
    server = LineServer([encode_lines(batch.t_s, batch.values)], port=port)
    got = _drain(source, frames=20, timeout_s=3.0)
    source.close()
    server.join()
    assert len(got) == 20 and source.status.connections == 1


def test_faulty_frames_are_flagged_and_kept_in_the_record_not_dropped(tmp_path, module, system):
    good = _frames(module, system, 6)
    lines = encode_lines(good.t_s, good.values).decode().splitlines()
    cells = [line.split(",") for line in lines]
    cells[1][3] = ""  # a missing channel
    cells[2][4] = "1e6"  # far outside its range
    cells[3][0] = "garbage"  # no time stamp
    cells[4][5] = "oops"  # a cell that is not a number
    payload = ("\n".join(",".join(c) for c in cells) + "\n").encode()
    server = LineServer([payload])
    source = TcpSource("127.0.0.1", server.port, system.channels)
    path = tmp_path / "faults.csv"
    recorder = Recorder(path, system.channels, result_columns(system.axes))
    state = LiveState(system)
    pipeline = Pipeline(system, source, recorder=recorder, state=state)
    deadline = time.monotonic() + 5.0
    while pipeline.frames < 6 and time.monotonic() < deadline:
        pipeline.step(0.02)
    recorder.close()
    source.close()
    server.join()
    record = read_record(path)
    assert len(record) == 6
    fault = record.columns["fault"].astype(int)
    assert fault[0] == 0 and fault[5] == 0
    assert fault[1] & 1 and fault[2] & 2 and fault[3] & Fault.MALFORMED and fault[4] & 1
    assert np.isfinite(record.columns["ex_um"][[0, 5]]).all()
    assert np.isnan(record.columns["ex_um"][1:5]).all()
    assert np.isnan(record.columns["t_s"][3]) and record.columns["t_s"][4] == good.t_s[4]
    snapshot = state.snapshot()
    assert snapshot["frames"] == 6 and snapshot["faults"] == 4
    assert {s["name"]: s["missing"] for s in snapshot["sensors"]}[system.channels[2]] == 1
    assert state.describe_fault(Fault.MALFORMED | 1).startswith("malformed frame")


def test_pipeline_results_equal_the_measurement_system_on_the_same_frames(module, system):
    source = SimSource(module, system.channels, rate_hz=5000.0)
    pipeline = Pipeline(system, source)
    frames = []
    original = pipeline.process

    enough = threading.Event()  # 1000 frames (0.2 s at 5 kHz), however long a loaded machine takes to give them

    def keep(batch):
        fault, results = original(batch)
        frames.append((batch, results))
        if sum(len(b) for b, _ in frames) > 1000:
            enough.set()
        return fault, results

    pipeline.process = keep
    summary = pipeline.run(stop=enough, duration_s=30.0)
    assert summary.frames == sum(len(b) for b, _ in frames) > 1000
    batch = FrameBatch.concatenate([b for b, _ in frames], len(system.channels))
    direct = system.process(batch.frames(system.channels))
    np.testing.assert_allclose(np.concatenate([r["ex_m"] for _, r in frames]), direct["ex_m"], rtol=1e-12, atol=1e-18)
    assert summary.latency_p99_ms > 0


def test_source_specs_and_their_errors(tmp_path, system):
    assert parse_source("sim") == ("sim", "")
    assert parse_source("tcp:127.0.0.1:9000") == ("tcp", "127.0.0.1:9000")
    for bad in ("simulator", "tcp:host", "tcp:127.0.0.1:70000", "replay:", "udp:1"):
        with pytest.raises(AxiscalError):
            parse_source(bad)
    with pytest.raises(AxiscalError, match="replay file not found"):
        open_source(f"replay:{tmp_path / 'none.csv'}", system.channels)
    assert isinstance(open_source("tcp:127.0.0.1:9", system.channels), TcpSource)


def test_serial_source_without_pyserial_is_a_clear_error(monkeypatch, system):
    monkeypatch.setitem(sys.modules, "serial", None)
    with pytest.raises(AxiscalError, match="needs the optional package pyserial"):
        SerialSource("/dev/null", system.channels)


def test_latency_ring_keeps_the_most_recent_delays_in_order():
    class Channels:
        channels = ("a_um",)
        axes = ("X",)

    pipeline = Pipeline(Channels(), None, latency_capacity=7)
    rng = np.random.default_rng(0)
    kept: list[float] = []
    for _ in range(40):
        delays = rng.normal(size=int(rng.integers(0, 12)))
        pipeline._keep_latency(delays)
        kept.extend(delays.tolist())
        for last in (None, 1, 3, 7, 50):
            window = min(len(kept), 7 if last is None else min(last, 7))
            np.testing.assert_array_equal(pipeline.latencies_s(last), kept[len(kept) - window :])


class _PtySerial:
    """Stands in for pyserial's ``serial`` module: a ``Serial`` that opens a pseudo-terminal."""

    class SerialException(OSError):
        pass

    class Serial:
        def __init__(self, device, baud, timeout=0):
            self.fd = os.open(device, os.O_RDWR | os.O_NOCTTY | os.O_NONBLOCK)
            tty.setraw(self.fd)

        def fileno(self):
            return self.fd

        @property
        def in_waiting(self):
            return struct.unpack("i", fcntl.ioctl(self.fd, termios.FIONREAD, b"\0\0\0\0"))[0]

        def read(self, size):
            try:
                return os.read(self.fd, size)
            except BlockingIOError:
                return b""

        def close(self):
            os.close(self.fd)


def test_serial_source_reads_the_line_protocol_and_retries_when_the_port_fails(monkeypatch, module, system):
    monkeypatch.setitem(sys.modules, "serial", _PtySerial)
    controller, device = os.openpty()
    tty.setraw(device)
    path = os.ttyname(device)
    source = SerialSource(path, system.channels, baud=115200, backoff=Backoff(initial_s=0.01, maximum_s=0.05))
    assert len(source.read(0.01)) == 0 and source.status.state == "streaming"
    batch = _frames(module, system, 40)
    data = encode_lines(batch.t_s, batch.values)

    def write_all():
        view = memoryview(data)
        while view:
            view = view[os.write(controller, view[:512]) :]

    writer = threading.Thread(target=write_all, daemon=True)
    writer.start()
    got = _drain(source, frames=40)
    writer.join(timeout=5)
    np.testing.assert_array_equal(got.values, batch.values)
    assert source.status.state == "streaming"
    os.close(controller)
    os.close(device)
    deadline = time.monotonic() + 2.0
    while source.status.retries == 0 and time.monotonic() < deadline:
        source.read(0.02)
    source.close()
    assert source.status.retries >= 1 and "serial" in source.status.description


def test_tcp_source_memory_stays_bounded_under_a_line_without_end(module, system):
    """32 MB without a line end: one malformed frame, the frames after it decoded, memory never holds the line."""
    import tracemalloc

    before, after = _frames(module, system, 50), _frames(module, system, 50, start=50)
    flood = 32 << 20
    payload = encode_lines(before.t_s, before.values) + b"7" * flood + b"\n" + encode_lines(after.t_s, after.values)
    server = LineServer([payload])
    source = TcpSource("127.0.0.1", server.port, system.channels)
    tracemalloc.start()
    try:
        got = _drain(source, frames=101, timeout_s=30.0)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
        source.close()
        server.join()
    assert len(got) == 101 and np.flatnonzero(got.malformed).tolist() == [50]
    np.testing.assert_array_equal(got.t_s[51:], after.t_s)
    assert source.decoder.overlong_lines == 1
    # the line is never held: under load the reader takes larger reads from the socket (8.0 MiB was seen), far
    # below the 32 MiB that came without a line end
    assert peak < 12 << 20, f"peak {peak / 2**20:.1f} MiB while {flood >> 20} MiB came without a line end"


def test_an_rtx_capture_replays_as_the_reading_of_one_channel(tmp_path, system):
    from axiscal.io.importers.rtx import write_rtx
    from axiscal.live.sources import RtxSource

    samples_nm = np.array([0.0, 1500.0, -250.0, 12.5, 7.0])
    path = tmp_path / "x axis.rtx"
    write_rtx(path, samples_nm, sample_rate_hz=200.0, unit="nm")
    source = RtxSource(path, "nm", "x_psd_y_um", system.channels, pace=False)
    batch = source.read(1.0)
    assert source.finished and len(batch) == 5
    np.testing.assert_allclose(batch.t_s, np.arange(5) / 200.0)
    column = system.channels.index("x_psd_y_um")
    np.testing.assert_allclose(batch.values[:, column], samples_nm / 1000.0)  # nm in the file, um in the channel
    assert np.isnan(np.delete(batch.values, column, axis=1)).all() and not batch.malformed.any()
    assert "200 Hz" in source.status.description and "as x_psd_y_um" in source.status.description
    paced = RtxSource(path, "nm", "x_psd_y_um", system.channels)
    start = time.monotonic()
    assert len(_drain(paced, frames=5)) == 5 and time.monotonic() - start > 0.015  # at the capture's 200 Hz
    with pytest.raises(AxiscalError, match="channel 'x_nope_um' is not one of"):
        RtxSource(path, "nm", "x_nope_um", system.channels)
    with pytest.raises(AxiscalError, match="unknown length unit 'parsec'"):
        RtxSource(path, "parsec", "x_psd_y_um", system.channels)
    with pytest.raises(AxiscalError, match="expected rtx:FILE:UNIT:CHANNEL"):
        parse_source(f"rtx:{path}:nm")
    with pytest.raises(AxiscalError, match="rtx capture not found"):
        open_source("rtx:/no/such.rtx:mm:x_scale_mm", system.channels)


def test_sim_source_computes_its_frames_ahead_not_once_a_read(module, system):
    """One ``VirtualModule.frames`` call makes AHEAD_S of stream: a call costs about the same for 1 frame as for 200."""
    from axiscal.live.playback import AHEAD_S

    calls = []

    class Counting:
        def frames(self, t, *, path):
            calls.append(len(t))
            return module.frames(t, path=path)

    source = SimSource(Counting(), system.channels, rate_hz=2000.0)
    batch = _drain(source, frames=400)
    np.testing.assert_array_equal(batch.t_s[:400], np.arange(400) / 2000.0)  # every frame once, in order, on time
    assert sum(calls) >= len(batch) and all(n >= AHEAD_S * 2000.0 for n in calls)
    assert len(calls) <= len(batch) / (AHEAD_S * 2000.0) + 1


def test_the_pipeline_reads_the_source_at_most_once_a_batch_interval(module, system):
    """Frames that arrive within batch_interval_s of the last read make one batch (each batch costs a fixed time);
    during the run another thread holding the interpreter lock gives it up within 0.5 ms."""
    source = SimSource(module, system.channels, rate_hz=5000.0)
    reads = []
    read = source.read

    switching = []

    enough = threading.Event()  # 0.3 s of reads, or more where a loaded machine gave fewer than 8 batches by then

    def timed(timeout_s):
        start = time.monotonic()
        switching.append(sys.getswitchinterval())
        batch = read(timeout_s)
        if len(batch):
            reads.append(start)
            if len(reads) >= 8 and start - reads[0] >= 0.3:
                enough.set()
        return batch

    source.read = timed
    pipeline = Pipeline(system, source, batch_interval_s=0.01)
    pipeline.run(stop=enough, duration_s=30.0)
    assert pipeline.batches >= 5 and (reads[-1] - reads[0]) / (len(reads) - 1) >= 0.0099  # the cadence; one read may catch up
    assert pipeline.frames >= 0.1 * 5000 and gc.get_freeze_count() == 0  # the collector's frozen objects are given back
    assert max(switching) <= 0.0005 < sys.getswitchinterval()  # another thread gives the lock up fast during the run only
    for bad in (-0.001, 0.2, float("nan")):
        with pytest.raises(AxiscalError, match="batch_interval_s"):
            Pipeline(system, source, batch_interval_s=bad)
