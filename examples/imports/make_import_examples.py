"""Write the import examples (run from the repository root: python examples/imports/make_import_examples.py).

* runs_per_column.csv + runs_per_column.toml: a laser software export with a few title lines, a
  semicolon between cells and a decimal comma, one row per target (forward pass, then reverse
  pass) and one column of deviations in um per run (5 runs, 11 targets over 500 mm).
* reading_per_row.txt + reading_per_row.toml: one row per reading, tab separated, positions in
  inches as the laser counts them (it counts down as the axis moves up), run and direction columns
  with the words F and R.
* capture.rtx: a Renishaw-layout dynamic capture (200 samples at 1 kHz, mm), built to the layout
  the rtx2csv project describes; not a file from the instrument.

    axiscal import map examples/imports/runs_per_column.toml examples/imports/runs_per_column.csv -o run.csv
    axiscal positioning run.csv
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1] / "src"))

from axiscal.io.importers import write_rtx  # noqa: E402

INCH_MM = 25.4


def runs_per_column(rng: np.random.Generator) -> None:
    targets = np.linspace(0.0, 500.0, 11)
    pitch = 8.0 * np.sin(targets / 500.0 * np.pi) - 0.01 * targets  # um
    rows = ["Linear calibration export", "Machine: router X axis;Date: 2026-11-20", "",
            "Target (mm);" + ";".join(f"Run {r}" for r in range(1, 6))]
    for direction, order in ((+1, targets), (-1, targets[::-1])):
        for t in order:
            i = int(np.flatnonzero(targets == t)[0])
            values = pitch[i] + direction * 1.5 + rng.normal(0.0, 0.4, 5)
            rows.append(f"{t:.3f};" + ";".join(f"{v:.3f}" for v in values))
    (HERE / "runs_per_column.csv").write_text("\n".join(r.replace(".", ",") for r in rows) + "\n", encoding="utf-8")


def reading_per_row(rng: np.random.Generator) -> None:
    targets_in = np.linspace(0.0, 10.0, 6)
    rows = ["Target[in]\tLaser[in]\tRun\tDir"]
    for run in (1, 2, 3):
        for word, order in (("F", targets_in), ("R", targets_in[::-1])):
            for t in order:
                error_in = 0.0002 * t / 10.0 + (0.00006 if word == "F" else -0.00006) + rng.normal(0.0, 0.00002)
                rows.append(f"{t:.4f}\t{-(t + error_in):.6f}\t{run}\t{word}")
    (HERE / "reading_per_row.txt").write_text("\n".join(rows) + "\n", encoding="utf-8")


if __name__ == "__main__":
    rng = np.random.default_rng(11)
    runs_per_column(rng)
    reading_per_row(rng)
    t = np.arange(200) / 1000.0
    write_rtx(HERE / "capture.rtx", 100.0 + 0.002 * np.sin(2 * np.pi * 25.0 * t) + rng.normal(0, 0.0002, t.size),
              sample_rate_hz=1000.0, unit="mm", header={"Date": "20/11/2026 10:00:00", "Axis": "X"})
