"""Per-axis error tables: the six error motions of one axis (linear or rotary) against its position.

An axis moving along letter ``L`` has six error motions named after ISO 230-1: ``ELL`` (positioning),
the two straightness errors ``E<M>L`` across the motion, and the rotations ``EAL``, ``EBL``, ``ECL``
about X, Y and Z. They are those of the moving carriage relative to the body that carries it (see
docs/conventions.md). File format (docs/formats.md): CSV, first column ``position_mm``, then any of
the six columns with a unit suffix (``_nm|_um|_mm`` for translations, ``_urad|_mrad|_arcsec`` for
rotations); missing columns are zero; positions strictly increasing. A rotary axis A, B or C
(ISO 230-7) has ``position_deg`` instead and, by default, a periodic table: it interpolates across
360 degrees, from its last row back to its first.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from axiscal.conventions import ROTARY_LETTERS, component_names
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_choice, check_number
from axiscal.io.tabular import CsvTable, read_csv
from axiscal.units import ANGLE_UNITS, MM, angle_factor, length_factor, split_unit

__all__ = ["INTERPOLATIONS", "MAX_TRANSLATION_ERROR_M", "MAX_ANGLE_ERROR_RAD", "ErrorTable", "read_error_table"]

INTERPOLATIONS = ("linear", "cubic")
_DEG = ANGLE_UNITS["deg"]
_TURN = 360.0 * _DEG
#: largest translation error motion accepted in a table (10 mm): beyond it a value has no physical meaning
MAX_TRANSLATION_ERROR_M = 0.01
#: largest rotation error motion accepted (0.01 rad, about 2000 arcsec): the model is first order in angles
MAX_ANGLE_ERROR_RAD = 0.01
#: largest position accepted in a table (1 km, the range of an ideal axis)
_MAX_POSITION_M = 1000.0

#: the axis letters an error table is for
_LETTERS = ("X", "Y", "Z", *ROTARY_LETTERS)


def _floats(value: object, what: str) -> np.ndarray:
    """``value`` as a float array; anything that is not numbers (text, true/false) raises AxiscalError."""
    try:
        if value is None or isinstance(value, (bool, np.bool_, str)):
            raise TypeError
        if isinstance(value, (list, tuple)):  # true/false would pass as 1/0
            if any(isinstance(v, (bool, np.bool_)) for v in np.asarray(value, dtype=object).ravel()):
                raise TypeError
        elif np.asarray(value).dtype == bool:
            raise TypeError
        return np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise AxiscalError(f"{what} must be numbers, not {value!r:.60}") from None


def _first_too_large(values: np.ndarray) -> tuple[int, int] | None:
    """(row, sample) of the first error motion over its limit, or None."""
    limits = np.array([MAX_TRANSLATION_ERROR_M] * 3 + [MAX_ANGLE_ERROR_RAD] * 3)[:, None]
    over = np.abs(values) > limits
    if not np.any(over):
        return None
    row, sample = np.argwhere(over)[0]
    return int(row), int(sample)


@dataclass(frozen=True)
class ErrorTable:
    """Six error motions of one axis sampled at increasing positions (SI units).

    Parameters
    ----------
    letter : str
        The axis letter: X, Y, Z, or a rotary axis A, B, C.
    position_m : ndarray, shape (n,)
        Strictly increasing positions: metres, or radians for a rotary axis.
    values : ndarray, shape (6, n)
        Rows tx, ty, tz (metres) and ea, eb, ec (radians): e.g. for X the rows are EXX, EYX, EZX,
        EAX, EBX, ECX.
    interpolation : {"linear", "cubic"}
        Between rows: linear (default) or a not-a-knot cubic spline.
    hold_ends : bool
        Outside the table, hold the end values instead of raising (default False).
    periodic : bool, optional
        Positions repeat every 360 degrees: between the last row and the first plus 360 degrees
        the table interpolates towards the first row. Default: True for a rotary axis, False for
        a linear one (where it is refused).

    Raises
    ------
    AxiscalError
        An unknown axis letter or interpolation, values of the wrong shape, fewer than 2 rows,
        non-finite values, positions not strictly increasing, or a periodic table that spans
        more than 360 degrees.

    Examples
    --------
    >>> table = ErrorTable.from_components("X", [0.0, 0.2], {"EXX": [0.0, 4e-6]})
    >>> table.evaluate([0.1])[0].tolist()  # EXX at X = 100 mm, metres
    [2e-06]
    """

    letter: str
    position_m: np.ndarray
    values: np.ndarray
    interpolation: str = "linear"
    hold_ends: bool = False
    periodic: bool | None = None
    _slopes: np.ndarray = field(init=False, repr=False, compare=False)
    _uniform_step: float | None = field(init=False, repr=False, compare=False)
    _bin_width: float = field(init=False, repr=False, compare=False)
    _bin_rows: np.ndarray | None = field(init=False, repr=False, compare=False)
    _spline: object = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        check_choice("letter", self.letter, _LETTERS)
        component_names(self.letter)
        position = np.ascontiguousarray(_floats(self.position_m, f"axis {self.letter}: positions"))
        values = np.ascontiguousarray(_floats(self.values, f"axis {self.letter}: values"))
        rotary = self.letter in ROTARY_LETTERS
        periodic = rotary if self.periodic is None else self.periodic
        if not isinstance(periodic, (bool, np.bool_)) or (periodic and not rotary):
            raise AxiscalError(f"axis {self.letter}: periodic must be True or False, and only a rotary axis is periodic")
        object.__setattr__(self, "periodic", bool(periodic))
        if position.ndim != 1 or values.shape != (6, position.size):
            raise AxiscalError(f"axis {self.letter}: values must have shape (6, {position.size}), got {values.shape}")
        if position.size < 2:
            raise AxiscalError(f"axis {self.letter}: an error table needs at least 2 rows")
        if not (np.all(np.isfinite(position)) and np.all(np.isfinite(values))):
            raise AxiscalError(f"axis {self.letter}: error table holds non-finite values")
        if np.any(np.abs(position) > _MAX_POSITION_M):
            raise AxiscalError(f"axis {self.letter}: positions beyond {_MAX_POSITION_M:g} m have no physical meaning")
        over = _first_too_large(values)
        if over is not None:
            row, sample = over
            raise AxiscalError(
                f"axis {self.letter}: {component_names(self.letter)[row]} at row {sample + 1} is beyond the largest "
                f"error motion accepted ({MAX_TRANSLATION_ERROR_M} m, {MAX_ANGLE_ERROR_RAD} rad)"
            )
        steps = np.diff(position)
        if np.any(steps <= 0):
            k = int(np.argmax(steps <= 0)) + 1
            raise AxiscalError(f"axis {self.letter}: positions not strictly increasing at row {k + 1}")
        if not isinstance(self.hold_ends, (bool, np.bool_)):
            raise AxiscalError(f"hold_ends must be True or False, not {self.hold_ends!r}")
        if not isinstance(self.interpolation, str) or self.interpolation not in INTERPOLATIONS:
            raise AxiscalError(f"unknown interpolation '{self.interpolation}'; use one of {', '.join(INTERPOLATIONS)}")
        if self.periodic:
            span = position[-1] - position[0]
            if span > _TURN * (1 + 1e-12):
                raise AxiscalError(f"axis {self.letter}: a periodic table spans at most 360 deg, not {span / _DEG:.6g} deg")
            if span < _TURN * (1 - 1e-12):  # close the circle: interpolate back to the first row
                position = np.append(position, position[0] + _TURN)
                values = np.column_stack([values, values[:, :1]])
                steps = np.diff(position)
            if self.interpolation == "cubic":
                raise AxiscalError(f"axis {self.letter}: a periodic table interpolates linearly")
        object.__setattr__(self, "position_m", position)
        object.__setattr__(self, "values", values)
        object.__setattr__(self, "_slopes", np.diff(values, axis=1) / steps)
        uniform = bool(np.allclose(steps, steps[0], rtol=1e-9, atol=0.0))
        object.__setattr__(self, "_uniform_step", float(steps[0]) if uniform else None)
        # Uneven tables: a lookup of the row at the start of bins narrower than the smallest step,
        # so each bin holds at most one row boundary and one comparison finds the row.
        bins = int(np.ceil(2.0 * (position[-1] - position[0]) / steps.min())) + 1
        bin_rows = None
        if not uniform and bins <= 1 << 22:
            edges = position[0] + np.arange(bins) * (0.5 * steps.min())
            bin_rows = np.clip(np.searchsorted(position, edges, side="right") - 1, 0, position.size - 2)
        object.__setattr__(self, "_bin_width", 0.5 * float(steps.min()))
        object.__setattr__(self, "_bin_rows", bin_rows)
        spline = None
        if self.interpolation == "cubic":
            from scipy.interpolate import CubicSpline

            spline = CubicSpline(position, values, axis=1)
        object.__setattr__(self, "_spline", spline)

    @classmethod
    def zeros(cls, letter: str, start_m: float = -1e3, end_m: float = 1e3) -> "ErrorTable":
        """An ideal axis: all six error motions zero, holding its ends.

        Parameters
        ----------
        letter : str
            X, Y, Z, or A, B, C (a periodic table over a full turn).
        start_m, end_m : float
            Range of a linear table, metres.

        Returns
        -------
        ErrorTable
        """
        check_choice("letter", letter, _LETTERS)
        if letter in ROTARY_LETTERS:
            return cls(letter, np.array([0.0, _TURN]), np.zeros((6, 2)), periodic=True)
        start_m, end_m = check_number("start_m", start_m), check_number("end_m", end_m)
        return cls(letter, np.array([start_m, end_m]), np.zeros((6, 2)), hold_ends=True)

    @classmethod
    def from_components(
        cls, letter: str, position_m: np.ndarray, components: Mapping[str, np.ndarray], **options
    ) -> "ErrorTable":
        """Build a table from its components by ISO 230-1 name; missing components are zero.

        Parameters
        ----------
        letter : str
            X, Y or Z.
        position_m : ndarray, shape (n,)
            Strictly increasing positions, metres.
        components : mapping of str to ndarray, shape (n,)
            ``{"EXX": ..., "ECX": ...}``: translations in metres, rotations in radians.
        **options
            ``interpolation``, ``hold_ends`` (see the class).

        Returns
        -------
        ErrorTable

        Raises
        ------
        AxiscalError
            A name that is not a component of the axis, or any reason of the class.
        """
        check_choice("letter", letter, _LETTERS)
        if not isinstance(components, Mapping):
            raise AxiscalError(f"components must map ISO 230-1 names such as E{'X'}{letter} to values, not {components!r:.40}")
        names = component_names(letter)
        unknown = set(components) - set(names)
        if unknown:
            raise AxiscalError(f"axis {letter}: unknown components {sorted(unknown)}; expected {', '.join(names)}")
        position = _floats(position_m, f"axis {letter}: positions")
        values = np.zeros((6, position.size))
        for row, name in enumerate(names):
            if name in components:
                component = _floats(components[name], name)
                if component.shape != position.shape:
                    raise AxiscalError(f"{name} has shape {component.shape}; the positions have {position.shape}")
                values[row] = component
        return cls(letter, position, values, **options)

    @property
    def names(self) -> tuple[str, ...]:
        """ISO 230-1 names of the six rows (for X: EXX, EYX, EZX, EAX, EBX, ECX)."""
        return component_names(self.letter)

    @property
    def start_m(self) -> float:
        """First position of the table, metres."""
        return float(self.position_m[0])

    @property
    def end_m(self) -> float:
        """Last position of the table, metres."""
        return float(self.position_m[-1])

    def component(self, name: str) -> np.ndarray:
        """The sampled values of one component.

        Parameters
        ----------
        name : str
            ISO 230-1 name, e.g. ``"EBX"``.

        Returns
        -------
        ndarray, shape (n,)
            Metres or radians.

        Raises
        ------
        AxiscalError
            If ``name`` is not a component of this axis.
        """
        if not isinstance(name, str) or name not in self.names:
            raise AxiscalError(f"unknown component {name!r} of axis {self.letter}; use one of {', '.join(self.names)}")
        return self.values[self.names.index(name)]

    def first_outside(self, q_m: np.ndarray) -> int | None:
        """Index of the first position outside the table.

        Parameters
        ----------
        q_m : ndarray, shape (N,)
            Positions, metres.

        Returns
        -------
        int or None
            None when all are inside (with ``hold_ends`` or a periodic table: when none is NaN).
        """
        q_m = _floats(q_m, f"positions of axis {self.letter}")
        if self.hold_ends or self.periodic:
            if np.isnan(q_m).any():
                return int(np.argmax(np.isnan(q_m)))
            return None
        outside = ~((q_m >= self.start_m) & (q_m <= self.end_m))
        return int(np.argmax(outside)) if np.any(outside) else None

    def check_range(self, q_m: np.ndarray, *, path: str | None = None, lines: Sequence[int] | None = None) -> None:
        """Raise naming the first position outside the table (unless ``hold_ends``).

        Parameters
        ----------
        q_m : ndarray, shape (N,)
            Positions, metres.
        path : str, optional
            Where the positions came from, for the message.
        lines : sequence of int, optional
            ``lines[k]`` is the file line of position k.

        Raises
        ------
        AxiscalError
            ``"X = 200 mm is outside the error table of axis X (0 to 190 mm)"``.
        """
        k = self.first_outside(q_m)
        if k is not None:
            q_m = np.ravel(_floats(q_m, f"positions of axis {self.letter}"))
            factor, unit = (_DEG, "deg") if self.letter in ROTARY_LETTERS else (MM, "mm")
            raise AxiscalError(
                f"{self.letter} = {float(q_m[k]) / factor:.6g} {unit} is outside the error table of axis {self.letter} "
                f"({self.start_m / factor:.6g} to {self.end_m / factor:.6g} {unit})",
                path=path,
                line=lines[k] if lines else None,
            )

    def evaluate(self, q_m: np.ndarray) -> np.ndarray:
        """The six error motions at given positions, interpolated.

        Parameters
        ----------
        q_m : ndarray, shape (N,)
            Positions, metres.

        Returns
        -------
        ndarray, shape (6, N)
            Rows tx, ty, tz (metres) and ea, eb, ec (radians).

        Raises
        ------
        AxiscalError
            A position outside the table (unless ``hold_ends``).
        """
        q = _floats(q_m, f"positions of axis {self.letter}")
        if q.ndim == 0:
            return self.evaluate(q[None])[:, 0]
        self.check_range(q)
        if self.periodic:
            q = self.start_m + np.mod(q - self.start_m, _TURN)
        q = np.clip(q, self.start_m, self.end_m)
        if self._spline is not None:
            return self._spline(q)
        if self._uniform_step is not None:
            index = ((q - self.start_m) * (1.0 / self._uniform_step)).astype(np.intp)
            np.minimum(index, self.position_m.size - 2, out=index)
        elif self._bin_rows is not None:
            index = self._bin_rows[((q - self.start_m) * (1.0 / self._bin_width)).astype(np.intp)]
            index += q >= self.position_m[index + 1]
            np.minimum(index, self.position_m.size - 2, out=index)
        else:
            index = np.searchsorted(self.position_m, q, side="right") - 1
            np.clip(index, 0, self.position_m.size - 2, out=index)
        dq = q - self.position_m[index]
        return self.values[:, index] + self._slopes[:, index] * dq


def read_error_table(
    path: str | Path, letter: str, *, interpolation: str = "linear", hold_ends: bool = False, periodic: bool | None = None
) -> ErrorTable:
    """Read the error table of one axis from a CSV file (docs/formats.md).

    Parameters
    ----------
    path : str or Path
        CSV: ``position_mm`` (``position_deg`` for a rotary axis) first, strictly increasing, then
        any of the axis' six components with a unit suffix (``EXX_um``, ``EBX_arcsec``, ...);
        missing components are zero.
    letter : str
        The axis, X, Y, Z, A, B or C.
    interpolation : {"linear", "cubic"}
        Between rows.
    hold_ends : bool
        Hold the end values outside the table instead of raising.
    periodic : bool, optional
        Interpolate across 360 degrees (default: True for a rotary axis).

    Returns
    -------
    ErrorTable
        SI units.

    Raises
    ------
    AxiscalError
        A missing file, an unknown or repeated column, an unknown unit, a bad cell or positions
        not strictly increasing, naming the file and the line.

    Examples
    --------
    >>> table = read_error_table("examples/xz_module/x_errors.csv", "X")  # doctest: +SKIP
    >>> table.component("EXX")  # metres  # doctest: +SKIP
    """
    check_choice("letter", letter, _LETTERS)
    table = read_csv(path, min_rows=2)
    try:
        return _table_from_csv(table, letter, interpolation=interpolation, hold_ends=hold_ends, periodic=periodic)
    except AxiscalError as exc:
        raise exc.located(path=str(path)) from None


def _table_from_csv(
    table: CsvTable, letter: str, *, interpolation: str, hold_ends: bool, periodic: bool | None
) -> ErrorTable:
    names = component_names(letter)
    first, scale = ("position_deg", _DEG) if letter in ROTARY_LETTERS else ("position_mm", MM)
    if table.header[0] != first:
        raise AxiscalError(f"first column must be '{first}', found '{table.header[0]}'", line=table.header_line)
    position = table.numeric(first) * scale
    steps = np.diff(position)
    if np.any(steps <= 0):
        k = int(np.argmax(steps <= 0)) + 1
        raise AxiscalError(f"{first} is not strictly increasing", line=table.lines[k])
    values = np.zeros((6, position.size))
    seen: dict[str, str] = {}
    for column in table.header[1:]:
        stem, unit = split_unit(column) if "_" in column else (column, "")
        if stem not in names:
            raise AxiscalError(
                f"unknown column '{column}' for axis {letter}; expected {', '.join(n + '_<unit>' for n in names)}",
                line=table.header_line,
            )
        if stem in seen:
            raise AxiscalError(f"'{stem}' given twice ('{seen[stem]}' and '{column}')", line=table.header_line)
        seen[stem] = column
        row = names.index(stem)
        try:
            if row < 3:
                factor = length_factor(unit, allowed=("nm", "um", "mm"), what=column)
            else:
                factor = angle_factor(unit, allowed=("urad", "mrad", "arcsec"), what=column)
        except AxiscalError as exc:
            raise exc.located(line=table.header_line) from None
        values[row] = table.numeric(column) * factor
        over = _first_too_large(values)
        if over is not None:
            raise AxiscalError(
                f"{column} = {values[over] / factor:g} has no physical meaning (limits: "
                f"{MAX_TRANSLATION_ERROR_M / MM:g} mm, {MAX_ANGLE_ERROR_RAD:g} rad)",
                line=table.lines[over[1]],
            )
    if np.any(np.abs(position) > _MAX_POSITION_M):
        k = int(np.argmax(np.abs(position) > _MAX_POSITION_M))
        raise AxiscalError(f"{first} beyond {_MAX_POSITION_M / scale:g} has no physical meaning", line=table.lines[k])
    return ErrorTable(letter, position, values, interpolation=interpolation, hold_ends=hold_ends, periodic=periodic)
