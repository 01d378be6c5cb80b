"""The least dwell the stop detector can use: the virtual machine's program at that dwell gives every stop, at the window alone none."""

from __future__ import annotations

from importlib import resources
from pathlib import Path

import numpy as np
import pytest

from axiscal.capture.run import CaptureSettings
from axiscal.capture.sources import plan_motions
from axiscal.capture.steps import plan_steps
from axiscal.capture.stops import SETTLE_S, detect_stops, least_dwell_s
from axiscal.capture.virtual import simulate_motions
from axiscal.errors import AxiscalError
from axiscal.model.machine import load_machine
from axiscal.positioning.plan import plan_test


def test_the_least_dwell_is_the_window_and_the_settling():
    assert least_dwell_s(0.5) == 0.7 and SETTLE_S == 0.2
    assert least_dwell_s(2.0, settle_s=0.0) == 2.0
    for bad in (0.0, -1.0, float("nan")):
        with pytest.raises(AxiscalError, match="window_s"):
            least_dwell_s(bad)
    with pytest.raises(AxiscalError, match="settle_s"):
        least_dwell_s(0.5, settle_s=-0.1)


@pytest.mark.parametrize("seed", [0, 1])
def test_the_virtual_machine_stops_long_enough_at_the_least_dwell_and_not_at_the_window(seed):
    settings = CaptureSettings()
    steps = plan_steps(plan_test(0.0, 0.15, 5, runs=2, overrun_m=0.005, seed=1))
    machine = load_machine(Path(str(resources.files("axiscal") / "data" / "xz_module" / "machine.toml")))

    def stops_at_targets(dwell_s: float) -> int:
        rec = simulate_motions(plan_motions(steps, dwell_s=dwell_s), machine, axis="X", seed=seed).recording
        found = detect_stops(rec.time_s, rec.reading_m, stability_m=settings.stability_m, window_s=settings.window_s)
        return sum(1 for s in found if s.first_index > 0 and np.nanmin(abs(s.value_m - steps.target_m)) < 1e-4)

    assert stops_at_targets(least_dwell_s(settings.window_s)) == steps.readings
    # a dwell of the window alone: the axis holds no whole window after it settles (only where it stays at the end)
    assert stops_at_targets(settings.window_s) <= 1
