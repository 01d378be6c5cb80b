"""docs/workbench.md says what the workbench drives now: every instrument and controller its runner takes, and the least dwell."""

from __future__ import annotations

from pathlib import Path

from axiscal.capture.run import CaptureSettings
from axiscal.capture.stops import least_dwell_s
from axiscal.workbench import CONTROLLERS, INSTRUMENTS

DOC = Path(__file__).resolve().parents[2] / "docs" / "workbench.md"


def test_the_page_names_every_device_the_workbench_drives():
    text = DOC.read_text(encoding="utf-8")
    connect = text.split("### 4 Connect", 1)[1].split("### 5 Run", 1)[0]
    for kind in INSTRUMENTS + CONTROLLERS:
        assert f"`{kind}:" in connect or f"`{kind}`" in connect, kind
    assert "another spec is refused" not in text and "drives the virtual machine (`sim`)" not in text


def test_the_page_states_the_least_dwell_the_plan_step_asks_for():
    text = " ".join(DOC.read_text(encoding="utf-8").split())
    assert f"the least dwell is {least_dwell_s(CaptureSettings().window_s):g} s" in text
