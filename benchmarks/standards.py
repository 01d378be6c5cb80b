"""Speed of the thermal, flatness and level evaluations on large inputs.

Run from the repository root::

    .venv/bin/python benchmarks/standards.py [--runs 3]

Prints the median of ``--runs`` wall-clock times of

- ``correlate`` of a 48 h ETVE record sampled every second (172 800 samples, lags up to 12 h)
  through one FFT cross-correlation, against the plain loop over the lags it replaces (timed on
  a 1 % sample of the lags and scaled up);
- ``surface_from_lines`` of a grid of 41 rows and 41 columns with both diagonals, 41 stations
  per line (3 444 stations, 1 763 unknowns after merging), and of a Union Jack;
- ``flatness_zone`` (least squares and the minimum zone by linear programming) of 10 000 points;
- ``level_profile`` of 10^6 readings.

The least squares of ``surface_from_lines`` and ``flatness_zone`` run in LAPACK: on a machine
whose cores are busy, set ``OPENBLAS_NUM_THREADS=1`` (BLAS threads waiting for busy cores make
the grid ten times slower).
"""

from __future__ import annotations

import argparse
import statistics
import time
from collections.abc import Callable

import numpy as np

from axiscal.flatness import FlatnessLine, flatness_zone, surface_from_lines
from axiscal.levels import level_profile
from axiscal.thermal import correlate


def median_time(function: Callable[[], object], runs: int) -> float:
    """Median wall-clock time of ``runs`` calls, seconds."""
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        function()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def grid_lines(count: int) -> list[FlatnessLine]:
    """Rows and columns over a 1.2 x 0.8 m plate, count of each, count stations a line, and both diagonals."""
    rng = np.random.default_rng(0)
    lines = []
    for k, y in enumerate(np.linspace(0, 0.8, count)):
        lines.append(FlatnessLine(f"row {k}", [0, y], [1.2, y], np.linspace(0, 1.2, count), rng.normal(0, 1e-6, count)))
    for k, x in enumerate(np.linspace(0, 1.2, count)):
        lines.append(FlatnessLine(f"col {k}", [x, 0], [x, 0.8], np.linspace(0, 0.8, count), rng.normal(0, 1e-6, count)))
    diagonal = np.hypot(1.2, 0.8)
    for name, start, end in (("SW-NE", [0, 0], [1.2, 0.8]), ("NW-SE", [0, 0.8], [1.2, 0])):
        lines.append(FlatnessLine(name, start, end, np.linspace(0, diagonal, count), rng.normal(0, 1e-6, count)))
    return lines


def plain_lagged_correlation(d: np.ndarray, t: np.ndarray, lags: np.ndarray) -> None:
    for lag in lags:
        a, b = (d[lag:], t[:t.size - lag]) if lag >= 0 else (d[:lag], t[-lag:])
        np.corrcoef(a, b)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=3)
    runs = parser.parse_args().runs
    rng = np.random.default_rng(1)

    n = 48 * 3600
    time_s = np.arange(n, dtype=float)
    temperature = 20 + np.convolve(np.cumsum(rng.normal(0, 0.01, n + 600)), np.ones(600) / 600, mode="valid")[:n]
    displacement = 3e-6 * np.roll(temperature, 1800) + rng.normal(0, 5e-8, n)
    fft = median_time(lambda: correlate(time_s, displacement, temperature, max_lag_s=12 * 3600), runs)
    lags = np.arange(-12 * 3600, 12 * 3600 + 1)
    sample = lags[::100]
    loop = median_time(lambda: plain_lagged_correlation(displacement, temperature, sample), 1) * lags.size / sample.size
    print(f"correlate, {n} samples, {lags.size} lags:        {fft:8.3f} s   (plain loop over the lags: ~{loop:.0f} s)")

    lines = grid_lines(41)
    stations = sum(line.distance_m.size for line in lines)
    grid = median_time(lambda: surface_from_lines(lines), runs)
    print(f"surface_from_lines, grid of {len(lines)} lines, {stations} stations: {grid:8.3f} s")

    from axiscal.flatness.files import read_flatness_lines

    jack = read_flatness_lines("examples/flatness/union_jack_levels.toml").lines
    union = median_time(lambda: surface_from_lines(jack), runs * 10)
    print(f"surface_from_lines, Union Jack (8 lines):           {union * 1e3:8.2f} ms")

    x, y = rng.uniform(0, 1.2, 10_000), rng.uniform(0, 0.8, 10_000)
    z = 1e-6 * np.sin(3 * x) * np.cos(4 * y) + rng.normal(0, 1e-7, x.size)
    zone = median_time(lambda: flatness_zone(x, y, z), runs)
    print(f"flatness_zone, 10000 points (least squares + LP):   {zone:8.3f} s")

    readings = rng.normal(0, 1e-5, 10**6)
    positions = np.arange(10**6) * 0.1
    levels = median_time(lambda: level_profile(positions, readings, foot_m=0.1), runs)
    print(f"level_profile, 10^6 readings:                       {levels * 1e3:8.2f} ms")


if __name__ == "__main__":
    main()
