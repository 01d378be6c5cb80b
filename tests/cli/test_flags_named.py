"""A library message names the argument (``rate_hz``); the command line maps it to its flag (``--rate``)."""

from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest

from axiscal.cli.common import flags_named
from axiscal.errors import AxiscalError
from axiscal.live.session import check_record_target
from axiscal.measurement import offline

SRC = Path(__file__).resolve().parents[2] / "src" / "axiscal"
FLAG = re.compile(r"(?<![\w-])--[a-z][a-z0-9-]*")
COMMAND = re.compile(r"axiscal [a-z ]+--json")  # a file format named by the command that writes it


def messages_naming_flags() -> list[str]:
    found = []
    for path in sorted(SRC.rglob("*.py")):
        if "cli" in path.relative_to(SRC).parts:
            continue
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            called = getattr(node, "func", None)
            if isinstance(node, ast.Call) and getattr(called, "id", getattr(called, "attr", None)) == "AxiscalError":
                for part in ast.walk(node):
                    if isinstance(part, ast.Constant) and isinstance(part.value, str) and FLAG.search(COMMAND.sub("", part.value)):
                        found.append(f"{path.relative_to(SRC)}:{part.lineno}: {part.value}")
    return found


def test_no_library_message_names_a_command_line_flag():
    assert messages_naming_flags() == []


@pytest.mark.parametrize("call, words", [
    (lambda: offline.simulate_frames(rate_hz=100000.0, duration_s=1000.0), "rate_hz x duration_s gives 100000000 frames"),
    (lambda: offline.calibrate_sensitivity(Path(__file__).parents[2] / "examples/xz_module/sensors_qd_run.csv", "x_qd_u_um",
                                           reference_offset_m=(0.0, 0.001, 0.002)), "reference_offset_m applies to translation"),
])
def test_the_library_names_its_argument(call, words):
    with pytest.raises(AxiscalError, match=words):
        call()


def test_an_existing_record_names_the_argument(tmp_path):
    (tmp_path / "r.csv").write_text("precious\n")
    with pytest.raises(AxiscalError, match="give force=True to replace it"):
        check_record_target(tmp_path / "r.csv", [])


@pytest.mark.parametrize("argv, line", [
    (["simulate", "frames", "--rate", "100000", "--duration", "1000"], "--rate x --duration gives 100000000 frames; allowed 1 to 10000000"),
    (["calibrate", "sensitivity", "{ex}/xz_module/sensors_qd_run.csv", "--channel", "x_qd_u_um", "--reference-offset-mm", "0,1,2"],
     "--reference-offset-mm applies to translation channels (scale, PSD), not to angles"),
    (["live", "--rate", "1e9"], "--rate must be a positive number of frames per second up to 100000, got 1e+09"),
    (["live", "--update-hz", "100"], "--update-hz must be 0.1 to 60 refreshes per second, got 100"),
])
def test_the_command_line_names_the_flag(run_cli, examples, argv, line):
    status, out, err = run_cli(*[a.format(ex=examples) for a in argv])
    assert status == 2 and out == "" and err == f"axiscal: error: {line}\n"


def test_the_command_line_names_force(run_cli, tmp_path):
    (tmp_path / "r.csv").write_text("precious\n")
    status, _, err = run_cli("live", "--no-server", "--duration", "0.05", "--record", tmp_path / "r.csv")
    assert status == 2 and err.endswith("the record file exists; choose another file, or give --force to replace it\n")


def test_flags_named_maps_the_head_word_and_identifiers_anywhere():
    flags = {"seed": "--seed", "rate_hz": "--rate", "duration_s": "--duration", "force=True": "--force"}
    for message, shown in [
        ("seed must not be negative", "--seed must not be negative"),
        ("the seed of a run", "the seed of a run"),  # a plain word is a flag only at the head
        ("rate_hz x duration_s gives 9 frames", "--rate x --duration gives 9 frames"),
        ("give force=True to replace it", "give --force to replace it"),
        ("max_rate_hz is 5", "max_rate_hz is 5"),  # never part of a longer name
    ]:
        with pytest.raises(AxiscalError) as info, flags_named(flags):
            raise AxiscalError(message, path="f.csv", line=3)
        assert info.value.message == shown and info.value.path == "f.csv" and info.value.line == 3
