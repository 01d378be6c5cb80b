"""The forward check: run a program's moves through the machine model and measure how far the tool is from a nominal path.

Written apart from the pre-compensation: it reads programs with the dialect's reader, walks every
straight and circular move as the control does (straight lines between points, arcs about their
centre) and compares the model's actual tool point with the nominal path of the original program,
sampled finely enough that its own discretisation is below a nanometre.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.spatial import cKDTree

from axiscal.io.gcode import PLANE_AXES, program_motions


def _walk(motion, count: int, letters) -> np.ndarray:
    """``count`` points along a motion (excluding its start), one column per letter."""
    t = np.arange(1, count + 1) / count
    start = np.array([motion.start_m[k] for k in letters])
    end = np.array([motion.end_m[k] for k in letters])
    points = start[None, :] + t[:, None] * (end - start)[None, :]
    if motion.kind == "arc":
        a, b, _ = PLANE_AXES[motion.plane]
        ca, cb = motion.centre_m[a], motion.centre_m[b]
        radius = math.hypot(motion.start_m[a] - ca, motion.start_m[b] - cb)
        theta = math.atan2(motion.start_m[b] - cb, motion.start_m[a] - ca) + motion.sweep_rad * t
        points[:, letters.index(a)] = ca + radius * np.cos(theta)
        points[:, letters.index(b)] = cb + radius * np.sin(theta)
    return points


def path_points(text: str, dialect: str, letters, *, step_m: float, arc_sagitta_m: float | None = None, **read):
    """Points along every non-rapid move of a program whose start is known, shape (N, len(letters))."""
    out = []
    for motion in program_motions(text, dialect=dialect, **read):
        if motion.kind in ("dwell", "rapid") or not all(k in motion.start_m for k in letters):
            continue
        length = math.dist([motion.start_m[k] for k in letters], [motion.end_m[k] for k in letters])
        count = max(2, math.ceil(length / step_m))
        if motion.kind == "arc" and arc_sagitta_m is not None:
            a, b, _ = PLANE_AXES[motion.plane]
            radius = math.hypot(motion.start_m[a] - motion.centre_m[a], motion.start_m[b] - motion.centre_m[b])
            dtheta = 2 * math.sqrt(2 * arc_sagitta_m / radius)
            count = max(count, math.ceil(abs(motion.sweep_rad) / dtheta))
        first = np.array([[motion.start_m[k] for k in letters]])
        out.append(np.vstack([first, _walk(motion, count, letters)]))
    return out


def largest_departure(machine, original: str, rewritten: str, dialect: str, *, reach=(0, 1, 2), **read) -> float:
    """Largest distance of the tool along the rewritten program from the original's nominal path, metres.

    The nominal path is a polyline: arcs are cut into chords of 0.1 nm sagitta (about 6 um long at a
    radius of 40 mm) and straight moves, straight in the nominal kinematics, every 5 um, so that a
    tool point's nearest vertices lie on its own stretch of path. Each tool point's distance is
    taken to the pieces of the polyline beside its four nearest vertices.
    """
    letters = list(machine.letters)

    def positions(points):
        return {k: points[:, i] for i, k in enumerate(letters)}

    pieces = path_points(original, dialect, letters, step_m=5e-6, arc_sagitta_m=1e-10, **read)
    # one chain of vertices per stretch of path without a rapid move in it
    chains: list[list[np.ndarray]] = []
    for p in pieces:
        if chains and np.array_equal(chains[-1][-1][-1], p[0]):
            chains[-1].append(p[1:])
        else:
            chains.append([p])
    polyline = [machine.nominal_point(positions(np.vstack(chain)))[:, list(reach)] for chain in chains]
    vertices = np.vstack(polyline)
    piece = np.concatenate([np.full(len(p), i) for i, p in enumerate(polyline)])
    tool = path_points(rewritten, dialect, letters, step_m=0.25e-3, **read)
    actual = np.vstack([machine.actual_point(positions(p))[:, list(reach)] for p in tool])
    _, near = cKDTree(vertices).query(actual, k=4)
    best = np.full(len(actual), np.inf)
    for nearest in near.T:
        for side in (-1, 1):
            other = np.clip(nearest + side, 0, len(vertices) - 1)
            same = (piece[other] == piece[nearest]) & (other != nearest)
            a, b = vertices[nearest], vertices[other]
            ab = b - a
            t = np.clip(((actual - a) * ab).sum(axis=1) / np.maximum((ab * ab).sum(axis=1), 1e-300), 0.0, 1.0)
            d = np.linalg.norm(actual - a - t[:, None] * ab, axis=1)
            best = np.minimum(best, np.where(same, d, np.linalg.norm(actual - a, axis=1)))
    return float(best.max())
