"""The capture page in headless Chromium: its plot has axis labels, ticks with numbers and a grid."""

from __future__ import annotations

import json
import time

import pytest

from axiscal.capture import capture, plan_steps
from axiscal.capture.board import CaptureBoard
from axiscal.capture.sources import plan_motions
from axiscal.capture.virtual import simulate_motions
from axiscal.live.server import LiveServer, create_board_app
from axiscal.model.machine import load_machine
from axiscal.positioning.plan import plan_test
from axiscal.report.demo import builtin_example

pytestmark = pytest.mark.filterwarnings("ignore::UserWarning")

PLOT = """JSON.stringify({
  labels: Array.from(document.querySelectorAll('#plot .axis-label')).map(t => t.textContent),
  ticks: document.querySelectorAll('#plot .tick').length,
  numbers: Array.from(document.querySelectorAll('#plot .tick-label')).map(t => t.textContent),
  grid: document.querySelectorAll('#plot .grid').length,
  stops: document.querySelectorAll('#plot circle').length})"""


def test_the_capture_plot_has_axis_labels_ticks_and_a_grid(browser_page):
    plan = plan_test(0.0, 0.19, 5, runs=1, seed=3)
    machine = load_machine(builtin_example() / "machine.toml")
    recording = simulate_motions(plan_motions(plan_steps(plan), dwell_s=1.2), machine, axis="X", rate_hz=200.0, seed=2)
    board = CaptureBoard(plan_steps(plan), "sim")
    capture(plan, recording.recording, on_stop=board.stop)
    server = LiveServer(create_board_app(board.snapshot, page="capture.html"), port=0).start()
    with server:
        page = browser_page.page
        page.goto(server.url)
        deadline = time.monotonic() + 20.0
        plot = {}
        while time.monotonic() < deadline:
            plot = json.loads(page.evaluate(PLOT))
            if plot["stops"]:
                break
            time.sleep(0.1)
    assert plot["stops"] == 10
    assert plot["labels"] == ["target position / mm", "deviation (actual − target) / µm"]
    assert plot["ticks"] >= 6 and plot["grid"] == plot["ticks"]
    # the target axis runs 0 .. 190 mm: its numbers are round
    assert "0" in plot["numbers"] and any(n in plot["numbers"] for n in ("100", "150", "180"))
    assert not browser_page.errors
