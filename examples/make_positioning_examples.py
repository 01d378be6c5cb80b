"""Write examples/positioning_run.csv, laser_raw_run.csv and rotary_run.csv (run: python examples/make_positioning_examples.py).

A plausible 800 mm ball-screw axis, not a measurement: a scale error of +12 um/m, a periodic screw
error of 1.2 um amplitude over the 10 mm lead, a reversal of about 3.5 um that grows slightly along
the travel, a slow thermal drift of 0.15 um per run and 0.5 um of random scatter. Targets are those
of `axiscal plan --start-mm 0 --end-mm 800 --targets 17 --seed 1`, 5 runs each way.

laser_raw_run.csv holds the same test as raw laser readings (computed with the vacuum wavelength)
of an axis in air at about 21.4 degC and 100.9 kPa with the steel at 21.0 degC: reading =
position_at_20C * (1 + alpha (t_material - 20)) * n_air. `axiscal positioning` must turn it back
into the deviations of positioning_run.csv (to the rounding of the files).

rotary_run.csv is a plausible worm-driven rotary table, not a measurement: targets every 30 deg
from 0 to 360 deg (0 and 360 are the same target), 5 runs each way, a once-per-turn error of 6
arcsec (eccentricity of the encoder), a 2 arcsec error eight times per turn, a reversal of about
4 arcsec and 0.6 arcsec of random scatter.

The files are plain CSV (header first); what they are is in the JSON sidecar beside each.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from axiscal.instruments.air import refractive_index
from axiscal.io.atomic import write_text
from axiscal.io.jsonio import write_sidecar
from axiscal.materials import STEEL_EXPANSION_PER_K
from axiscal.positioning.plan import plan_targets
from axiscal.units import MM, UM

HERE = Path(__file__).resolve().parent
RUNS = 5
ALPHA = STEEL_EXPANSION_PER_K
WAVELENGTH_NM = 632.991


def deviations_um(rng: np.random.Generator, targets_mm: np.ndarray) -> dict[tuple[int, str], np.ndarray]:
    systematic = 0.012 * targets_mm + 1.2 * np.sin(2 * np.pi * targets_mm / 10.0 + 0.6) - 2.0
    half_reversal = 0.5 * (3.5 + 0.0015 * targets_mm)
    out = {}
    for run in range(1, RUNS + 1):
        drift = 0.15 * (run - 1)
        for direction, sign in (("+", -1.0), ("-", 1.0)):
            noise = rng.normal(0.0, 0.5, targets_mm.size)
            out[(run, direction)] = systematic + sign * half_reversal + drift + noise
    return out


def main() -> None:
    targets_mm = plan_targets(0.0, 800 * MM, 17, seed=1) / MM
    rng = np.random.default_rng(3441)
    devs = deviations_um(rng, targets_mm)
    plain = ["target_mm,run,direction,deviation_um"]
    raw = ["target_mm,run,direction,actual_mm,air_temperature_c,pressure_pa,humidity_pct,material_temperature_c"]
    for run in range(1, RUNS + 1):
        for direction in ("+", "-"):
            order = range(targets_mm.size) if direction == "+" else range(targets_mm.size - 1, -1, -1)
            for i in order:
                t = targets_mm[i]
                d = round(float(devs[(run, direction)][i]), 3)
                plain.append(f"{t:.3f},{run},{direction},{d:.3f}")
                air_t = round(21.4 + 0.05 * (run - 1) + 0.1 * t / 800.0, 3)
                pressure = 100900.0 - 8.0 * (run - 1)
                humidity = 43.0
                material = round(21.0 + 0.03 * (run - 1), 3)
                n = float(refractive_index(air_t, pressure, humidity, WAVELENGTH_NM))
                position_20c_mm = t + d * UM / MM
                reading_mm = position_20c_mm * (1 + ALPHA * (material - 20.0)) * n
                raw.append(
                    f"{t:.3f},{run},{direction},{reading_mm:.7f},{air_t:.3f},{pressure:.1f},{humidity:.1f},{material:.3f}"
                )
    about = {"synthetic": True, "made_by": "examples/make_positioning_examples.py", "axis_length_mm": 800, "runs": RUNS}
    write_text(HERE / "positioning_run.csv", "\n".join(plain) + "\n")
    write_sidecar(
        HERE / "positioning_run.csv",
        kind="positioning run",
        description="bidirectional ISO 230-2 test of an 800 mm axis (synthetic)",
        **about,
    )
    write_text(HERE / "laser_raw_run.csv", "\n".join(raw) + "\n")
    write_sidecar(
        HERE / "laser_raw_run.csv",
        kind="positioning run",
        description="the same test as raw laser readings with air and material temperatures (synthetic)",
        units={"actual_mm": "mm, raw laser reading computed with the vacuum wavelength"},
        wavelength_nm=WAVELENGTH_NM,
        expansion_per_k=ALPHA,
        **about,
    )


def rotary() -> None:
    rng = np.random.default_rng(2302)
    targets_deg = np.arange(0.0, 361.0, 30.0)
    phase = np.radians(targets_deg)
    systematic = 6.0 * np.sin(phase + 0.4) + 2.0 * np.sin(8 * phase) - 1.0
    rows = ["target_deg,run,direction,deviation_arcsec"]
    for run in range(1, RUNS + 1):
        for direction, sign in (("+", -1.0), ("-", 1.0)):
            values = systematic + sign * 2.0 + 0.1 * (run - 1) + rng.normal(0.0, 0.6, targets_deg.size)
            order = range(targets_deg.size) if direction == "+" else range(targets_deg.size - 1, -1, -1)
            rows += [f"{targets_deg[i]:.0f},{run},{direction},{values[i]:.2f}" for i in order]
    write_text(HERE / "rotary_run.csv", "\n".join(rows) + "\n")
    write_sidecar(
        HERE / "rotary_run.csv",
        kind="positioning run",
        description="bidirectional ISO 230-2 test of a rotary table over the full circle (synthetic)",
        synthetic=True,
        made_by="examples/make_positioning_examples.py",
        runs=RUNS,
    )


if __name__ == "__main__":
    main()
    rotary()
