"""Make examples/identification/: a moving-bridge CMM with known polynomial errors, measured with a 5 x 5 ball plate in four positions.

The positions: XY; XZ; YZ with the stylus 30 mm along X; XZ again with the stylus 30 mm along Y.
Together they determine every term of poly:3 (docs/identification.md).

Run from the repository root: ``python examples/make_identification_examples.py``. The true machine
is written too (``examples/identification/true_machine/``), so the identification can be checked
against it.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from axiscal.identification import ParameterSet, parse_model, write_artefact, write_machine_folder
from axiscal.identification.simulate import plate_grid, simulate_ball_plate
from axiscal.model.machine import Axis, Machine

HERE = Path(__file__).resolve().parent / "identification"
TRAVEL = {"X": (0.0, 0.5), "Y": (0.0, 0.5), "Z": (0.0, 0.5)}


def main() -> None:
    rng = np.random.default_rng(2026)
    ideal = Machine("FYXZ", {k: Axis(k) for k in "XYZ"}, name="moving-bridge CMM")
    parameters = ParameterSet(ideal, parse_model("poly:3"), TRAVEL)
    theta = np.array([3e-6 if t.unit == "m" else 5e-6 for t in parameters.terms]) * rng.standard_normal(len(parameters.terms))
    true = parameters.identified_machine(theta)
    write_machine_folder(true, HERE / "true_machine", comment="the virtual CMM the example plates were measured on")
    start = HERE / "start"
    start.mkdir(parents=True, exist_ok=True)
    (start / "machine.toml").write_text(
        '# the chain of the CMM; no error tables yet: identify starts from zero\n'
        'name = "moving-bridge CMM"\nchain = "FYXZ"\n\n'
        + "".join(f'[axes.{k}]\nerrors = "{k.lower()}_zero.csv"\n\n' for k in "XYZ")
    )
    for k in "XYZ":
        a, b = TRAVEL[k]
        (start / f"{k.lower()}_zero.csv").write_text(f"position_mm,E{k}{k}_um\n{a * 1e3:.1f},0\n{b * 1e3:.1f},0\n")
    plate = plate_grid(5, 0.1)
    eye = np.eye(3)
    poses = {
        "plate_xy": (eye, [0.05, 0.05, 0.05], (0.0, 0.0, 0.0)),
        "plate_xz": (np.column_stack([eye[0], eye[2], -eye[1]]), [0.05, 0.45, 0.05], (0.0, 0.0, 0.0)),
        "plate_yz": (np.column_stack([eye[1], eye[2], eye[0]]), [0.45, 0.05, 0.05], (0.03, 0.0, 0.0)),
        "plate_xz_probe_y": (np.column_stack([eye[0], eye[2], -eye[1]]), [0.05, 0.45, 0.05], (0.0, 0.03, 0.0)),
    }
    for name, (rotation, origin, tool) in poses.items():
        artefact = simulate_ball_plate(true, plate, rotation, np.array(origin), np.array(tool), noise_m=0.2e-6, rng=rng,
                                       repeats=2, name=name, centre_u_m=0.25e-6)
        write_artefact(artefact, HERE / f"{name}.toml")


if __name__ == "__main__":
    main()
