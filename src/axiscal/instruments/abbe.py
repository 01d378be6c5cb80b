"""Abbe-Bryan transfer of measured error motions to another point (paper 000, eqs 4-5).

A rigid carriage that translates by ``delta`` at point M and rotates by the small angles ``eps``
(rad, about X, Y, Z) moves any other point P of it by

    delta_P = delta_M + eps × (P - M).

Each translation component is usually measured at its own point (the scale's read head for
positioning, the PSD's spot for straightness), so :func:`transfer_components` takes one offset
``P - M_i`` per component i and keeps component i of each transfer. Paper 000 eq (4) writes this
pattern for the X axis with a slip in its second line (``L_bx`` twice; the first must be ``L_bz``,
see docs/papers.md); eq (5) for the Z axis is consistent with the vector form.
"""

from __future__ import annotations

import numpy as np

from axiscal.errors import AxiscalError

__all__ = ["transfer_point", "transfer_components"]


def transfer_point(delta_m: np.ndarray, eps_rad: np.ndarray, offset_m: np.ndarray) -> np.ndarray:
    """Error at P from the error at M: ``delta + eps × (P - M)``.

    Parameters
    ----------
    delta_m : ndarray, shape (..., 3)
        Translation error at M, metres.
    eps_rad : ndarray, shape (..., 3)
        Rotation errors about X, Y, Z (EA, EB, EC), radians.
    offset_m : ndarray, shape (..., 3)
        ``P - M``, metres.

    Returns
    -------
    ndarray, shape (..., 3)
        Translation error at P, metres.
    """
    delta, eps, offset = (np.asarray(a, dtype=float) for a in (delta_m, eps_rad, offset_m))
    for name, a in (("delta_m", delta), ("eps_rad", eps), ("offset_m", offset)):
        if a.shape[-1:] != (3,):
            raise AxiscalError(f"{name} must have 3 components in its last dimension, got shape {a.shape}")
    return delta + np.cross(eps, offset)


def transfer_components(delta_m: np.ndarray, eps_rad: np.ndarray, offsets_m: np.ndarray) -> np.ndarray:
    """Transfer each translation component from its own measuring point M_i to P.

    Parameters
    ----------
    delta_m : ndarray, shape (..., 3)
        Component i measured at M_i, metres.
    eps_rad : ndarray, shape (..., 3)
        Rotation errors about X, Y, Z, radians.
    offsets_m : ndarray, shape (3, 3)
        Row i is ``P - M_i`` (the Abbe or Bryan offsets of the sensor measuring component i).

    Returns
    -------
    ndarray, shape (..., 3)
        ``delta_i + (eps × (P - M_i))_i`` for i = x, y, z, metres.
    """
    offsets = np.asarray(offsets_m, dtype=float)
    if offsets.shape != (3, 3):
        raise AxiscalError(f"offsets_m must have shape (3, 3), one row per component, got {offsets.shape}")
    eps = np.asarray(eps_rad, dtype=float)
    out = np.array(delta_m, dtype=float, copy=True)
    for i in range(3):
        out[..., i] += np.cross(eps, offsets[i])[..., i]
    return out
