"""The CSV reader on a 10^6-row profile: axiscal.io.read_csv against plain pandas, and the command end to end.

Run from the repository root::

    .venv/bin/python benchmarks/io.py [--rows 1000000] [--runs 5]

Writes a profile (``position_mm,deviation_um``, six decimals, as ``axiscal straightness`` reads)
into a temporary folder and prints the median of ``--runs`` wall-clock times of

- ``read_csv(path)`` followed by ``numeric`` of both columns (goal: within 1.5x of pandas),
- plain ``pandas.read_csv(path)`` on the same file, run in turn with the line above (A B A B ...)
  so that the load of a shared machine touches both alike; the ratio is the median of the
  ratios of each round,
- ``axiscal straightness FILE`` as a subprocess: start-up, reading and the fit (goal: <= 1.0 s), and
  the processor time it used (user + system, all its threads): on a shared machine the wall-clock
  time follows the other work, the processor time much less.
"""

from __future__ import annotations

import argparse
import resource
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
import pandas as pd
from timing import interleaved, median, median_ratio

from axiscal.io.tabular import read_csv


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
        times = interleaved({"ours": lambda: ours(path), "pandas": lambda: pd.read_csv(path)}, args.runs)
        run = [str(a) for a in command] + ["straightness", str(path)]
        cpu: list[float] = []

        def cli() -> None:
            before = resource.getrusage(resource.RUSAGE_CHILDREN)
            subprocess.run(run, check=True, capture_output=True)
            after = resource.getrusage(resource.RUSAGE_CHILDREN)
            cpu.append(after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime)

        end_to_end = median(interleaved({"cli": cli}, args.runs)["cli"])
    reader, plain = median(times["ours"]), median(times["pandas"])
    ratio = median_ratio(times["ours"], times["pandas"])
    print(f"profile: {args.rows} rows, {size_mb:.1f} MB; median of {args.runs} runs, reader and pandas in turn")
    print("| what | seconds | |")
    print("|---|---|---|")
    print(f"| read_csv + numeric of both columns | {reader:.3f} | {ratio:.2f} x pandas, median of the rounds' ratios (goal <= 1.5) |")
    print(f"| pandas.read_csv(path) | {plain:.3f} | |")
    print(f"| axiscal straightness FILE (subprocess) | {end_to_end:.3f} | goal <= 1.0 |")
    print(f"| its processor time (user + system) | {median(cpu):.3f} | |")


if __name__ == "__main__":
    main()
