"""``axiscal run --on-the-fly`` against stop-and-go on the virtual controller, feed by feed.

    .venv/bin/python benchmarks/run_on_the_fly_speed.py [--repeats 3] [--feeds 1000,2000,4000,8000,12000]

What ``axiscal run PLAN --controller sim --source sim:umd [--on-the-fly --feed-mm-min F]`` does, in one
process: the virtual controller drives the built-in XZ module's X axis through a plan (20 to 80 mm,
5 targets, 2 runs each way), the simulated µMD reads its carriage; each repeat takes the plan once stop
and go (dwell 0.3 s, window 0.1 s) and once on the fly at every feed. Printed per feed: the largest
|on the fly - stop and go| over every target, run and direction, um (median and largest of the
repeats), and that error over the speed, us (the delay the estimate leaves: the error grows as the
speed times it). The streams are joined through the computer's clock, so a loaded machine shows more.
"""

from __future__ import annotations

import argparse
import statistics
import tempfile
from pathlib import Path

import numpy as np

from axiscal.capture.connected import open_run_devices, run_to_file
from axiscal.capture.drive import DriveSettings
from axiscal.capture.fly_drive import fly_plan
from axiscal.capture.run import CaptureSettings
from axiscal.io.tabular import read_csv
from axiscal.positioning.plan import plan_test, write_plan


def _deviations(path: Path) -> np.ndarray:
    return read_csv(path).numeric("deviation_um")


def _stop_and_go(plan: Path, folder: Path, seed: int) -> np.ndarray:
    controller, source = open_run_devices("sim", "sim:umd", seed=seed)
    try:
        files = run_to_file(plan, controller, source, folder / f"stop{seed}.csv",
                            drive=DriveSettings(feed_m_per_s=0.2, dwell_s=0.3), settings=CaptureSettings(window_s=0.1))
    finally:
        source.close()
        controller.close()
    return _deviations(files.run_csv)


def _fly(plan: Path, folder: Path, seed: int, feed_mm_min: float) -> np.ndarray:
    controller, source = open_run_devices("sim", "sim:umd", seed=seed)
    try:
        flown = fly_plan(plan, controller, source, folder / f"fly{seed}_{feed_mm_min:g}.csv",
                         drive=DriveSettings(feed_m_per_s=feed_mm_min / 60e3))
    finally:
        source.close()
        controller.close()
    return _deviations(flown.run_csv)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--feeds", default="1000,2000,4000,8000,12000", help="feeds in mm/min, comma-separated")
    args = parser.parse_args()
    feeds = [float(f) for f in args.feeds.split(",")]
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        plan = folder / "plan.csv"
        write_plan(plan_test(0.020, 0.080, 5, runs=2, seed=3), plan)
        errors: dict[float, list[float]] = {f: [] for f in feeds}
        for seed in range(args.repeats):
            reference = _stop_and_go(plan, folder, seed)
            for feed in feeds:
                errors[feed].append(float(np.max(np.abs(_fly(plan, folder, seed, feed) - reference))))
    print(f"plan: 20-80 mm, 5 targets, 2 runs each way; {args.repeats} repeats (stop and go: dwell 0.3 s, window 0.1 s)")
    print(f"{'feed mm/min':>11} {'max|fly-sg| um median':>22} {'largest':>8} {'over speed us':>14}")
    for feed in feeds:
        worst = max(errors[feed])
        print(f"{feed:>11g} {statistics.median(errors[feed]):>22.2f} {worst:>8.2f} {worst / (feed / 60.0) * 1e3:>14.1f}")


if __name__ == "__main__":
    main()
