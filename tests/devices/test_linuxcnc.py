"""axiscal drives a real LinuxCNC (Debian's linuxcnc-uspace, headless sim) and reads a µMD laser through a pty.

The machine is LinuxCNC itself: linuxcncrsh on TCP 5007, core_sim HAL, soft limits -1 .. 201 mm; the laser
reads joint 0's motor position (HAL sampler, 1 kHz) plus a known mechanical error (linuxcnc_harness.py).
"""

from __future__ import annotations

import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import pytest

from axiscal.capture.connected import dry_run, open_run_devices, run_to_file
from axiscal.capture.drive import DriveSettings
from axiscal.capture.run import CaptureSettings
from axiscal.errors import AxiscalError
from axiscal.io.tabular import read_csv
from axiscal.positioning.plan import plan_test, write_plan as _write_plan


def write_plan(plan, path: Path) -> Path:
    _write_plan(plan, path)
    return path
from axiscal.report.cycle import CycleSettings, closed_cycle

sys.path.insert(0, str(Path(__file__).parent))
from linuxcnc_harness import LinuxcncSim, mechanical_error_mm  # noqa: E402

# One LinuxCNC runs on a machine: under pytest-xdist this module's tests run on one worker, one after
# another, with the module's one simulator (tests/conftest.py, ONE_AT_A_TIME).
CONTROLLER = "linuxcnc:127.0.0.1"
DRIVE = DriveSettings(axis="X", feed_m_per_s=0.1, dwell_s=0.4)
SETTINGS = CaptureSettings(stability_m=0.2e-6, window_s=0.2)


@pytest.fixture(scope="module")
def machine():
    # outside pytest's own temporary folder, which is private to root: LinuxCNC runs as another user
    folder = Path(tempfile.mkdtemp(prefix="axiscal-linuxcnc-"))
    sim = LinuxcncSim(folder)
    sim.start()
    yield sim
    sim.close()
    shutil.rmtree(folder, ignore_errors=True)


@pytest.fixture(scope="module")
def plan_csv(tmp_path_factory) -> Path:
    plan = plan_test(0.010, 0.190, 5, runs=2, overrun_m=0.005, seed=4)
    return write_plan(plan, tmp_path_factory.mktemp("plan") / "plan.csv")


def _devices(machine):
    return open_run_devices(CONTROLLER, f"umd:{machine.pty}", ini=machine.ini)


def test_run_takes_every_stop_within_50_nm_of_the_truth(machine, plan_csv, tmp_path):
    controller, source = _devices(machine)
    try:
        files = run_to_file(plan_csv, controller, source, tmp_path / "run.csv", drive=DRIVE, settings=SETTINGS)
    finally:
        source.close()
        controller.close()
    table = read_csv(files.run_csv)
    target = table.numeric("target_mm")
    deviation = table.numeric("deviation_um")
    truth = np.array([mechanical_error_mm(x) for x in target]) * 1e3
    assert len(target) == 20
    assert np.max(np.abs(deviation - truth)) < 0.05


def test_cycle_on_linuxcnc_restarted_with_its_comp_file(machine, tmp_path):
    # one run each way: the figures asserted (E as found and as left) are those of the mean positions
    plan_csv = write_plan(plan_test(0.010, 0.190, 5, runs=1, overrun_m=0.005, seed=4), tmp_path / "plan.csv")
    result = closed_cycle(plan_csv, CONTROLLER, f"umd:{machine.pty}", tmp_path / "cycle",
                          CycleSettings(restart=machine.restart, ini=str(machine.ini)), drive=DRIVE, settings=SETTINGS)
    loaded = "COMP_FILE = " in machine.ini.read_text()  # the as-left run was on the machine with its table
    machine.comp = None
    machine.restart(None)  # the next tests find the machine as it was
    assert loaded
    found, left = result.summary["as_found"]["E_um"], result.summary["as_left"]["E_um"]
    assert found > 30
    assert left <= 0.2 * found
    assert (tmp_path / "cycle" / "as-left" / "report" / "report.html").is_file()


def test_targets_beyond_the_soft_limits_are_refused_before_any_move(machine, tmp_path):
    plan = write_plan(plan_test(0.150, 0.200, 5, runs=1, overrun_m=0.005, seed=1), tmp_path / "far.csv")
    controller, source = _devices(machine)
    try:
        before = controller.position("X")
        with pytest.raises(AxiscalError, match=r"beyond the soft limits of LinuxCNC .* nothing was moved"):
            dry_run(plan, controller)
        with pytest.raises(AxiscalError, match="beyond the soft limits"):
            run_to_file(plan, controller, source, tmp_path / "far_run.csv", drive=DRIVE, settings=SETTINGS)
        assert controller.position("X") == before
    finally:
        source.close()
        controller.close()


def test_without_the_ini_linuxcnc_s_own_refusal_ends_the_run_at_its_step(machine, tmp_path):
    plan = write_plan(plan_test(0.150, 0.200, 5, runs=1, overrun_m=0.005, seed=1), tmp_path / "far.csv")
    controller, source = open_run_devices(CONTROLLER, f"umd:{machine.pty}")
    try:
        with pytest.raises(AxiscalError, match=r"step \d+.*refused the move .*would exceed X's positive limit|refused the move"):
            run_to_file(plan, controller, source, tmp_path / "far_run.csv", drive=DRIVE, settings=SETTINGS)
    finally:
        source.close()
        controller.close()


def test_a_linuxcnc_that_stops_answering_ends_the_run_within_2_s(machine, plan_csv, tmp_path):
    controller, source = _devices(machine)
    rsh = subprocess.run(["pgrep", "-x", "linuxcncrsh"], capture_output=True, text=True).stdout.split()
    assert rsh
    frozen_at = []

    def freeze(progress):
        if progress.taken == 2 and not frozen_at:
            for pid in rsh:
                os.kill(int(pid), signal.SIGSTOP)
            frozen_at.append(time.monotonic())

    try:
        with pytest.raises(AxiscalError, match="run stopped"):
            run_to_file(plan_csv, controller, source, tmp_path / "run.csv", drive=DRIVE, settings=SETTINGS, progress=freeze)
        assert time.monotonic() - frozen_at[0] < 2.0 + DRIVE.dwell_s + 1.0  # the step's dwell, then the move: silence
    finally:
        for pid in rsh:
            os.kill(int(pid), signal.SIGCONT)
        source.close()
        controller.close()
    assert (tmp_path / "run.csv.partial").is_file()


def test_ctrl_c_stops_keeps_the_partial_and_resume_finishes(machine, plan_csv, tmp_path):
    out = tmp_path / "run.csv"
    command = [sys.executable, "-m", "axiscal.cli.main", "run", str(plan_csv), "--controller", CONTROLLER, "--source",
               f"umd:{machine.pty}", "--ini", str(machine.ini), "-o", str(out), "--feed-mm-min", "6000", "--dwell-s", "0.4",
               "--window-s", "0.2", "--stability-um", "0.2"]
    env = {**os.environ, "PYTHONPATH": str(Path(__file__).parents[2] / "src")}
    # Ctrl-C as a terminal delivers it, however the tests were started: a background job of a non-interactive
    # shell (`make test &` in a script) starts with SIGINT ignored, every child inherits that, and the run
    # would never see the signal. A handler set here is the default again in the child (exec resets it).
    ignored = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        process = subprocess.Popen(command, stderr=subprocess.PIPE, stdout=subprocess.PIPE, text=True, env=env)
    finally:
        signal.signal(signal.SIGINT, ignored)
    partial = tmp_path / "run.csv.partial"
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline and (not partial.is_file() or len(partial.read_text().splitlines()) < 4):
        time.sleep(0.1)
    process.send_signal(signal.SIGINT)
    _, err = process.communicate(timeout=30)
    assert process.returncode == 2, err[-3000:]
    lines = [line for line in err.splitlines() if line.startswith("axiscal: error")]
    assert len(lines) == 1 and "--resume" in lines[0] and "run.csv.partial" in lines[0]
    done = subprocess.run(command + ["--resume"], capture_output=True, text=True, env=env, timeout=120)
    assert done.returncode == 0, done.stderr
    table = read_csv(out)
    assert len(table) == 20
    truth = np.array([mechanical_error_mm(x) for x in table.numeric("target_mm")]) * 1e3
    assert np.max(np.abs(table.numeric("deviation_um") - truth)) < 0.05


def test_not_homed_after_a_restart_is_one_line(machine, plan_csv, tmp_path):
    machine.stop()
    machine.home = lambda: machine._rsh(["set estop off", "set machine on"])  # on, but not homed again after the restart
    try:
        machine.start()
        controller, source = _devices(machine)
        try:
            with pytest.raises(AxiscalError, match=r"axis X \(joint 0\) is not homed: home the machine first"):
                run_to_file(plan_csv, controller, source, tmp_path / "run.csv", drive=DRIVE, settings=SETTINGS)
        finally:
            source.close()
            controller.close()
    finally:
        del machine.home
        if machine.sampler is not None:  # it started: homing it is enough for the next tests
            machine.home()
        else:
            machine.restart(None)


CERTIFICATE_FIELDS = {"customer": "Example Customer GmbH", "customer_address": "2 Spindle Road, Machine Town",
                      "manufacturer": "LinuxCNC project", "condition": "in use", "instrument_serial": "L-1",
                      "certificate": "NMI-77", "instrument_calibrated": "2026-03-02", "instrument_calibrated_by": "an NMI",
                      "certificate_number": "AX-2026-0101", "issue_date": "2026-11-28", "lab_name": "Example Calibration Ltd",
                      "lab_address": "1 Metrology Way", "lab_country": "DE", "signatory_name": "J. Example",
                      "signatory_role": "Head of calibration", "tolerance_source": "the customer's order"}


def test_a_one_axis_visit_clicked_through_in_chromium_on_linuxcnc(machine, browser_page, tmp_path):
    """The workbench's page in Chromium on the real LinuxCNC and the µMD laser on a pty: a visit of X with its
    certificate's fields, planned, connected, run as found, its table loaded by a restart, run as left, the
    before/after table, and Finish writing the certificate and its DCC."""
    from axiscal.workbench import serve_workbench

    server = serve_workbench(tmp_path / "data", db=str(tmp_path / "history.sqlite"), port=0)
    page = browser_page.page
    try:
        page.goto(server.url)
        page.get_by_role("button", name="2 New visit").click()
        page.wait_for_selector("#test-boxes input[value=positioning-Z]")
        for axis in "YZ":  # the harness's LinuxCNC has X only
            page.uncheck(f"#test-boxes input[value=positioning-{axis}]")
        fields = {"title": "Visit on LinuxCNC", "operator": "J. Doe", "machine": "LinuxCNC sim", "serial": "LC1",
                  "date": "2026-11-26", "length_U_ppm": "0.5", "eve_um": "1"} | CERTIFICATE_FIELDS
        for name, value in fields.items():
            page.fill(f"#visit-form [name={name}]", value)
        page.select_option("#visit-form [name=language]", "de")
        page.click("#visit-form button[type=submit]")
        page.wait_for_selector("#visit-saved:not([hidden])")

        page.get_by_role("button", name="3 Plan").click()
        page.locator(".tests-list[data-mode=plan] tr[data-test=positioning-X] button").click()
        # within LinuxCNC's soft limits (-1 to 201 mm); the default feed (1000 mm/min) over 90 mm
        for name, value in {"start_mm": "10", "end_mm": "100", "targets": "5", "runs": "1", "overrun_mm": "5",
                            "dwell_s": "0.7"}.items():
            page.fill(f"#plan-form [name={name}]", value)
        page.click("#plan-form button[type=submit]")
        page.wait_for_selector("#program:has-text('G1 X')")

        page.get_by_role("button", name="4 Connect").click()
        page.fill("#connect-form [name=instrument]", f"umd:{machine.pty}")
        page.fill("#connect-form [name=controller]", CONTROLLER)
        page.fill("#connect-form [name=ini]", str(machine.ini))  # the machine's INI: its soft limits shown
        page.click("#connect-form button[type=submit]")
        page.wait_for_selector("#light-controller[data-state=ok]", timeout=30_000)
        page.wait_for_selector("#light-instrument[data-state=ok]")
        told = page.locator("#told-controller").text_content()
        assert "homed" in told and "soft limits X-1 to 201 mm (INI file)" in told

        page.get_by_role("button", name="5 Run").click()
        row = ".tests-list[data-mode=run] tr[data-test=positioning-X]"
        page.locator(f"{row} button").click()
        page.wait_for_selector(f"{row} td.state[data-state=done]", timeout=180_000)
        assert page.locator("#progress").text_content() == "10 of 10 stops"

        page.get_by_role("button", name="7 Compensate").click()
        page.click("#compensate")
        page.wait_for_selector("#comp-download:not([hidden])")
        table = server.bench.data / page.get_attribute("#comp-download", "href").split("/files/", 1)[1].split("?", 1)[0]
        machine.restart(table)  # the operator loads the table: COMP_FILE in the INI, LinuxCNC restarted and homed
        page.click("#run-as-left")
        page.wait_for_selector("#run-phase:has-text('as-left')")
        page.wait_for_selector("#run-state[data-state=done]", timeout=180_000)
        page.get_by_role("button", name="7 Compensate").click()
        page.click("#before-after")
        page.wait_for_selector("#ba-status[data-state=done]", timeout=60_000)
        e = page.locator("#changes tbody tr", has_text="E").first
        before, after = (float(e.locator("td").nth(i).text_content().split()[0].replace(",", ".")) for i in (2, 3))
        assert after <= 0.2 * before

        page.get_by_role("button", name="8 Finish").click()
        page.click("#finish")
        page.wait_for_selector("#report-links li", timeout=120_000)
        names = page.locator("#report-links a").all_text_contents()
        assert any("dcc" in name.lower() for name in names), names
        dcc = next(server.bench.data.rglob("dcc.xml")).read_text(encoding="utf-8")
        assert "<dcc:uniqueIdentifier>AX-2026-0101</dcc:uniqueIdentifier>" in dcc
        assert any("Kalibrierschein" in p.read_text(encoding="utf-8") for p in server.bench.data.rglob("certificate.html"))
        assert not browser_page.errors, browser_page.errors
    finally:
        server.stop()
        machine.comp = None
        machine.restart(None)  # the next tests find the machine as it was
