"""Write the flatness examples (run from the repository root: python examples/make_flatness_examples.py).

* examples/flatness/moody_1955.toml: the Union Jack of J. C. Moody, "How to calibrate surface
  plates in the plant", The Tool Engineer, October 1955: a 64 x 40 inch plate, readings in arcsec
  with a 4-inch foot, as corrected by B. Allen (2018; two misprints: NE-NW reading 9 is 18.8, not
  18.3, and NE-SW reading 19 is 4.3, not 4.2). Allen's worksheets take every rise over 4 inches,
  the diagonals' too; so does this file.
* examples/flatness/union_jack_levels.toml: a simulated 1200 x 800 mm plate with a twist of
  4 um corner to corner and a 2 um bow, measured with a level of 100 mm foot (the diagonals with
  a foot of their length / 14), readings in um/m rounded to 0.01 um/m.
* examples/flatness/grid.toml: the same plate measured as a grid (5 lines along x, 5 along y,
  and the two diagonals through their crossings) with a straightedge: each line's deviations in
  um every 100 mm (the diagonals every 180 mm, their stations written to 0.1 um so that they
  fall on the crossings), with an offset and tilt of its own.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent / "flatness"

MOODY = {  # line: (from, to, readings in arcsec)
    "NW-SE": ("NW", "SE", [6.5, 6.0, 5.0, 5.2, 5.5, 5.6, 5.5, 5.0, 5.5, 4.8, 5.0, 5.2, 5.3, 4.9, 4.6, 4.2, 5.3, 4.9, 4.5, 3.5]),
    "NE-SW": ("NE", "SW", [6.6, 5.4, 5.4, 5.2, 5.5, 5.7, 5.0, 5.0, 5.4, 4.5, 4.4, 4.5, 4.5, 4.8, 4.2, 4.2, 4.2, 4.8, 4.3, 3.2]),
    "NE-NW": ("NE", "NW", [20.5, 19.7, 20.5, 20.3, 20.2, 19.9, 19.0, 19.5, 18.8, 18.6, 18.7, 18.6, 18.4, 18.5, 19.0, 17.9]),
    "NE-SE": ("NE", "SE", [3.5, 2.1, 2.5, 2.8, 3.4, 3.2, 3.5, 4.0, 4.2, 3.5]),
    "SE-SW": ("SE", "SW", [16.4, 15, 15.6, 15.5, 15.1, 15.3, 15.1, 14.6, 14, 13.5, 13.5, 13.3, 13.3, 13.4, 14, 13.9]),
    "NW-SW": ("NW", "SW", [6, 4.6, 4.5, 4.7, 5.0, 4.5, 5.9, 6, 6, 4.9]),
    "E-W": ("E", "W", [11.7, 12.4, 12.1, 12.5, 12.0, 11.5, 11.5, 11.3, 11.3, 10.3, 10.8, 10.3, 10, 10.7, 10.4, 10.4]),
    "N-S": ("N", "S", [6.6, 6.4, 6.3, 6.5, 6.6, 6.9, 7.5, 7.4, 7.1, 7]),
}


def places(width: float, depth: float) -> dict[str, tuple[float, float]]:
    return {"SW": (0, 0), "SE": (width, 0), "NE": (width, depth), "NW": (0, depth), "S": (width / 2, 0),
            "N": (width / 2, depth), "W": (0, depth / 2), "E": (width, depth / 2)}


def plate_um(x_mm: np.ndarray, y_mm: np.ndarray) -> np.ndarray:
    """The simulated plate, um: a twist of 4 um corner to corner and a bow of 2 um."""
    u, v = x_mm / 600.0 - 1.0, y_mm / 400.0 - 1.0
    return 2.0 * u * v + 2.0 * (1.0 - (u ** 2 + v ** 2) / 2.0)


def numbers(values, fmt: str) -> str:
    return "[" + ", ".join(fmt.format(v) for v in values) + "]"


def moody() -> str:
    spot = places(64 * 25.4, 40 * 25.4)
    out = ['title = "Moody (1955), 64 x 40 in surface plate"', "foot_mm = 101.6", ""]
    for name, (a, b, readings) in MOODY.items():
        out += ["[[lines]]", f'name = "{name}"', f"from_mm = {numbers(spot[a], '{:g}')}",
                f"to_mm = {numbers(spot[b], '{:g}')}", f"angle_arcsec = {numbers(readings, '{:g}')}", ""]
    return "\n".join(out)


def union_jack() -> str:
    spot = places(1200.0, 800.0)
    lines = {"SW-NE": ("SW", "NE", 14), "NW-SE": ("NW", "SE", 14), "SW-SE": ("SW", "SE", 12), "NW-NE": ("NW", "NE", 12),
             "SW-NW": ("SW", "NW", 8), "SE-NE": ("SE", "NE", 8), "W-E": ("W", "E", 12), "S-N": ("S", "N", 8)}
    rng = np.random.default_rng(1)
    out = ['title = "Simulated 1200 x 800 mm plate, Union Jack with a level"', "foot_mm = 100", ""]
    for name, (a, b, steps) in lines.items():
        start, end = np.array(spot[a]), np.array(spot[b])
        t = np.linspace(0.0, 1.0, steps + 1)
        xy = start + t[:, None] * (end - start)
        foot = float(np.hypot(*(end - start))) / steps
        slope = np.diff(plate_um(xy[:, 0], xy[:, 1])) / foot * 1e3 + rng.normal(0.0, 0.02, steps)  # um/m
        out += ["[[lines]]", f'name = "{name}"', f"from_mm = {numbers(start, '{:g}')}", f"to_mm = {numbers(end, '{:g}')}"]
        if abs(foot - 100.0) > 1e-9:
            out.append(f"foot_mm = {foot:.4f}")
        out += [f"angle_um_per_m = {numbers(slope, '{:.2f}')}", ""]
    return "\n".join(out)


def grid() -> str:
    rng = np.random.default_rng(2)
    out = ['title = "Simulated 1200 x 800 mm plate, grid of straightedge lines"', ""]
    rows = [(f"y = {y:g}", (0.0, y), (1200.0, y), 13) for y in np.linspace(0.0, 800.0, 5)]
    columns = [(f"x = {x:g}", (x, 0.0), (x, 800.0), 9) for x in np.linspace(0.0, 1200.0, 5)]
    diagonals = [("SW-NE", (0.0, 0.0), (1200.0, 800.0), 9), ("NW-SE", (0.0, 800.0), (1200.0, 0.0), 9)]
    for name, start, end, count in rows + columns + diagonals:
        length = float(np.hypot(end[0] - start[0], end[1] - start[1]))
        s = np.linspace(0.0, length, count)
        t = s / length
        x, y = start[0] + t * (end[0] - start[0]), start[1] + t * (end[1] - start[1])
        deviation = plate_um(x, y) + rng.normal(0.0, 0.3) + rng.normal(0.0, 2.0) * t + rng.normal(0.0, 0.01, s.size)
        out += ["[[lines]]", f'name = "{name}"', f"from_mm = {numbers(start, '{:g}')}", f"to_mm = {numbers(end, '{:g}')}",
                f"position_mm = {numbers(s, '{:.4f}')}", f"deviation_um = {numbers(deviation, '{:.3f}')}", ""]
    return "\n".join(out)


def main() -> None:
    HERE.mkdir(exist_ok=True)
    (HERE / "moody_1955.toml").write_text(moody(), encoding="utf-8")
    (HERE / "union_jack_levels.toml").write_text(union_jack(), encoding="utf-8")
    (HERE / "grid.toml").write_text(grid(), encoding="utf-8")


if __name__ == "__main__":
    main()
