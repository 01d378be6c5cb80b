"""A live run set up in one call: settings checked, record with its sidecar, summary."""

from __future__ import annotations

import json

import pandas as pd
import pytest

from axiscal.errors import AxiscalError
from axiscal.live.session import LiveSession


def test_a_session_records_a_plain_csv_with_its_sidecar(tmp_path):
    record = tmp_path / "run" / "live.csv"
    with LiveSession(rate_hz=500.0, record=record, server=False) as session:
        assert session.url is None
        summary = session.run(duration_s=0.3)
    assert summary.frames > 0 and summary.frames_acknowledged == summary.frames_written == summary.frames
    assert summary.progress_text(summary.mean_rate_hz, label="done").startswith("done ")
    frame = pd.read_csv(record)
    assert len(frame) == summary.frames and list(frame.columns[:2]) == ["t_s", "x_cmd_mm"]
    meta = json.loads(record.with_suffix(".json").read_text())
    assert meta["kind"] == "live record" and meta["machine"].startswith("built-in virtual module") and "started" in meta


@pytest.mark.parametrize(
    ("settings", "message"),
    [
        ({"rate_hz": 0.0}, "rate_hz must be a positive"),
        ({"duration_s": -1.0}, "duration_s must be positive"),
        ({"port": 70000}, "port must be 0-65535"),
        ({"rate_hz": 1e9}, "up to 100000"),
        ({"rate_hz": float("nan")}, "rate_hz must be a positive"),
        ({"duration_s": float("inf")}, "duration_s must be positive"),
        ({"update_hz": 0.0}, "update_hz must be 0.1 to 60"),
        ({"update_hz": 1e300}, "update_hz must be 0.1 to 60"),
        ({"update_hz": float("nan")}, "update_hz must be 0.1 to 60"),
        ({"load_kg": -2.0}, "load_kg must be a finite mass"),
        ({"load_kg": float("inf")}, "load_kg must be a finite mass"),
        ({"seed": -1}, "seed must not be negative"),
        ({"path": "circle"}, "unknown path"),
        ({"source": "udp:1"}, "unknown source"),
    ],
)
def test_bad_settings_are_one_error(settings, message):
    with pytest.raises(AxiscalError, match=message):
        LiveSession(server=False, **settings)


def test_recording_over_the_replayed_file_is_refused(tmp_path):
    run = tmp_path / "run.csv"
    run.write_text("t_s\n0\n")
    for name in (run, tmp_path / "." / "run.csv"):
        with pytest.raises(AxiscalError, match="would overwrite run.csv, a file this run reads"):
            LiveSession(source=f"replay:{run}", record=name, server=False, force=True)
    assert run.read_text() == "t_s\n0\n"


def test_a_hard_or_symbolic_link_to_an_input_is_the_input(tmp_path, examples):
    run = tmp_path / "run.csv"
    run.write_text("t_s\n0\n")
    (tmp_path / "hard.csv").hardlink_to(run)
    (tmp_path / "soft.csv").symlink_to(run)
    for name in ("hard.csv", "soft.csv"):
        with pytest.raises(AxiscalError, match="a file this run reads"):
            LiveSession(source=f"replay:{run}", record=tmp_path / name, server=False, force=True)
    machine = tmp_path / "machine.toml"
    machine.hardlink_to(examples / "xz_module" / "sensors_machine.toml")
    (tmp_path / "rec.json").hardlink_to(machine)  # the record's sidecar would overwrite the machine file
    with pytest.raises(AxiscalError, match="would overwrite rec.json"):
        LiveSession(machine=machine, source=f"replay:{examples / 'xz_module' / 'sensors_frames.csv'}", record=tmp_path / "rec.csv", server=False)
    assert run.read_text() == "t_s\n0\n"


def test_an_existing_record_is_kept_unless_force(tmp_path):
    record = tmp_path / "old.csv"
    record.write_text("precious\n")
    with pytest.raises(AxiscalError, match="the record file exists; choose another file, or give force=True"):
        LiveSession(record=record, server=False)
    assert record.read_text() == "precious\n"
    with LiveSession(record=record, server=False, force=True) as session:
        summary = session.run(duration_s=0.1)
    assert record.read_text().startswith("t_s,") and summary.frames > 0


def test_the_library_parts_refuse_unbounded_rates_before_allocating(system):
    """The sim source and the broadcaster check their rates themselves (a Python user may call them directly)."""
    from axiscal.live.server import Broadcaster
    from axiscal.live.sources import SimSource
    from axiscal.live.state import LiveState
    from axiscal.measurement.virtual import VirtualModule

    module = VirtualModule(seed=0)
    for rate in (1e9, float("inf"), float("nan"), -1.0):
        with pytest.raises(AxiscalError, match="rate must be"):
            SimSource(module, system.channels, rate_hz=rate)
    for update in (1e300, float("nan"), 0.0):
        with pytest.raises(AxiscalError, match="update rate must be"):
            Broadcaster(LiveState(system), update_hz=update)
