"""Speed of the volumetric Monte Carlo: draws x points per second, here and on a 2-worker Dask LocalCluster.

Run: .venv/bin/python benchmarks/uncertainty.py [--draws 10000] [--points 1000] [--repeat 3]

The machine is examples/xfyz_machine ("XFYZ", 21 errors: 18 error motions from 100-row tables and
three squareness terms), every error motion given a standard uncertainty (0.5 um for
translations, 2 urad for rotations, at every row) and every squareness term 1 urad. Prints the
best of --repeat runs of axiscal.uncertainty.volumetric_monte_carlo (the intervals of ex, ey, ez
and of |e|) locally, then on a
LocalCluster of 2 single-threaded worker processes (the cluster started once, outside the
timing), and the largest difference between the two intervals (zero: same seed, same chunks).
"""

from __future__ import annotations

import argparse
import os
import time
from pathlib import Path

import numpy as np
from timing import best_time

import axiscal
from axiscal.uncertainty import MachineUncertainty, volumetric_monte_carlo

ROOT = Path(__file__).resolve().parents[1]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--draws", type=int, default=10_000)
    parser.add_argument("--points", type=int, default=1_000)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--no-dask", action="store_true", help="Only the local run.")
    args = parser.parse_args()

    machine = axiscal.load_machine(ROOT / "examples" / "xfyz_machine" / "machine.toml")
    per_row = np.array([0.5e-6] * 3 + [2e-6] * 3)[:, None]
    tables = {k: np.broadcast_to(per_row, machine.table(k).values.shape).copy() for k in machine.letters}
    uncertainty = MachineUncertainty(tables, {"EC0Y": 1e-6, "EB0Z": 1e-6, "EA0Z": 1e-6})
    rng = np.random.default_rng(0)
    q = {k: rng.uniform(*machine.travel_m(k), args.points) for k in machine.letters}
    work = args.draws * args.points

    def run(**options):
        return volumetric_monte_carlo(machine, uncertainty, q, args.draws, seed=1, **options)

    cpu_start = time.process_time()
    local = best_time(run, args.repeat)
    cpu = (time.process_time() - cpu_start) / args.repeat  # this process's CPU time: less moved by other work
    print(f"machine: {machine.name} ({machine.chain}), 21 uncertain errors, {args.draws:,d} draws x {args.points:,d} points")
    print(f"local          : {local:6.2f} s = {work / local / 1e6:5.2f} M draw-points/s ({os.cpu_count()} cores);"
          f" CPU {cpu:.2f} s per run")
    if args.no_dask:
        return
    from dask.distributed import Client, LocalCluster

    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, Client(cluster) as client:
        run(scheduler=client)  # warm the workers (imports)
        remote = best_time(lambda: run(scheduler=client), args.repeat)
        same = np.abs(run().high - run(scheduler=client).high).max()
    print(f"2-worker dask  : {remote:6.2f} s = {work / remote / 1e6:5.2f} M draw-points/s")
    print(f"largest difference between the local and the dask interval: {same:.1e} m")


if __name__ == "__main__":
    main()
