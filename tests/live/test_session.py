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
        ({"rate_hz": 0.0}, "--rate must be a positive"),
        ({"duration_s": -1.0}, "--duration must be positive"),
        ({"port": 70000}, "--port must be 0-65535"),
        ({"rate_hz": 1e9}, "up to 100000"),
        ({"rate_hz": float("nan")}, "--rate must be a positive"),
        ({"duration_s": float("inf")}, "--duration must be positive"),
        ({"update_hz": 0.0}, "--update-hz must be 0.1 to 60"),
        ({"update_hz": 1e300}, "--update-hz must be 0.1 to 60"),
        ({"update_hz": float("nan")}, "--update-hz must be 0.1 to 60"),
        ({"load_kg": -2.0}, "--load-kg must be a finite mass"),
        ({"load_kg": float("inf")}, "--load-kg must be a finite mass"),
        ({"seed": -1}, "--seed must not be negative"),
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
    with pytest.raises(AxiscalError, match="names the file being replayed"):
        LiveSession(source=f"replay:{run}", record=run, server=False)


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
