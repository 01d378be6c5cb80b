"""The fault bits of a measured frame: one flag set for the measurement system and the live pipeline.

A frame's ``fault`` column is an integer made of these bits (0: good). The values are those of
every record written so far, so old records keep their meaning:

======  ==========  =========================================================================
 bit     value       meaning
======  ==========  =========================================================================
 0       1           a channel is missing (NaN, empty cell or absent column)
 1       2           a channel is outside its valid range
 2       4           an axis' commanded position is outside the travel the error model covers
 8       256         the line or row could not be read as a frame (no readable time stamp, or
                     more fields than columns)
======  ==========  =========================================================================
"""

from __future__ import annotations

import enum
from collections.abc import Mapping

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_count, check_mapping, check_same_length

__all__ = ["Fault", "FAULT_TEXT", "fault_text", "fault_legend", "mark_malformed"]


class Fault(enum.IntFlag):
    """Fault bits of one frame; combine with ``|``, test with ``&``.

    Attributes
    ----------
    MISSING : int
        1: a channel is missing.
    RANGE : int
        2: a channel is outside its valid range.
    POSITION : int
        4: a commanded position is outside the error model's travel.
    MALFORMED : int
        256: the line or row could not be read as a frame.

    Examples
    --------
    >>> int(Fault.MISSING | Fault.POSITION)
    5
    >>> fault_text(Fault.MISSING | Fault.POSITION)
    'missing channel; position outside the error model'
    """

    MISSING = 1
    RANGE = 2
    POSITION = 4
    MALFORMED = 256


#: each fault bit in words, in the order :func:`fault_text` names them (an unreadable frame first)
FAULT_TEXT: dict[Fault, str] = {
    Fault.MALFORMED: "malformed frame (no readable time stamp, or more fields than columns)",
    Fault.MISSING: "missing channel",
    Fault.RANGE: "channel out of range",
    Fault.POSITION: "position outside the error model",
}


def fault_text(fault: int) -> str:
    """The fault bits of a frame in words.

    Parameters
    ----------
    fault : int
        The frame's fault bits.

    Returns
    -------
    str
        ``"ok"`` for 0, otherwise the meaning of each bit set, joined by ``"; "`` (bits no
        :class:`Fault` names are given in hexadecimal).

    Examples
    --------
    >>> fault_text(0)
    'ok'
    >>> fault_text(2)
    'channel out of range'
    """
    fault = check_count("fault", fault, minimum=0)
    if fault == 0:
        return "ok"
    words = [text for bit, text in FAULT_TEXT.items() if fault & bit]
    unknown = fault & ~sum(int(bit) for bit in FAULT_TEXT)
    if unknown:
        words.append(f"unknown fault bits {unknown:#x}")
    return "; ".join(words)


def fault_legend() -> dict[str, str]:
    """Every fault bit's value (as text, for JSON keys) and meaning, for a record's or result's metadata.

    Returns
    -------
    dict of str to str
        ``{"1": "missing channel", "2": ..., "4": ..., "256": ...}``.
    """
    return {str(int(bit)): FAULT_TEXT[bit] for bit in sorted(FAULT_TEXT)}


def mark_malformed(results: Mapping[str, np.ndarray], malformed: np.ndarray) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    """Add :attr:`Fault.MALFORMED` to the frames that could not be read, and blank their results.

    Parameters
    ----------
    results : mapping of str to ndarray, shape (N,)
        What :meth:`~axiscal.measurement.pipeline.MeasurementSystem.process` returned (``"t_s"``,
        ``"fault"`` and the SI results).
    malformed : ndarray of bool, shape (N,)
        Frames whose line or row could not be read as a frame.

    Returns
    -------
    fault : ndarray of int64, shape (N,)
        The fault bits with bit 256 where malformed.
    results : dict of str to ndarray
        The results, NaN where malformed (``t_s`` and ``fault`` as they were).

    Examples
    --------
    >>> fault, out = mark_malformed({"t_s": np.array([0.0, np.nan]), "fault": np.array([0, 0]), "e_m": np.array([1e-6, 2e-6])}, np.array([False, True]))
    >>> fault.tolist(), out["e_m"].tolist()
    ([0, 256], [1e-06, nan])
    """
    check_mapping("results", results, ("fault",), what="the results of MeasurementSystem.process (with 'fault')")
    flags = np.asarray(malformed)
    if flags.ndim != 1 or flags.dtype != bool:
        raise AxiscalError(f"malformed must be a one-dimensional array of bool, one per frame, not {malformed!r}"[:200])
    fault = np.asarray(results["fault"])
    if fault.ndim != 1 or fault.dtype.kind not in "iu":
        raise AxiscalError("results['fault'] must be a one-dimensional array of fault bits (integers)")
    columns = {name: check_array(f"results['{name}']", value, ndim=1, finite=False) for name, value in results.items() if name != "fault"}
    check_same_length(malformed=flags, fault=fault, **columns)
    malformed = flags
    fault = fault.astype(np.int64) | np.where(malformed, int(Fault.MALFORMED), 0)
    if not malformed.any():
        return fault, dict(results)
    return fault, {name: value if name in ("t_s", "fault") else np.where(malformed, np.nan, value) for name, value in results.items()}
