"""Write the squareness examples (run from the repository root: python examples/make_squareness_examples.py).

squareness_x.csv and squareness_y.csv are two straightness runs of an XY plane built on paper 002's
worked case: fitted slopes k = -0.00044783 (X run) and 1 / 3001.62173825 (Y run, the paper's
k' = 3001.62173825 is the same line written as y = k' x + b). Each run adds a smooth straightness
profile that is even about the middle of the travel, so it leaves the least-squares slope as it is.
With the paper's prism deviation of 2.7 arcsec,

    axiscal squareness --first examples/squareness_x.csv --second examples/squareness_y.csv \
        --prism-deviation-arcsec 2.7

gives 20.95 arcsec (the paper prints 20.9). cmm_points.csv holds CMM readings (x_mm, y_mm, z_mm)
for `axiscal cmm compensate`: the corners of paper 004's 15 mm x 15 mm x 15 mm working volume
and a few points between.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from axiscal.units import MM, UM

HERE = Path(__file__).resolve().parent

SLOPE_X = -0.00044783
SLOPE_Y = 1.0 / 3001.62173825


def run(path: Path, position_mm: np.ndarray, slope: float, bow_um: float, ripple_um: float) -> None:
    mid = 0.5 * (position_mm[0] + position_mm[-1])
    half = 0.5 * (position_mm[-1] - position_mm[0])
    s = (position_mm - mid) / half
    deviation_um = slope * position_mm * MM / UM + bow_um * s**2 + ripple_um * np.cos(3 * np.pi * s)
    lines = ["position_mm,deviation_um"]
    lines += [f"{q:.1f},{d:.4f}" for q, d in zip(position_mm, deviation_um)]
    path.write_text("\n".join(lines) + "\n")


def cmm_points(path: Path) -> None:
    corners = [(x, y, z) for z in (0.0, 15.0) for y in (0.0, 15.0) for x in (0.0, 15.0)]
    extra = [(7.5, 7.5, 7.5), (3.0, 12.0, 9.0), (12.5, 2.5, 14.0)]
    lines = ["x_mm,y_mm,z_mm"] + [f"{x:.3f},{y:.3f},{z:.3f}" for x, y, z in corners + extra]
    path.write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    run(HERE / "squareness_x.csv", np.arange(0.0, 601.0, 25.0), SLOPE_X, 3.0, 0.8)
    run(HERE / "squareness_y.csv", np.arange(0.0, 501.0, 25.0), SLOPE_Y, -2.0, 0.5)
    cmm_points(HERE / "cmm_points.csv")
