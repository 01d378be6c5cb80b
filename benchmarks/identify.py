"""Speed of identification from artefacts: a 5 x 5 ball plate in four positions on a CMM, and 10^4 multilateration ranges.

Run: .venv/bin/python benchmarks/identify.py [--repeat 3]

1. A moving-bridge CMM ("FYXZ") with random poly:3 errors (3 um, 5 urad), a 5 x 5 plate at 100 mm
   pitch in the XY, XZ and YZ planes and the XY plane raised, each ball measured 5 times (500
   centres, 1500 residuals) with 0.2 um noise; identified with poly:3 (57 terms + 24 pose unknowns).
2. The same machine measured by a tracking interferometer from 5 stations at 667 targets with the
   reflector in 3 places on the tool (10^4 ranges, 0.2 um noise); identified with poly:3 (57 terms
   + 60 station unknowns).
Prints the fit time (best of --repeat), the residual standard deviation, the rank and the largest
difference of the identified map from the true one over the workspace after removing a rigid-body
motion.
"""

from __future__ import annotations

import argparse

import numpy as np
from timing import best_time

from axiscal.identification import ParameterSet, identify, map_difference, parse_model
from axiscal.identification.simulate import plate_grid, simulate_ball_plate, simulate_multilateration
from axiscal.model.machine import Axis, Machine, axis_positions_from_grid

TRAVEL = {"X": (0.0, 0.5), "Y": (0.0, 0.5), "Z": (0.0, 0.5)}


def report(label: str, seconds: float, result, true: Machine) -> None:
    grid = axis_positions_from_grid("X=20:480:46,Y=20:480:46,Z=20:480:46")
    worst = np.abs(map_difference(result.machine, true, grid)).max()
    residuals = sum(r.size for r in result.residuals.values())
    print(
        f"{label}: {residuals} residuals, {len(result.names)} unknowns (rank {result.rank}), fit {seconds:.2f} s, "
        f"s = {result.residual_std * 1e6:.3f} um, map within {worst * 1e6:.3f} um of the truth (rigid body removed)"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    rng = np.random.default_rng(0)
    ideal = Machine("FYXZ", {k: Axis(k) for k in "XYZ"})
    parameters = ParameterSet(ideal, parse_model("poly:3"), TRAVEL)
    theta = np.array([3e-6 if t.unit == "m" else 5e-6 for t in parameters.terms]) * rng.standard_normal(len(parameters.terms))
    true = parameters.identified_machine(theta)

    eye = np.eye(3)
    xz, yz = np.column_stack([eye[0], eye[2], -eye[1]]), np.column_stack([eye[1], eye[2], eye[0]])
    positions = [(eye, (0.05, 0.05, 0.05), (0.0, 0.0, 0.0)), (xz, (0.05, 0.45, 0.05), (0.0, 0.03, 0.0)),
                 (yz, (0.45, 0.05, 0.05), (0.03, 0.0, 0.0)), (yz, (0.45, 0.05, 0.05), (0.0, 0.0, 0.0))]
    plates = [simulate_ball_plate(true, plate_grid(5, 0.1), r, np.array(o), np.array(t), noise_m=0.2e-6, rng=rng, repeats=5, name=f"plate{k}")
              for k, (r, o, t) in enumerate(positions)]
    seconds = best_time(lambda: identify(ideal, plates, model="poly:3", travel=TRAVEL), args.repeat)
    report("ball plate, 4 positions x 25 balls x 5 repeats, poly:3", seconds, identify(ideal, plates, model="poly:3", travel=TRAVEL), true)

    targets = rng.uniform(0.05, 0.45, (667, 3))
    stations = np.array([[-0.6, -0.6, 0.0], [1.1, -0.6, 0.1], [1.1, 1.1, 0.0], [-0.6, 1.1, 0.2], [0.25, 0.25, 1.2]])
    reflectors = ((0.0, 0.0, -0.03), (0.03, 0.0, 0.0), (0.0, 0.03, 0.0))
    trackers = [simulate_multilateration(true, stations, np.full(5, 0.2), targets, np.array(r), noise_m=0.2e-6, rng=rng, name=f"tracker{k}")
                for k, r in enumerate(reflectors)]
    seconds = best_time(lambda: identify(ideal, trackers, model="poly:3", travel=TRAVEL), args.repeat)
    report("multilateration, 5 stations x 667 targets x 3 reflector positions = 10^4 ranges, poly:3", seconds,
           identify(ideal, trackers, model="poly:3", travel=TRAVEL), true)

if __name__ == "__main__":
    main()
