"""The dashboard in a real browser: headless Chromium shows live values equal to the pipeline's own numbers.

Debian's Chromium is driven by Playwright through the ``browser_page`` fixture of tests/conftest.py. Without Chromium this
test fails (CI installs it: .ci/run).
"""

from __future__ import annotations

import threading
import time

import numpy as np
import pytest

from axiscal.live.dashboard import DashboardProcess
from axiscal.live.pipeline import Pipeline
from axiscal.live.playback import AHEAD_S
from axiscal.live.recorder import Recorder, read_record
from axiscal.live.server import LiveServer, create_app
from axiscal.live.sources import SimSource
from axiscal.live.state import LiveState, result_columns
from axiscal.measurement.display import to_display
from axiscal.measurement.virtual import VirtualModule

READ_PAGE = """() => {
  if (!document.getElementById("v-t_s")) return null;
  const value = id => document.getElementById(id).dataset.value;
  const text = id => document.getElementById(id).textContent;
  const names = ["t_s", "ex_um", "ey_um", "ez_um", "e_um", "px_mm", "py_mm", "pz_mm"];
  const inked = (id, rgb) => {
    const canvas = document.getElementById(id);
    if (!canvas) return 0;
    const data = canvas.getContext("2d").getImageData(0, 0, canvas.width, canvas.height).data;
    let count = 0;
    for (let i = 0; i < data.length; i += 4) {
      if (Math.abs(data[i] - rgb[0]) < 40 && Math.abs(data[i + 1] - rgb[1]) < 40 && Math.abs(data[i + 2] - rgb[2]) < 40 && data[i + 3] > 100) count++;
    }
    return count;
  };
  return {
    version: Number(document.body.dataset.version),
    values: Object.fromEntries(names.map(n => [n, value("v-" + n)])),
    texts: Object.fromEntries(names.map(n => [n, text("v-" + n)])),
    frames: text("frames"),
    connection: text("connection"),
    sensors: Array.from(document.querySelectorAll("#sensors tr")).map(r => [r.cells[0].textContent, r.dataset.state]),
    sensorSummary: text("sensor-summary"),
    stale: text("stale"),
    historyInk: inked("history", [214, 39, 40]),
    profileInk: inked("profile-EXX_um", [31, 119, 180]),
    profiles: document.querySelectorAll("canvas[id^=profile-]").length,
  };
}"""


ERROR_KINDS = """() => Object.fromEntries(
  ["EXX", "EYX", "EZX", "EAX", "EBX", "ECX", "EXZ", "EYZ", "EZZ", "EAZ", "EBZ", "ECZ"].map(s => [s, errorKind(s, s[2])]))"""


class PsdDropsOut:
    """The virtual module, but the X axis' PSD (channel x_psd_y_um) reads nothing from ``from_s`` on."""

    def __init__(self, module):
        self.module = module
        self.from_s = np.inf

    def frames(self, t_s, *, path="diagonal"):
        frames, truth = self.module.frames(t_s, path=path)
        truth = to_display(truth)
        frames["x_psd_y_um"] = np.where(t_s >= self.from_s, np.nan, frames["x_psd_y_um"])
        return frames, truth


@pytest.fixture(scope="module")
def module():
    return VirtualModule(seed=0)


SERVERS = {
    # what axiscal live serves: the page from a process of its own, fed the batches through a pipe
    "own process": lambda state: DashboardProcess(state, port=0, update_hz=10.0).start(),
    # the same app from a thread of the loop's process
    "thread": lambda state: LiveServer(create_app(state, update_hz=10.0), port=0).start(),
}


@pytest.mark.parametrize("serve", SERVERS.values(), ids=SERVERS.keys())
def test_dashboard_in_headless_chromium_shows_the_pipeline_numbers(tmp_path, module, browser_page, serve):
    system = module.measurement_system()
    record_path = tmp_path / "live.csv"
    recorder = Recorder(record_path, system.channels, result_columns(system.axes))
    state = LiveState(system)
    instrument = PsdDropsOut(module)
    source = SimSource(instrument, system.channels, rate_hz=1000.0)
    pipeline = Pipeline(system, source, recorder=recorder, state=state)
    stop = threading.Event()
    runner = threading.Thread(target=pipeline.run, kwargs={"stop": stop, "duration_s": 30.0})
    server = serve(state)
    runner.start()
    seen: list[dict] = []
    try:
        page = browser_page.page
        page.goto(server.url)
        deadline = time.monotonic() + 20.0
        while time.monotonic() < deadline:
            shown = page.evaluate(READ_PAGE)
            if shown and shown["version"] > 0 and shown["values"]["t_s"] and shown["historyInk"] > 50 and shown["profileInk"] > 50:
                seen.append(shown)
                if len(seen) >= 2 and seen[-1]["values"]["t_s"] != seen[0]["values"]["t_s"]:
                    break
            page.wait_for_timeout(200)
        kinds = page.evaluate(ERROR_KINDS)
        # then a sensor drops out: the page must say so and mark the point's values as old
        instrument.from_s = time.monotonic() - source.clock_offset_s
        faulty = None
        deadline = time.monotonic() + 20.0
        while time.monotonic() < deadline:
            shown = page.evaluate(READ_PAGE)
            if shown["stale"] and shown["sensorSummary"].startswith("1 of"):
                faulty = shown
                break
            page.wait_for_timeout(200)
        errors = list(browser_page.errors)
    finally:
        stop.set()
        runner.join(timeout=5)
        server.stop()
        recorder.close()
    assert not errors, errors
    assert len(seen) >= 2, "the page did not show live values that change"
    shown = seen[-1]
    assert float(shown["values"]["t_s"]) > float(seen[0]["values"]["t_s"])
    assert shown["connection"] == "live"
    assert int(shown["frames"]) > 0
    assert shown["profiles"] == 12
    assert shown["sensors"] == [[name, "ok"] for name in system.channels]
    assert shown["sensorSummary"] == f"all {len(system.channels)} ok" and shown["stale"] == ""
    assert faulty is not None, "the page did not show the sensor that dropped out"
    assert faulty["sensorSummary"] == f"1 of {len(system.channels)} faulty: x_psd_y_um missing"
    assert faulty["sensors"] == [[name, "missing" if name == "x_psd_y_um" else "ok"] for name in system.channels]
    # the last good frame's values, shown as old: the source computes its frames up to AHEAD_S before they are
    # due, so frames good when computed may stand up to AHEAD_S past the moment the sensor dropped out
    assert float(faulty["values"]["t_s"]) < instrument.from_s + AHEAD_S
    assert faulty["stale"].startswith("no good frame for ")
    # the charts' titles name each ISO 230-1 error motion by what it is (docs/conventions.md)
    assert kinds == {
        "EXX": "positioning", "EYX": "straightness", "EZX": "straightness", "EAX": "roll", "EBX": "pitch", "ECX": "yaw",
        "EXZ": "straightness", "EYZ": "straightness", "EZZ": "positioning",
        "EAZ": "tilt about X", "EBZ": "tilt about Y", "ECZ": "roll",
    }
    record = read_record(record_path)
    for values, texts in ((s["values"], s["texts"]) for s in seen):
        rows = np.flatnonzero(np.abs(record.columns["t_s"] - float(values["t_s"])) < 1e-7)
        assert len(rows) == 1, values["t_s"]
        for name in ("ex_um", "ey_um", "ez_um", "e_um", "px_mm", "py_mm", "pz_mm"):
            recorded = record.columns[name][rows[0]]
            assert float(values[name]) == pytest.approx(recorded, rel=1e-8, abs=1e-9), name
            digits = 3 if name.endswith("_um") else 4
            assert float(texts[name]) == pytest.approx(recorded, abs=0.6 * 10.0**-digits), name
