"""Make examples/ballbar/ballbar_run.csv: the ballbar trace of a virtual machine with known errors.

Run from the repository root: ``python examples/ballbar/make_ballbar_example.py``. The same trace
comes from the command line with

    axiscal simulate ballbar --radius-mm 100 --plane XY --feed-mm-min 1000 --squareness-urad 25 \
        --scale-ppm X=15 --scale-ppm Y=-5 --backlash-um X=4 --backlash-um Y=6 --servo-mismatch-ms 2 \
        --reversal-spike-um X=3 --reversal-spike-um Y=5 --cyclic-error-um X=1.2 --cyclic-pitch-mm X=5 \
        --centre-um X=8 --centre-um Y=-5 --noise-um 0.1 --seed 1 -o examples/ballbar/ballbar_run.csv

and ``axiscal ballbar examples/ballbar/ballbar_run.csv --radius-mm 100 --plane XY --feed-mm-min 1000``
reads the errors back.
"""

from __future__ import annotations

import math
from pathlib import Path

from axiscal.circular import MM_PER_MIN, MS, PPM, simulate_ballbar, write_trace
from axiscal.units import ANGLE_UNITS, MM, UM

HERE = Path(__file__).resolve().parent

#: the machine's errors, in the units of the file and the command line
ERRORS = {
    "feed_mm_min": 1000.0,
    "squareness_urad": 25.0,
    "scale_ppm": {"X": 15.0, "Y": -5.0},
    "backlash_um": {"X": 4.0, "Y": 6.0},
    "servo_mismatch_ms": 2.0,
    "reversal_spike_um": {"X": 3.0, "Y": 5.0},
    "cyclic_error_um": {"X": 1.2},
    "cyclic_pitch_mm": {"X": 5.0},
    "centre_um": {"X": 8.0, "Y": -5.0},
    "noise_um": 0.1,
    "seed": 1,
}


def main() -> None:
    e = ERRORS
    trace = simulate_ballbar(
        radius=100.0 * MM,
        plane="XY",
        feed=e["feed_mm_min"] * MM_PER_MIN,
        squareness=e["squareness_urad"] * ANGLE_UNITS["urad"],
        scale={k: v * PPM for k, v in e["scale_ppm"].items()},
        backlash={k: v * UM for k, v in e["backlash_um"].items()},
        servo_mismatch=e["servo_mismatch_ms"] * MS,
        reversal_spike={k: v * UM for k, v in e["reversal_spike_um"].items()},
        cyclic_error={k: v * UM for k, v in e["cyclic_error_um"].items()},
        cyclic_pitch={k: v * MM for k, v in e["cyclic_pitch_mm"].items()},
        centre_offset={k: v * UM for k, v in e["centre_um"].items()},
        step=math.radians(0.1),
        noise=e["noise_um"] * UM,
        seed=e["seed"],
    )
    out = write_trace(HERE / "ballbar_run.csv", trace, simulated=ERRORS)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
