"""Two machines' volumetric maps compared after removing the rigid-body motion no artefact can see (least squares, small angles).

An artefact fixes the machine's errors only up to a rigid-body motion of the whole workspace
(``e' = e + t + ω × p``): its own pose absorbs it. Two maps are therefore compared as
``d = e₁ - e₂ - (t + ω × p)`` with ``t, ω`` fitted by least squares over the points.
"""

from __future__ import annotations

import numpy as np

from axiscal.io.arguments import check_instance
from axiscal.model.machine import Machine

__all__ = ["map_difference"]


def map_difference(first: Machine, second: Machine, positions: dict) -> np.ndarray:
    """Volumetric error of ``first`` minus that of ``second`` at ``positions``, less the best rigid-body motion.

    Parameters
    ----------
    first, second : Machine
        Two models of the same chain.
    positions : dict of str to ndarray, shape (N,)
        Axis positions (metres; radians for rotary axes).

    Returns
    -------
    ndarray, shape (N, 3)
        The difference left, metres.
    """
    check_instance("first", first, Machine)
    check_instance("second", second, Machine)
    points = first.nominal_point(positions)
    difference = first.volumetric_error(positions) - second.volumetric_error(positions)
    n = len(points)
    design = np.zeros((n, 3, 6))
    design[:, :, :3] = np.eye(3)
    x, y, z = points.T
    # ω × p: rows (ωy z - ωz y, ωz x - ωx z, ωx y - ωy x)
    design[:, 0, 4], design[:, 0, 5] = z, -y
    design[:, 1, 3], design[:, 1, 5] = -z, x
    design[:, 2, 3], design[:, 2, 4] = y, -x
    motion = np.linalg.lstsq(design.reshape(3 * n, 6), difference.ravel(), rcond=None)[0]
    return difference - (design.reshape(3 * n, 6) @ motion).reshape(n, 3)
