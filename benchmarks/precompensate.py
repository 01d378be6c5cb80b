"""Pre-compensation of a 10^5-line part program on the example machine tool (goal: <= 5 s).

Run from the repository root::

    .venv/bin/python benchmarks/precompensate.py [--lines 100000] [--runs 3]

Makes a seeded LinuxCNC program like a CAM system's finishing pass: short feed moves (0.2 to 2 mm)
wandering over the XFYZ example's travel, an arc in every 200 blocks, a few comments, and prints the
median wall-clock time of ``precompensate_program`` and of ``axiscal precompensate`` as a
subprocess (start-up, reading, writing), with the lines in and out.
"""

from __future__ import annotations

import argparse
import math
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from axiscal.model.machine import load_machine
from axiscal.precompensation import rewrite_program

MACHINE = Path(__file__).resolve().parents[1] / "examples" / "xfyz_machine" / "machine.toml"


def part_program(lines: int, seed: int = 1) -> str:
    """A finishing pass of ``lines`` blocks inside X 100..700, Y 100..400, Z 100..300 mm."""
    rng = np.random.default_rng(seed)
    out = ["%", "(finishing pass)", "G21 G90 G94 G17", "G0 X400 Y250 Z200", "G1 F1500"]
    x, y, z = 400.0, 250.0, 200.0
    heading = 0.0
    while len(out) < lines - 2:
        heading += rng.normal(0.0, 0.4)
        step = rng.uniform(0.2, 2.0)
        nx, ny = x + step * math.cos(heading), y + step * math.sin(heading)
        if not (100 < nx < 700 and 100 < ny < 400):
            heading += math.pi
            continue
        z = min(300.0, max(100.0, z + rng.normal(0.0, 0.05)))
        if len(out) % 200 == 0:
            # a half circle of radius `step` / 2 to the next point, by its radius
            out.append(f"G2 X{nx:.4f} Y{ny:.4f} R{step / 2 + 1e-4:.4f}")
        elif len(out) % 500 == 0:
            out.append(f"G1 X{nx:.4f} Y{ny:.4f} Z{z:.4f} (row {len(out)})")
        else:
            out.append(f"G1 X{nx:.4f} Y{ny:.4f} Z{z:.4f}")
        x, y = nx, ny
    out += ["M2", "%"]
    return "\n".join(out) + "\n"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--lines", type=int, default=100_000)
    parser.add_argument("--runs", type=int, default=3)
    args = parser.parse_args()
    text = part_program(args.lines)
    machine = load_machine(MACHINE)
    times = []
    for _ in range(args.runs):
        start = time.perf_counter()
        result = rewrite_program(text, machine, dialect="linuxcnc")
        times.append(time.perf_counter() - start)
    print(f"precompensate_program, {result.lines_in} lines in, {result.lines_out} out, {result.rewritten} of"
          f" {result.moves} moves rewritten: {statistics.median(times):.2f} s (median of {args.runs}; goal <= 5 s)")
    print(f"  largest correction {result.largest_correction_m * 1e6:.2f} um, largest predicted residual"
          f" {result.largest_residual_m * 1e6:.3f} um")
    with tempfile.TemporaryDirectory() as folder:
        program = Path(folder) / "part.ngc"
        program.write_text(text)
        times = []
        for _ in range(args.runs):
            start = time.perf_counter()
            subprocess.run([str(Path(sys.executable).parent / "axiscal"), "precompensate", str(program), "--machine", str(MACHINE),
                            "--dialect", "linuxcnc", "-o", str(Path(folder) / "out.ngc")], check=True, capture_output=True)
            times.append(time.perf_counter() - start)
    print(f"axiscal precompensate (subprocess, start-up included): {statistics.median(times):.2f} s")


if __name__ == "__main__":
    main()
