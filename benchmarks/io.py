"""The CSV reader on a 10^6-row profile: axiscal.io.read_csv against plain pandas, and the command end to end.

Run from the repository root::

    .venv/bin/python benchmarks/io.py [--rows 1000000] [--runs 5]

Writes a profile (``position_mm,deviation_um``, six decimals, as ``axiscal straightness`` reads)
into a temporary folder and prints the median of ``--runs`` wall-clock times of

- ``read_csv(path)`` followed by ``numeric`` of both columns (goal: within 2x of pandas),
- plain ``pandas.read_csv(path)`` on the same file,
- ``axiscal straightness FILE`` as a subprocess: start-up, reading and the fit (goal: <= 1.0 s).
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pandas as pd

from axiscal.io.tabular import read_csv


def median_time(function: Callable[[], object], runs: int) -> float:
    """Median wall-clock time of ``runs`` calls, seconds."""
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        function()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def write_profile(path: Path, rows: int) -> None:
    """A straight-ish profile over 1000 mm with a waviness of a few micrometres."""
    position_mm = np.linspace(0.0, 1000.0, rows)
    deviation_um = 3.0 * np.sin(position_mm / 37.0) + 0.4 * np.cos(position_mm / 5.0)
    frame = pd.DataFrame({"position_mm": position_mm, "deviation_um": deviation_um})
    frame.to_csv(path, index=False, float_format="%.6f")


def ours(path: Path) -> None:
    table = read_csv(path, min_rows=2)
    table.numeric("position_mm")
    table.numeric("deviation_um")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rows", type=int, default=1_000_000)
    parser.add_argument("--runs", type=int, default=5)
    args = parser.parse_args()
    axiscal = Path(sys.executable).with_name("axiscal")
    command = [str(axiscal)] if axiscal.exists() else [sys.executable, "-m", "axiscal.cli.main"]
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "profile.csv"
        write_profile(path, args.rows)
        size_mb = path.stat().st_size / 1e6
        ours(path)  # warm the page cache and pandas' import
        reader = median_time(lambda: ours(path), args.runs)
        plain = median_time(lambda: pd.read_csv(path), args.runs)
        end_to_end = median_time(lambda: subprocess.run([*command, "straightness", str(path)], check=True, capture_output=True), args.runs)
    print(f"profile: {args.rows} rows, {size_mb:.1f} MB; median of {args.runs} runs")
    print("| what | seconds | |")
    print("|---|---|---|")
    print(f"| read_csv + numeric of both columns | {reader:.3f} | {reader / plain:.2f} x pandas (goal <= 2) |")
    print(f"| pandas.read_csv(path) | {plain:.3f} | |")
    print(f"| axiscal straightness FILE (subprocess) | {end_to_end:.3f} | goal <= 1.0 |")


if __name__ == "__main__":
    main()
