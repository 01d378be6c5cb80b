"""The virtual ballbar machine: its file, its sidecar, its refusals."""

from __future__ import annotations

import json
import math

import numpy as np
import pandas as pd
import pytest

from axiscal.circular.reader import read_ballbar
from axiscal.circular.report import PPM
from axiscal.circular.simulation import simulate_ballbar, trace_csv, write_trace
from axiscal.errors import AxiscalError
from axiscal.units import MM, UM


def test_written_trace_reads_back_with_pandas_and_the_reader(tmp_path):
    trace = simulate_ballbar(backlash={"X": 3 * UM}, noise=0.1 * UM, step=math.radians(0.5), seed=4)
    path = write_trace(tmp_path / "run.csv", trace, simulated={"backlash_um": {"X": 3.0}})
    frame = pd.read_csv(path)
    assert list(frame.columns) == ["angle_deg", "direction", "radius_deviation_um"]
    assert len(frame) == trace.angles.size and set(frame["direction"]) == {"ccw", "cw"}
    back = read_ballbar(path, radius=trace.radius, plane="XY")
    np.testing.assert_allclose(back.deviations, trace.deviations, atol=0.5e-4 * UM)
    sidecar = json.loads((tmp_path / "run.json").read_text())
    assert sidecar["kind"] == "ballbar trace" and sidecar["radius_mm"] == 100.0
    assert sidecar["simulated"]["backlash_um"] == {"X": 3.0}


def test_same_seed_same_trace_and_directions_in_the_order_run():
    a = simulate_ballbar(noise=0.2 * UM, seed=9, directions=("cw", "ccw"), step=math.radians(1.0))
    b = simulate_ballbar(noise=0.2 * UM, seed=9, directions=("cw", "ccw"), step=math.radians(1.0))
    assert trace_csv(a) == trace_csv(b)
    assert a.directions[0] == "cw" and a.directions[-1] == "ccw"
    cw = a.angles[:360]
    assert np.all(np.diff(cw) < 0)  # cw runs towards decreasing angle


@pytest.mark.parametrize(
    "kwargs, message",
    [
        ({"radius": -1.0}, "radius"),
        ({"step": math.radians(2.0)}, "step"),
        ({"noise": -1 * UM}, "noise"),
        ({"backlash": {"Z": 1 * UM}}, "not in the plane"),
        ({"cyclic_error": {"X": 1 * UM}}, "pitch"),
        ({"directions": ("up",)}, "directions"),
        ({"squareness": math.nan}, "squareness"),
    ],
)
def test_bad_machines_are_refused(kwargs, message):
    with pytest.raises(AxiscalError, match=message):
        simulate_ballbar(**kwargs)


def test_each_axis_error_lands_on_its_axis_in_other_planes():
    # scale of Z only, in ZX: the first axis, so dR = R s cos^2 a
    trace = simulate_ballbar(plane="ZX", scale={"Z": 10 * PPM}, directions=("ccw",), step=math.radians(1.0), radius=50 * MM)
    np.testing.assert_allclose(trace.deviations, 50 * MM * 10 * PPM * np.cos(trace.angles) ** 2, atol=1e-11)
