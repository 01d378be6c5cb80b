"""Speed of the volumetric model: points per second for a 3-axis, 21-error machine and a five-axis trunnion.

Run: .venv/bin/python benchmarks/volumetric.py [--points 1000000] [--loop-points 2000]

The machine is examples/xfyz_machine ("XFYZ", 100-row tables per axis, three squareness terms).
Prints points per second of Machine.volumetric_error at 10^6 points (best of several runs), the
same for the plain per-point loop of 4x4 matrix products (on fewer points), and their ratio.
Then the five-axis trunnion of examples/trunnion_machine ("CAFXYZ", 33 error motions, 8 location
and 3 squareness errors): points per second of the position error alone and of the position and
tool axis orientation error together (Machine.pose_error).
"""

from __future__ import annotations

import argparse
import os
from pathlib import Path

import numpy as np
from timing import best_time

import axiscal

ROOT = Path(__file__).resolve().parents[1]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--points", type=int, default=1_000_000)
    parser.add_argument("--loop-points", type=int, default=2000)
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()

    machine = axiscal.load_machine(ROOT / "examples" / "xfyz_machine" / "machine.toml")
    rng = np.random.default_rng(0)
    travel = {k: machine.travel_m(k) for k in machine.letters}
    q = {k: rng.uniform(*travel[k], args.points) for k in machine.letters}
    q_loop = {k: v[: args.loop_points] for k, v in q.items()}

    fast = best_time(lambda: machine.volumetric_error(q), args.repeat)
    single = best_time(lambda: machine.volumetric_error(q, workers=1), args.repeat)
    loop = best_time(lambda: machine.reference_volumetric_error(q_loop), 1)
    agree = np.abs(machine.volumetric_error(q_loop) - machine.reference_volumetric_error(q_loop)).max()

    fast_rate = args.points / fast
    loop_rate = args.loop_points / loop
    print(f"machine: {machine.name} ({machine.chain}), 21 errors, tables of {machine.table('X').position_m.size} rows")
    print(f"vectorised model : {args.points:>9,d} points in {fast * 1e3:8.1f} ms = {fast_rate / 1e6:6.2f} M points/s ({os.cpu_count()} threads)")
    print(f"  on one thread  : {args.points:>9,d} points in {single * 1e3:8.1f} ms = {args.points / single / 1e6:6.2f} M points/s")
    print(f"plain 4x4 loop   : {args.loop_points:>9,d} points in {loop * 1e3:8.1f} ms = {loop_rate / 1e3:6.2f} k points/s")
    print(f"ratio            : {fast_rate / loop_rate:,.0f} x")
    print(f"largest difference between the two: {agree:.2e} m")

    trunnion = axiscal.load_machine(ROOT / "examples" / "trunnion_machine" / "machine.toml")
    q5 = {k: rng.uniform(*trunnion.travel_m(k), args.points) for k in trunnion.letters}
    position = best_time(lambda: trunnion.volumetric_error(q5), args.repeat)
    pose = best_time(lambda: trunnion.pose_error(q5), args.repeat)
    print(f"machine: {trunnion.name} ({trunnion.chain})")
    print(f"position error   : {args.points:>9,d} points in {position * 1e3:8.1f} ms = {args.points / position / 1e6:6.2f} M points/s")
    print(f"  and orientation: {args.points:>9,d} points in {pose * 1e3:8.1f} ms = {args.points / pose / 1e6:6.2f} M points/s")


if __name__ == "__main__":
    main()
