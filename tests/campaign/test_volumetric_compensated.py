"""The model of a compensated machine: an as-left campaign's volumetric section shows what is left."""

from __future__ import annotations

import shutil
from importlib import resources
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as hs

from axiscal.campaign import compensated_machine, load_campaign, run_campaign
from axiscal.compensation.readback import ControllerCompensation
from axiscal.errors import AxiscalError
from axiscal.model import ErrorTable, load_machine
from axiscal.model.machine import Axis, Machine

XZ = Path(str(resources.files("axiscal") / "data" / "xz_module"))


def test_a_hand_computed_compensated_table():
    """EXX = 100 um/m; the controller takes 100 um/m off: sent to 0.2 m - 20 um, the axis stands where EXX is
    19.998 um, so 2 nm are left at 0.2 m (and 1 nm at 0.1 m): e(m) + k(c) with m = c + k(c)."""
    table = ErrorTable.from_components("X", [0.0, 0.2], {"EXX": [0.0, 20e-6], "EYX": [0.0, 4e-6]})
    machine = Machine("FX", {"X": Axis("X", table)})
    loaded = ControllerCompensation("linuxcnc", np.array([0.0, 0.2]), np.array([0.0, -20e-6]), np.array([0.0, -20e-6]))
    left = compensated_machine(machine, {"X": loaded}).table("X")
    values = left.evaluate(np.array([0.1, 0.2]))
    assert values[0] == pytest.approx([-1e-9, -2e-9], abs=1e-18)
    assert values[1] == pytest.approx([2e-6 * (1 - 1e-4), 4e-6 * (1 - 1e-4)], abs=1e-18)  # EYX where the axis stands


@settings(max_examples=30, deadline=None)
@given(hs.integers(0, 2**32 - 1))
def test_the_compensated_table_against_a_plain_loop(seed):
    """At every commanded position of the new table: each error motion where the axis stands, and the axis' own
    positioning error plus the mean of the + and - corrections."""
    rng = np.random.default_rng(seed)
    q = np.sort(rng.choice(np.linspace(-0.1, 0.5, 61), rng.integers(2, 12), replace=False))
    table = ErrorTable("Z", q, rng.normal(0, 10e-6, (6, q.size)))
    nodes = np.sort(rng.choice(np.linspace(-0.2, 0.6, 81), rng.integers(1, 10), replace=False))
    loaded = ControllerCompensation("fanuc", nodes, rng.normal(0, 20e-6, nodes.size), rng.normal(0, 20e-6, nodes.size))
    machine = Machine("FZ", {"Z": Axis("Z", table)})
    left = compensated_machine(machine, {"Z": loaded}).table("Z")
    assert left.start_m == table.start_m and left.end_m == table.end_m
    for c, row in zip(left.position_m, left.values.T):
        k = 0.5 * (np.interp(c, nodes, loaded.plus_m) + np.interp(c, nodes, loaded.minus_m))
        stands = min(max(c + k, table.start_m), table.end_m)
        expected = [float(np.interp(stands, q, table.values[i])) for i in range(6)]
        expected[2] += k
        assert row == pytest.approx(expected, abs=1e-15)
    # the correction's own points inside the travel are rows of the new table: linear between them, exact
    inside = nodes[(nodes > table.start_m) & (nodes < table.end_m)]
    assert np.all(np.isin(inside, left.position_m))


def test_a_rotary_or_missing_axis_is_refused():
    machine = load_machine(XZ / "machine.toml")
    loaded = ControllerCompensation("linuxcnc", np.array([0.0, 0.2]), np.zeros(2), np.zeros(2))
    with pytest.raises(AxiscalError, match="a compensation for axis 'Y': the machine's linear axes are X, Z"):
        compensated_machine(machine, {"Y": loaded})
    with pytest.raises(AxiscalError, match="ControllerCompensation"):
        compensated_machine(machine, {"X": "X.comp"})


CAMPAIGN = """\
[campaign]
title = "XZ module as left"
date = 2026-11-20
operator = "A. Technician"

[machine]
name = "XZ linear module"
model = "machine.toml"
controller = "linuxcnc"
compensation = { X = "X.comp" }

[[tests]]
kind = "positioning"
axis = "X"
file = "positioning_x.csv"
"""


@pytest.fixture
def folder(tmp_path, examples):
    for name in ("machine.toml", "x_errors.csv", "z_errors.csv"):
        shutil.copy(XZ / name, tmp_path / name)
    shutil.copy(examples / "campaign" / "positioning_x.csv", tmp_path / "positioning_x.csv")
    table = load_machine(XZ / "machine.toml").table("X")
    exx_mm = table.values[0] / 1e-3
    # a correction that takes EXX off exactly at the table's points (LinuxCNC type 1: nominal, forward, reverse)
    (tmp_path / "X.comp").write_text("".join(f"{q / 1e-3:.4f} {-e:.7f} {-e:.7f}\n" for q, e in zip(table.position_m, exx_mm)))
    (tmp_path / "campaign.toml").write_text(CAMPAIGN)
    return tmp_path


def test_the_campaign_s_volumetric_section_draws_the_compensated_machine(folder):
    left = run_campaign(folder).model
    (folder / "campaign.toml").write_text(CAMPAIGN.replace('compensation = { X = "X.comp" }\n', ""))
    found = run_campaign(folder).model
    assert "with the linuxcnc compensation loaded (X: X.comp): what is left" in left["method"]
    assert "compensation" not in found["method"]
    assert left["figures"]["max_um"] < found["figures"]["max_um"] - 5.0
    expected = compensated_machine(load_machine(folder / "machine.toml"), {})  # no file: the machine as found
    assert expected.table("X").values == pytest.approx(load_machine(folder / "machine.toml").table("X").values)


@pytest.mark.parametrize(
    ("old", "new", "words"),
    [
        ('controller = "linuxcnc"\n', "", "[machine] compensation needs [machine] controller"),
        ('model = "machine.toml"\n', "", "[machine] compensation needs [machine] model"),
        ('{ X = "X.comp" }', '{ A = "X.comp" }', "[machine] compensation: 'A' is not a linear axis"),
        ('{ X = "X.comp" }', '{ X = "nothing.comp" }', "[machine] compensation X: data file 'nothing.comp' not found"),
        ('{ X = "X.comp" }', "{}", "[machine] compensation names no file"),
        ('{ X = "X.comp" }', '"X.comp"', "[machine] compensation must be a table"),
    ],
)
def test_a_bad_compensation_names_the_line(folder, old, new, words):
    (folder / "campaign.toml").write_text(CAMPAIGN.replace(old, new))
    with pytest.raises(AxiscalError) as caught:
        load_campaign(folder)
    assert words in caught.value.message and caught.value.line == (CAMPAIGN.replace(old, new).splitlines().index(
        next(line for line in CAMPAIGN.replace(old, new).splitlines() if line.startswith("compensation"))) + 1)


def test_a_file_the_controller_would_refuse_is_named(folder):
    (folder / "X.comp").write_text("0 0 0\nten 1 1\n")
    with pytest.raises(AxiscalError) as caught:
        load_campaign(folder)
    assert caught.value.path == str(folder / "X.comp")
