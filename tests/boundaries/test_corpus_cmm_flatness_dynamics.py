"""The CMM, flatness and dynamics commands at their boundaries: malformed files and the values that once gave
a figure where none could be given.

Two parts. The corpus of :mod:`test_corpus` (every mutation of a valid file) fed to ``cmm acceptance``,
``cmm probing`` and ``flatness``: a command reads the file correctly (status 0) or refuses it in one line
naming it. Then the boundary cases found by measuring the release, each once a traceback, a silent
figure or an answer with no meaning: each now one line, ``axiscal: error: FILE[:LINE]: problem``, status 2.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from test_corpus import MUTATIONS

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
E0 = EXAMPLES / "cmm" / "e0_gauge_blocks.csv"
SPHERE = EXAMPLES / "cmm" / "sphere_single.csv"
RECORDING = EXAMPLES / "capture" / "recording_x.csv"
PLAN = EXAMPLES / "capture" / "plan_x.csv"

pytestmark = pytest.mark.filterwarnings("error::RuntimeWarning")

#: command -> (the valid input, its arguments with {input})
COMMANDS = {
    "cmm acceptance": (E0, ("cmm", "acceptance", "{input}", "--mpe-a-um", "1.8", "--mpe-k", "300", "--json")),
    "cmm probing": (SPHERE, ("cmm", "probing", "{input}", "--diameter-mm", "25.00018", "--pform-mpe-um", "1.7", "--json")),
    "flatness": (EXAMPLES / "flatness" / "grid.toml", ("flatness", "{input}", "--json")),
}
CASES = [(command, mutation) for command in COMMANDS for mutation in MUTATIONS]


def _one_line(status: int, out: str, err: str) -> None:
    assert "Traceback" not in err
    assert status == 2 and out == "", (status, err)
    assert err.startswith("axiscal: error: ") and err.count("\n") == 1, err


@pytest.mark.parametrize(("command", "mutation"), CASES, ids=[f"{c}-{m}" for c, m in CASES])
def test_a_malformed_input_is_read_or_refused_in_one_line(run_cli, tmp_path, command, mutation):
    source, argv = COMMANDS[command]
    target = tmp_path / ("input" + source.suffix)
    target.write_bytes(MUTATIONS[mutation](source.read_bytes()))
    status, out, err = run_cli(*[a.format(input=target) for a in argv])
    assert "Traceback" not in err
    assert status in (0, 2), (status, err)
    if status == 2:
        _one_line(status, out, err)


def _rows(path: Path) -> list[str]:
    return path.read_text().splitlines()


def _write(tmp_path: Path, name: str, lines: list[str]) -> Path:
    path = tmp_path / name
    path.write_text("\n".join(lines) + "\n")
    return path


def _scaled(tmp_path, column, factor):
    lines = _rows(E0)
    k = lines[0].split(",").index(column)
    cells = lines[3].split(",")
    cells[k] = f"{float(cells[k]) * factor:.9g}"
    lines[3] = ",".join(cells)
    return _write(tmp_path, "e0.csv", lines)


def _points(tmp_path, directions):
    rng = np.random.default_rng(0)
    points = 12.5 * np.asarray(directions) + rng.normal(0, 0.3e-3, np.shape(directions))
    return _write(tmp_path, "sphere.csv", ["x_mm,y_mm,z_mm", *(f"{x:.6f},{y:.6f},{z:.6f}" for x, y, z in points)])


def _great_circle():
    a = np.linspace(0, 2 * np.pi, 25, endpoint=False)
    return np.column_stack([np.cos(a), np.sin(a), np.zeros(25)])


def _cap(half_angle_deg):
    t = np.radians(np.r_[0.0, np.full(8, half_angle_deg / 2), np.full(16, half_angle_deg)])
    a = np.r_[0.0, np.arange(8) * np.pi / 4, np.arange(16) * np.pi / 8]
    return np.column_stack([np.sin(t) * np.cos(a), np.sin(t) * np.sin(a), np.cos(t)])


def _recording(tmp_path, change):
    lines = _rows(RECORDING)
    change(lines)
    return _write(tmp_path, "recording.csv", lines)


def _time(lines, k, value):
    cells = lines[k].split(",")
    cells[0] = f"{value:.6f}"
    lines[k] = ",".join(cells)


def _repeat_time(lines):
    _time(lines, 301, float(lines[300].split(",")[0]))


def _gap(lines):
    for k in range(1501, len(lines)):
        _time(lines, k, float(lines[k].split(",")[0]) + 1e6)


def _plan_off(tmp_path):
    lines = _rows(PLAN)
    for i in range(1, len(lines)):
        cells = lines[i].split(",")
        cells[3:5] = [f"{float(c) + 3:.3f}" if c else c for c in cells[3:5]]
        lines[i] = ",".join(cells)
    return _write(tmp_path, "plan.csv", lines)


def _flatness(tmp_path, positions):
    text = (f'[[lines]]\nname = "a"\nfrom_mm = [0, 0]\nto_mm = [200, 0]\nposition_mm = {positions}\n'
            'deviation_um = [0, 1, 2, 0]\n'
            '[[lines]]\nname = "b"\nfrom_mm = [0, 0]\nto_mm = [0, 200]\nposition_mm = [0, 100, 200]\ndeviation_um = [0, 1, 0]\n')
    path = tmp_path / "lines.toml"
    path.write_text(text)
    return path


#: name -> (argv made from tmp_path, the words of the refusal, the file line it names or None)
BOUNDARIES = {
    # ISO 10360-2
    "measured in um under measured_mm": (lambda p: ("cmm", "acceptance", _scaled(p, "measured_mm", 1000)),
                                         "times the nominal", 4),
    "nominals in metres": (lambda p: ("cmm", "acceptance", _scaled(p, "nominal_mm", 0.001)), "times the nominal", 4),
    "E150 MPE without E150 rows": (
        lambda p: ("cmm", "acceptance", _write(p, "e0.csv", [r for r in _rows(E0) if not r.endswith(",150")]),
                   "--e150-mpe-a-um", "2"), "--e150-mpe-a-um is given, but the measurements hold no E150 value", None),
    "MPE 1e300": (lambda p: ("cmm", "acceptance", E0, "--mpe-a-um", "1e300"), "--mpe-a-um must be above 0 and at most 10000",
                  None),
    "uncertainty 1e300": (lambda p: ("cmm", "acceptance", E0, "--uncertainty-um", "1e300"), "--uncertainty-um must be 0 to 10000",
                          None),
    # ISO 10360-5
    "PForm MPE 1e300": (lambda p: ("cmm", "probing", SPHERE, "--diameter-mm", "25", "--pform-mpe-um", "1e300"),
                        "--pform-mpe-um must be above 0 and at most 10000", None),
    "diameter 100 times the sphere's": (lambda p: ("cmm", "probing", SPHERE, "--diameter-mm", "2500"),
                                        "not on the calibrated one (--diameter-mm 2500 mm)", None),
    "a great circle": (lambda p: ("cmm", "probing", _points(p, _great_circle()), "--diameter-mm", "25"),
                       "stylus 1: the points cover too little of the sphere", None),
    "a 10-degree cap": (lambda p: ("cmm", "probing", _points(p, _cap(10.0)), "--diameter-mm", "25"),
                        "stylus 1: the points cover too little of the sphere", None),
    # flatness
    "a position_mm repeated": (lambda p: ("flatness", _flatness(p, "[0, 100, 100, 200]")),
                               "line 'a': position_mm: position 100 mm is given twice", 5),
    # dynamics
    "a time stamp repeated": (lambda p: ("dynamics", _recording(p, _repeat_time)), "is given twice: two samples at one time",
                              302),
    "a gap of 1e6 s": (lambda p: ("dynamics", _recording(p, _gap)), "a gap of 1e+06 s", 1502),
    "a plan 3 mm off": (lambda p: ("dynamics", RECORDING, "--plan", _plan_off(p)), "none of its 10 stops is within 0.5 mm",
                        None),
    "a sensor column as the reading": (lambda p: ("dynamics", RECORDING, "--channel", "air_temperature_c", "--unit", "mm"),
                                       "the channel air_temperature_c is a sensor's column", None),
}


@pytest.mark.parametrize("case", list(BOUNDARIES))
def test_a_boundary_case_is_refused_in_one_line(run_cli, tmp_path, case):
    make, words, line = BOUNDARIES[case]
    argv = make(tmp_path)
    status, out, err = run_cli(*argv)
    _one_line(status, out, err)
    assert words in err, err
    if line is not None:
        assert f":{line}: " in err, err
