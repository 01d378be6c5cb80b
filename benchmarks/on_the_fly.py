"""On-the-fly capture against stop-and-go capture on the virtual machine (median of 5 runs of each).

    .venv/bin/python benchmarks/on_the_fly.py [--repeats 5] [--feeds 1000,3000] [--rate-hz 1000]

The plan: ISO 230-2 linear cycle, X of the built-in XZ module, 0 to 190 mm, 5 targets, 5 runs
each way. Stop-and-go: the plan's program with a 2 s dwell at each target, captured by
:func:`axiscal.capture.capture_run` (mean of each stop's last 0.5 s). On the fly: the program
with ``on_the_fly=True`` run in path mode (``continuous=True``), the controller's position
stream recorded 8 ms late, taken by :func:`axiscal.capture.on_the_fly_run` (delay estimated).
Each repeat uses its own noise seeds. Printed per feed and per axis (a repeatable axis, and the
virtual axis's default 0.2 um scatter from one arrival to the next, which a pass does not have):

- the largest |on the fly - stop and go| over every target, run and direction, um;
- the largest difference of the mean deviations (over the 5 runs) at a target, um;
- the delay's error, ns;
- the machine time of each program, s, and the evaluation time of each capture, ms.
"""

from __future__ import annotations

import argparse
import statistics
import time

import numpy as np

from axiscal.capture import FlyRecording, VirtualAxis, capture_run, on_the_fly_run, simulate_motions
from axiscal.capture.on_the_fly import on_the_fly
from axiscal.io.gcode import program_motions
from axiscal.model.machine import load_machine
from axiscal.positioning.plan import gcode_program, plan_test
from axiscal.report.demo import builtin_example

DELAY_S = 0.008


def one(plan, machine, spec, feed, rate_hz, seed):
    sg = simulate_motions(program_motions(gcode_program(plan, dwell_s=2.0, feed_mm_per_min=feed), dialect="linuxcnc"),
                          machine, axis="X", spec=spec, seed=2 * seed, rate_hz=rate_hz)
    fl = simulate_motions(program_motions(gcode_program(plan, on_the_fly=True, feed_mm_per_min=feed), dialect="linuxcnc"),
                          machine, axis="X", spec=spec, seed=2 * seed + 1, rate_hz=rate_hz, continuous=True,
                          position_delay_s=DELAY_S)
    r = fl.recording
    fly = FlyRecording(r.time_s, r.reading_m, r.time_s, fl.position_m, r.channels, "<virtual machine>")
    t0 = time.perf_counter()
    reference = capture_run(plan, sg.recording)
    t1 = time.perf_counter()
    run = on_the_fly_run(plan, fly)
    t2 = time.perf_counter()
    delay = on_the_fly(plan, fly).delay_s
    worst = max(np.abs(run.deviations_up - reference.deviations_up).max(), np.abs(run.deviations_down - reference.deviations_down).max())
    means = max(np.abs(run.deviations_up.mean(1) - reference.deviations_up.mean(1)).max(),
                np.abs(run.deviations_down.mean(1) - reference.deviations_down.mean(1)).max())
    return {"worst_um": worst * 1e6, "means_um": means * 1e6, "delay_error_ns": (delay - DELAY_S) * 1e9,
            "machine_sg_s": sg.settings["duration_s"], "machine_fly_s": fl.settings["duration_s"],
            "eval_sg_ms": (t1 - t0) * 1e3, "eval_fly_ms": (t2 - t1) * 1e3}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--feeds", default="1000,3000", help="feeds in mm/min, comma-separated")
    parser.add_argument("--rate-hz", type=float, default=1000.0)
    args = parser.parse_args()
    machine = load_machine(builtin_example() / "machine.toml")
    plan = plan_test(0.0, 0.19, 5, runs=5, seed=7)
    print(f"plan: {plan.description}; laser {args.rate_hz:g} Hz; position stream {DELAY_S * 1e3:g} ms late;"
          f" median of {args.repeats}")
    print(f"{'feed mm/min':>11} {'axis':>14} {'max|fly-sg| um':>15} {'means um':>9} {'delay err ns':>13}"
          f" {'machine s sg/fly':>17} {'eval ms sg/fly':>15}")
    for feed in (float(f) for f in args.feeds.split(",")):
        for label, spec in (("repeatable", VirtualAxis(repeatability_m=0.0)), ("0.2 um scatter", VirtualAxis())):
            rows = [one(plan, machine, spec, feed, args.rate_hz, seed) for seed in range(args.repeats)]
            med = {k: statistics.median(r[k] for r in rows) for k in rows[0]}
            print(f"{feed:>11g} {label:>14} {med['worst_um']:>15.3f} {med['means_um']:>9.3f} {med['delay_error_ns']:>13.1f}"
                  f" {med['machine_sg_s']:>8.1f}/{med['machine_fly_s']:<8.1f} {med['eval_sg_ms']:>7.0f}/{med['eval_fly_ms']:<7.0f}")


if __name__ == "__main__":
    main()
