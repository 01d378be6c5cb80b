"""Level run files: the reader, the evaluation behind ``axiscal levels`` and the profile it writes.

ISO 230-1 straightness and angular error motion from electronic level readings (see
:mod:`axiscal.levels.profile`). A run file has ``position_mm`` (where the rear foot stood) and the
reading as ``angle_arcsec``, ``angle_urad`` or ``angle_um_per_m``, optionally
``reference_<same unit>`` from a second level on a fixed part of the machine. The profile written
(``position_mm, deviation_um``, with a JSON sidecar) is a profile :func:`axiscal.straightness.read_profile`
reads.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_instance, check_number, check_path, check_same_length, render_checked
from axiscal.io.jsonio import write_sidecar
from axiscal.io.tabular import read_csv, write_csv
from axiscal.io.templates import render_template
from axiscal.levels.profile import LevelProfile, level_profile
from axiscal.straightness.reference import REFERENCES, ReferenceLine, reference_line
from axiscal.units import ARCSEC, MM, UM, URAD

__all__ = ["ANGLE_COLUMNS", "LevelRun", "read_level_run", "LevelEvaluation", "evaluate_levels"]

#: the reading's column name -> radians per unit (um/m is a slope: 1e-6 rad)
ANGLE_COLUMNS = {"angle_arcsec": ARCSEC, "angle_urad": URAD, "angle_um_per_m": 1e-6}


@dataclass(frozen=True)
class LevelRun:
    """A level run read from a file, SI.

    Attributes
    ----------
    position_m : ndarray, shape (n,)
        Rear-foot positions, metres.
    angle_rad : ndarray, shape (n,)
        Readings, radians (slopes).
    reference_rad : ndarray, shape (n,) or None
        The reference level's readings, radians; None without a ``reference_`` column.
    unit : str
        The unit the file spells (``"arcsec"``, ``"urad"`` or ``"um_per_m"``).
    path : str
        The file.
    """

    position_m: np.ndarray
    angle_rad: np.ndarray
    reference_rad: np.ndarray | None
    unit: str
    path: str

    def __post_init__(self) -> None:
        object.__setattr__(self, "position_m", check_array("position_m", self.position_m, ndim=1))
        object.__setattr__(self, "angle_rad", check_array("angle_rad", self.angle_rad, ndim=1))
        if self.reference_rad is not None:
            object.__setattr__(self, "reference_rad", check_array("reference_rad", self.reference_rad, ndim=1))
        check_same_length(position_m=self.position_m, angle_rad=self.angle_rad, reference_rad=self.reference_rad)
        check_path("path", self.path)


def read_level_run(path: str | Path) -> LevelRun:
    """Read a level run: ``position_mm`` and one ``angle_<unit>`` column, optionally ``reference_<unit>``.

    Parameters
    ----------
    path : str or Path
        The CSV file.

    Returns
    -------
    LevelRun

    Raises
    ------
    AxiscalError
        A missing file or column, no angle column or more than one, a reference column in another
        unit, a cell that is not a finite number, fewer than 2 rows, or a position not above the
        one before; each naming the file and, where there is one, the line.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "run.csv"
    >>> _ = path.write_text("position_mm,angle_um_per_m\\n0,2\\n100,-1\\n")
    >>> read_level_run(path).angle_rad.tolist()
    [2e-06, -1e-06]
    """
    table = read_csv(check_path("path", path), min_rows=2)
    table.require("position_mm")
    found = [name for name in ANGLE_COLUMNS if table.has(name)]
    if len(found) != 1:
        problem = "no reading column" if not found else f"more than one reading column ({', '.join(found)})"
        raise AxiscalError(f"{problem}: give one of {', '.join(ANGLE_COLUMNS)}", path=table.path, line=table.header_line)
    name = found[0]
    unit = name.removeprefix("angle_")
    others = [c for c in table.header if c.startswith("reference_") and c != f"reference_{unit}"]
    if others:
        raise AxiscalError(f"column '{others[0]}': the reference level is read in the unit of the reading ({name}),"
                           f" as reference_{unit}", path=table.path, line=table.header_line)
    position = table.numeric("position_mm") * MM
    steps = np.diff(position)
    if np.any(steps <= 0.0):
        k = int(np.flatnonzero(steps <= 0.0)[0]) + 1
        raise AxiscalError("positions must increase", path=table.path, line=table.lines[k])
    factor = ANGLE_COLUMNS[name]
    reference = table.numeric(f"reference_{unit}") * factor if table.has(f"reference_{unit}") else None
    return LevelRun(position, table.numeric(name) * factor, reference, unit, table.path)


@dataclass(frozen=True)
class LevelEvaluation:
    """The profile of a level run and its straightness about a reference line.

    Attributes
    ----------
    run : LevelRun
        The readings as read.
    profile : LevelProfile
        The integrated profile and the corrected angles, SI.
    line : ReferenceLine
        The profile's reference line and straightness (ISO 230-1), SI.
    """

    run: LevelRun
    profile: LevelProfile
    line: ReferenceLine

    def __post_init__(self) -> None:
        check_instance("run", self.run, LevelRun, what="a LevelRun (read_level_run)")
        check_instance("profile", self.profile, LevelProfile, what="a LevelProfile (level_profile)")
        check_instance("line", self.line, ReferenceLine, what="a ReferenceLine (reference_line)")

    def payload(self) -> dict[str, Any]:
        """The JSON object: the straightness as ``axiscal straightness`` gives it, and the angles.

        Returns
        -------
        dict
            ``straightness_um``, ``slope_urad``, ``intercept_um``, ``reference``,
            ``angular_error_urad``, ``angular_error_arcsec``, ``foot_mm``, ``integration``,
            ``readings``, ``differential``.
        """
        p = self.profile
        return {
            "straightness_um": self.line.straightness_m / UM,
            "slope_urad": self.line.slope / URAD,
            "intercept_um": self.line.intercept_m / UM,
            "reference": self.line.reference,
            "angular_error_urad": p.angular_error_rad / URAD,
            "angular_error_arcsec": p.angular_error_rad / ARCSEC,
            "foot_mm": p.foot_m / MM,
            "integration": p.integration,
            "readings": int(p.angle_rad.size),
            "differential": self.run.reference_rad is not None,
        }

    def profile_columns(self) -> dict[str, np.ndarray]:
        """The profile as written by ``-o``: ``position_mm`` and ``deviation_um``."""
        return {"position_mm": self.profile.position_m / MM, "deviation_um": self.profile.deviation_m / UM}

    def report(self) -> str:
        """The readable summary (um, urad and arcsec)."""
        return render_checked(render_template, "levels.txt.j2", **self.payload()).rstrip("\n")


def evaluate_levels(
    path: str | Path,
    *,
    foot_m: float,
    reference: str = "least-squares",
    output: str | Path | None = None,
) -> LevelEvaluation:
    """Straightness and angular error motion of a level run file (what ``axiscal levels`` does).

    Parameters
    ----------
    path : str or Path
        The run, read by :func:`read_level_run`.
    foot_m : float, keyword-only
        The level's foot spacing, metres.
    reference : {"least-squares", "end-points", "minimum-zone"}, keyword-only
        The reference line of the straightness (default least squares).
    output : str or Path, optional, keyword-only
        Write the profile (``position_mm, deviation_um``) here, with its JSON sidecar.

    Returns
    -------
    LevelEvaluation

    Raises
    ------
    AxiscalError
        A bad file (see :func:`read_level_run`), a foot spacing that is not a positive number, an
        unknown reference line; naming the file.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "run.csv"
    >>> _ = path.write_text("position_mm,angle_urad\\n0,10\\n100,0\\n200,-10\\n")
    >>> round(evaluate_levels(path, foot_m=0.1, reference="end-points").payload()["straightness_um"], 6)
    1.0
    """
    foot_m = check_number("foot_m", foot_m, positive=True)
    if not isinstance(reference, str) or reference not in REFERENCES:
        raise AxiscalError(f"unknown reference line {reference!r}; use one of {', '.join(REFERENCES)}")
    if output is not None:
        check_path("output", output)
    run = read_level_run(path)
    try:
        profile = level_profile(run.position_m, run.angle_rad, foot_m=foot_m, reference_rad=run.reference_rad)
        line = reference_line(profile.position_m, profile.deviation_m, reference=reference)
    except AxiscalError as exc:
        raise exc.located(path=path) from None
    evaluation = LevelEvaluation(run, profile, line)
    if output is not None:
        write_csv(output, evaluation.profile_columns(), fmt={"position_mm": "{:.4f}", "deviation_um": "{:.5f}"})
        write_sidecar(output, kind="straightness profile from levels", sources=[path], foot_mm=foot_m / MM,
                      integration=profile.integration, differential=run.reference_rad is not None,
                      method="ISO 230-1, level readings integrated over the foot spacing")
    return evaluation
