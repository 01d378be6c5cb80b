"""Speed of the volumetric model: points per second for a 3-axis, 21-error machine and a five-axis trunnion.

Run: .venv/bin/python benchmarks/volumetric.py [--points 1000000] [--loop-points 2000] [--runs 5]

The machine is examples/xfyz_machine ("XFYZ", 100-row tables per axis, three squareness terms);
the five-axis trunnion is examples/trunnion_machine ("CAFXYZ", 33 error motions, 8 location and
3 squareness errors). Each round runs, in turn, Machine.volumetric_error of the XFYZ machine at
10^6 points (compiled, on every core, then on one thread), the same through the NumPy arrays of the
model (which it uses below 65536 points; here in chunks of 65536 on every core, as the model ran
before it was compiled), the plain per-point loop of 4x4 matrix products (on fewer points), and the
trunnion's position error alone and with the tool axis orientation (Machine.pose_error), compiled
and through the NumPy arrays. Running them in turn (A B A B ...) lets a drift of a shared machine's load
touch them alike. Printed: the median of ``--runs`` rounds of each, and the median over rounds of
each figure's ratio to the plain loop of the same round.
"""

from __future__ import annotations

import argparse
import os
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np
from timing import interleaved, median, median_ratio

import axiscal
from axiscal.model.kinematics import _pose_error, _volumetric_error

ROOT = Path(__file__).resolve().parents[1]
CHUNK = 65536


def numpy_model(machine, q: dict[str, np.ndarray], *, pose: bool) -> np.ndarray:
    """The model's NumPy arrays over all the points, in chunks of 65536 on every core."""
    n = len(next(iter(q.values())))
    tool, workpiece = np.array(machine.tool_m), np.array(machine.workpiece_m)
    out = np.empty((n, 5 if pose else 3))

    def fill(start: int) -> None:
        part = {k: v[start : start + CHUNK] for k, v in q.items()}
        if pose:
            out[start : start + CHUNK] = np.column_stack(_pose_error(machine._tool_links, machine._workpiece_links, tool, part))
        elif machine.rotary:
            out[start : start + CHUNK] = _pose_error(machine._tool_links, machine._workpiece_links, tool, part, orientation=False)[0]
        else:
            out[start : start + CHUNK] = _volumetric_error(machine._tool_links, machine._workpiece_links, tool, workpiece, part)

    with ThreadPoolExecutor(os.cpu_count() or 1) as pool:
        list(pool.map(fill, range(0, n, CHUNK)))
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--points", type=int, default=1_000_000)
    parser.add_argument("--loop-points", type=int, default=2000)
    parser.add_argument("--runs", type=int, default=5)
    args = parser.parse_args()

    machine = axiscal.load_machine(ROOT / "examples" / "xfyz_machine" / "machine.toml")
    trunnion = axiscal.load_machine(ROOT / "examples" / "trunnion_machine" / "machine.toml")
    rng = np.random.default_rng(0)
    q = {k: rng.uniform(*machine.travel_m(k), args.points) for k in machine.letters}
    q_loop = {k: v[: args.loop_points] for k, v in q.items()}
    q5 = {k: rng.uniform(*trunnion.travel_m(k), args.points) for k in trunnion.letters}
    machine.volumetric_error(q_loop)  # load the compiled model before timing
    trunnion.pose_error(q5)

    times = interleaved({
        "fast": lambda: machine.volumetric_error(q),
        "single": lambda: machine.volumetric_error(q, workers=1),
        "numpy": lambda: numpy_model(machine, q, pose=False),
        "loop": lambda: machine.reference_volumetric_error(q_loop),
        "position": lambda: trunnion.volumetric_error(q5),
        "pose": lambda: trunnion.pose_error(q5),
        "numpy position": lambda: numpy_model(trunnion, q5, pose=False),
        "numpy pose": lambda: numpy_model(trunnion, q5, pose=True),
    }, args.runs)
    agree = np.abs(machine.volumetric_error(q_loop) - machine.reference_volumetric_error(q_loop)).max()
    agree_numpy = max(np.abs(machine.volumetric_error(q) - numpy_model(machine, q, pose=False)).max(),
                      np.abs(np.column_stack(trunnion.pose_error(q5)) - numpy_model(trunnion, q5, pose=True)).max())

    def rate(name: str, points: int) -> float:
        return points / median(times[name])

    def speedup(name: str) -> float:
        """Median over rounds of (points/s of ``name``) / (points/s of the plain loop)."""
        return args.points / args.loop_points / median_ratio(times[name], times["loop"])

    print(f"median of {args.runs} rounds, each running every line below in turn; {os.cpu_count()} cores")
    print(f"machine: {machine.name} ({machine.chain}), 21 errors, tables of {machine.table('X').position_m.size} rows")
    print(f"compiled model   : {args.points:>9,d} points in {median(times['fast']) * 1e3:8.1f} ms = "
          f"{rate('fast', args.points) / 1e6:6.2f} M points/s (goal >= 15), {speedup('fast'):,.0f} x the plain loop")
    print(f"  on one thread  : {args.points:>9,d} points in {median(times['single']) * 1e3:8.1f} ms = "
          f"{rate('single', args.points) / 1e6:6.2f} M points/s, {speedup('single'):,.0f} x the plain loop")
    print(f"NumPy arrays     : {args.points:>9,d} points in {median(times['numpy']) * 1e3:8.1f} ms = "
          f"{rate('numpy', args.points) / 1e6:6.2f} M points/s; compiled is "
          f"{1 / median_ratio(times['fast'], times['numpy']):.1f} x faster")
    print(f"plain 4x4 loop   : {args.loop_points:>9,d} points in {median(times['loop']) * 1e3:8.1f} ms = "
          f"{rate('loop', args.loop_points) / 1e3:6.2f} k points/s")
    print(f"largest difference from the plain loop: {agree:.2e} m; between compiled and NumPy: {agree_numpy:.2e}")
    print(f"machine: {trunnion.name} ({trunnion.chain})")
    print(f"position error   : {args.points:>9,d} points in {median(times['position']) * 1e3:8.1f} ms = "
          f"{rate('position', args.points) / 1e6:6.2f} M points/s, {speedup('position'):,.0f} x the plain loop of XFYZ")
    print(f"  and orientation: {args.points:>9,d} points in {median(times['pose']) * 1e3:8.1f} ms = "
          f"{rate('pose', args.points) / 1e6:6.2f} M points/s (goal >= 5), {speedup('pose'):,.0f} x the plain loop of XFYZ")
    for name in ("position", "pose"):
        print(f"  NumPy {name:<9}: {args.points:>9,d} points in {median(times['numpy ' + name]) * 1e3:8.1f} ms = "
              f"{rate('numpy ' + name, args.points) / 1e6:6.2f} M points/s; compiled is "
              f"{1 / median_ratio(times[name], times['numpy ' + name]):.1f} x faster")


if __name__ == "__main__":
    main()
