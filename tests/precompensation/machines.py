"""Machines for the pre-compensation tests: the shipped examples and synthetic chains with smooth errors."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from axiscal.model.machine import Axis, Machine, load_machine
from axiscal.model.tables import ErrorTable

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def smooth_table(letter: str, start_m: float, end_m: float, seed: int) -> ErrorTable:
    """Six error motions of a few micrometres and microradians, smooth over the travel (cubic)."""
    rng = np.random.default_rng(seed)
    position = np.linspace(start_m, end_m, 17)
    phase = (position - start_m) / (end_m - start_m) * 2 * np.pi
    amplitude = np.r_[rng.uniform(2e-6, 6e-6, 3), rng.uniform(2e-6, 8e-6, 3)]
    values = amplitude[:, None] * np.sin(phase[None, :] * rng.uniform(0.5, 2.0, (6, 1)) + rng.uniform(0, 6, (6, 1)))
    return ErrorTable(letter, position, values, interpolation="cubic")


def synthetic(chain: str, travel_m: dict[str, tuple[float, float]], name: str, *, tool_m=(0.0, 0.0, -0.1)) -> Machine:
    axes = {k: Axis(k, smooth_table(k, *travel_m[k], seed=i)) for i, k in enumerate(travel_m)}
    return Machine(chain, axes, squareness_rad={"EC0Y": 20e-6, "EB0Z": -15e-6, "EA0Z": 10e-6}, tool_m=tool_m, name=name)


def machines() -> dict[str, Machine]:
    """XFYZ machine tool, a moving-bridge CMM (FYXZ), a gantry router (FXYZ), the XZ module, the trunnion."""
    return {
        "xfyz": load_machine(EXAMPLES / "xfyz_machine" / "machine.toml"),
        "cmm": synthetic("FYXZ", {"Y": (0.0, 0.7), "X": (0.0, 0.5), "Z": (-0.4, 0.0)}, "moving-bridge CMM"),
        "router": synthetic("FXYZ", {"X": (0.0, 1.2), "Y": (0.0, 0.8), "Z": (-0.2, 0.0)}, "gantry router", tool_m=(0.0, 0.0, -0.05)),
        "module": load_machine(EXAMPLES / "xz_module" / "machine.toml"),
        "trunnion": load_machine(EXAMPLES / "trunnion_machine" / "machine.toml"),
    }


def ideal(chain: str = "XFYZ") -> Machine:
    letters = [c for c in chain if c != "F"]
    return Machine(chain, {k: Axis(k) for k in letters}, name="ideal")
