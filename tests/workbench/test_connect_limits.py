"""Connect says what a grbl board's ``$`` settings bound a run by: its soft limits ($20) and the axis's travel
($130), with the soft limits they give; with the soft limits off it says grbl refuses no move beyond its travel."""

from __future__ import annotations

import os
import sys
from pathlib import Path

import pytest

from axiscal.devices.controllers import open_controller
from axiscal.devices.simulators import close_pty_pair, open_pty_pair
from axiscal.workbench import connect

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "devices"))
from controller_sims import Axis, GrblSim  # noqa: E402


@pytest.fixture
def grbl_on(monkeypatch):
    """Connect with a simulated grbl 1.1h (on a pty) as the controller, its soft limits on or off."""
    import axiscal.capture.connected as connected

    opened, made = connected.open_run_devices, []

    def start(soft_limits: bool) -> None:
        fd, path = open_pty_pair()
        os.set_blocking(fd, False)
        sim = GrblSim(fd, Axis((0.0, 190.0)), soft_limits=soft_limits)
        sim.start()
        made.append((sim, fd))

        def with_grbl(controller, source, **kwargs):
            _virtual, instrument = opened("sim", source, **kwargs)
            _virtual.close()
            return open_controller(f"grbl:{path}"), instrument

        monkeypatch.setattr(connected, "open_run_devices", with_grbl)

    yield start
    for sim, fd in made:
        sim.stop()
        close_pty_pair(fd)


def test_grbls_soft_limits_and_travel_are_told(grbl_on):
    grbl_on(True)
    c = connect("sim:umd", "sim")
    told = dict(c.controller_told)
    assert c.controller_state == "ok" and told["kind"].startswith("grbl on ")
    assert told["$20 soft limits"] == "on" and told["$130 X max travel"] == "190 mm"
    assert told["soft limits X"] == "0 to 190 mm"  # $23 = 7: homed toward + on X, machine positions 0 to the travel


def test_grbl_without_soft_limits_is_said_to_refuse_no_move(grbl_on):
    grbl_on(False)
    told = dict(connect("sim:umd", "sim").controller_told)
    assert told["$20 soft limits"] == "off: grbl refuses no move beyond its travel"
    assert "soft limits X" not in told and "soft limits" not in told  # not said to refuse a move itself
