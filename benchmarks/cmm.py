"""CMM tests: the least-squares sphere against SciPy's solver, and the two commands on the examples.

    .venv/bin/python benchmarks/cmm.py [--repeats 5] [--trials 200]

1. ``fit_sphere`` on ``--trials`` sets of 25 points (the ISO 10360-5 pattern on a 25 mm sphere
   300 mm from the origin, 1 um of noise): the largest difference of centre and radius from
   ``scipy.optimize.least_squares`` on the same geometric residuals, and the median time of a fit
   beside SciPy's.
2. ``axiscal cmm acceptance`` (135 values) and ``axiscal cmm probing`` (125 points, five styli)
   on the shipped examples, as whole processes: the median of ``--repeats`` runs.
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
from scipy.optimize import least_squares

from axiscal.cmm import fit_sphere

EXAMPLES = Path(__file__).resolve().parents[1] / "examples" / "cmm"


def pattern() -> np.ndarray:
    out = []
    for polar, count, turn in [(0.0, 1, 0.0), (22.5, 4, 0.0), (45.0, 8, 22.5), (67.5, 4, 22.5), (90.0, 8, 22.5)]:
        for k in range(count):
            a, t = np.radians(turn + 360.0 * k / count), np.radians(polar)
            out.append((np.sin(t) * np.cos(a), np.sin(t) * np.sin(a), np.cos(t)))
    return np.array(out)


def median_time(call, repeats: int) -> float:
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        call()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--trials", type=int, default=200)
    args = parser.parse_args()
    rng = np.random.default_rng(1)
    centre, radius = np.array([0.31, 0.22, -0.18]), 0.0125
    worst_centre = worst_radius = 0.0
    ours, theirs = [], []
    for _ in range(args.trials):
        points = centre + (radius + rng.normal(0, 1e-6, 25))[:, None] * pattern()
        start = time.perf_counter()
        fit = fit_sphere(points)
        ours.append(time.perf_counter() - start)
        start = time.perf_counter()
        plain = least_squares(lambda p: np.linalg.norm(points - p[:3], axis=1) - p[3], np.r_[centre, radius],
                              xtol=1e-15, ftol=1e-15, gtol=1e-15).x
        theirs.append(time.perf_counter() - start)
        worst_centre = max(worst_centre, float(np.abs(fit.centre_m - plain[:3]).max()))
        worst_radius = max(worst_radius, abs(fit.radius_m - plain[3]))
    print(f"fit_sphere vs scipy least_squares, {args.trials} sets of 25 points:")
    print(f"  largest difference: centre {worst_centre:.2e} m, radius {worst_radius:.2e} m")
    print(f"  median time: fit_sphere {statistics.median(ours) * 1e6:.0f} us, "
          f"least_squares {statistics.median(theirs) * 1e6:.0f} us")
    axiscal = [sys.executable, "-m", "axiscal.cli.main"]
    acceptance = axiscal + ["cmm", "acceptance", str(EXAMPLES / "e0_gauge_blocks.csv"), "--mpe-a-um", "1.8", "--mpe-k", "300",
                            "--json"]
    probing = axiscal + ["cmm", "probing", str(EXAMPLES / "sphere_five_styli.csv"), "--diameter-mm", "25.00018", "--json"]
    for name, argv in (("cmm acceptance (135 values)", acceptance), ("cmm probing (5 styli x 25 points)", probing)):
        seconds = median_time(lambda: subprocess.run(argv, check=True, capture_output=True), args.repeats)
        print(f"axiscal {name}: median of {args.repeats} whole processes {seconds:.2f} s")


if __name__ == "__main__":
    main()
