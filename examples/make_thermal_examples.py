"""Write the thermal test examples (run from the repository root: python examples/make_thermal_examples.py).

* examples/thermal/etve_run.csv: an ETVE test (ISO 230-3) of 24 h sampled every 5 min. The air
  follows a daily swing of 1.2 K peak to peak plus a 0.4 K step at 9 h (a door left open); the
  machine's column follows the air through a first-order lag of 1.5 h. The displacement of the
  functional point is X = 1.5 um/K, Y = -0.6 um/K and Z = -4.0 um/K times the column's
  temperature change, the tilts A = 0.8 urad/K and B = 0 of the same, plus 0.05 um (0.05 urad)
  of sensor noise (seed 3).
* examples/thermal/drift_run.csv: a spindle distortion test: two cycles of 3 h running and 1.5 h
  stopped, every 2 min. The Z displacement settles as a first-order system of time constant
  0.8 h towards -12 um while running and back while stopped; X towards 1.5 um; the spindle
  housing warms by 6 K with the same time constant (seed 4).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent / "thermal"


def first_order(t_h: np.ndarray, driver: np.ndarray, tau_h: float) -> np.ndarray:
    """The response of a first-order lag of time constant tau_h to a driver sampled at t_h (exact for steps between samples)."""
    out = np.empty_like(driver)
    out[0] = driver[0]
    for k in range(1, driver.size):
        a = np.exp(-(t_h[k] - t_h[k - 1]) / tau_h)
        out[k] = a * out[k - 1] + (1 - a) * driver[k]
    return out


def etve_run() -> str:
    rng = np.random.default_rng(3)
    t = np.arange(0.0, 24.0 + 1e-9, 5 / 60)
    air = 20.3 + 0.6 * np.sin(2 * np.pi * (t - 8.0) / 24.0) + 0.4 * (t >= 9.0)
    column = first_order(t, air, 1.5)
    change = column - column[0]
    noise = lambda: rng.normal(0.0, 0.05, t.size)  # noqa: E731
    rows = ["time_h,x_um,y_um,z_um,a_urad,b_urad,temperature_air_c,temperature_column_c"]
    for row in zip(t, 1.5 * change + noise(), -0.6 * change + noise(), -4.0 * change + noise(), 0.8 * change + noise(),
                   noise(), air, column):
        rows.append(",".join(f"{v:.4f}" if i == 0 else f"{v:.3f}" for i, v in enumerate(row)))
    return "\n".join(rows) + "\n"


def drift_run() -> str:
    rng = np.random.default_rng(4)
    step = np.arange(271)  # 9 h in steps of 2 min; a cycle is 135 steps, 90 of them running
    t = step * 2 / 60
    running = (step % 135 < 90) & (step < 270)
    load = running.astype(float)
    shifted = np.concatenate([[0.0], load[:-1]])  # the spindle runs during the step that follows the sample
    state = first_order(t, shifted, 0.8)
    rows = ["time_h,x_um,z_um,temperature_spindle_c,temperature_air_c,running"]
    for k in range(t.size):
        rows.append(f"{t[k]:.4f},{1.5 * state[k] + rng.normal(0, 0.03):.3f},{-12.0 * state[k] + rng.normal(0, 0.03):.3f},"
                    f"{21.0 + 6.0 * state[k] + rng.normal(0, 0.02):.3f},{20.5 + rng.normal(0, 0.02):.3f},{int(running[k])}")
    return "\n".join(rows) + "\n"


def main() -> None:
    HERE.mkdir(exist_ok=True)
    (HERE / "etve_run.csv").write_text(etve_run(), encoding="utf-8")
    (HERE / "drift_run.csv").write_text(drift_run(), encoding="utf-8")


if __name__ == "__main__":
    main()
