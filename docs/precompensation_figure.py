"""Draw docs/precompensation_before_after.png: a part's tool path error before and after pre-compensation.

Run from the repository root: ``.venv/bin/python docs/precompensation_figure.py``. The part (a plunge,
a straight cut, two arcs, an incremental move) runs on the example machine tool
(examples/xfyz_machine). Before: the model's volumetric error along the programmed path. After: the
distance of the tool, moved along the rewritten program, from the nominal path (the nominal path
cut into 0.1 nm chords; each tool point measured to the pieces beside its nearest vertices).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from scipy.spatial import cKDTree

from axiscal.io.figures import pyplot, save_figure
from axiscal.io.gcode import PLANE_AXES, program_motions
from axiscal.model.machine import load_machine
from axiscal.precompensation import rewrite_program

ROOT = Path(__file__).resolve().parents[1]
OUT = Path(__file__).resolve().parent / "precompensation_before_after.png"
PART = """%
(part)
G21 G90 G94 G17
N10 G0 X100 Y100 Z150
N20 G1 Z120 F800 (plunge)
N30 G1 X300 Y150
N40 G2 X340 Y190 I0 J40
N50 G3 X300 Y230 R40
G91
G1 X-20 Y-10
G90
G0 Z200
M2
%
"""


def samples(text: str, step_m: float, sagitta_m: float | None = None) -> list[np.ndarray]:
    """Points (X, Y, Z) along every non-rapid move, one array per move (its start first)."""
    out = []
    for motion in program_motions(text, dialect="linuxcnc"):
        if motion.kind in ("rapid", "dwell"):
            continue
        start = np.array([motion.start_m[k] for k in "XYZ"])
        end = np.array([motion.end_m[k] for k in "XYZ"])
        count = max(2, math.ceil(np.linalg.norm(end - start) / step_m))
        if motion.kind == "arc":
            a, b, _ = PLANE_AXES[motion.plane]
            radius = math.hypot(motion.start_m[a] - motion.centre_m[a], motion.start_m[b] - motion.centre_m[b])
            count = max(count, math.ceil(abs(motion.sweep_rad) * radius / step_m))
            if sagitta_m is not None:
                count = max(count, math.ceil(abs(motion.sweep_rad) / (2 * math.sqrt(2 * sagitta_m / radius))))
        t = np.arange(count + 1) / count
        points = start + t[:, None] * (end - start)
        if motion.kind == "arc":
            theta = math.atan2(motion.start_m[b] - motion.centre_m[b], motion.start_m[a] - motion.centre_m[a]) + motion.sweep_rad * t
            points[:, "XYZ".index(a)] = motion.centre_m[a] + radius * np.cos(theta)
            points[:, "XYZ".index(b)] = motion.centre_m[b] + radius * np.sin(theta)
        out.append(points)
    return out


def main() -> None:
    machine = load_machine(ROOT / "examples" / "xfyz_machine" / "machine.toml")
    result = rewrite_program(PART, machine, dialect="linuxcnc")
    q = lambda p: {k: p[:, i] for i, k in enumerate("XYZ")}  # noqa: E731
    before = np.vstack(samples(PART, 0.2e-3))
    s_before = np.r_[0.0, np.cumsum(np.linalg.norm(np.diff(before, axis=0), axis=1))]
    error_before = np.linalg.norm(machine.volumetric_error(q(before)), axis=1)
    nominal = np.vstack([machine.nominal_point(q(p)) for p in samples(PART, 5e-6, 1e-10)])
    after = np.vstack(samples(result.text, 0.2e-3))
    s_after = np.r_[0.0, np.cumsum(np.linalg.norm(np.diff(after, axis=0), axis=1))]
    actual = machine.actual_point(q(after))
    _, near = cKDTree(nominal).query(actual, k=4)
    error_after = np.full(len(actual), np.inf)
    for index in near.T:
        for side in (-1, 1):
            other = np.clip(index + side, 0, len(nominal) - 1)
            a, ab = nominal[index], nominal[other] - nominal[index]
            t = np.clip(((actual - a) * ab).sum(axis=1) / np.maximum((ab * ab).sum(axis=1), 1e-300), 0, 1)
            error_after = np.minimum(error_after, np.linalg.norm(actual - a - t[:, None] * ab, axis=1))
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(8, 4.2))
    ax.semilogy(s_before * 1e3, error_before * 1e6, label="as programmed: the model's error along the path")
    ax.semilogy(s_after * 1e3, np.maximum(error_after * 1e6, 1e-4), label="pre-compensated: distance from the nominal path")
    ax.axhline(result.tolerance_m * 1e6, color="k", ls="--", lw=1, label="tolerance 0.5 um")
    ax.set_xlabel("path length along the part, mm (plunge, straight cut, two arcs, incremental move)")
    ax.set_ylabel("tool off the nominal path, um")
    ax.set_title(f"{machine.name}: {result.lines_in} lines in, {result.lines_out} out")
    ax.set_ylim(1e-3, 100)
    ax.legend(loc="lower right", fontsize=8)
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    save_figure(fig, OUT)
    print(f"{OUT}: before up to {error_before.max() * 1e6:.1f} um, after up to {error_after.max() * 1e6:.3f} um")


if __name__ == "__main__":
    main()
