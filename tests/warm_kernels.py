"""Compile axiscal's numba kernels once, before the suite's processes start.

numba caches a compiled kernel beside its source (``__pycache__/*.nbi``, ``*.nbc``), so a process
finding the cache loads it in a fraction of a second. A fresh clone has none: the first tests of each
pytest worker, and every command line they start before a cache is written, then compile the same
kernels again (about 20 CPU s for the model's chain alone). ``make test`` runs this script beside the
documentation's build so they are compiled once, through the paths the program itself takes: the
model's forward chain and its inverse on enough points to run compiled, a part program long enough
to be read in bulk and pre-compensated, and a short live session writing its record. When every
kernel module already has a cache newer than its source, it does nothing.

Run from the repository's root: ``python tests/warm_kernels.py``.
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SOURCE = ROOT / "src" / "axiscal"
KERNELS = ["model/chain_kernel.py", "model/inverse_kernel.py", "precompensation/format_kernel.py",
           "precompensation/path_kernel.py", "io/gcode/scan_kernel.py", "live/record_text.py"]
MACHINE = ROOT / "examples" / "xfyz_machine" / "machine.toml"


def _cached(module: Path) -> bool:
    """Whether numba has a cache of ``module`` newer than its source."""
    caches = list((module.parent / "__pycache__").glob(f"{module.stem}.*.nbi"))
    return bool(caches) and min(c.stat().st_mtime for c in caches) >= module.stat().st_mtime


def _program(path: Path, lines: int) -> None:
    """A part program of short straight moves with a line number on every block, as CAM systems write them."""
    with path.open("w", encoding="ascii") as out:
        out.write("G21 G90\n")
        for k in range(lines):
            out.write(f"N{10 * k} G1 X{100 + k % 400 * 0.5:.3f} Y{100 + k % 7 * 0.1:.3f} Z{50 + k % 5 * 0.1:.3f} F3000\n")
        out.write("M2\n")


def main() -> int:
    if all(_cached(SOURCE / name) for name in KERNELS):
        return 0
    import numpy as np

    from axiscal.model import load_machine
    from axiscal.precompensation import precompensate_file

    machine = load_machine(MACHINE)
    n = 70_000  # above the point count from which the chain and its inverse run compiled
    rng = np.random.default_rng(0)
    positions = {"X": rng.uniform(0.0, 0.6, n), "Y": rng.uniform(0.0, 0.4, n), "Z": rng.uniform(0.0, 0.3, n)}
    machine.volumetric_error(positions)
    machine.command_for(machine.actual_point(positions))
    with tempfile.TemporaryDirectory(prefix="axiscal-warm-") as folder:
        program = Path(folder) / "part.ngc"
        _program(program, 30_000)
        precompensate_file(program, machine, Path(folder) / "part_comp.ngc", dialect="linuxcnc")
        # the live record's text is written by the recording process the command line starts
        env = {**os.environ, "MPLBACKEND": "Agg"}
        done = subprocess.run([sys.executable, "-m", "axiscal.cli.main", "live", "--rate", "1000", "--duration", "1",
                               "--port", "0", "--record", str(Path(folder) / "live.csv")],
                              env=env, capture_output=True, text=True)
        if done.returncode:
            print(f"warm_kernels: the live session failed:\n{done.stderr}", file=sys.stderr)
    return done.returncode


if __name__ == "__main__":
    sys.exit(main())
