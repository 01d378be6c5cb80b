"""Write examples/capture/: a plan, its LinuxCNC program and the virtual machine's laser recording of it.

    python examples/make_capture_example.py

The X axis of the built-in XZ module (examples/xz_module), 5 targets over 190 mm, one run each way,
a 1 s dwell at each target, the laser read at 100 Hz: `axiscal capture examples/capture/plan_x.csv
--from examples/capture/recording_x.csv -o positioning_x.csv` takes the run from it.
"""

from __future__ import annotations

import shutil
from pathlib import Path

from axiscal.capture import measure_axis

OUT = Path(__file__).resolve().parent / "capture"


def main() -> None:
    if OUT.exists():
        shutil.rmtree(OUT)
    OUT.mkdir()
    machine = Path(__file__).resolve().parent / "xz_module" / "machine.toml"
    measure_axis(OUT, machine, axis="X", start_m=0.0, end_m=0.19, targets=5, runs=1, seed=7, rate_hz=100.0)
    for name in ("positioning_x.csv", "positioning_x.json"):
        (OUT / name).unlink()  # the capture is what the user runs


if __name__ == "__main__":
    main()
