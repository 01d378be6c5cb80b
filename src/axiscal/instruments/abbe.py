"""Abbe-Bryan transfer of measured error motions to another point (paper 000, eqs 4-5).

A rigid carriage that translates by ``delta`` at point M and rotates by the small angles ``eps``
(rad, about X, Y, Z) moves any other point P of it by

    delta_P = delta_M + eps × (P - M).

Each translation component is usually measured at its own point (the scale's read head for
positioning, the PSD's spot for straightness), so :func:`transfer_components` takes one offset
``P - M_i`` per component i and keeps component i of each transfer. Paper 000 eq (4) writes this
pattern for the X axis with a slip in its second line (``L_bx`` twice; the first must be ``L_bz``,
see docs/papers.md); eq (5) for the Z axis is consistent with the vector form.

This is the one implementation of the transfer: the measurement pipeline (sensor points to the
functional point), the calibration (reference instrument to sensor point, section 4.2) and the
virtual instrument (carriage origin to a sensor point) all call it.
"""

from __future__ import annotations

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_broadcast

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

    Raises
    ------
    AxiscalError
        If an argument does not have 3 components in its last dimension.

    Examples
    --------
    >>> transfer_point([0.0, 0.0, 0.0], [0.0, 0.0, 1e-5], [0.0, 0.1, 0.0])
    array([-1.e-06,  0.e+00,  0.e+00])
    """
    delta, eps, offset = (check_array(n, a, last=3) for n, a in (("delta_m", delta_m), ("eps_rad", eps_rad), ("offset_m", offset_m)))
    delta, eps, offset = check_broadcast(delta_m=delta, eps_rad=eps, offset_m=offset)
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

    Raises
    ------
    AxiscalError
        If ``offsets_m`` is not (3, 3), ``delta_m``, ``eps_rad`` do not end in 3 components or do
        not broadcast, or a value is not a finite number.

    Examples
    --------
    >>> import numpy as np
    >>> offsets = np.array([[0.0, 0.0, 0.1], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]])
    >>> transfer_components([0.0, 0.0, 0.0], [0.0, 1e-5, 0.0], offsets)
    array([1.e-06, 0.e+00, 0.e+00])
    """
    offsets = check_array("offsets_m", offsets_m)
    if offsets.shape != (3, 3):
        raise AxiscalError(f"offsets_m must have shape (3, 3), one row per component, got {offsets.shape}")
    eps = check_array("eps_rad", eps_rad, last=3)
    out = np.array(check_array("delta_m", delta_m, last=3), copy=True)
    out, eps = check_broadcast(delta_m=out, eps_rad=eps)
    return _transfer_components(out.copy(), eps, offsets)


def _transfer_components(out: np.ndarray, eps: np.ndarray, offsets: np.ndarray) -> np.ndarray:
    """:func:`transfer_components` on checked arrays of one shape (..., 3), ``out`` a copy it may change.

    The measurement pipeline's path: its arrays are built and checked once per batch, so the
    checks of the public function are not repeated there.
    """
    ea, eb, ec = eps[..., 0], eps[..., 1], eps[..., 2]
    # (eps x r)_x = eb rz - ec ry, (eps x r)_y = ec rx - ea rz, (eps x r)_z = ea ry - eb rx;
    # a zero arm adds nothing, so the common case (one offset per sensor) costs two products
    _, ry, rz = offsets[0]
    if ry or rz:
        out[..., 0] += eb * rz - ec * ry
    rx, _, rz = offsets[1]
    if rx or rz:
        out[..., 1] += ec * rx - ea * rz
    rx, ry, _ = offsets[2]
    if rx or ry:
        out[..., 2] += ea * ry - eb * rx
    return out
