"""Write the 3D-printer squareness example (run from the repository root: python examples/printer/make_printer_example.py).

A dial indicator on the print head runs along the two edges of a granite square lying on the bed:
x_run.csv moves X and reads the deviation along Y, y_run.csv moves Y and reads the deviation along
X (200 mm each, every 10 mm, 1 um indicator steps with a little scatter). The square is set down
turned by 100 urad; the printer's Y axis leans so that the included angle of +X and +Y is
90 deg + 150 arcsec. Then

    axiscal squareness --first examples/printer/x_run.csv --second examples/printer/y_run.csv --json > xy.json
    axiscal export skew --firmware klipper --from xy.json

prints Klipper's SET_SKEW line (and likewise marlin, rrf).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
#: the square's own rotation on the bed, rad (cancels between the two runs)
SQUARE_ROTATION = 100e-6
#: included angle of +X and +Y minus 90 deg, arcsec
SQUARENESS_ARCSEC = 150.0


def write_run(path: Path, slope: float, rng: np.random.Generator) -> None:
    position_mm = np.arange(0.0, 201.0, 10.0)
    deviation_um = slope * position_mm * 1000.0 + rng.normal(0.0, 0.6, position_mm.size)
    lines = ["position_mm,deviation_um"] + [f"{p:.1f},{d:.1f}" for p, d in zip(position_mm, np.round(deviation_um))]
    path.write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    rng = np.random.default_rng(230)
    s = math.radians(SQUARENESS_ARCSEC / 3600.0)
    # theta = 90 deg - atan(k1) - atan(k2)  (docs/squareness.md): k1 + k2 = -s for small angles
    k1 = math.tan(SQUARE_ROTATION)
    k2 = math.tan(-s - SQUARE_ROTATION)
    write_run(HERE / "x_run.csv", k1, rng)
    write_run(HERE / "y_run.csv", k2, rng)
