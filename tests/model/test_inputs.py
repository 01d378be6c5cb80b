"""Reading the model's inputs: points, point specifications, targets and diagonal readings."""

from __future__ import annotations

import numpy as np
import pytest

from axiscal.errors import AxiscalError
from axiscal.model.inputs import (
    parse_point,
    read_interferometer,
    read_points,
    read_targets,
)
from axiscal.model.machine import load_machine


def test_parse_point():
    assert parse_point("X=0,Z=190") == {"X": 0.0, "Z": 0.19}
    assert parse_point(" x = 10 ") == {"X": 0.01}
    for bad in ("X=0;Z=0", "Q=1", "X=", "X=1,X=2", "X=nan", ""):
        with pytest.raises(AxiscalError, match="--from '.*': expected axis positions in mm"):
            parse_point(bad, "--from")


def test_read_points_and_targets(examples, tmp_path):
    machine = load_machine(examples / "xz_module" / "machine.toml")
    points = tmp_path / "p.csv"
    points.write_text("x_mm,Z_mm,note\n0,0,a\n\n100,50,b\n")
    positions, lines = read_points(points, machine)
    np.testing.assert_allclose(positions["X"], [0.0, 0.1])
    np.testing.assert_allclose(positions["Z"], [0.0, 0.05])
    assert lines == (2, 4)
    targets = tmp_path / "t.csv"
    targets.write_text("x_mm,y_mm,z_mm\n1,2,3\n")
    target, lines = read_targets(targets)
    np.testing.assert_allclose(target, [[0.001, 0.002, 0.003]])


def test_interferometer_readings_must_match_the_diagonal(tmp_path):
    readings = tmp_path / "r.csv"
    readings.write_text("nominal_mm,measured_mm\n0,0\n10,10.001\n")
    np.testing.assert_allclose(read_interferometer(readings), [0.0, 0.010001])
    np.testing.assert_allclose(read_interferometer(readings, np.array([0.0, 0.0100009])), [0.0, 0.010001])
    with pytest.raises(AxiscalError, match=r"r.csv:3: nominal_mm 10.000000 does not match"):
        read_interferometer(readings, np.array([0.0, 0.0105]))
    with pytest.raises(AxiscalError, match="2 readings for a diagonal of 3 points"):
        read_interferometer(readings, np.array([0.0, 0.005, 0.01]))
