"""Throughput of the measurement pipeline: raw frames per second through MeasurementSystem.process.

Run: .venv/bin/python benchmarks/realtime.py [--frames 1000000] [--repeat 5] [--profile]

The system is the virtual XZ module of paper 000 (2 axes, 14 raw channels, calibrated, with the
plane-mirror correction). Frames come from VirtualModule.frames along the raster path (made once,
not timed). For several batch sizes it prints frames per second of the whole pipeline (range
checks, calibration, sensor equations, Abbe-Bryan, HTM chain, corrected position; best of
--repeat runs, one core) and, with --profile, the cProfile top entries of the largest batch. Live latency at a 10 kHz source is measured by benchmarks/realtime_live.py.
"""

from __future__ import annotations

import argparse
import cProfile
import os
import platform
import pstats

import numpy as np
from timing import best_time

from axiscal.live.pipeline import MS
from axiscal.measurement.virtual import VirtualModule


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--frames", type=int, default=1_000_000, help="frames in the largest batch")
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--profile", action="store_true", help="print the cProfile top entries for the largest batch")
    args = parser.parse_args()

    module = VirtualModule(seed=0)
    system = module.measurement_system()
    frames, _ = module.frames(np.arange(args.frames) * 1e-4, path="raster")
    print(f"axiscal measurement pipeline, virtual XZ module: {len(system.channels)} channels, axes {''.join(system.axes)}")
    print(f"python {platform.python_version()}, numpy {np.__version__}, {os.cpu_count()} cpus visible (one used)")
    print(f"{'batch':>10} {'time/batch':>12} {'frames/s':>14}")
    sizes = [n for n in (100, 1_000, 10_000, 100_000, 1_000_000) if n <= args.frames]
    if args.frames not in sizes:
        sizes.append(args.frames)
    for size in sizes:
        batch = {k: v[:size] for k, v in frames.items()}
        batches = max(1, min(1000, 200_000 // size))
        elapsed = best_time(lambda: [system.process(batch) for _ in range(batches)], args.repeat) / batches
        print(f"{size:>10} {elapsed / MS:>10.3f} ms {size / elapsed:>14,.0f}")
    if args.profile:
        profile = cProfile.Profile()
        profile.enable()
        for _ in range(3):
            system.process(frames)
        profile.disable()
        pstats.Stats(profile).sort_stats("tottime").print_stats(12)


if __name__ == "__main__":
    main()
