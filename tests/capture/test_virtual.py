"""The virtual machine: each controller's table loaded into the virtual controller leaves a small residual."""

from __future__ import annotations

import numpy as np
import pytest

from axiscal.capture import capture, plan_steps, simulate_capture
from axiscal.capture.sources import plan_motions
from axiscal.capture.virtual import simulate_motions
from axiscal.cli.main import main
from axiscal.compensation.formats import compensation_table
from axiscal.compensation.readback import read_compensation
from axiscal.errors import AxiscalError
from axiscal.model.machine import load_machine
from axiscal.positioning.evaluation import iso230_2
from axiscal.positioning.plan import plan_test, write_plan
from axiscal.report.demo import builtin_example


@pytest.fixture(scope="module")
def machine():
    return load_machine(builtin_example() / "machine.toml")


@pytest.fixture(scope="module")
def plan():
    return plan_test(0.0, 0.19, 8, runs=2, seed=5)


@pytest.fixture(scope="module")
def as_found(machine, plan):
    recording = simulate_motions(plan_motions(plan_steps(plan), dwell_s=1.0), machine, axis="X", rate_hz=400.0, seed=1).recording
    return capture(plan, recording).run


@pytest.mark.parametrize("controller, options, bidirectional", [
    ("linuxcnc", {}, True),
    ("fanuc", {"bidirectional": True}, True),
    ("fanuc", {}, False),
    ("siemens", {}, False),
    ("heidenhain", {}, True),
])
def test_each_controllers_table_in_the_virtual_controller(machine, plan, as_found, controller, options, bidirectional):
    table = compensation_table(as_found, controller, **options)
    loaded = read_compensation(table.text, controller, reference_position_m=float(as_found.targets[0]))
    recording = simulate_motions(plan_motions(plan_steps(plan), dwell_s=1.0), machine, axis="X", rate_hz=400.0, seed=2,
                                 compensation=loaded).recording
    as_left = capture(plan, recording).run
    found, left = iso230_2(as_found).figures(), iso230_2(as_left).figures()
    # a one-curve table leaves the reversal (4 um); a two-direction table takes it out too
    assert left["E"] <= 0.2 * found["E"]
    assert abs(left["B"]) < (1.5e-6 if bidirectional else 5e-6)
    if bidirectional:
        assert left["E"] < 2.5e-6


def test_the_program_file_runs_in_each_dialect(machine, plan, tmp_path):
    # the plan's program written in a dialect is read back by the same dialect's reader and run
    for dialect in ("linuxcnc", "fanuc", "heidenhain", "sinumerik"):
        program = tmp_path / f"x_{dialect}.txt"
        write_plan(plan, None, gcode_path=program, dialect=dialect, dwell_s=1.0)
        simulated = simulate_capture(program, machine, axis="X", dialect=dialect, rate_hz=200.0)
        assert len(simulated.dwells) == plan.readings
        assert capture(plan, simulated.recording, settings=None).run.runs == 2


def test_bad_requests(machine, plan, tmp_path):
    program = tmp_path / "x.ngc"
    write_plan(plan, None, gcode_path=program)
    with pytest.raises(AxiscalError, match="not a linear axis"):
        simulate_capture(program, machine, axis="Y")
    with pytest.raises(AxiscalError, match="needs its controller"):
        simulate_capture(program, machine, axis="X", compensation=program)
    (tmp_path / "bad.comp").write_text("0 0 0\n# no\n")
    with pytest.raises(AxiscalError, match=r"bad.comp:2: LinuxCNC would stop reading"):
        simulate_capture(program, machine, axis="X", compensation=tmp_path / "bad.comp", controller="linuxcnc")


def test_simulate_capture_command(tmp_path, capsys):
    assert main(["plan", "--start-mm", "0", "--end-mm", "190", "--targets", "5", "--runs", "1", "--seed", "2",
                 "-o", str(tmp_path / "plan.csv"), "--gcode", str(tmp_path / "x.ngc"), "--dwell-s", "1"]) == 0
    machine_toml = str(builtin_example() / "machine.toml")
    assert main(["simulate", "capture", str(tmp_path / "x.ngc"), "--machine", machine_toml, "--axis", "X",
                 "-o", str(tmp_path / "rec.csv"), "--rate-hz", "200"]) == 0
    assert main(["capture", str(tmp_path / "plan.csv"), "--from", str(tmp_path / "rec.csv"), "-o", str(tmp_path / "run.csv")]) == 0
    assert main(["compensate", str(tmp_path / "run.csv"), "--format", "linuxcnc", "-o", str(tmp_path / "x.comp")]) == 0
    assert main(["simulate", "capture", str(tmp_path / "x.ngc"), "--machine", machine_toml, "--axis", "X",
                 "-o", str(tmp_path / "left.csv"), "--rate-hz", "200", "--compensation", str(tmp_path / "x.comp"),
                 "--controller", "linuxcnc"]) == 0
    assert main(["capture", str(tmp_path / "plan.csv"), "--from", str(tmp_path / "left.csv"), "-o", str(tmp_path / "left_run.csv"),
                 "--json"]) == 0
    assert '"stops": 10' in capsys.readouterr().out
    assert np.isfinite(iso230_2(capture(tmp_path / "plan.csv", tmp_path / "left.csv").run).figures()["E"])
