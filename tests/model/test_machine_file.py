"""The machine file against its declared schema: every wrong type, stray term or path outside the
machine's folder is one error naming the file, the line and the key; nothing is read from outside."""

from __future__ import annotations

import shutil
from importlib import resources
from pathlib import Path

import pytest

from axiscal.errors import AxiscalError
from axiscal.model.machine import load_machine

XZ = Path(str(resources.files("axiscal") / "data" / "xz_module"))


@pytest.fixture
def folder(tmp_path):
    for name in ("machine.toml", "x_errors.csv", "z_errors.csv"):
        shutil.copy(XZ / name, tmp_path / name)
    return tmp_path


def _error(folder: Path, old: str, new: str) -> AxiscalError:
    path = folder / "machine.toml"
    text = path.read_text()
    assert old in text
    path.write_text(text.replace(old, new, 1))
    with pytest.raises(AxiscalError) as caught:
        load_machine(path)
    return caught.value


def _line(folder: Path, needle: str) -> int:
    return next(i for i, line in enumerate((folder / "machine.toml").read_text().splitlines(), 1) if needle in line)


@pytest.mark.parametrize(
    ("old", "new", "needle", "words"),
    [
        ('chain = "FXZ"', 'chain = "FXZ"\nhold_ends = "false"', "hold_ends", "hold_ends must be true or false"),
        ("tool_mm = [0.0, -40.0, 0.0]", "tool_mm = [true, 0, 0]", "tool_mm", "tool_mm must be a list of 3 numbers"),
        ("tool_mm = [0.0, -40.0, 0.0]", 'tool_mm = "0, -40, 0"', "tool_mm", "tool_mm must be a list of 3 numbers"),
        ("tool_mm = [0.0, -40.0, 0.0]", "tool_mm = [0, nan, 0]", "tool_mm", "tool_mm must be a list of 3 numbers"),
        ('chain = "FXZ"', "chain = 5", "chain", "chain must be a text"),
        ("EB0Z_arcsec = -42.4", 'EB0Z_arcsec = "-42.4"', "EB0Z_arcsec", "must be a number"),
        ("EB0Z_arcsec = -42.4", "EB0Z_arcsec = -42.4\nEC0Y_arcsec = 5.0", "EC0Y_arcsec", "has no axis Y"),
        ("EB0Z_arcsec = -42.4", "EB0Z_arcsec = -42.4\nEA0Z_arcsec = 5.0", "EA0Z_arcsec", "has no axis Y"),
        ('errors = "x_errors.csv"', 'errors = "/etc/shadow"', "/etc/shadow", "absolute path"),
        ('errors = "x_errors.csv"', 'errors = "../x_errors.csv"', "../x_errors.csv", "leaves the folder"),
        ('chain = "FXZ"', 'chain = "FXZ"\nsquareness_placement = "sideways"', "squareness_placement", "must be one of"),
        ('origin_mm = [0.0, 0.0, 50.0]', "origin_mm = [0.0, 0.0]", "origin_mm", "list of 3 numbers"),
    ],
)
def test_each_mistake_names_its_line(folder, old, new, needle, words):
    error = _error(folder, old, new)
    assert words in error.message, error.message
    assert error.path == str(folder / "machine.toml")
    assert error.line == _line(folder, needle), str(error)


def test_a_path_outside_is_never_read(folder, tmp_path_factory):
    secret = tmp_path_factory.mktemp("elsewhere") / "secret.csv"
    secret.write_text("the first line of a secret\n")
    error = _error(folder, 'errors = "x_errors.csv"', f'errors = "{secret}"')
    assert "secret" not in error.message.replace(str(secret), "") and "first line" not in str(error)
