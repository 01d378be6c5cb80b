"""Connect like a technician: the computer's serial ports, every spec checked before connecting, and what the
instrument and the controller said about themselves (or the line a controller that is not ready answered)."""

from __future__ import annotations

import warnings

import pytest
from serial.tools.list_ports_common import ListPortInfo

from axiscal.errors import AxiscalError
from axiscal.workbench import FormErrors, Workbench, check_spec, checked, connect, create_workbench_app, serial_ports

with warnings.catch_warnings():  # Starlette's notice that its test client will move to httpx2
    warnings.simplefilter("ignore")
    from starlette.testclient import TestClient


def _port(device, description="n/a", vid=None, pid=None, serial_number=None):
    info = ListPortInfo(device, skip_link_detection=True)
    info.description, info.vid, info.pid, info.serial_number = description, vid, pid, serial_number
    if vid is not None:
        info.hwid = f"USB VID:PID={vid:04X}:{pid:04X}"
    return info


@pytest.fixture
def ports(monkeypatch):
    listed = [_port("/dev/ttyUSB0", "FT232R USB UART", 0x0403, 0x6001, "A50285BI"), _port("/dev/ttyS0")]
    monkeypatch.setattr("serial.tools.list_ports.comports", lambda *a, **k: listed)
    return listed


def test_the_serial_ports_are_pyserials_list_with_their_usb_ids(ports):
    listed = serial_ports()
    assert [p["device"] for p in listed] == ["/dev/ttyS0", "/dev/ttyUSB0"]
    usb = listed[1]
    assert (usb["description"], usb["vid"], usb["pid"], usb["serial_number"]) == ("FT232R USB UART", "0403", "6001", "A50285BI")
    assert listed[0]["description"] == "" and listed[0]["vid"] is None


@pytest.mark.parametrize("role, spec", [
    ("instrument", "sim"), ("instrument", "sim:umd"), ("instrument", "umd:/dev/ttyUSB0@115200"), ("instrument", "attocube:192.0.2.7"),
    ("instrument", "sylvac:/dev/null"),  # a path that exists (a pty, a symlink by id) is taken as it is
    ("controller", "sim"), ("controller", "linuxcnc:cnc.local"), ("controller", "linuxcnc:[::1]:5007"),
    ("controller", "grbl:/dev/ttyUSB0"), ("controller", "grbl:tcp:192.0.2.8:23"), ("controller", "moonraker:http://printer.local:7125"),
])
def test_good_specs_are_taken(ports, role, spec):
    assert check_spec(role, f"  {spec} ") == spec


@pytest.mark.parametrize("role, spec, said", [
    ("instrument", "umd:/dev/ttyUSB9", "this computer has no serial port /dev/ttyUSB9 (its ports: /dev/ttyS0, /dev/ttyUSB0)"),
    ("instrument", "umd:/dev/ttyUSB0@fast", "the baud rate after @ must be a whole number"),
    ("instrument", "umd:", "name its port, host, socket or address after 'umd:'"),
    ("instrument", "sim:laser", "a simulated instrument is sim:"),
    ("instrument", "renishaw:/dev/ttyUSB0", "use one of sim, umd, sylvac, mahr, touchdro, attocube"),
    ("instrument", "attocube::80", "expected attocube:HOST[:PORT]"),
    ("controller", "linuxcnc:cnc.local:99999", "expected linuxcnc:HOST[:PORT] with a port 1-65535"),
    ("controller", "grbl:tcp:192.0.2.8", "expected grbl:tcp:HOST:PORT"),
    ("controller", "moonraker:not a url", "expected moonraker:http://HOST[:PORT]"),
    ("controller", "klipper:/tmp/no-such-klippy-socket", "no Klipper API socket at /tmp/no-such-klippy-socket"),
    ("controller", "sim:fast", "the virtual controller is 'sim' alone"),
    ("controller", "", "must be a spec such as 'sim'"),
])
def test_a_spec_that_cannot_be_used_is_one_line_before_anything_is_opened(ports, role, spec, said):
    with pytest.raises(AxiscalError) as refused:
        check_spec(role, spec)
    assert said in str(refused.value) and "\n" not in str(refused.value)


def test_the_connect_form_names_the_field_whose_spec_cannot_be_used(ports):
    with pytest.raises(FormErrors) as caught:
        checked("connect", {"instrument": "umd:/dev/ttyUSB9", "controller": "moonraker:not a url"})
    assert set(caught.value.fields) == {"instrument", "controller"}
    assert caught.value.fields["instrument"].startswith("'umd:/dev/ttyUSB9': this computer has no serial port")


def test_what_a_umd_and_a_controller_said_about_themselves():
    c = connect("sim:umd", "sim")
    told = dict(c.instrument_told)
    assert (told["µMD"], told["sample rate"], told["counts per cycle"]) == ("2", "1000 Hz", "2") and told["firmware"]
    controller = dict(c.controller_told)
    assert controller["ready"].startswith("yes") and controller["soft limits X"] == "0 to 190 mm"
    assert (c.instrument_state, c.controller_state, c.refused) == ("ok", "ok", "")


def test_a_controller_that_is_not_homed_is_said_in_one_line_and_no_run_starts(tmp_path, monkeypatch):
    import axiscal.capture.connected as connected

    opened = connected.open_run_devices

    def not_homed(*args, **kwargs):
        made, source = opened(*args, **kwargs)
        made.homed = False
        return made, source

    monkeypatch.setattr(connected, "open_run_devices", not_homed)
    bench = Workbench(tmp_path / "data", db=str(tmp_path / "h.sqlite"))
    bench.new_visit({"title": "V", "date": "2026-11-26", "operator": "J", "machine": "M", "instrument": "Laser",
                     "A_um": 45, "E_um": 40, "R_um": 5, "B_um": 6, "tests": ["positioning-X"]})
    bench.make_plan({"start_mm": 20, "end_mm": 170, "targets": 5, "runs": 1, "overrun_mm": 5, "dwell_s": 1})
    answer = bench.connect({"instrument": "sim:umd", "controller": "sim"})
    assert answer["lights"] == {"instrument": "ok", "controller": "refused"}
    assert answer["refused"] == ("virtual controller (sim): axis X is not homed: home the machine first"
                                 " (axiscal run never homes)")
    with pytest.raises(AxiscalError, match="^the controller is not ready: virtual controller .* is not homed"):
        bench.start_run("as-found")


def test_the_page_asks_for_the_ports(ports, tmp_path):
    bench = Workbench(tmp_path / "data", db=str(tmp_path / "h.sqlite"))
    with TestClient(create_workbench_app(bench), base_url="http://127.0.0.1:8770") as client:
        listed = client.get("/api/ports").json()
        assert [p["device"] for p in listed] == ["/dev/ttyS0", "/dev/ttyUSB0"]
        refused = client.post("/api/connect", json={"instrument": "umd:/dev/ttyUSB9", "controller": "sim"})
        assert refused.status_code == 422 and "no serial port /dev/ttyUSB9" in refused.json()["fields"]["instrument"]
