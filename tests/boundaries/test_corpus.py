"""A corpus of malformed inputs fed to every command that reads a data file.

Each case is a valid file of the command's format, mutated in one of the ways hand-edited,
spreadsheet-exported or cut-short files go wrong. A command either reads it correctly (status 0)
or refuses it with one line, ``axiscal: error: FILE[:LINE]: problem``, status 2, no traceback, and
the output file that was there before is left as it was. Nothing else is acceptable.
"""

from __future__ import annotations

import shutil
from collections.abc import Callable
from importlib import resources
from pathlib import Path

import pytest

XZ = Path(str(resources.files("axiscal") / "data" / "xz_module"))
EXAMPLES = Path(__file__).resolve().parents[2] / "examples"

#: the mutations: name -> function of the valid file's bytes
MUTATIONS: dict[str, Callable[[bytes], bytes]] = {
    "empty": lambda b: b"",
    "header only": lambda b: b.splitlines(keepends=True)[0],
    "bom and crlf": lambda b: b"\xef\xbb\xbf" + b.replace(b"\n", b"\r\n"),
    "cr only": lambda b: b.replace(b"\n", b"\r"),
    "nul byte": lambda b: b[: len(b) // 2] + b"\x00" + b[len(b) // 2 :],
    "long cell": lambda b: _cell(b, 1, b"1" * 200_000),
    "underscore number": lambda b: _cell(b, 2, b"1_000"),
    "full-width digits": lambda b: _cell(b, 2, "１２".encode()),
    "nan": lambda b: _cell(b, 2, b"nan"),
    "inf": lambda b: _cell(b, 2, b"inf"),
    "huge": lambda b: _cell(b, 2, b"1e308"),
    "ragged row": lambda b: _line(b, 3, lambda line: line + b",7"),
    "short row": lambda b: _line(b, 3, lambda line: line.rsplit(b",", 1)[0]),
    "repeated column": lambda b: _line(b, 0, lambda line: line + b"," + line.split(b",")[0]),
    "unknown unit": lambda b: _line(b, 0, lambda line: line.replace(b"_mm", b"_furlong", 1).replace(b"_um", b"_furlong", 1)),
    "truncated": lambda b: b[: int(len(b) * 0.6)],
    "binary": lambda b: bytes(range(256)) * 4,
    "latin-1": lambda b: _line(b, 0, lambda line: line + b",\xe9"),
    "form feed": lambda b: _line(b, 2, lambda line: line + b"\x0c"),
    "unicode line separator": lambda b: _line(b, 2, lambda line: line + "\u2028".encode()),
}


def _line(data: bytes, index: int, change: Callable[[bytes], bytes]) -> bytes:
    lines = data.split(b"\n")
    index = min(index, len(lines) - 1)
    lines[index] = change(lines[index])
    return b"\n".join(lines)


def _cell(data: bytes, index: int, value: bytes) -> bytes:
    def replace(line: bytes) -> bytes:
        cells = line.split(b",")
        cells[-1] = value
        return b",".join(cells)

    return _line(data, index, replace)


#: command -> (the valid input it reads, its arguments with {input} and {out}), each writing to {out} where it can
COMMANDS: dict[str, tuple[Path, tuple[str, ...]]] = {
    "positioning": (EXAMPLES / "positioning_run.csv", ("positioning", "{input}", "--json")),
    "compensate": (EXAMPLES / "positioning_run.csv", ("compensate", "{input}", "--format", "linuxcnc", "-o", "{out}")),
    "straightness": (EXAMPLES / "straightness_profile.csv", ("straightness", "{input}", "--json")),
    "squareness": (EXAMPLES / "squareness_x.csv",
                   ("squareness", "--first", "{input}", "--second", str(EXAMPLES / "squareness_y.csv"), "--json")),
    "separate": (EXAMPLES / "probe_readings.csv", ("separate", "{input}", "--spacing-mm", "15", "-o", "{out}")),
    "ballbar": (EXAMPLES / "ballbar" / "ballbar_run.csv", ("ballbar", "{input}", "--radius-mm", "100", "--json")),
    "measure": (XZ / "sensors_frames.csv", ("measure", "{input}", "-o", "{out}")),
    "diagonal": (XZ / "diagonal_laser.csv",
                 ("diagonal", "--machine", str(XZ / "machine.toml"), "--from", "X=0,Z=0", "--to", "X=190,Z=190",
                  "--interferometer", "{input}", "-o", "{out}")),
    "volumetric": (None, ("volumetric", "--machine", str(XZ / "machine.toml"), "--points", "{input}", "-o", "{out}")),
    "dynamics": (EXAMPLES / "capture" / "recording_x.csv", ("dynamics", "{input}", "--json")),
    "periodic": (EXAMPLES / "dynamics" / "step_cycle_run.csv", ("periodic", "{input}", "--json")),
    "on-the-fly": (EXAMPLES / "dynamics" / "fly_recording.csv",
                   ("on-the-fly", str(EXAMPLES / "dynamics" / "fly_plan.csv"), "--from", "{input}", "-o", "{out}")),
    "error table": (XZ / "x_errors.csv",
                    ("volumetric", "--machine", "{folder}/machine.toml", "--grid", "X=0:190:10,Z=0:190:10", "-o", "{out}")),
}

pytestmark = pytest.mark.filterwarnings("error::RuntimeWarning")

CASES = [(command, mutation) for command in COMMANDS for mutation in MUTATIONS]


@pytest.mark.parametrize(("command", "mutation"), CASES, ids=[f"{c}-{m}" for c, m in CASES])
def test_a_malformed_input_is_read_or_refused_in_one_line(run_cli, tmp_path, command, mutation):
    source, argv = COMMANDS[command]
    if command == "volumetric":
        valid = b"x_mm,z_mm\n0,0\n100,50\n150,150\n190,190\n"
    else:
        valid = source.read_bytes()
    if command == "error table":  # the machine's X table is the file that is mutated
        for name in ("machine.toml", "z_errors.csv"):
            shutil.copy(XZ / name, tmp_path / name)
        target = tmp_path / "x_errors.csv"
    else:
        target = tmp_path / ("input" + (source.suffix if source is not None else ".csv"))
    target.write_bytes(MUTATIONS[mutation](valid))
    out = tmp_path / "previous_output.csv"
    out.write_text("the previous output\n")
    args = [a.format(input=target, out=out, folder=tmp_path) for a in argv]
    status, stdout, stderr = run_cli(*args)
    assert "Traceback" not in stderr
    assert status in (0, 2), (status, stderr)
    if status == 2:
        assert stderr.count("\n") == 1 and stderr.startswith("axiscal: error: "), stderr
        assert out.read_text() == "the previous output\n", "a refused input changed the output file"
