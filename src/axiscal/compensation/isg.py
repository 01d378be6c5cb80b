"""Beckhoff TwinCAT CNC / ISG kernel volumetric compensation files: the ISG CSV parameter file and its list.

The ISG kernel (Beckhoff TwinCAT CNC, TF5280 Volumetric Compensation) takes the machine's error
parameters, named as in ISO 230-1 (component errors ``EXX, EYX, ... ECC``; position errors
``X0Y, ... C0C``), from parameter files named in a compensation list (``file[j]``,
``file_format[j]``). Its "ISG CSV" file format, as the public manual describes it:

- a header row names the columns: arguments (``X, Y, Z`` in mm, ``A, B, C`` in degrees) and
  error parameters; the rows below hold the records, columns separated by blanks;
- row comments start with ``//``; a ``#`` starts a new block with its own header ("file break");
- parameter values are in millimetres for offsets and radians for angles;
- with ``interpolation GRID`` (the default) the records must lie on a grid and are linearly
  interpolated between its nodes.

:class:`IsgTable` is one block in SI units; :meth:`IsgTable.text` writes it and
:func:`read_isg_csv` reads every block of a file back. :func:`volcomp_list_text` writes the
compensation list that names the file (``chain``, ``workpiece_axes``, ``X 1``, ``Y 2``, ``Z 3``,
``interpolation``, ``file[0]``, ``file_format[0] ISG_CSV``), as in the manual's example.

The list's ``chain`` (P-VOLC-00007) orders the axes from the workpiece to the tool, as ISO 230-1
writes a chain (the manual's machine with its B and C axes in the workpiece is ``CBYXZ``), and
``workpiece_axes`` (P-VOLC-00008, default 0: every axis in the tool) says how many of them, from the
start of the chain, lie on the workpiece side. The manual's rule: treat an axis as the measurement
treated it. An error parameter is the error motion of its own axis: a workpiece-side axis moves the
workpiece, so its errors move the tool relative to the workpiece the opposite way.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_mapping
from axiscal.io.arguments import check_instance, check_integer, check_path
from axiscal.io.tabular import read_text
from axiscal.units import MM

__all__ = ["ISG_ARGUMENTS", "IsgTable", "read_isg_csv", "parse_isg_csv", "volcomp_list_text", "grid_values",
           "check_distinct_axis_numbers"]

#: the arguments a parameter may depend on: the axis values (mm; degrees for A, B, C)
ISG_ARGUMENTS = ("X", "Y", "Z", "A", "B", "C")
#: a component error (E, direction, axis) or a position error (direction, 0, axis), ISO 230-1 names
_PARAMETER = re.compile(r"E[XYZABC][XYZABC]|[XYZABC]0[XYZABC]")
#: decimals written: 1e-7 mm (0.1 nm) and 1e-10 rad; arguments 1e-6 mm and 1e-6 degree
_VALUE_DECIMALS = {"length": 7, "angle": 10}
_ARGUMENT_DECIMALS = 6


def _is_angle(parameter: str) -> bool:
    """Whether an error parameter is an angle (its direction letter is A, B or C)."""
    direction = parameter[1] if parameter.startswith("E") else parameter[0]
    return direction in "ABC"


@dataclass(frozen=True)
class IsgTable:
    """One block of an ISG CSV parameter file: error parameters over their arguments (SI).

    Attributes
    ----------
    arguments : tuple of str
        The argument columns, from :data:`ISG_ARGUMENTS` (none for constant position errors).
    parameters : tuple of str
        The error parameter columns (``EXX``, ``EYX``, ... ``X0Y``, ...).
    argument_si : ndarray, shape (N, len(arguments))
        The arguments of each record: metres, radians for A, B, C.
    parameter_si : ndarray, shape (N, len(parameters))
        The parameters of each record: metres for offsets, radians for angles.
    """

    arguments: tuple[str, ...]
    parameters: tuple[str, ...]
    argument_si: np.ndarray
    parameter_si: np.ndarray

    def __post_init__(self) -> None:
        for name in self.arguments:
            if name not in ISG_ARGUMENTS:
                raise AxiscalError(f"{name!r} is not an ISG argument ({', '.join(ISG_ARGUMENTS)})")
        for name in self.parameters:
            if not isinstance(name, str) or _PARAMETER.fullmatch(name) is None:
                raise AxiscalError(f"{name!r} is not an ISO 230-1 error parameter (EXX ... ECC, X0X ... C0C)")
        names = self.arguments + self.parameters
        if len(set(names)) != len(names):
            raise AxiscalError(f"a column is named twice in {' '.join(names)}")
        if not self.parameters:
            raise AxiscalError("an ISG table holds at least one error parameter")
        rows = self.parameter_si.shape[0]
        if self.argument_si.shape != (rows, len(self.arguments)) or self.parameter_si.shape != (rows, len(self.parameters)):
            raise AxiscalError("argument_si and parameter_si must have one row per record and one column per name")
        if not (np.isfinite(self.argument_si).all() and np.isfinite(self.parameter_si).all()):
            raise AxiscalError("an ISG table holds finite numbers only")

    def columns_file_units(self) -> np.ndarray:
        """Every column in the file's units (mm, degrees, mm or rad), shape (N, columns)."""
        arguments = np.column_stack([
            self.argument_si[:, j] / (math.pi / 180.0 if name in "ABC" else MM) for j, name in enumerate(self.arguments)
        ]) if self.arguments else np.zeros((self.parameter_si.shape[0], 0))
        values = np.column_stack([
            self.parameter_si[:, j] / (1.0 if _is_angle(name) else MM) for j, name in enumerate(self.parameters)
        ])
        return np.hstack([arguments, values])

    def text(self) -> str:
        """The block as an ISG CSV file: the header row, then one record per row, blank-separated.

        Returns
        -------
        str
            Arguments in mm (degrees for A, B, C) with 6 decimals; offsets in mm with 7 decimals
            (0.1 nm), angles in rad with 10.
        """
        names = self.arguments + self.parameters
        table = self.columns_file_units()
        formats = [f"{{:.{_ARGUMENT_DECIMALS}f}}"] * len(self.arguments)
        formats += [f"{{:.{_VALUE_DECIMALS['angle' if _is_angle(p) else 'length']}f}}" for p in self.parameters]
        columns = [[fmt.format(v + 0.0) for v in table[:, j]] for j, fmt in enumerate(formats)]
        lines = [" ".join(names)] + [" ".join(row) for row in zip(*columns)]
        return "\n".join(lines) + "\n"


def parse_isg_csv(text: str, *, source: str | None = None) -> tuple[IsgTable, ...]:
    """Every block of an ISG CSV parameter file, from its text.

    Parameters
    ----------
    text : str
        The file's content.
    source : str, optional, keyword-only
        The file, named in errors.

    Returns
    -------
    tuple of IsgTable
        One per block (a ``#`` line starts the next), SI units.

    Raises
    ------
    AxiscalError
        Naming the line: a header that names something not an ISG argument or an ISO 230-1 error
        parameter, a record whose count of values differs from the header's, a value that is not
        a finite number, a block without records.
    """
    check_instance("text", text, str)
    blocks: list[IsgTable] = []
    header: list[str] | None = None
    header_line = 0
    rows: list[list[float]] = []

    def fail(message: str, line: int) -> AxiscalError:
        return AxiscalError(message, path=source, line=line)

    def close(line: int) -> None:
        if header is None:
            return
        if not rows:
            raise fail(f"the block headed {' '.join(header)} holds no record", header_line)
        arguments = tuple(name for name in header if name in ISG_ARGUMENTS)
        if list(arguments) != header[:len(arguments)]:
            raise fail("the arguments come before the error parameters in the header", header_line)
        values = np.array(rows, dtype=float)
        k = len(arguments)
        scale_arguments = np.array([math.pi / 180.0 if a in "ABC" else MM for a in arguments])
        scale_values = np.array([1.0 if _is_angle(p) else MM for p in header[k:]])
        try:
            blocks.append(IsgTable(arguments, tuple(header[k:]), values[:, :k] * scale_arguments, values[:, k:] * scale_values))
        except AxiscalError as error:
            raise fail(error.message, header_line) from None

    for number, raw in enumerate(text.splitlines(), start=1):
        line = raw.split("//", 1)[0].strip()
        if not line:
            continue
        if line.startswith("#"):
            close(number)
            header, rows = None, []
            continue
        fields = line.split()
        if header is None:
            names = [f.upper() for f in fields]
            for name in names:
                if name not in ISG_ARGUMENTS and _PARAMETER.fullmatch(name) is None:
                    raise fail(f"{name!r} is not an ISG argument ({', '.join(ISG_ARGUMENTS)}) or an ISO 230-1 error"
                               " parameter (EXX ... ECC, X0X ... C0C)", number)
            header, header_line = names, number
            continue
        if len(fields) != len(header):
            raise fail(f"{len(fields)} values where the header names {len(header)} columns", number)
        try:
            record = [float(f) for f in fields]
        except ValueError:
            bad = next(f for f in fields if not _is_number(f))
            raise fail(f"{bad[:20]!r} is not a number", number) from None
        if not all(math.isfinite(v) for v in record):
            raise fail("a value is not a finite number", number)
        rows.append(record)
    close(len(text.splitlines()))
    if not blocks:
        raise AxiscalError("no ISG CSV block (a header row and its records) in the file", path=source)
    return tuple(blocks)


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def read_isg_csv(path: str | Path) -> tuple[IsgTable, ...]:
    """Every block of the ISG CSV parameter file ``path`` (see :func:`parse_isg_csv`).

    Parameters
    ----------
    path : str or Path
        The file.

    Returns
    -------
    tuple of IsgTable

    Raises
    ------
    AxiscalError
        A file that cannot be read, or as :func:`parse_isg_csv`.
    """
    path = check_path("path", path)
    return parse_isg_csv(read_text(path), source=str(path))


def volcomp_list_text(files: list[str], *, axis_numbers: dict[str, int] | None = None, workpiece_axes: int = 0,
                      interpolation: str = "GRID", chain: str | None = None) -> str:
    """The compensation list (``*.lis``) that names the parameter files for the ISG kernel.

    Parameters
    ----------
    files : list of str
        The parameter files (``file[j]``), each of format ``ISG_CSV``.
    axis_numbers : dict of str to int, optional, keyword-only
        Logical axis number of each participating axis (default X 1, Y 2, Z 3).
    workpiece_axes : int, keyword-only
        How many axes of the kinematic chain, counted from its start, lie on the workpiece side
        (``workpiece_axes``, P-VOLC-00008; default 0: every axis carries the tool).
    interpolation : {"GRID", "SCATTER", "AUTO"}, keyword-only
        How the kernel interpolates the parameters (P-VOLC-00014; default GRID).
    chain : str, optional, keyword-only
        The kinematic chain (``chain``, P-VOLC-00007): the numbered axes in their order from the
        workpiece to the tool, e.g. ``"XYZ"`` (the kernel's default when the line is left out).

    Returns
    -------
    str
        One ``key value`` line each.

    Raises
    ------
    AxiscalError
        For no file, an axis not X, Y, Z, A, B, C, a number below 1, two axes given one number, a
        chain that does not name each numbered axis once, a bad count or interpolation.
    """
    check_instance("files", files, (list, tuple))
    if not files or not all(isinstance(f, str) and f and not any(c.isspace() for c in f) for f in files):
        raise AxiscalError("files must name at least one parameter file, without blanks")
    numbers = {"X": 1, "Y": 2, "Z": 3} if axis_numbers is None else dict(axis_numbers)
    for letter, number in numbers.items():
        if letter not in ISG_ARGUMENTS:
            raise AxiscalError(f"axis_numbers names {letter!r}, not one of {', '.join(ISG_ARGUMENTS)}")
        if check_integer(f"axis_numbers[{letter!r}]", number) < 1:
            raise AxiscalError(f"logical axis numbers start at 1, not {number}")
    check_distinct_axis_numbers(numbers)
    if chain is not None:
        check_instance("chain", chain, str)
        if sorted(chain) != sorted(numbers):
            raise AxiscalError(f"chain must name each numbered axis ({', '.join(numbers)}) once, not {chain[:20]!r}")
    if check_integer("workpiece_axes", workpiece_axes) < 0 or workpiece_axes > len(numbers):
        raise AxiscalError(f"workpiece_axes must be 0 to {len(numbers)}, not {workpiece_axes}")
    if interpolation not in ("GRID", "SCATTER", "AUTO"):
        raise AxiscalError(f"interpolation must be GRID, SCATTER or AUTO, not {interpolation!r}")
    rows = [] if chain is None else [("chain", chain)]
    rows += [("workpiece_axes", str(workpiece_axes))] + [(k, str(v)) for k, v in numbers.items()]
    rows += [("interpolation", interpolation)]
    for j, name in enumerate(files):
        rows += [(f"file[{j}]", name), (f"file_format[{j}]", "ISG_CSV")]
    width = max(len(k) for k, _ in rows) + 2
    return "\n".join(f"{k:<{width}}{v}" for k, v in rows) + "\n"


def check_distinct_axis_numbers(numbers: dict[str, int]) -> None:
    """Refuse two axes given the same logical axis number (the control would drive one axis for both).

    Parameters
    ----------
    numbers : dict of str to int
        Logical axis number of each axis letter.

    Returns
    -------
    None

    Raises
    ------
    AxiscalError
        Naming the two axes and their number.
    """
    check_mapping("numbers", numbers, what="a mapping of axis letters to logical axis numbers")
    seen: dict[int, str] = {}
    for letter, number in numbers.items():
        if number in seen:
            raise AxiscalError(f"axes {seen[number]} and {letter} are both given logical axis number {number}")
        seen[number] = letter


def grid_values(table: IsgTable) -> tuple[dict[str, np.ndarray], np.ndarray]:
    """The grid a block's records lie on: each argument's node values and the parameters on it.

    Parameters
    ----------
    table : IsgTable

    Returns
    -------
    nodes : dict of str to ndarray
        Each argument's sorted distinct values, SI.
    values : ndarray, shape (n_1, ..., n_k, len(parameters))
        The parameters at every node, in the order of ``table.arguments``.

    Raises
    ------
    AxiscalError
        When the records are not every node of a grid once (the kernel's GRID interpolation
        refuses such data).
    """
    check_instance("table", table, IsgTable)
    nodes = {name: np.unique(table.argument_si[:, j]) for j, name in enumerate(table.arguments)}
    shape = tuple(v.size for v in nodes.values())
    if int(np.prod(shape)) != table.argument_si.shape[0]:
        raise AxiscalError(f"the {table.argument_si.shape[0]} records are not the {int(np.prod(shape))} nodes of a grid")
    index = tuple(np.searchsorted(nodes[name], table.argument_si[:, j]) for j, name in enumerate(table.arguments))
    values = np.full(shape + (len(table.parameters),), np.nan)
    values[index] = table.parameter_si
    if np.isnan(values).any():
        raise AxiscalError("a node of the grid is given twice and another not at all")
    return nodes, values

