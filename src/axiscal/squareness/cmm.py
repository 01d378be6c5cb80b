"""Squareness of a three-axis CMM (paper 004): the file-level call of ``axiscal cmm compensate``, and every name of the room's CMM work.

The compensation model of eq (6) and the squareness from PSD runs are
:mod:`axiscal.squareness.cmm_squareness` (with the signs stated there); the gauge block check that
verifies it is :mod:`axiscal.squareness.gauge_blocks`. This module, the top of the two, reads and
writes the files, and its names stay importable from here.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_path
from axiscal.io.atomic import write_text
from axiscal.io.jsonio import write_sidecar
from axiscal.io.tabular import read_csv, write_csv
from axiscal.squareness.cmm_squareness import (
    MAX_CMM_SQUARENESS_ARCMIN,
    PAPER_004_SQUARENESS_ARCMIN,
    CmmSquareness,
    _squareness,
    compensate,
    psd_squareness,
    readings_for,
    squareness_from_psd_runs,
)
from axiscal.squareness.gauge_blocks import (
    PAPER_004_GAUGE_BLOCKS_MM,
    PAPER_004_IMPROVEMENT_UM,
    GaugeBlockCheck,
    GaugeBlockStudy,
    Plane,
    gauge_block_length,
    gauge_block_study,
    least_squares_plane,
    simulate_gauge_block,
)
from axiscal.units import ARCMIN, MM

__all__ = [
    "PAPER_004_IMPROVEMENT_UM",
    "PAPER_004_SQUARENESS_ARCMIN",
    "PAPER_004_GAUGE_BLOCKS_MM",
    "MAX_CMM_SQUARENESS_ARCMIN",
    "CmmSquareness",
    "compensate",
    "readings_for",
    "psd_squareness",
    "squareness_from_psd_runs",
    "Plane",
    "least_squares_plane",
    "gauge_block_length",
    "GaugeBlockCheck",
    "simulate_gauge_block",
    "CmmCompensation",
    "compensate_file",
    "GaugeBlockStudy",
    "gauge_block_study",
]


@dataclass(frozen=True)
class CmmCompensation:
    """Points of a file moved by eq (6) of paper 004 (or its inverse).

    Attributes
    ----------
    points_m : ndarray, shape (n, 3)
        The points as read, metres.
    moved_m : ndarray, shape (n, 3)
        Corrected coordinates (or, inverse, the readings the CMM shows), metres.
    csv_text : str
        The CSV: the input's columns as they were, then ``x_corrected_mm, y_corrected_mm,
        z_corrected_mm`` (inverse: ``*_reading_mm``).
    metadata : dict
        What the sidecar holds besides kind and sources: the model, a_xy, a_xz, a_yz in arcmin.
    """

    points_m: np.ndarray
    moved_m: np.ndarray
    csv_text: str
    metadata: dict[str, Any]


def compensate_file(
    points_path: str | Path,
    squareness: CmmSquareness,
    *,
    inverse: bool = False,
    output: str | Path | None = None,
) -> CmmCompensation:
    """Correct the CMM readings of a file by eq (6) of paper 004, or go the other way.

    Parameters
    ----------
    points_path : str or Path
        CSV with ``x_mm, y_mm, z_mm`` (other columns are carried through).
    squareness : CmmSquareness
        a_xy, a_xz, a_yz, radians.
    inverse : bool, keyword-only
        From true coordinates to the readings the CMM shows (:func:`readings_for`).
    output : str or Path, optional, keyword-only
        Write the CSV here, with its JSON sidecar.

    Returns
    -------
    CmmCompensation

    Raises
    ------
    AxiscalError
        Missing file or column, or a cell that is not a finite number (naming file and line).
    """
    squareness = _squareness(squareness)
    if not isinstance(inverse, (bool, np.bool_)):
        raise AxiscalError(f"inverse must be True or False, not {inverse!r}")
    table = read_csv(check_path("points_path", points_path))
    table.require("x_mm", "y_mm", "z_mm")
    points = np.column_stack([table.numeric(name) for name in ("x_mm", "y_mm", "z_mm")]) * MM
    moved = readings_for(points, squareness) if inverse else compensate(points, squareness)
    suffix = "reading" if inverse else "corrected"
    columns: dict[str, Any] = {name: table.text(name) for name in table.header}
    for k, axis in enumerate("xyz"):
        columns[f"{axis}_{suffix}_mm"] = moved[:, k] / MM
    text = write_csv(None, columns, fmt="{:.6f}")
    metadata: dict[str, Any] = {
        "model": f"paper 004 eq (6){' inverse' if inverse else ''}",
        "squareness_arcmin": {
            "a_xy": squareness.xy_rad / ARCMIN,
            "a_xz": squareness.xz_rad / ARCMIN,
            "a_yz": squareness.yz_rad / ARCMIN,
        },
        "iso_terms_arcmin": {term: value / ARCMIN for term, value in squareness.iso().items()},
    }
    if output is not None:
        write_text(output, text)
        write_sidecar(output, kind="cmm compensation", sources=[points_path], **metadata)
    return CmmCompensation(points, moved, text, metadata)
