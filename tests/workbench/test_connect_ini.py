"""Connect for the whole machine: every axis the visit runs a test on is checked ready and its soft limits told;
LinuxCNC's INI file (the Connect step's field) gives them, is checked at once, is kept with the visit, bounds the
plan, and is given to the run, which refuses a plan beyond it before any move (as ``axiscal run --ini`` does).

LinuxCNC is a stand-in on a real socket speaking linuxcncrsh (linuxcncrsh_fake.py); the laser is the simulated
µMD. tests/devices/test_linuxcnc.py's browser visit does the same on the real LinuxCNC.
"""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from axiscal.devices.controllers import open_controller
from axiscal.errors import AxiscalError
from axiscal.workbench import FormErrors, Workbench, checked, connect

sys.path.insert(0, str(Path(__file__).parent))
from linuxcncrsh_fake import LinuxcncrshFake  # noqa: E402

INI = """[TRAJ]
COORDINATES = XYZ
LINEAR_UNITS = mm

[AXIS_X]
MIN_LIMIT = -1.0
MAX_LIMIT = 120.0   # shorter than the machine's travel

[AXIS_Y]
MIN_LIMIT = 0
MAX_LIMIT = 450
"""
VISIT = {"title": "V", "date": "2026-11-27", "operator": "J", "machine": "M", "instrument": "Laser",
         "A_um": 45, "E_um": 40, "R_um": 5, "B_um": 6, "tests": ["positioning-X", "positioning-Y", "positioning-Z"]}


@pytest.fixture
def linuxcnc(monkeypatch):
    """The LinuxCNC stand-in as the controller; the simulated µMD as the instrument (its axis the virtual one's)."""
    import axiscal.capture.connected as connected

    fake, opened = LinuxcncrshFake(), connected.open_run_devices

    def with_linuxcnc(controller, source, **kwargs):
        virtual, instrument = opened("sim", "sim:umd", seed=kwargs.get("seed", 0))
        virtual.close()
        return open_controller(controller, ini=kwargs.get("ini")), instrument

    monkeypatch.setattr(connected, "open_run_devices", with_linuxcnc)
    yield fake
    fake.close()


@pytest.fixture
def ini(tmp_path) -> Path:
    path = tmp_path / "mill.ini"
    path.write_text(INI, encoding="utf-8")
    return path


def test_each_axis_is_told_its_ini_soft_limits(linuxcnc, ini):
    c = connect("sim:umd", linuxcnc.spec, axes=("X", "Y", "Z"), ini=ini)
    told = dict(c.controller_told)
    assert c.controller_state == "ok" and told["ready"].startswith("yes") and told["INI file"] == str(ini)
    assert told["soft limits X"] == "-1 to 120 mm (INI file)" and told["soft limits Y"] == "0 to 450 mm (INI file)"
    assert told["soft limits Z"] == "not in the INI file (LinuxCNC refuses a move beyond its own)"
    assert c.limits == (("X", pytest.approx(-1e-3), pytest.approx(0.120)), ("Y", 0.0, pytest.approx(0.450)))
    assert c.ini == str(ini)


def test_without_the_ini_linuxcnc_tells_no_limits(linuxcnc):
    told = dict(connect("sim:umd", linuxcnc.spec, axes=("X", "Y")).controller_told)
    assert told["soft limits"] == "not told (the controller refuses a move beyond its own)"
    assert "soft limits X" not in told


@pytest.mark.parametrize("given, said", [
    ("no-such.ini", "no INI file at "), (".", "no INI file at "),
])
def test_an_ini_that_is_not_there_is_named_beside_its_field(tmp_path, given, said, monkeypatch):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(FormErrors) as refused:
        checked("connect", {"instrument": "sim", "controller": "linuxcnc:127.0.0.1", "ini": given})
    assert refused.value.fields["ini"].startswith(said) and "\n" not in refused.value.fields["ini"]


def test_an_ini_that_cannot_be_read_is_one_line(ini):
    ini.write_text("MIN_LIMIT = -1\n[AXIS_X]\n", encoding="utf-8")  # a key before any section
    with pytest.raises(FormErrors) as refused:
        checked("connect", {"instrument": "sim", "controller": "linuxcnc:127.0.0.1", "ini": str(ini)})
    said = refused.value.fields["ini"]
    assert "cannot read the LinuxCNC INI file" in said and str(ini) in said and "\n" not in said


def test_an_ini_is_linuxcncs_alone(ini):
    with pytest.raises(FormErrors) as refused:
        checked("connect", {"instrument": "sim", "controller": "sim", "ini": str(ini)})
    assert refused.value.fields == {"ini": "an INI file is LinuxCNC's: name the controller linuxcnc:HOST, or leave the"
                                           " INI file empty"}
    with pytest.raises(AxiscalError, match="^an INI file is LinuxCNC's: the controller 'sim' takes none$"):
        connect("sim", "sim", ini=ini)


def test_the_visit_connects_its_axes_keeps_the_ini_and_holds_the_plan_and_the_run_to_it(linuxcnc, ini, tmp_path):
    bench = Workbench(tmp_path / "data", db=str(tmp_path / "h.sqlite"))
    bench.new_visit(VISIT | {"tests": ["positioning-X", "positioning-Y"]})
    answer = bench.connect({"instrument": "sim:umd", "controller": linuxcnc.spec, "ini": str(ini)})
    told = dict(answer["told"]["controller"])
    assert (told["soft limits X"], told["soft limits Y"]) == ("-1 to 120 mm (INI file)", "0 to 450 mm (INI file)")
    assert "soft limits Z" not in told  # Z is not tested in this visit

    # the plan is held against the limits told: within the machine's travel (800 mm) but beyond the INI's
    plan = {"start_mm": 10, "end_mm": 150, "targets": 5, "runs": 1, "overrun_mm": 5, "dwell_s": 1}
    with pytest.raises(FormErrors) as beyond:
        bench.make_plan(plan)
    assert beyond.value.fields == {"end_mm": "the moves reach 5 to 155 mm, beyond the controller's soft limits of X"
                                             " (-1 to 120 mm, told at Connect)"}
    with pytest.raises(FormErrors) as overrun:
        bench.make_plan(plan | {"start_mm": 2, "end_mm": 100})
    assert list(overrun.value.fields) == ["overrun_mm"]

    # the INI survives a restart of the workbench, with the visit
    again = Workbench(tmp_path / "data", db=str(tmp_path / "h.sqlite"))
    assert again.state()["connection"] == {"instrument": "sim:umd", "controller": linuxcnc.spec, "ini": str(ini)}

    # a plan written before Connect, beyond the INI's limits: the run is refused before any move
    bench.connection = None
    bench.make_plan(plan)
    bench.connect({"instrument": "sim:umd", "controller": linuxcnc.spec, "ini": str(ini)})
    bench.start_run("as-found")
    assert bench.run.wait(30) == "failed"
    assert "beyond the soft limits of LinuxCNC at 127.0.0.1" in bench.run.message and "nothing was moved" in bench.run.message
    assert linuxcnc.moves == []


def test_the_virtual_controller_tells_each_tested_axis_s_travel_and_the_virtual_machine_none(tmp_path):
    """With a simulated instrument each run's virtual controller refuses a move beyond its axis's travel: those are
    the limits told and the plan is held to them; the virtual machine (sim and sim) runs the overrun beyond them."""
    bench = Workbench(tmp_path / "data", db=str(tmp_path / "h.sqlite"))
    bench.new_visit(VISIT)
    told = dict(bench.connect({"instrument": "sim:umd", "controller": "sim"})["told"]["controller"])
    assert (told["soft limits X"], told["soft limits Y"], told["soft limits Z"]) == ("0 to 800 mm", "0 to 500 mm", "0 to 400 mm")
    plan = {"axis": "Y", "start_mm": 0, "end_mm": 150, "targets": 5, "runs": 1, "overrun_mm": 5, "dwell_s": 1}
    with pytest.raises(FormErrors) as beyond:
        bench.make_plan(plan)
    assert beyond.value.fields == {"overrun_mm": "the moves reach -5 to 155 mm, beyond the controller's soft limits of Y"
                                                 " (0 to 500 mm, told at Connect)"}
    told = dict(bench.connect({"instrument": "sim", "controller": "sim"})["told"]["controller"])
    assert told["soft limits"] == "none: the virtual machine runs a plan's overrun beyond the travels too"
    assert bench.make_plan(plan)["axis"] == "Y"
