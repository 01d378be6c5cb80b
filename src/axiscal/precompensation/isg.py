"""The machine model written for the ISG kernel (Beckhoff TwinCAT CNC): a volumetric table on a grid, or axis tables.

Two ways of loading what the model knows into a TwinCAT CNC:

- **volumetric** (TF5280 Volumetric Compensation, ISG CSV file): the model's volumetric error
  ``e(q) = actual_point(q) - nominal_point(q)`` at every node q of a regular grid of axis
  positions, written as the component errors ``EXX, EYY, EZZ`` depending on the arguments
  ``X, Y, Z`` (the form of the manual's own example ``X Y Z EXX EYY``), with a compensation list
  that declares the machine's chain and its workpiece axes (``chain``, ``workpiece_axes``) and GRID
  interpolation. In the kernel's ISO 230-1 model a component error is the error motion of its own
  axis: a tool-side axis's ``EXX`` puts the tool off by ``+EXX`` along X, a workpiece-side axis's
  (it moves the workpiece) by ``-EXX``; and the kernel moves a workpiece-side axis the opposite
  way to move the tool, as the model does. So each column holds the error along its axis with the
  sign of its side (``EXX = -e_x`` for a table X), the tool error the kernel sees at a node is
  exactly ``e(q)``, and its correction moves every axis as :func:`precompensate_points` and the
  axis lists do. The error is written in the frame's directions (the directions the linear axes
  move in): on a machine whose rotary table stands at an angle, turned from the workpiece's.
- **axis** (leadscrew error compensation, ``kw.ssfk`` compensation value lists): for each linear
  axis its own positioning error (the component ``EXX`` of X, ``EYY`` of Y, ``EZZ`` of Z from the
  model's error tables) at the grid's points along it, one list per axis. Straightness, angular
  and squareness errors are not in these lists.

Use one or the other: both at once would compensate the positioning errors twice.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from axiscal.compensation.curve import ErrorCurve
from axiscal.compensation.isg import IsgTable, check_distinct_axis_numbers, volcomp_list_text
from axiscal.compensation.screwmaps import TwincatTable, twincat_table
from axiscal.conventions import AXIS_INDEX
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_choice, check_instance, check_path
from axiscal.io.atomic import write_text
from axiscal.io.jsonio import write_sidecar
from axiscal.model.machine import Machine, axis_positions_from_grid
from axiscal.precompensation.points import machine_with_tool
from axiscal.units import MM

__all__ = ["ISG_KINDS", "IsgExport", "isg_chain", "isg_volumetric_table", "isg_axis_tables", "export_isg", "parse_axis_numbers"]

#: what ``axiscal export grid --format`` writes for the ISG kernel
ISG_KINDS = ("volumetric", "axis")
_LINEAR = ("X", "Y", "Z")


@dataclass(frozen=True)
class IsgExport:
    """What :func:`export_isg` wrote.

    Attributes
    ----------
    kind : {"volumetric", "axis"}
    files : tuple of Path
        The files written (parameter file, compensation list and sidecar; or one list per axis).
    volumetric : IsgTable or None
        The volumetric table (kind "volumetric").
    axes : dict of str to TwincatTable
        The axis lists (kind "axis").
    largest_m : float
        Largest error written, metres.
    chain : str
        The list's ``chain`` (kind "volumetric"; see :func:`isg_chain`), else "".
    workpiece_axes : int
        The list's ``workpiece_axes`` (kind "volumetric"), else 0.
    """

    kind: str
    files: tuple[Path, ...]
    volumetric: IsgTable | None
    axes: dict[str, TwincatTable]
    largest_m: float
    chain: str = ""
    workpiece_axes: int = 0


def _grid(model: Machine, grid: str) -> tuple[dict[str, np.ndarray], list[str]]:
    """The grid's positions of every axis of the model (rotary axes at their one angle), and its linear axes."""
    check_instance("grid", grid, str)
    positions = axis_positions_from_grid(grid)
    for letter in positions:
        if letter not in model.letters:
            raise AxiscalError(f"grid '{grid}' names {letter}, not an axis of chain '{model.chain}'")
    linear = [k for k in _LINEAR if k in model.letters]
    missing = [k for k in linear if k not in positions]
    if missing:
        raise AxiscalError(f"grid '{grid}' must name every linear axis of chain '{model.chain}'; add {', '.join(missing)}")
    n = next(iter(positions.values())).size
    for letter in model.rotary:
        values = np.unique(positions.get(letter, np.zeros(1)))
        if values.size != 1:
            raise AxiscalError(f"grid '{grid}': rotary axis {letter} stands still; name it with one angle (e.g. {letter}=0)")
        positions[letter] = np.full(n, values[0])
    return positions, linear


def _rotation(letter: str, angle: float) -> np.ndarray:
    """The nominal rotation of a rotary axis (A, B, C about X, Y, Z, right-hand rule) by ``angle`` radians."""
    c, s = np.cos(angle), np.sin(angle)
    i = "ABC".index(letter)
    j, k = (i + 1) % 3, (i + 2) % 3
    rotation = np.eye(3)
    rotation[j, j], rotation[j, k], rotation[k, j], rotation[k, k] = c, -s, s, c
    return rotation


def isg_chain(machine: Machine | str) -> tuple[str, int]:
    """The machine's linear axes as the ISG kernel's compensation list declares them: ``chain``, ``workpiece_axes``.

    Parameters
    ----------
    machine : Machine or str
        The machine model or its description file.

    Returns
    -------
    chain : str
        The linear axes in the order of the machine's chain, from the workpiece to the tool
        (``"XFYZ"`` and ``"FXYZ"`` both give ``"XYZ"``, ``"YXFZ"`` gives ``"YXZ"``).
    workpiece_axes : int
        How many of them move the workpiece (1 for ``"XFYZ"``, 0 for ``"FXYZ"``).
    """
    model = machine_with_tool(machine, None)
    return ("".join(k for k in model.chain.upper() if k in _LINEAR),
            sum(1 for k in model.workpiece_side if k in _LINEAR))


def isg_volumetric_table(machine: Machine | str, grid: str, *, tool_m: tuple[float, float, float] | None = None) -> IsgTable:
    """The model's volumetric error on a grid as an ISG CSV block ``X Y Z EXX EYY EZZ``, for the list of :func:`isg_chain`.

    Parameters
    ----------
    machine : Machine or str
        The machine model or its description file.
    grid : str
        ``"X=0:800:50,Y=0:500:50,Z=0:300:50"`` (mm, ends inclusive, or one value); every linear
        axis of the machine is named; a rotary axis may be named with one angle in degrees.
    tool_m : sequence of 3 floats, optional, keyword-only
        The functional point in the last tool-side carriage's frame, metres (default: the machine's).

    Returns
    -------
    IsgTable
        Arguments: the machine's linear axes (metres); parameters ``E<D><D>`` for each of them: the
        volumetric error (tool relative to workpiece, in the frame's directions) along that axis,
        metres, negated for an axis on the workpiece side (the kernel's model mirrors it back).

    Raises
    ------
    AxiscalError
        A grid not of that form or that leaves out a linear axis, names an axis the machine does not
        have or a rotary axis with more than one angle; a rotary axis that carries a linear axis
        standing at an angle other than 0; a node outside an error table.

    Examples
    --------
    >>> table = isg_volumetric_table("examples/xfyz_machine/machine.toml", "X=50:750:350,Y=50:450:200,Z=50:350:150")  # doctest: +SKIP
    >>> table.parameters, table.parameter_si.shape  # doctest: +SKIP
    (('EXX', 'EYY', 'EZZ'), (27, 3))
    """
    model = machine_with_tool(machine, tool_m)
    positions, linear = _grid(model, grid)
    turned = np.eye(3)
    for side in (model.workpiece_side, model.tool_side):
        standing = [k for k in side if k in model.rotary and positions[k][0] != 0.0]
        for k in standing:
            carried = [a for a in side[side.index(k) + 1:] if a in _LINEAR]
            if carried:
                raise AxiscalError(f"grid '{grid}': rotary axis {k} carries {', '.join(carried)} in chain '{model.chain}';"
                                   f" the kernel's axes move along the frame's directions only with {k}=0")
    for k in model.workpiece_side:
        if k in model.rotary:
            turned = turned @ _rotation(k, float(positions[k][0]))
    error = model.volumetric_error({k: positions[k] for k in model.letters}) @ turned.T
    sign = {k: -1.0 if k in model.workpiece_side else 1.0 for k in linear}
    arguments = np.column_stack([positions[k] for k in linear])
    values = np.column_stack([sign[k] * error[:, AXIS_INDEX[k]] for k in linear])
    return IsgTable(tuple(linear), tuple(f"E{k}{k}" for k in linear), arguments, values)


def isg_axis_tables(machine: Machine | str, grid: str, *, axis_numbers: dict[str, int] | None = None) -> dict[str, TwincatTable]:
    """Each linear axis's own positioning error from the model, as a TwinCAT CNC ``kw.ssfk`` list.

    Parameters
    ----------
    machine : Machine or str
        The machine model or its description file.
    grid : str
        As :func:`isg_volumetric_table`; each linear axis's ``start:end:step`` gives its list's
        points (``kw_startpos``, ``interval``, ``kw_nr_max``), a whole number of 0.1 um apart.
    axis_numbers : dict of str to int, optional, keyword-only
        Logical axis number (``kopf.achs_nr``) of each axis (default X 1, Y 2, Z 3).

    Returns
    -------
    dict of str to TwincatTable
        One unilateral list per linear axis: the component ``E<D><D>`` of its error table
        (actual - setpoint), in 0.1 um.

    Raises
    ------
    AxiscalError
        As :func:`isg_volumetric_table`; an axis given one position only; a step that is not a
        whole number of 0.1 um; a point outside the axis's error table.
    """
    model = machine_with_tool(machine, None)
    positions, linear = _grid(model, grid)
    numbers = {"X": 1, "Y": 2, "Z": 3} if axis_numbers is None else dict(axis_numbers)
    check_distinct_axis_numbers(numbers)
    tables = {}
    for letter in linear:
        nodes = np.unique(positions[letter])
        if nodes.size < 2:
            raise AxiscalError(f"grid '{grid}' gives axis {letter} one position: a list needs its start:end:step")
        if letter not in numbers:
            raise AxiscalError(f"axis_numbers gives no logical axis number for {letter}")
        error = model.table(letter).evaluate(nodes)[AXIS_INDEX[letter]]
        tables[letter] = twincat_table(ErrorCurve(nodes, error, error), axis=letter, axis_number=numbers[letter],
                                       interval_m=float(nodes[1] - nodes[0]), bilateral=False)
    return tables


def parse_axis_numbers(text: str | None) -> dict[str, int] | None:
    """``"X=1,Y=2,Z=3"`` as a mapping of axis letters to logical axis numbers (None passes through).

    Parameters
    ----------
    text : str or None

    Returns
    -------
    dict of str to int or None

    Raises
    ------
    AxiscalError
        For a part not of the form ``LETTER=NUMBER`` with a whole number of at least 1, an axis
        named twice, or two axes given one number.
    """
    if text is None:
        return None
    check_instance("axis_numbers", text, str)
    numbers = {}
    for part in text.split(","):
        letter, sep, value = part.partition("=")
        letter = letter.strip().upper()
        if not sep or letter not in AXIS_INDEX or not value.strip().isdigit() or int(value) < 1:
            raise AxiscalError(f"axis_numbers must read like X=1,Y=2,Z=3 (whole numbers from 1), not {text[:40]!r}")
        if letter in numbers:
            raise AxiscalError(f"axis_numbers names {letter} twice")
        numbers[letter] = int(value)
    check_distinct_axis_numbers(numbers)
    return numbers


def export_isg(machine: Machine | str, grid: str, path: str | Path, *, kind: str = "volumetric",
               tool_m: tuple[float, float, float] | None = None, axis_numbers: dict[str, int] | None = None) -> IsgExport:
    """Write the model for the ISG kernel: what ``axiscal export grid --format isg`` and ``isg-axis`` do.

    Parameters
    ----------
    machine : Machine or str
        The machine model or its description file.
    grid : str
        See :func:`isg_volumetric_table`.
    path : str or Path
        kind "volumetric": the ISG CSV parameter file; its compensation list is written beside it
        as ``NAME.lis`` (naming the file by its name alone: copy both to the control's folder)
        and its sidecar as ``NAME.json``. kind "axis": the lists are ``STEM_X.lis``, ``STEM_Y.lis``,
        ... beside ``path``.
    kind : {"volumetric", "axis"}, keyword-only
        See the module's description.
    tool_m : sequence of 3 floats, optional, keyword-only
        The functional point (kind "volumetric"), metres (default: the machine's).
    axis_numbers : dict of str to int, optional, keyword-only
        Logical axis numbers (default X 1, Y 2, Z 3).

    Returns
    -------
    IsgExport

    Raises
    ------
    AxiscalError
        As :func:`isg_volumetric_table` and :func:`isg_axis_tables`; a file that cannot be written.
    """
    path = check_path("path", path)
    check_choice("kind", kind, ISG_KINDS)
    if kind == "axis":
        if tool_m is not None:
            raise AxiscalError("tool_m applies to the volumetric table, not to the axis lists")
        tables = isg_axis_tables(machine, grid, axis_numbers=axis_numbers)
        files = []
        for letter, table in tables.items():
            target = path.with_name(f"{path.stem}_{letter}.lis")
            write_text(target, table.text())
            files.append(target)
        largest = max(float(np.abs(t.pos).max()) for t in tables.values()) * 0.1e-6
        return IsgExport(kind, tuple(files), None, tables, largest)
    model = machine_with_tool(machine, tool_m)
    table = isg_volumetric_table(model, grid)
    listing = path.with_suffix(".lis")
    if listing == path:
        raise AxiscalError("the parameter file needs another suffix than .lis (its list is NAME.lis)", path=str(path))
    numbers = axis_numbers if axis_numbers is not None else {k: i + 1 for i, k in enumerate(_LINEAR) if k in table.arguments}
    if any(k not in numbers for k in table.arguments):
        raise AxiscalError(f"axis_numbers gives no logical axis number for {', '.join(k for k in table.arguments if k not in numbers)}")
    chain, workpiece_axes = isg_chain(model)
    extra = [k for k in numbers if k not in chain]
    if extra:
        raise AxiscalError(f"axis_numbers names {', '.join(extra)}, not a linear axis of chain '{model.chain}'")
    listing_text = volcomp_list_text([path.name], axis_numbers=numbers, workpiece_axes=workpiece_axes,
                                     interpolation="GRID", chain=chain)
    write_text(path, table.text())
    write_text(listing, listing_text)
    sidecar = write_sidecar(
        path, kind="ISG volumetric compensation", units={"arguments": "mm", "EXX, EYY, EZZ": "mm"},
        description="the model's volumetric error (actual - nominal tool point, in the frame's directions) at every grid"
                    " node, as the component errors EXX, EYY, EZZ of an ISG kernel with the list's chain and workpiece"
                    " axes (a workpiece-side axis's column negated: the kernel mirrors its errors) and GRID interpolation",
        grid=grid, machine=f"{model.name or model.chain} ({model.chain})", tool_mm=[v / MM for v in model.tool_m],
        compensation_list=listing.name, chain=chain, workpiece_axes=workpiece_axes,
    )
    return IsgExport(kind, (path, listing, sidecar), table, {}, float(np.abs(table.parameter_si).max()), chain,
                     workpiece_axes)
