"""Compensated commands: the inverse of the model, from targets (array or CSV) to commands in SI."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from axiscal.errors import AxiscalError
from axiscal.model.inverse import inverse_commands
from axiscal.model.machine import load_machine


def test_commands_put_the_tool_on_the_targets(examples, tmp_path):
    machine = load_machine(examples / "xfyz_machine" / "machine.toml")
    wanted = {"X": np.array([0.1, 0.4]), "Y": np.array([0.2, 0.05]), "Z": np.array([0.3, 0.1])}
    result = inverse_commands(machine, machine.actual_point(wanted))
    assert list(result.command_m) == ["X", "Y", "Z"]
    for k in "XYZ":
        np.testing.assert_allclose(result.command_m[k], wanted[k], atol=1e-12)
    path = result.write_csv(tmp_path / "commands.csv")
    table = pd.read_csv(path)
    assert list(table.columns) == ["x_mm", "y_mm", "z_mm", "x_command_mm", "y_command_mm", "z_command_mm"]
    np.testing.assert_allclose(table["y_command_mm"], [200.0, 50.0], atol=1e-6)
    assert (tmp_path / "commands.json").exists()


def test_targets_from_a_file_and_errors_naming_it(examples, tmp_path):
    machine_file = examples / "xz_module" / "machine.toml"
    targets = tmp_path / "t.csv"
    targets.write_text("x_mm,y_mm,z_mm\n50,-40,150\n")
    result = inverse_commands(machine_file, targets)
    assert result.sources == (str(machine_file), str(targets))
    assert result.command_m["X"][0] == pytest.approx(0.05, abs=1e-4)
    targets.write_text("x_mm,y_mm,z_mm\n50,-40,150\n5000,-40,150\n")
    with pytest.raises(AxiscalError, match=f"{targets}"):
        inverse_commands(machine_file, targets)
    targets.write_text("x_mm,z_mm\n50,150\n")
    with pytest.raises(AxiscalError, match="missing column 'y_mm'"):
        inverse_commands(machine_file, targets)
