"""Write the CMM examples (run from the repository root: python examples/make_cmm_examples.py).

A simulated bridge CMM of 700 x 700 x 500 mm (longest space diagonal 1109 mm) with a scale error
of 2.5 um/m along X, 1.5 um/m along Y, -1 um/m along Z, a squareness of 4 urad in XY, and 0.25 um
of repeatability (1 sigma), as its software reports the readings (to 0.1 um):

* examples/cmm/e0_gauge_blocks.csv: ISO 10360-2 length test, gauge blocks of 20, 100, 250, 400
  and 700 mm in seven positions (the four space diagonals, then X, Y and Z), three repeats each,
  and with the 150 mm ram offset in two positions (E150); columns position, length, nominal_mm,
  measured_mm, repeat, ram_offset_mm.
* examples/cmm/sphere_single.csv: ISO 10360-5 single-stylus test, the 25 points on a 25 mm
  sphere (one at the pole; 4 at 22.5 deg below it; 8 at 45 deg, turned 22.5 deg; 4 at 67.5 deg;
  8 at the equator, turned 22.5 deg), with a three-lobed probe of 0.6 um and 0.15 um of noise.
* examples/cmm/sphere_five_styli.csv: the multi-stylus test, 25 points with each of five styli
  (one vertical, four horizontal along +X, -X, +Y, -Y), each stylus's calibration off by a few
  tenths of a micrometre; column stylus.
* examples/cmm/campaign.toml: a campaign holding both tests, with the maker's MPE as tolerances.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent / "cmm"
SPHERE_MM = 25.00018  # calibrated diameter
#: the gauge blocks, by their calibrated lengths
LENGTHS_MM = {"L1": 20.00003, "L2": 99.99991, "L3": 250.00021, "L4": 399.99962, "L5": 700.00048}
#: the positions (unit direction of the gauge): four space diagonals, then X, Y, Z
DIRECTIONS = {
    "1": (1, 1, 1), "2": (-1, 1, 1), "3": (1, -1, 1), "4": (1, 1, -1),
    "5": (1, 0, 0), "6": (0, 1, 0), "7": (0, 0, 1),
}
#: stylus -> (the pole of its points, the offset of its centre in mm)
STYLI = {"T1": ((0, 0, 1), (0, 0, 0)), "T2": ((-1, 0, 0.2), (0.3e-3, -0.1e-3, 0.2e-3)),
         "T3": ((1, 0, 0.2), (-0.2e-3, 0.2e-3, -0.3e-3)), "T4": ((0, -1, 0.2), (0.1e-3, 0.4e-3, 0.1e-3)),
         "T5": ((0, 1, 0.2), (-0.1e-3, -0.3e-3, 0.0))}
SCALE = np.array([2.5e-6, 1.5e-6, -1.0e-6])
SQUARENESS_XY = 4e-6


def measured_length(nominal: float, direction, rng, noise: float = 0.25e-3, extra: float = 0.0) -> float:
    u = np.asarray(direction, dtype=float)
    u /= np.linalg.norm(u)
    d = nominal * u
    e = d * SCALE
    e[0] += SQUARENESS_XY * d[1]
    return nominal + float(e @ u) + extra * nominal / 1000 + rng.normal(0.0, noise)


def length_rows(rng) -> list[str]:
    rows = ["position,length,nominal_mm,measured_mm,repeat,ram_offset_mm"]
    for offset, positions, extra in ((0, DIRECTIONS, 0.0), (150, {"1": DIRECTIONS["1"], "5": DIRECTIONS["5"]}, 0.6e-3)):
        for position, direction in positions.items():
            for label, nominal in LENGTHS_MM.items():
                for repeat in (1, 2, 3):
                    value = measured_length(nominal, direction, rng, extra=extra)
                    rows.append(f"{position},{label},{nominal:.5f},{value:.4f},{repeat},{offset}")
    return rows


def pattern(axis=(0.0, 0.0, 1.0)) -> np.ndarray:
    """The 25 directions of the pattern about ``axis`` (the pole)."""
    rings = [(0.0, 1, 0.0), (22.5, 4, 0.0), (45.0, 8, 22.5), (67.5, 4, 22.5), (90.0, 8, 22.5)]
    out = []
    for polar, count, turn in rings:
        for k in range(count):
            azimuth = np.radians(turn + 360.0 * k / count)
            t = np.radians(polar)
            out.append((np.sin(t) * np.cos(azimuth), np.sin(t) * np.sin(azimuth), np.cos(t)))
    v = np.array(out)
    pole = np.asarray(axis, dtype=float)
    pole /= np.linalg.norm(pole)
    if np.allclose(pole, (0, 0, 1)):
        return v
    # rotate (0, 0, 1) onto pole about the axis perpendicular to both
    k = np.cross((0, 0, 1), pole)
    s, c = np.linalg.norm(k), pole[2]
    k /= s
    kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    rotation = np.eye(3) + s * kx + (1 - c) * kx @ kx
    return v @ rotation.T


def sphere_points(rng, axis, centre_offset_mm=(0.0, 0.0, 0.0), lobes: float = 0.6e-3) -> np.ndarray:
    v = pattern(axis)
    azimuth = np.arctan2(v[:, 1], v[:, 0])
    radius = SPHERE_MM / 2 + 0.2e-3 + lobes / 2 * np.cos(3 * azimuth) * np.hypot(v[:, 0], v[:, 1]) \
        + rng.normal(0.0, 0.15e-3, len(v))
    centre = np.array([310.0, 220.0, -180.0]) + np.asarray(centre_offset_mm)
    return centre + radius[:, None] * v


def main() -> None:
    HERE.mkdir(exist_ok=True)
    rng = np.random.default_rng(10360)
    (HERE / "e0_gauge_blocks.csv").write_text("\n".join(length_rows(rng)) + "\n")
    single = sphere_points(rng, (0, 0, 1))
    (HERE / "sphere_single.csv").write_text(
        "x_mm,y_mm,z_mm\n" + "".join(f"{x:.4f},{y:.4f},{z:.4f}\n" for x, y, z in single))
    rows = ["stylus,x_mm,y_mm,z_mm"]
    for name, (axis, offset) in STYLI.items():
        for x, y, z in sphere_points(rng, axis, offset, lobes=0.4e-3):
            rows.append(f"{name},{x:.4f},{y:.4f},{z:.4f}")
    (HERE / "sphere_five_styli.csv").write_text("\n".join(rows) + "\n")


if __name__ == "__main__":
    main()
