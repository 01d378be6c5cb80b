"""The live record: round trip, pandas, a cut last line, and crash safety (SIGKILL of a running ``axiscal live``)."""

from __future__ import annotations

import errno
import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from axiscal.errors import AxiscalError
from axiscal.live.recorder import FORMAT_LINE, Recorder, read_record

CHANNELS = ("x_scale_mm", "x_psd_y_um")
RESULTS = ("ex_um", "ey_um", "ez_um")


def _write(path: Path, n: int = 50) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    rng = np.random.default_rng(0)
    t = np.arange(n) / 1000.0
    values = rng.normal(size=(n, 2)) * [50.0, 3.0]
    values[7, 1] = np.nan
    fault = np.zeros(n, dtype=np.int64)
    fault[7] = 1
    ex = rng.normal(size=n)
    ex[7] = np.nan
    with Recorder(path, CHANNELS, RESULTS, metadata={"source": "test"}) as recorder:
        for k in range(0, n, 8):
            recorder.append(t[k : k + 8], values[k : k + 8], fault[k : k + 8], {"ex_um": ex[k : k + 8], "ey_um": ex[k : k + 8] * 2})
        assert recorder.frames_written == n
    assert recorder.frames_acknowledged == n
    return t, values, ex


def test_record_round_trip_through_read_record(tmp_path):
    path = tmp_path / "r.csv"
    t, values, ex = _write(path)
    record = read_record(path)
    assert record.metadata["kind"] == "live record" and record.metadata["source"] == "test"
    assert record.metadata["channels"] == list(CHANNELS) and record.metadata["results"] == list(RESULTS)
    assert record.metadata["fault_bits"] == {"1": "missing channel", "2": "channel out of range", "4": "position outside the error model", "256": "malformed frame (no readable time stamp, or more fields than columns)"}
    assert record.comments == ()
    assert list(record.columns) == ["t_s", *CHANNELS, "fault", *RESULTS]
    np.testing.assert_allclose(record.columns["t_s"], t, atol=5e-7)
    np.testing.assert_allclose(record.columns["x_scale_mm"], values[:, 0], rtol=1e-8)
    np.testing.assert_allclose(record.columns["ex_um"], ex, rtol=1e-8)
    assert np.isnan(record.columns["ez_um"]).all()
    assert record.columns["fault"][7] == 1 and np.isnan(record.columns["x_psd_y_um"][7])
    assert not record.truncated


def test_record_is_plain_csv_pandas_reads_with_no_options(tmp_path):
    path = tmp_path / "r.csv"
    t, values, ex = _write(path)
    assert path.read_text().splitlines()[0] == ",".join(["t_s", *CHANNELS, "fault", *RESULTS])
    assert not any(line.startswith("#") for line in path.read_text().splitlines())
    frame = pd.read_csv(path)
    assert list(frame.columns) == ["t_s", *CHANNELS, "fault", *RESULTS]
    np.testing.assert_allclose(frame["ex_um"].to_numpy(), ex, rtol=1e-8)
    assert frame["fault"].dtype.kind == "i"


def test_a_cut_last_line_is_dropped_by_read_record_and_readable_by_pandas(tmp_path):
    path = tmp_path / "r.csv"
    _write(path)
    data = path.read_bytes()
    path.write_bytes(data[: data.rfind(b"\n", 0, len(data) - 1) + 12])
    record = read_record(path)
    assert record.truncated and len(record) == 49
    frame = pd.read_csv(path)
    assert len(frame) == 50
    np.testing.assert_allclose(frame["t_s"].to_numpy()[:49], record.columns["t_s"])


def test_records_in_the_earlier_format_are_still_read(tmp_path):
    # format 1: comment lines (format line, source, fault bits) before the header, no sidecar
    path = tmp_path / "old.csv"
    path.write_text(FORMAT_LINE + "\n# source: sim\nt_s,x_scale_mm,fault,ex_um\n0.001,1.5,0,0.25\n0.002,1.6,1,nan\n0.003,1.")
    record = read_record(path)
    assert record.comments == (FORMAT_LINE[1:].strip(), "source: sim") and record.metadata == {}
    assert record.truncated and record.columns["t_s"].tolist() == [0.001, 0.002]
    assert record.columns["ex_um"][0] == 0.25 and np.isnan(record.columns["ex_um"][1])


def test_only_a_live_record_loses_a_last_line_without_newline(tmp_path):
    path = tmp_path / "plain.csv"
    path.write_text("t_s,a\n0.1,1\n0.2,2")  # not written by the recorder: the last line is a frame
    record = read_record(path)
    assert not record.truncated and record.columns["t_s"].tolist() == [0.1, 0.2]


def test_bad_record_files_name_file_and_line(tmp_path):
    path = tmp_path / "bad.csv"
    path.write_text("time,a\n0.1,1\n")
    with pytest.raises(AxiscalError, match="no 't_s' column"):
        read_record(path)
    path.write_text("t_s,a\n0.1,1,2\n")
    with pytest.raises(AxiscalError, match=r":2: 3 cells where the header has 2"):
        read_record(path)
    with pytest.raises(AxiscalError, match="file not found"):
        read_record(tmp_path / "missing.csv")


def test_recorder_refuses_a_path_it_cannot_open(tmp_path):
    with pytest.raises(AxiscalError, match="cannot open the record file"):
        Recorder(tmp_path / "no" / "such" / "dir.csv", CHANNELS, RESULTS)


def test_acknowledged_frames_survive_sigkill_of_the_live_process(tmp_path):
    path = tmp_path / "crash.csv"
    rate = 2000
    command = [sys.executable, "-m", "axiscal.cli.main", "live", "--no-server", "--rate", str(rate), "--record", str(path), "--duration", "30"]
    process = subprocess.Popen(command, stderr=subprocess.PIPE, stdout=subprocess.DEVNULL, text=True, env=os.environ | {"PYTHONUNBUFFERED": "1"})
    acknowledged = 0
    deadline = time.monotonic() + 20.0
    try:
        while acknowledged < 1500 and time.monotonic() < deadline:
            line = process.stderr.readline()
            if not line:
                break
            found = re.search(r"recorded (\d+)/(\d+)", line)
            if found:
                acknowledged = int(found.group(1))
    finally:
        process.send_signal(signal.SIGKILL)
        process.wait(timeout=10)
    assert process.returncode == -signal.SIGKILL
    assert acknowledged >= 1500
    record = read_record(path)
    assert len(record) >= acknowledged
    # every frame up to the last one written is there, none lost, none repeated
    np.testing.assert_allclose(record.columns["t_s"], np.arange(len(record)) / rate, atol=1e-6)
    assert (record.columns["fault"] == 0).all()
    assert np.isfinite(record.columns["ex_um"]).all()
    frame = pd.read_csv(path)
    assert len(frame) >= acknowledged
    np.testing.assert_allclose(frame["ex_um"].to_numpy()[:acknowledged], record.columns["ex_um"][:acknowledged])


def test_a_failing_write_is_one_error_naming_the_file_and_what_was_kept(tmp_path, monkeypatch):
    assert Path("/dev/full").exists(), "/dev/full (Linux) gives every write 'no space left on device'"
    with pytest.raises(AxiscalError, match=r"/dev/full: cannot write the record file \(No space left on device\)"):
        Recorder("/dev/full", CHANNELS, RESULTS)
    recorder = Recorder(tmp_path / "r.csv", CHANNELS, RESULTS)
    recorder.append(np.zeros(3), np.zeros((3, 2)), np.zeros(3, dtype=np.int64), {})
    recorder.sync()

    def disk_full(fd, data):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    monkeypatch.setattr(os, "write", disk_full)
    with pytest.raises(AxiscalError, match=r"r.csv: cannot write the record file \(No space left on device\); 3 frames were acknowledged"):
        recorder.append(np.ones(1), np.zeros((1, 2)), np.zeros(1, dtype=np.int64), {})
    monkeypatch.undo()
    recorder.close()
    assert len(read_record(tmp_path / "r.csv")) == 3


def test_a_cell_that_is_not_a_number_is_a_missing_reading_as_in_measure(tmp_path):
    """read_record (the replay source) and read_frames (axiscal measure) read cells by one rule."""
    from axiscal.measurement.offline import read_frames

    path = tmp_path / "odd.csv"
    path.write_text("t_s,a\n0.1,1\n0.2,oops\nlate,3\n0.4,\n")
    record = read_record(path).columns
    frames = read_frames(path, ["a"])
    for name in ("t_s", "a"):
        np.testing.assert_array_equal(record[name], frames[name])
    np.testing.assert_array_equal(frames["a"], [1, np.nan, 3, np.nan])
    assert np.isnan(frames["t_s"][2])


@pytest.mark.parametrize("end", ["\r", "\r\n", "\n"])
def test_records_with_any_line_end_read_alike(tmp_path, end):
    path = tmp_path / "ends.csv"
    path.write_bytes(end.join(["t_s,a", "0.1,1", "0.2,2", ""]).encode())
    record = read_record(path)
    assert record.columns["t_s"].tolist() == [0.1, 0.2] and record.columns["a"].tolist() == [1, 2]
