"""The pre-compensation on a regular 3D grid, for controls and tools that interpolate a table themselves.

At every grid point q (programmed X, Y, Z axis positions; rotary axes standing at given angles) the
correction is ``c - q`` with c the pre-compensated command of :func:`precompensate_points` (the
machine model's inverse): command ``q + correction`` and the tool lands on the nominal point of q.
The file is a plain CSV, one row per grid point, the first axis named in the grid varying slowest
and the last fastest (C order), with the grid's layout in its JSON sidecar.

Siemens VCS and HEIDENHAIN KinematicsComp take their volumetric tables from the maker's own tools,
and the printer firmware (Marlin, Klipper, RepRapFirmware) take 2D bed meshes of Z only; the one
public volumetric format, the ISG kernel's (TwinCAT CNC), is written by
:mod:`axiscal.precompensation.isg`.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_instance, check_path
from axiscal.io.jsonio import write_sidecar
from axiscal.io.tabular import write_csv
from axiscal.model.machine import Machine, axis_positions_from_grid
from axiscal.precompensation.points import machine_with_tool, precompensate_points
from axiscal.units import MM, UM

__all__ = ["CorrectionGrid", "correction_grid", "write_correction_grid", "export_correction_grid", "GRID_COLUMNS"]

#: the columns of the grid file
GRID_COLUMNS = ("x_mm", "y_mm", "z_mm", "x_correction_um", "y_correction_um", "z_correction_um")
_LINEAR = ("X", "Y", "Z")


@dataclass(frozen=True)
class CorrectionGrid:
    """The correction at every point of a regular grid (SI).

    Attributes
    ----------
    axes_m : dict of str to ndarray
        The values of each gridded axis, in the order the grid names them (metres; radians for
        a rotary axis named with one value).
    programmed_m : ndarray, shape (N, 3)
        X, Y, Z of every grid point, C order over ``axes_m`` (the last axis varies fastest), metres.
    correction_m : ndarray, shape (N, 3)
        Command minus programmed position at every point, metres (0 for an axis the machine lacks).
    machine : str
        The machine model's name and chain.
    tool_m : tuple of 3 floats
        The functional point used, metres.
    """

    axes_m: dict[str, np.ndarray]
    programmed_m: np.ndarray
    correction_m: np.ndarray
    machine: str
    tool_m: tuple[float, float, float]


def correction_grid(machine: Machine | str, grid: str, *, tool_m: tuple[float, float, float] | None = None) -> CorrectionGrid:
    """The pre-compensation correction on a regular grid of programmed points.

    Parameters
    ----------
    machine : Machine or str
        The machine model or its description file.
    grid : str
        ``"X=0:800:50,Y=0:500:50,Z=0:300:50"``: per axis ``start:end:step`` in mm, ends inclusive, or
        one value; every linear axis of the machine is named; a rotary axis of the machine may be
        named with one angle in degrees (``"C=90"``; default 0).
    tool_m : sequence of 3 floats, optional, keyword-only
        The functional point in the last tool-side carriage's frame, metres (default: the machine's).

    Returns
    -------
    CorrectionGrid

    Raises
    ------
    AxiscalError
        A grid that is not of that form, that leaves out a linear axis of the machine, names an
        axis the machine does not have or a rotary axis with more than one angle, or a point whose
        command leaves the error tables (naming it).

    Examples
    --------
    >>> result = correction_grid("examples/xfyz_machine/machine.toml", "X=50:750:100,Y=50:450:100,Z=50:350:100")  # doctest: +SKIP
    >>> result.correction_m.shape  # doctest: +SKIP
    (160, 3)
    """
    model = machine_with_tool(machine, tool_m)
    check_instance("grid", grid, str)
    positions = axis_positions_from_grid(grid)
    named = [part.partition("=")[0].strip().upper() for part in grid.split(",")]
    for letter in named:
        if letter not in model.letters:
            raise AxiscalError(f"grid '{grid}' names {letter}, not an axis of chain '{model.chain}'")
    linear = [k for k in model.letters if k not in model.rotary]
    missing = [k for k in linear if k not in positions]
    if missing:
        raise AxiscalError(f"grid '{grid}' must name every linear axis of chain '{model.chain}'; add {', '.join(missing)}")
    rotary = {}
    for letter in model.rotary:
        values = np.unique(positions.get(letter, np.zeros(1)))
        if values.size != 1:
            raise AxiscalError(f"grid '{grid}': rotary axis {letter} stands still; name it with one angle (e.g. {letter}=0)")
        rotary[letter] = float(values[0])
    n = next(iter(positions.values())).size
    points = np.column_stack([positions.get(k, np.zeros(n)) for k in _LINEAR])
    try:
        result = precompensate_points(model, points, rotary_rad=rotary)
    except AxiscalError as error:
        if not error.message.startswith("point "):
            raise
        index = int(error.message.split(":", 1)[0].split()[1]) - 1
        where = ", ".join(f"{k}={points[index, i] / MM:g}" for i, k in enumerate(_LINEAR) if k in linear)
        raise AxiscalError(f"grid point {index + 1} ({where} mm){error.message.partition(':')[1]}"
                           f"{error.message.partition(':')[2]}; keep the grid inside the error tables") from None
    axes = {k: np.unique(positions[k]) for k in named}
    return CorrectionGrid(axes, points, result.correction_m, f"{model.name or model.chain} ({model.chain})", tuple(model.tool_m))


def write_correction_grid(result: CorrectionGrid, path: str | Path) -> list[Path]:
    """Write the grid as a plain CSV with its JSON sidecar, atomically.

    Parameters
    ----------
    result : CorrectionGrid
    path : str or Path
        The CSV; the sidecar is ``NAME.json`` beside it.

    Returns
    -------
    list of Path
        The CSV and the sidecar.

    Raises
    ------
    AxiscalError
        For a file that cannot be written.
    """
    check_instance("result", result, CorrectionGrid)
    path = check_path("path", path)
    columns = {name: result.programmed_m[:, i] / MM for i, name in enumerate(GRID_COLUMNS[:3])}
    columns |= {name: result.correction_m[:, i] / UM for i, name in enumerate(GRID_COLUMNS[3:])}
    write_csv(path, columns, fmt={**{c: "{:.4f}" for c in GRID_COLUMNS[:3]}, **{c: "{:.4f}" for c in GRID_COLUMNS[3:]}})
    layout = {}
    for letter, values in result.axes_m.items():
        if letter in "ABC":
            layout[letter] = {"angle_deg": round(float(np.degrees(values[0])), 9)}
        else:
            step = float(values[1] - values[0]) / MM if values.size > 1 else 0.0
            layout[letter] = {"start_mm": round(float(values[0]) / MM, 9), "step_mm": round(step, 9), "count": int(values.size)}
    sidecar = write_sidecar(
        path,
        kind="pre-compensation grid",
        units={"x_correction_um": "um, command minus programmed X", "y_correction_um": "um, command minus programmed Y",
               "z_correction_um": "um, command minus programmed Z"},
        description="command = programmed + correction puts the tool on the nominal point of the programmed one",
        order="C: the first axis of 'grid' varies slowest, the last fastest",
        grid=layout,
        machine=result.machine,
        tool_mm=[v / MM for v in result.tool_m],
    )
    return [path, sidecar]


def export_correction_grid(
    machine: Machine | str, grid: str, path: str | Path, *, tool_m: tuple[float, float, float] | None = None
) -> CorrectionGrid:
    """:func:`correction_grid` written to ``path`` (CSV and sidecar): what ``axiscal export grid`` does.

    Parameters
    ----------
    machine, grid, tool_m :
        See :func:`correction_grid`.
    path : str or Path
        The CSV.

    Returns
    -------
    CorrectionGrid

    Raises
    ------
    AxiscalError
        As :func:`correction_grid` and :func:`write_correction_grid`.
    """
    check_path("path", path)
    result = correction_grid(machine, grid, tool_m=tool_m)
    write_correction_grid(result, path)
    return result
