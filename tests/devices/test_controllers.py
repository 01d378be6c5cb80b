"""grbl, Marlin, Klipper and Moonraker drivers against protocol simulators written from their documents.

The serial ones through real pseudo-terminals, Klipper through a Unix socket, Moonraker over HTTP on
127.0.0.1; the instrument is the µMD simulator reading the simulated axis (``sim:umd``).
"""

from __future__ import annotations

import os
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import pytest

from axiscal.capture.connected import dry_run, run_to_file
from axiscal.capture.drive import DriveSettings
from axiscal.capture.run import CaptureSettings
from axiscal.devices.controllers import open_controller
from axiscal.devices.instruments import open_instrument
from axiscal.devices.simulators import close_pty_pair, open_pty_pair
from axiscal.errors import AxiscalError
from axiscal.io.tabular import read_csv
from axiscal.positioning.plan import plan_test, write_plan as _write_plan


def write_plan(plan, path: Path) -> Path:
    _write_plan(plan, path)
    return path

sys.path.insert(0, str(Path(__file__).parent))
from controller_sims import Axis, GrblSim, KlipperSim, MarlinSim, MoonrakerSim  # noqa: E402

DRIVE = DriveSettings(axis="X", feed_m_per_s=0.2, dwell_s=0.25)
SETTINGS = CaptureSettings(stability_m=0.05e-6, window_s=0.1)
KINDS = ("grbl", "marlin", "klipper", "moonraker")


class Rig:
    """A simulated controller, its spec, and its axis."""

    def __init__(self, kind: str, *, homed: bool = True, travel=(0.0, 200.0)):
        self.kind = kind
        self.axis = Axis(travel)
        self.fd = None
        if kind in ("grbl", "marlin"):
            self.fd, path = open_pty_pair()
            os.set_blocking(self.fd, False)
            self.sim = (GrblSim if kind == "grbl" else MarlinSim)(self.fd, self.axis, homed=homed)
            self.sim.start()
            self.spec = f"{kind}:{path}"
        elif kind == "klipper":
            self.path = tempfile.mktemp(prefix="klippy-uds-")
            self.sim = KlipperSim(self.path, self.axis, homed=homed)
            self.spec = f"klipper:{self.path}"
        else:
            self.sim = MoonrakerSim(self.axis, homed=homed)
            self.spec = f"moonraker:{self.sim.url}"

    def silence(self):
        target = self.sim if self.kind in ("grbl", "marlin") else self.sim.toolhead
        target.silent = True

    def close(self):
        self.sim.stop()
        if self.fd is not None:
            close_pty_pair(self.fd)
        if self.kind == "klipper" and os.path.exists(self.path):
            os.unlink(self.path)


@pytest.fixture
def rig(request):
    made = []

    def make(kind, **kwargs):
        r = Rig(kind, **kwargs)
        made.append(r)
        return r

    yield make
    for r in made:
        r.close()


@pytest.fixture(scope="module")
def plan_csv(tmp_path_factory) -> Path:
    return write_plan(plan_test(0.020, 0.120, 5, runs=1, overrun_m=0.002, seed=2),
                      tmp_path_factory.mktemp("plan") / "plan.csv")


@pytest.mark.parametrize("kind", KINDS)
def test_a_plan_driven_on_each_controller_reads_the_axis(kind, rig, plan_csv, tmp_path):
    r = rig(kind)
    controller = open_controller(r.spec)
    source = open_instrument("sim:umd", position=lambda t: r.axis.x_m())
    try:
        files = run_to_file(plan_csv, controller, source, tmp_path / "run.csv", drive=DRIVE, settings=SETTINGS)
    finally:
        source.close()
        controller.close()
    table = read_csv(files.run_csv)
    assert len(table) == 10
    assert np.max(np.abs(table.numeric("deviation_um"))) < 0.02  # the simulated axis has no error: noise only


@pytest.mark.parametrize("kind", KINDS)
def test_targets_beyond_the_soft_limits_are_refused_before_any_move(kind, rig, plan_csv):
    r = rig(kind, travel=(0.0, 100.0))
    controller = open_controller(r.spec)
    try:
        with pytest.raises(AxiscalError, match="beyond the soft limits .* nothing was moved"):
            dry_run(plan_csv, controller)
    finally:
        controller.close()
    assert r.axis.position()["X"] == 0.0


@pytest.mark.parametrize("kind", KINDS)
def test_an_unhomed_machine_is_one_line(kind, rig, plan_csv, tmp_path):
    r = rig(kind, homed=False)
    with pytest.raises(AxiscalError) as caught:
        controller = open_controller(r.spec)
        source = open_instrument("sim:umd", position=lambda t: r.axis.x_m())
        try:
            run_to_file(plan_csv, controller, source, tmp_path / "run.csv", drive=DRIVE, settings=SETTINGS)
        finally:
            source.close()
            controller.close()
    message = str(caught.value)
    assert "\n" not in message
    assert "home" in message.lower() or "alarm" in message.lower()


@pytest.mark.parametrize("kind", KINDS)
def test_a_controller_that_stops_answering_ends_the_run_within_2_s(kind, rig, plan_csv, tmp_path):
    r = rig(kind)
    controller = open_controller(r.spec)
    source = open_instrument("sim:umd", position=lambda t: r.axis.x_m())
    silenced = []

    def cut(progress):
        if progress.taken == 1 and not silenced:
            r.silence()
            silenced.append(time.monotonic())

    try:
        with pytest.raises(AxiscalError, match="run stopped"):
            run_to_file(plan_csv, controller, source, tmp_path / "run.csv", drive=DRIVE, settings=SETTINGS, progress=cut)
        assert time.monotonic() - silenced[0] < 2.0 + 0.5  # the reading's dwell ends first; then at most 2 s of silence
    finally:
        source.close()
        controller.close()
    assert len((tmp_path / "run.csv.partial").read_text().splitlines()) == 2  # the header and the step taken


def test_grbl_soft_limit_alarm_mid_run_is_one_line(rig, tmp_path):
    r = rig("grbl")
    r.sim.soft = True
    plan = write_plan(plan_test(0.150, 0.199, 5, runs=1, overrun_m=0.005, seed=2), tmp_path / "p.csv")
    controller = open_controller(r.spec)
    controller.limits = lambda axis: None  # as if $$ had not told: grbl's own alarm must end the run
    source = open_instrument("sim:umd", position=lambda t: r.axis.x_m())
    try:
        with pytest.raises(AxiscalError, match=r"ALARM:2\b.*soft limit"):
            run_to_file(plan, controller, source, tmp_path / "run.csv", drive=DRIVE, settings=SETTINGS)
    finally:
        source.close()
        controller.close()


def test_marlin_keepalives_keep_a_long_move_alive(rig, tmp_path):
    r = rig("marlin")
    controller = open_controller(r.spec)
    try:
        assert r.sim.keepalive_s == 1.0  # the driver asked M113 S1
        began = time.monotonic()
        controller.move_to("X", 0.060, 0.02)  # 3 s: longer than the silence allowed, carried by the keep-alives
        assert time.monotonic() - began > 2.5
        assert controller.position("X") == pytest.approx(0.060)
    finally:
        controller.close()


def test_unknown_and_malformed_controller_specs_are_one_line():
    for spec, pattern in (("fanuc:1.2.3.4", "unknown controller"), ("linuxcnc:host:99999", "port 1-65535"),
                          ("grbl:tcp:nohost", "grbl:tcp:HOST:PORT"), ("grbl:/dev/axiscal-none@115200", "does not exist"),
                          ("grbl:/dev/ttyS0@fast", "baud"), ("klipper:/nonexistent/klippy_uds", "cannot reach Klipper"),
                          ("moonraker:ftp://x", "http")):
        with pytest.raises(AxiscalError, match=pattern):
            open_controller(spec)


def test_run_on_the_fly_on_the_virtual_controller_agrees_with_stop_and_go(tmp_path):
    """The streams are joined through the computer's clock: their residual delay times the speed is left."""
    from axiscal.capture.connected import open_run_devices
    from axiscal.capture.fly_drive import fly_plan, pass_moves
    from axiscal.capture.steps import plan_steps

    # 60 mm of travel: each pass runs at 1000 mm/min, and the agreement asserted is set by the speed, not the length
    plan = write_plan(plan_test(0.005, 0.065, 5, runs=1, seed=1), tmp_path / "plan.csv")
    moves = pass_moves(plan_steps(plan))
    assert [round(x * 1e3, 3) for _, x in moves] == [0.0, 70.0, 0.0]  # one move a pass, past the last target
    controller, source = open_run_devices("sim", "sim:umd")
    try:
        flown = fly_plan(plan, controller, source, tmp_path / "fly.csv", drive=DriveSettings(feed_m_per_s=1000 / 60e3))
    finally:
        source.close()
        controller.close()
    controller, source = open_run_devices("sim", "sim:umd")
    try:
        still = run_to_file(plan, controller, source, tmp_path / "stop.csv", drive=DRIVE, settings=CaptureSettings(window_s=0.1))
    finally:
        source.close()
        controller.close()
    fly = read_csv(flown.run_csv).numeric("deviation_um")
    stop = read_csv(still.run_csv).numeric("deviation_um")
    assert np.max(np.abs(fly - stop)) < 2.0
    assert (tmp_path / "fly.recording.csv").is_file()
