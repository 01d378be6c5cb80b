"""Straightness files at the level of the commands: ISO 230-1 straightness of a profile file and multi-probe error separation from a readings file.

``axiscal straightness`` (:func:`evaluate_straightness_file`) and paper 001's error separation
(``axiscal separate``, :func:`separate_file`). This module is the top of the room's file work: the
readers it uses (:mod:`axiscal.straightness.readers`) and the simulated readings of ``axiscal
simulate probes`` (:mod:`axiscal.straightness.simulated`) sit below it, and their names are
importable from here too. Files are in the units their column names spell; everything returned is
SI. Data CSVs are written plain (header first, no comment lines) with a JSON sidecar holding their
metadata.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_instance, check_path
from axiscal.io.tabular import write_csv
from axiscal.straightness.readers import (
    Profile,
    _text_and_metadata,
    _write_data,
    read_probe_readings,
    read_profile,
    read_reversal_runs,
)
from axiscal.straightness.reference import ReferenceLine, reference_line
from axiscal.straightness.report import render_report
from axiscal.straightness.separation import METHODS, Separation, reversal, separate
from axiscal.straightness.simulated import MAX_READINGS, SimulatedReadings, simulate_probe_readings
from axiscal.units import ANGLE_UNITS, MM, UM

__all__ = [
    "SEPARATION_METHODS",
    "Profile",
    "read_profile",
    "read_probe_readings",
    "read_reversal_runs",
    "StraightnessEvaluation",
    "evaluate_straightness_file",
    "separation_columns",
    "SeparationRun",
    "separate_file",
    "MAX_READINGS",
    "SimulatedReadings",
    "simulate_probe_readings",
]

#: every method ``separate_file`` takes: those of :func:`separate` and ``"reversal"``
SEPARATION_METHODS = (*METHODS, "reversal")

URAD = ANGLE_UNITS["urad"]

# ---------------------------------------------------------------------------------------------
# axiscal straightness


@dataclass(frozen=True)
class StraightnessEvaluation:
    """The straightness of one profile file about its reference line.

    Attributes
    ----------
    profile : Profile
        The profile as read, metres.
    line : ReferenceLine
        The reference line and the straightness, SI.
    """

    profile: Profile
    line: ReferenceLine

    def __post_init__(self) -> None:
        check_instance("profile", self.profile, Profile, what="a Profile (read_profile)")
        check_instance("line", self.line, ReferenceLine, what="a ReferenceLine (reference_line)")

    def payload(self) -> dict[str, Any]:
        """The JSON object: ``straightness_um``, ``slope_urad``, ``intercept_um``, ``reference``."""
        return {
            "straightness_um": self.line.straightness_m / UM,
            "slope_urad": self.line.slope / URAD,
            "intercept_um": self.line.intercept_m / UM,
            "reference": self.line.reference,
        }

    def report(self) -> str:
        """The readable summary (three lines, um and urad)."""
        return render_report("straightness.txt.j2", **self.payload())


def evaluate_straightness_file(
    path: str | Path, *, reference: str = "least-squares", plot_path: str | Path | None = None
) -> StraightnessEvaluation:
    """Straightness of a profile file about a reference line (ISO 230-1), optionally plotted.

    Parameters
    ----------
    path : str or Path
        Profile CSV, read by :func:`read_profile`.
    reference : {"least-squares", "end-points", "minimum-zone"}, keyword-only
        Reference line (default least squares).
    plot_path : str or Path, optional, keyword-only
        Write the profile, its line and zone to this image (format from the suffix).

    Returns
    -------
    StraightnessEvaluation

    Raises
    ------
    AxiscalError
        A bad file (see :func:`read_profile`), an unknown reference, or a line that is not defined
        (end points: a repeated end position), naming the file.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "p.csv"
    >>> _ = path.write_text("position_mm,deviation_um\\n0,0\\n50,1\\n100,0\\n")
    >>> round(evaluate_straightness_file(path, reference="end-points").payload()["straightness_um"], 6)
    1.0
    """
    profile = read_profile(path)
    try:
        line = reference_line(profile.position_m, profile.deviation_m, reference=reference)
    except AxiscalError as exc:
        raise exc.located(path=path) from None
    if plot_path is not None:
        from axiscal.straightness.plot import plot_straightness

        plot_straightness(plot_path, profile.position_m, profile.deviation_m, line)
    return StraightnessEvaluation(profile, line)


# ---------------------------------------------------------------------------------------------
# axiscal separate


def _cells(values: np.ndarray, scale: float, fmt: str) -> list[str]:
    return ["" if not np.isfinite(v) else fmt.format(v / scale) for v in values]


def _separation(result: Separation, name: str) -> Separation:
    check_instance(name, result, Separation, what="a Separation (separate or reversal)")
    return result


def separation_columns(result: Separation) -> dict[str, list[str]]:
    """The columns a separation is written as.

    Parameters
    ----------
    result : Separation

    Returns
    -------
    dict of str to list of str
        ``position_mm``, ``profile_um``, ``motion_um`` and, when the method resolves yaw,
        ``yaw_urad``; an empty cell where a value is not resolved.
    """
    _separation(result, "result")
    columns = {
        "position_mm": _cells(result.position_m, MM, "{:.4f}"),
        "profile_um": _cells(result.profile_m, UM, "{:.5f}"),
        "motion_um": _cells(result.motion_m, UM, "{:.5f}"),
    }
    if np.any(np.isfinite(result.yaw_rad)):
        columns["yaw_urad"] = _cells(result.yaw_rad, URAD, "{:.5f}")
    return columns


@dataclass(frozen=True)
class SeparationRun:
    """A separation computed from files.

    Attributes
    ----------
    separation : Separation
        The result, SI.
    csv_text : str
        The CSV as written (header first, no comment lines).
    metadata : dict
        What the sidecar holds besides kind, units and sources: method, lost wavelengths (mm).
    """

    separation: Separation
    csv_text: str
    metadata: dict[str, Any]

    def __post_init__(self) -> None:
        _separation(self.separation, "separation")
        _text_and_metadata(self.csv_text, self.metadata)


def separate_file(
    readings_path: str | Path,
    *,
    method: str = "combined",
    spacing_ab_m: float | None = None,
    spacing_bc_m: float | None = None,
    reversed_path: str | Path | None = None,
    probes: int | None = None,
    min_gain: float = 0.05,
    parabola: bool = True,
    calibration_m: tuple[float, float] | None = None,
    output: str | Path | None = None,
    plot_path: str | Path | None = None,
) -> SeparationRun:
    """Separate workpiece profile and slide motion from a readings file (paper 001).

    Parameters
    ----------
    readings_path : str or Path
        Readings (``position_mm, a_um, b_um[, c_um]``); for ``method="reversal"`` the normal run
        (``position_mm, a_um``).
    method : str, keyword-only
        One of :data:`SEPARATION_METHODS` (default ``"combined"``).
    spacing_ab_m, spacing_bc_m : float, keyword-only
        Probe spacings A-B and B-C, metres (B-C defaults to A-B); needed by every method but
        reversal.
    reversed_path : str or Path, keyword-only
        Reversal: the run with the workpiece turned over.
    probes, min_gain, parabola, calibration_m : keyword-only
        Passed to :func:`axiscal.straightness.separation.separate`.
    output : str or Path, optional, keyword-only
        Write the CSV (``position_mm, profile_um, motion_um[, yaw_urad]``) here, with its JSON
        sidecar beside it. The CSV is a valid input of :func:`evaluate_straightness_file`.
    plot_path : str or Path, optional, keyword-only
        Write a plot of the separated profile and motion.

    Returns
    -------
    SeparationRun

    Raises
    ------
    AxiscalError
        A bad file, a missing spacing or reversed run, or readings the method cannot separate
        (naming the file).
    """
    check_path("readings_path", readings_path)
    if not isinstance(method, str) or method not in SEPARATION_METHODS:
        raise AxiscalError(f"unknown separation method {method!r}; use one of {', '.join(SEPARATION_METHODS)}")
    if method == "reversal":
        if reversed_path is None:
            raise AxiscalError("the reversal method needs reversed_path: the run with the workpiece turned over")
        result = reversal(*read_reversal_runs(readings_path, reversed_path))
        sources = [readings_path, reversed_path]
    else:
        if spacing_ab_m is None:
            raise AxiscalError(f"the {method} method needs spacing_ab_m, the probe spacing A-B")
        data = read_probe_readings(readings_path, spacing_ab_m=spacing_ab_m, spacing_bc_m=spacing_bc_m)
        try:
            result = separate(
                data, method=method, probes=probes, min_gain=min_gain, parabola=parabola, calibration_m=calibration_m
            )
        except AxiscalError as exc:
            raise exc.located(path=readings_path) from None
        sources = [readings_path]
    metadata: dict[str, Any] = {
        "method": result.method,
        "note": "profile and motion up to a common straight line",
        "lost_wavelength_mm": (np.sort(result.lost_wavelength_m)[::-1] / MM).tolist(),
    }
    text = write_csv(None, separation_columns(result))
    if output is not None:
        _write_data(output, text, kind="separation", sources=sources, **metadata)
    if plot_path is not None:
        from axiscal.straightness.plot import plot_separation

        plot_separation(plot_path, result)
    return SeparationRun(result, text, metadata)
