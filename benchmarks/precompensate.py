"""Whole-process time of ``axiscal precompensate`` on 10^5 and 10^6-line part programs, against an older revision.

Run from the repository root::

    .venv/bin/python benchmarks/precompensate.py [--lines 100000 1000000] [--runs 5] [--baseline REV]
    .venv/bin/python benchmarks/precompensate.py --stages [--lines 100000] [--runs 5]

Makes seeded LinuxCNC programs like a CAM system's finishing pass (short feed moves of 0.2 to 2 mm
wandering over the XFYZ example's travel, an arc in every 200 blocks, a few comments) and times
``axiscal precompensate`` as a whole process (start-up, reading, the model's inverse, the path
checks, writing) ``--runs`` times for each size, printing the median, for this tree and, in the same
run and alternating with it, for the source of ``--baseline`` (default: the last revision that read
every line block by block and kept a Block object per line) unpacked from git into a temporary
folder. The two outputs are compared: the same program must come out, to the byte. The baseline
needs git and this repository's history; ``--baseline none`` times this tree alone. ``--stages``
times, in one process, the reading of the program in bulk and block by block, and the model's
inverse of its points compiled and in NumPy.
"""

from __future__ import annotations

import argparse
import filecmp
import math
import os
import statistics
import subprocess
import sys
import tarfile
import tempfile
import time
from io import BytesIO
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
MACHINE = ROOT / "examples" / "xfyz_machine" / "machine.toml"
#: the last revision that read every line of a program block by block (Block objects for every line,
#: the text written one number at a time); its inverse already ran compiled
BASELINE = "487f78a"


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


def unpack(revision: str, folder: Path) -> Path:
    """The ``src`` folder of ``revision`` written under ``folder``."""
    archive = subprocess.run(["git", "-C", str(ROOT), "archive", "--format=tar", revision, "src"],
                             check=True, capture_output=True).stdout
    with tarfile.open(fileobj=BytesIO(archive)) as tar:
        tar.extractall(folder, filter="data")
    return folder / "src"


def run(source: Path, program: Path, output: Path) -> float:
    """Seconds of one whole ``axiscal precompensate`` process run on ``source``."""
    env = dict(os.environ, PYTHONPATH=str(source))
    start = time.perf_counter()
    subprocess.run([sys.executable, "-m", "axiscal.cli.main", "precompensate", str(program), "--machine", str(MACHINE),
                    "--dialect", "linuxcnc", "-o", str(output)], check=True, capture_output=True, env=env)
    return time.perf_counter() - start


def stages(lines: int, runs: int) -> None:
    """In-process: the reading of the program, and the model's inverse of as many points compiled and in NumPy."""
    from axiscal.io.gcode import read_program
    from axiscal.model import kinematics
    from axiscal.model.machine import load_machine

    text = part_program(lines)
    machine = load_machine(MACHINE)
    from axiscal.io.gcode import reader

    read_program(text, dialect="linuxcnc")  # the compiled scan loaded from numba's cache (or compiled)
    for label, bulk in (("in bulk", True), ("block by block", False)):
        reader._BULK = bulk
        times = []
        for _ in range(runs):
            start = time.perf_counter()
            program = read_program(text, dialect="linuxcnc")
            program.columns if bulk else program.blocks  # what each way hands on to the rewriting
            times.append(time.perf_counter() - start)
        print(f"  {lines:>9,} lines, reading the program {label:<15}: {statistics.median(times):6.2f} s")
    reader._BULK = True
    moves = [m for m in program.motions if m.kind != "dwell"]
    points = np.array([[m.end_m["X"], m.end_m["Y"], m.end_m["Z"]] for m in moves])
    target = machine.nominal_point({k: points[:, j] for j, k in enumerate("XYZ")})
    kinematics._COMPILED_FROM = 0
    machine.command_for(target[:1000])  # the compiled functions loaded from numba's cache (or compiled)
    for label, start_at in (("compiled", 0), ("NumPy", 1 << 62)):
        kinematics._COMPILED_FROM = start_at
        times = []
        for _ in range(runs):
            start = time.perf_counter()
            machine.command_for(target)
            times.append(time.perf_counter() - start)
        print(f"  {lines:>9,} lines, the inverse of {len(target):,} points, {label:<8}: {statistics.median(times):6.2f} s")
    kinematics._COMPILED_FROM = 65536


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--lines", type=int, nargs="+", default=[100_000, 1_000_000])
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--baseline", default=BASELINE, help="git revision timed alongside ('none': this tree alone)")
    parser.add_argument("--stages", action="store_true", help="time the reading and the inverse in this process instead")
    args = parser.parse_args()
    if args.stages:
        print(f"stages of axiscal precompensate in this process, median of {args.runs}; load average {os.getloadavg()[0]:.1f}")
        for lines in args.lines:
            stages(lines, args.runs)
        return
    with tempfile.TemporaryDirectory() as name:
        folder = Path(name)
        paths = {"this tree": ROOT / "src"}
        if args.baseline != "none":
            paths[f"baseline {args.baseline}"] = unpack(args.baseline, folder / "baseline")
        print(f"axiscal precompensate, whole process (start-up, read, solve, check, write), median of {args.runs};"
              f" {os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f} at the start")
        for lines in args.lines:
            program = folder / f"part_{lines}.ngc"
            program.write_text(part_program(lines))
            for label, source in paths.items():  # a first run of each: numba's cache written, files read once
                run(source, program, folder / f"{label.split()[0]}.ngc")
            times: dict[str, list[float]] = {label: [] for label in paths}
            for _ in range(args.runs):
                for label, source in paths.items():
                    times[label].append(run(source, program, folder / f"{label.split()[0]}.ngc"))
            same = len(paths) == 1 or filecmp.cmp(folder / "this.ngc", folder / "baseline.ngc", shallow=False)
            for label, values in times.items():
                print(f"  {lines:>9,} lines, {label:<18}: {statistics.median(values):6.2f} s"
                      f" (runs {', '.join(f'{v:.2f}' for v in values)})")
            print(f"  {lines:>9,} lines: outputs {'identical' if same else 'DIFFER'}")


if __name__ == "__main__":
    main()
