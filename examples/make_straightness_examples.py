"""Write the straightness and error-separation examples (run from the repository root:
python examples/make_straightness_examples.py).

The profile and motion are paper 001's simulation (under Fig. 4) in micrometres with n the
position in mm over a 300 mm workpiece: R(n) = sin(pi n / 2.5N) + 0.02 sin(2 pi n / 54)
+ 0.02 sin(2 pi n / 34), S(n) = sin(0.75 pi n / 2.5N) + G with the step G = 0.4 on
N/2.7 <= n <= N/1.5 (the printed range is empty; see docs/straightness.md). The slide also yaws
by 2 arcsec + 1 arcsec sin(2 pi x / 50 mm) and probes B and C sit 0.05 and 0.02 um off zero.

* separation_profile.csv, separation_motion.csv: R, and S with the yaw, every 1 mm.
* probe_readings.csv: three probes 15 mm apart, 1 mm steps, 0.005 um noise (seed 0), exactly
  what `axiscal simulate probes` writes for these files with those options (its settings in
  probe_readings.json beside it).
* straightness_profile.csv: R every 10 mm plus a tilt of 2 um over the length.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
N = 300
ARCSEC = np.pi / 648000


def profile_um(n: np.ndarray) -> np.ndarray:
    return np.sin(np.pi * n / (2.5 * N)) + 0.02 * np.sin(2 * np.pi * n / 54) + 0.02 * np.sin(2 * np.pi * n / 34)


def motion_um(n: np.ndarray) -> np.ndarray:
    return np.sin(0.75 * np.pi * n / (2.5 * N)) + 0.4 * ((n >= N / 2.7) & (n <= N / 1.5))


def yaw_urad(n: np.ndarray) -> np.ndarray:
    return 1e6 * ARCSEC * (2.0 + np.sin(2 * np.pi * n / 50))


def write(path: Path, header: str, rows: np.ndarray) -> None:
    """A plain CSV: the header first, no comment lines (this docstring of the module says what each file is)."""
    lines = [header] + [",".join(f"{v:.6f}" for v in row) for row in rows]
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")


def main() -> None:
    n = np.arange(0.0, N + 1)
    write(HERE / "separation_profile.csv", "position_mm,deviation_um", np.column_stack([n, profile_um(n)]))
    write(HERE / "separation_motion.csv", "position_mm,deviation_um,yaw_urad",
          np.column_stack([n, motion_um(n), yaw_urad(n)]))
    coarse = np.arange(0.0, N + 1, 10.0)
    write(HERE / "straightness_profile.csv", "position_mm,deviation_um",
          np.column_stack([coarse, profile_um(coarse) + 2.0 * coarse / N]))
    subprocess.run(
        [sys.executable, "-m", "axiscal.cli.main", "simulate", "probes",
         "--profile", "examples/separation_profile.csv", "--motion", "examples/separation_motion.csv",
         "--spacing-mm", "15", "--step-mm", "1", "--noise-um", "0.005", "--offsets-um", "0", "0.05", "0.02",
         "-o", "examples/probe_readings.csv"],
        check=True,
        cwd=HERE.parent,  # the sidecar names its sources as paths from the repository root
    )


if __name__ == "__main__":
    main()
