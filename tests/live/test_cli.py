"""``axiscal live`` end to end: --duration, --no-server, --record, replay of a record, TCP, the dashboard, bad input."""

from __future__ import annotations

import re
import socket
import threading

import numpy as np
import pandas as pd
import pytest

from axiscal.live.protocol import encode_lines, header_line
from axiscal.live.recorder import read_record
from axiscal.live.state import result_columns
from axiscal.measurement.display import to_display
from axiscal.measurement.virtual import VirtualModule


@pytest.fixture(scope="module")
def system():
    return VirtualModule(seed=0).measurement_system()


@pytest.fixture(scope="module")
def recorded(tmp_path_factory):
    """A one-second record of the default sim source at 1 kHz, made by the command itself."""
    from axiscal.cli.main import main

    path = tmp_path_factory.mktemp("live") / "sim.csv"
    assert main(["live", "--no-server", "--duration", "1", "--rate", "1000", "--record", str(path)]) == 0
    return path


def test_duration_and_no_server_record_every_frame_in_order(recorded, system):
    record = read_record(recorded)
    assert 500 <= len(record) <= 1001  # about --duration s at --rate (a busy machine may end a batch or two behind)
    np.testing.assert_allclose(record.columns["t_s"], np.arange(len(record)) / 1000.0, atol=1e-6)
    assert list(record.columns) == ["t_s", *system.channels, "fault", *result_columns(system.axes)]
    assert (record.columns["fault"] == 0).all()
    assert np.isfinite(record.columns["e_um"]).all() and record.columns["e_um"].max() > 1.0
    assert record.metadata["kind"] == "live record" and record.metadata["source"].startswith("sim")
    assert record.metadata["fault_bits"]["256"].startswith("malformed frame") and not record.comments
    assert recorded.read_text().startswith("t_s,")
    frame = pd.read_csv(recorded)
    assert len(frame) == len(record) and {"t_s", "ex_um", "ey_um", "ez_um"} <= set(frame.columns)


def test_summary_line_on_stdout(run_cli, tmp_path):
    status, out, err = run_cli("live", "--no-server", "--duration", "0.3", "--rate", "500", "--path", "back-and-forth")
    assert status == 0
    assert re.search(r"^done .*frames \d+ .*faults 0", out)


def test_the_priority_the_loop_got_is_said_on_stderr(run_cli):
    status, out, err = run_cli("live", "--no-server", "--duration", "0.2", "--rate", "500")
    assert status == 0
    assert re.search(r"^priority: (real-time|nice -?\d+|normal)", err, re.M), err


def test_a_record_replays_to_the_same_results(run_cli, recorded, tmp_path):
    again = tmp_path / "again.csv"
    status, out, err = run_cli("live", "--no-server", "--source", f"replay:{recorded}", "--no-pace", "--record", str(again))
    assert status == 0, err
    first, second = read_record(recorded), read_record(again)
    assert len(first) == len(second)
    for name in ("t_s", "ex_um", "ey_um", "ez_um", "px_mm", "EXX_um", "ECZ_urad"):
        np.testing.assert_allclose(second.columns[name], first.columns[name], rtol=1e-8, atol=1e-9, err_msg=name)


def test_tcp_source_through_the_command(run_cli, tmp_path, system):
    module = VirtualModule(seed=1)
    frames, _ = module.frames(np.arange(300) / 1000.0)
    payload = header_line(system.channels) + encode_lines(frames["t_s"], np.column_stack([frames[c] for c in system.channels]))
    listener = socket.create_server(("127.0.0.1", 0))
    listener.settimeout(5.0)

    def serve():
        connection, _ = listener.accept()
        with connection:
            connection.sendall(payload)

    sender = threading.Thread(target=serve, daemon=True)
    sender.start()
    path = tmp_path / "tcp.csv"
    port = listener.getsockname()[1]
    status, out, err = run_cli("live", "--no-server", "--source", f"tcp:127.0.0.1:{port}", "--duration", "2.0", "--record", str(path))
    sender.join(timeout=5)
    listener.close()
    assert status == 0, err
    record = read_record(path)
    assert len(record) == 300
    np.testing.assert_allclose(record.columns["x_psd_y_um"], frames["x_psd_y_um"], rtol=1e-8)
    direct = to_display(system.process(frames))
    np.testing.assert_allclose(record.columns["ex_um"], direct["ex_um"], rtol=1e-6, atol=1e-6)


def test_with_the_dashboard_on_a_free_port(run_cli):
    status, out, err = run_cli("live", "--duration", "0.6", "--port", "0", "--rate", "500")
    assert status == 0
    assert re.search(r"dashboard: http://127\.0\.0\.1:\d+/", err)


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--rate", "0"], "--rate must be a positive"),
        (["--rate", "nan"], "--rate must be a finite number, got nan"),
        (["--rate", "fast"], "'fast' is not a valid float"),
        (["--duration", "-1"], "--duration must be positive"),
        (["--port", "70000"], "--port must be 0-65535"),
        (["--rate", "1e9"], "--rate must be a positive number of frames per second up to 100000"),
        (["--rate", "inf"], "--rate must be a finite number, got inf"),
        (["--update-hz", "0"], "--update-hz must be 0.1 to 60"),
        (["--update-hz", "1e300"], "--update-hz must be 0.1 to 60"),
        (["--update-hz", "nan"], "--update-hz must be a finite number, got nan"),
        (["--update-hz", "-inf"], "--update-hz must be a finite number, got -inf"),
        (["--duration", "inf"], "--duration must be a finite number, got inf"),
        (["--duration", "nan"], "--duration must be a finite number, got nan"),
        (["--load-kg", "-2"], "--load-kg must be a finite mass"),
        (["--load-kg", "nan"], "--load-kg must be a finite number, got nan"),
        (["--load-kg", "inf"], "--load-kg must be a finite number, got inf"),
        (["--seed", "-1"], "--seed must not be negative"),
        (["--port", "nan"], "'nan' is not a valid integer"),
        (["--path", "circle"], "'circle' is not one of"),
        (["--source", "camera"], "unknown source 'camera'"),
        (["--source", "tcp:localhost"], "expected tcp:HOST:PORT"),
        (["--source", "replay:/no/such/file.csv"], "replay file not found"),
        (["--machine", "/no/such/machine.toml"], "file not found"),
        (["--no-such-option"], "No such option"),
    ],
)
def test_bad_arguments_give_one_line_and_status_2(run_cli, args, message):
    status, out, err = run_cli("live", "--no-server", "--duration", "0.1", *args)
    assert status == 2
    assert err.count("\n") == 1 and err.startswith("axiscal: error: ")
    assert message in err


def test_replay_of_a_file_without_the_channels_is_refused(run_cli, tmp_path):
    path = tmp_path / "other.csv"
    path.write_text("t_s,a_um\n0,1\n")
    status, out, err = run_cli("live", "--no-server", "--source", f"replay:{path}")
    assert status == 2 and "lacks channel column" in err and err.count("\n") == 1


def test_a_machine_without_sensors_is_refused(run_cli, examples):
    status, out, err = run_cli("live", "--no-server", "--machine", str(examples / "xfyz_machine" / "machine.toml"))
    assert status == 2 and "sensors" in err and err.count("\n") == 1


def test_shipped_frames_replayed_with_the_shipped_machine_keep_their_two_faults(run_cli, examples, tmp_path):
    from axiscal.measurement.pipeline import MeasurementSystem

    machine = examples / "xz_module" / "sensors_machine.toml"
    frames_path = examples / "xz_module" / "sensors_frames.csv"
    path = tmp_path / "replayed.csv"
    status, out, err = run_cli(
        "live", "--machine", str(machine), "--source", f"replay:{frames_path}", "--no-pace", "--no-server", "--record", str(path)
    )
    assert status == 0, err
    assert "frames 200" in out and "faults 2" in out
    record = read_record(path)
    system = MeasurementSystem.from_toml(machine)
    source = read_record(frames_path)
    direct = to_display(system.process({name: source.columns[name] for name in ("t_s", *system.channels)}))
    np.testing.assert_array_equal(record.columns["fault"], direct["fault"])
    assert np.flatnonzero(record.columns["fault"]).tolist() == [50, 120]
    np.testing.assert_allclose(record.columns["ex_um"], direct["ex_um"], rtol=1e-8, atol=1e-9)
    assert np.isnan(record.columns["ex_um"][[50, 120]]).all()


def test_recording_over_the_file_being_replayed_is_refused(run_cli, recorded):
    before = recorded.read_bytes()
    status, out, err = run_cli("live", "--no-server", "--source", f"replay:{recorded}", "--record", str(recorded), "--force")
    assert status == 2 and "a file this run reads" in err and err.count("\n") == 1
    assert recorded.read_bytes() == before


def test_an_existing_record_needs_force(run_cli, tmp_path):
    record = tmp_path / "old.csv"
    record.write_text("precious\n")
    status, out, err = run_cli("live", "--no-server", "--duration", "0.1", "--record", str(record))
    assert status == 2 and err.count("\n") == 1 and "--force" in err and record.read_text() == "precious\n"
    status, out, err = run_cli("live", "--no-server", "--duration", "0.1", "--record", str(record), "--force")
    assert status == 0, err
    assert pd.read_csv(record).columns[0] == "t_s"


def test_a_record_folder_that_cannot_be_made_is_one_error_line(run_cli, tmp_path):
    blocker = tmp_path / "a_file"
    blocker.write_text("not a folder\n")
    status, out, err = run_cli("live", "--no-server", "--duration", "0.1", "--record", str(blocker / "run.csv"))
    assert status == 2 and err.count("\n") == 1 and "cannot create the record's folder" in err


def test_measure_and_replay_agree_on_unreadable_cells_and_line_ends(run_cli, tmp_path):
    """A channel cell that is not a number is a missing reading, a t_s that is not one a malformed
    frame -- in `measure` and in `live --source replay:` alike; CR-only line ends read as LF."""
    status, out, err = run_cli("simulate", "frames", "--duration", "0.02", "-o", str(tmp_path / "f.csv"))
    assert status == 0, err
    lines = (tmp_path / "f.csv").read_text().splitlines()
    cells = lines[5].split(",")
    cells[1] = "abc"
    lines[5] = ",".join(cells)
    lines[9] = "late," + lines[9].split(",", 1)[1]
    odd = tmp_path / "odd.csv"
    odd.write_bytes(("\r".join(lines) + "\r").encode())
    status, out, err = run_cli("measure", str(odd), "-o", str(tmp_path / "measured.csv"))
    assert status == 0, err
    replayed = tmp_path / "replayed.csv"
    status, out, err = run_cli("live", "--no-server", "--no-pace", "--source", f"replay:{odd}", "--record", str(replayed))
    assert status == 0, err
    measured = pd.read_csv(tmp_path / "measured.csv")
    record = pd.read_csv(replayed)
    assert len(measured) == len(record) == 20
    np.testing.assert_array_equal(measured["fault"], record["fault"])
    assert measured["fault"][4] & 1 and measured["fault"][8] & 256
    assert np.flatnonzero(measured["fault"]).tolist() == [4, 8]
    np.testing.assert_allclose(measured["ex_um"], record["ex_um"], rtol=1e-8, atol=1e-9)


@pytest.mark.parametrize(
    ("args", "message"),
    [(["--bind", "256.1.1.1"], "cannot listen on 256.1.1.1"), (["--allow-host", "monitor:8765"], "without port or scheme")],
)
def test_bad_dashboard_addresses_are_one_error_line_and_leave_no_record(run_cli, tmp_path, args, message):
    record = tmp_path / "run.csv"
    status, out, err = run_cli("live", "--duration", "0.1", "--port", "0", "--record", str(record), *args)
    assert status == 2 and err.count("\n") == 1 and message in err
    assert not record.exists()


def test_an_rtx_capture_through_the_command(run_cli, tmp_path, system):
    """`--source rtx:FILE:UNIT:CHANNEL`: the capture's samples become the channel's readings in the record."""
    from axiscal.io.importers.rtx import write_rtx

    samples_mm = 100.0 + 0.001 * np.arange(300)
    capture = tmp_path / "laser.rtx"
    write_rtx(capture, samples_mm, sample_rate_hz=1000.0, unit="mm")
    record_path = tmp_path / "rtx_run.csv"
    status, out, err = run_cli(
        "live", "--no-server", "--no-pace", "--source", f"rtx:{capture}:mm:x_scale_mm", "--record", str(record_path)
    )
    assert status == 0, err
    assert "frames 300" in out
    frame = pd.read_csv(record_path)
    np.testing.assert_allclose(frame["t_s"], np.arange(300) / 1000.0, atol=1e-9)
    np.testing.assert_allclose(frame["x_scale_mm"], samples_mm, rtol=1e-14)
    assert (frame["fault"] & 1).all()  # the other channels are missing
    assert read_record(record_path).metadata["source"].startswith(f"rtx {capture}")
    status, out, err = run_cli("live", "--no-server", "--source", f"rtx:{capture}:mm:x_scale_mm", "--record", str(capture), "--force")
    assert status == 2 and "a file this run reads" in err
