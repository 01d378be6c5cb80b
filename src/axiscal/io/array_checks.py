"""Checks of arrays a public function is given: shape, finiteness and length, arrays of one length, arrays that broadcast together. :mod:`axiscal.io.arguments` gathers every check."""

from __future__ import annotations

from typing import Any

import numpy as np

from axiscal.errors import AxiscalError

from axiscal.io.scalar_checks import _of, _shown

__all__ = [
    "check_array",
    "check_same_length",
    "check_broadcast",
]


def check_array(
    name: str,
    values: Any,
    *,
    unit: str | None = None,
    ndim: int | None = None,
    min_len: int = 0,
    last: int | None = None,
    finite: bool = True,
    limit: float | None = None,
) -> np.ndarray:
    """``values`` as a float array, refused when not numbers, of the wrong shape or not finite.

    Parameters
    ----------
    name : str
        The argument's name, for the message.
    values : array_like
        Numbers (a NumPy array, list or scalar); not strings, None or bools.
    unit : str, optional
        The unit as the message says it; read from ``name`` when not given.
    ndim : int, optional
        The number of dimensions required (``1`` for a series).
    min_len : int
        The least number of entries along the first dimension (``0``: any, even empty).
    last : int, optional
        The length required of the last dimension (``3`` for points in space).
    finite : bool
        Refuse NaN and infinity (default).
    limit : float, optional
        The largest magnitude accepted: beyond it a value has no physical meaning and would
        overflow the arithmetic that follows.

    Returns
    -------
    ndarray of float

    Raises
    ------
    AxiscalError
        Naming ``name`` and what is wrong: not numbers, the shape, too few values, not finite.

    Examples
    --------
    >>> check_array("position_m", [0.0, 0.1], ndim=1, min_len=2)
    array([0. , 0.1])
    >>> check_array("position_m", [0.0, float("inf")], ndim=1)
    Traceback (most recent call last):
    ...
    axiscal.errors.AxiscalError: position_m must hold finite numbers of metres, not inf (entry 1)
    """
    raw = values
    if isinstance(raw, (str, bytes)) or raw is None:
        raise AxiscalError(f"{name} must be numbers{_of(name, unit)}, not {_shown(raw)}")
    try:
        array = np.asarray(raw)
        if array.dtype.kind in "bUSMmV" or array.dtype.kind == "O" and any(
            isinstance(v, (bool, np.bool_, str, bytes)) or v is None for v in array.ravel()
        ):
            raise TypeError
        array = np.asarray(array, dtype=float)
    except (TypeError, ValueError):
        raise AxiscalError(f"{name} must be numbers{_of(name, unit)}, not {_shown(raw)}") from None
    if ndim is not None and array.ndim != ndim:
        words = {0: "a single number", 1: "a one-dimensional array", 2: "a two-dimensional array"}.get(ndim, f"{ndim}-D")
        raise AxiscalError(f"{name} must be {words}, not of shape {array.shape}")
    if last is not None and (array.ndim == 0 or array.shape[-1] != last):
        raise AxiscalError(f"{name} must have {last} components in its last dimension, not shape {array.shape}")
    if min_len and (array.ndim == 0 or array.shape[0] < min_len):
        got = "a single number" if array.ndim == 0 else f"{array.shape[0]}"
        raise AxiscalError(f"{name} needs at least {min_len} values, got {got}")
    if finite and not np.all(np.isfinite(array)):
        where = int(np.argmax(~np.isfinite(array.ravel())))
        at = f" (entry {where})" if array.ndim else ""
        raise AxiscalError(f"{name} must hold finite numbers{_of(name, unit)}, not {array.ravel()[where]}{at}")
    if limit is not None and array.size and np.nanmax(np.abs(array)) > limit:
        raise AxiscalError(f"{name} holds {np.nanmax(np.abs(array)):g}, beyond any physical value (more than {limit:g}{_of(name, unit, ' ')})")
    return array


def check_same_length(**arrays: np.ndarray) -> int:
    """The common length of 1-D arrays, refused when they differ.

    Parameters
    ----------
    **arrays : ndarray
        The arrays by argument name (``None`` values are skipped).

    Returns
    -------
    int
        The common length (0 when none is given).

    Raises
    ------
    AxiscalError
        ``"position_m and deviation_m must have the same length, not 5 and 4"``.

    Examples
    --------
    >>> check_same_length(a_m=[1, 2], b_m=[3, 4])
    2
    """
    given = {k: len(v) for k, v in arrays.items() if v is not None}
    if len(set(given.values())) > 1:
        raise AxiscalError(f"{' and '.join(given)} must have the same length, not {' and '.join(map(str, given.values()))}")
    return next(iter(given.values()), 0)


def check_broadcast(**arrays: np.ndarray) -> list[np.ndarray]:
    """The arrays broadcast to one shape, refused when they do not match.

    Parameters
    ----------
    **arrays : ndarray
        The (already checked) arrays by argument name.

    Returns
    -------
    list of ndarray
        In the order given, all of the broadcast shape.

    Raises
    ------
    AxiscalError
        ``"length_m and misalignment_rad do not match in shape: (2,) and (3,)"``.

    Examples
    --------
    >>> [a.shape for a in check_broadcast(a_m=np.zeros((2, 1)), b_m=np.zeros(3))]
    [(2, 3), (2, 3)]
    """
    try:
        return list(np.broadcast_arrays(*arrays.values()))
    except ValueError:
        shapes = " and ".join(str(np.shape(a)) for a in arrays.values())
        names = ", ".join(arrays)
        raise AxiscalError(f"{names} do not match in shape: {shapes}") from None
