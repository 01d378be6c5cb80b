"""A column map: where a positioning test's quantities stand in an instrument's CSV or text export.

No standard describes these exports; the map (a small TOML file, see docs/importing.md) states
where each quantity is and in which unit, so that the import is a declared, checked conversion
rather than a retyping (:mod:`axiscal.io.importers.readings` reads the export through it). The result follows the columns of ISO 230-2 test data that
:func:`axiscal.positioning.read_positioning_run` reads: ``target_mm``, ``run``, ``direction``,
``deviation_um`` (deviation = position reached - target, ISO 230-2 clause 2.11).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from axiscal.errors import AxiscalError
from axiscal.io.schema import TomlLines
from axiscal.io.tabular import parse_toml, read_text
from axiscal.units import LENGTH_UNITS, MM, UM

__all__ = [
    "INCH",
    "IMPORT_UNITS",
    "POSITIONING_COLUMNS",
    "ColumnMap",
    "column_map",
    "read_column_map",
]

#: metres per inch (exact by definition, 25.4 mm)
INCH = 25.4 * MM
#: units a column map may give a length in, metres per unit
IMPORT_UNITS: dict[str, float] = {"nm": LENGTH_UNITS["nm"], "um": UM, "mm": MM, "m": 1.0, "in": INCH}
#: the columns of the positioning CSV the importer writes
POSITIONING_COLUMNS = ("target_mm", "run", "direction", "deviation_um")

_LAYOUTS = ("rows", "runs")
_KINDS = ("deviation", "position")
_DELIMITERS = {",": ",", ";": ";", "tab": "\t", "\t": "\t", "whitespace": None, "space": None}
_DIRECTION_WORDS = {
    "+": "+", "up": "+", "forward": "+", "fwd": "+", "f": "+", "pos": "+", "positive": "+",
    "-": "-", "down": "-", "reverse": "-", "rev": "-", "r": "-", "backward": "-", "neg": "-", "negative": "-",
}


@dataclass(frozen=True)
class ColumnMap:
    """Where a positioning test's quantities are in an instrument's export, and in which units.

    Parameters
    ----------
    layout : str
        ``"rows"``: one row per reading (a target, a reading and, optionally, run and direction
        columns). ``"runs"``: one row per target position, one reading column per run.
    target : str or int
        The target column: its header text, or its 1-based number when the file has no header.
    reading : str or int or None
        The reading column (layout ``"rows"``).
    readings : tuple of (str or int)
        The reading columns, one per run, in run order (layout ``"runs"``).
    run : str or int or None
        The run column (layout ``"rows"``); None: a new run starts each time the direction turns
        from - back to + (or, for a one-direction test, each time the target turns back).
    direction : str or int or None
        The direction column, or ``"+"`` / ``"-"`` for a test run in that one direction only;
        None: inferred from the order of the targets within each run (moving
        to a larger target is +, to a smaller one -; at a turning point the target that is repeated
        belongs to the new direction).
    target_unit, reading_unit : str
        ``nm``, ``um``, ``mm``, ``m`` or ``in``.
    kind : str
        ``"deviation"``: the reading is the deviation (position reached - target, times ``sign``);
        ``"position"``: the reading is the position reached (times ``sign``), the deviation is
        formed by subtracting the target.
    sign : int
        +1 or -1: -1 for software that reports target - actual, or a laser counting down as the
        axis moves up.
    delimiter : str or None
        Cell separator; None splits on white space.
    decimal : str
        ``"."`` or ``","`` (a decimal comma needs a delimiter other than ``,``).
    skip_lines : int
        Lines before the header (or before the first data line when ``header`` is False).
    header : bool
        Whether the first line read holds column names.
    direction_values : mapping of str to str
        Extra words of the direction column, each mapped to ``"+"`` or ``"-"`` (compared without
        case); +, -, up, down, forward, reverse, fwd, rev, f, r are known already.
    run_labels : tuple of str
        Labels of the runs for layout ``"runs"`` (default 1, 2, ...).
    source : str, optional
        The map file, named in errors.
    locate : callable, optional
        ``locate("units.target")`` -> the line of that key in the map file, named in errors.

    Raises
    ------
    AxiscalError
        For an unknown layout, kind, unit or decimal mark, a missing reading column, a sign other
        than +-1, or a column named by text in a file without a header.
    """

    layout: str
    target: str | int
    reading: str | int | None = None
    readings: tuple[str | int, ...] = ()
    run: str | int | None = None
    direction: str | int | None = None
    target_unit: str = "mm"
    reading_unit: str = "um"
    kind: str = "deviation"
    sign: int = 1
    delimiter: str | None = ","
    decimal: str = "."
    skip_lines: int = 0
    header: bool = True
    direction_values: Mapping[str, str] = field(default_factory=dict)
    run_labels: tuple[str, ...] = ()
    source: str | None = None
    locate: Callable[[str], int | None] | None = field(default=None, compare=False, repr=False)

    def _at(self, key: str) -> dict[str, Any]:
        """Where an error about ``key`` (dotted, as in the map file) points: the file and the key's line."""
        return {"path": self.source, "line": None if self.locate is None else self.locate(key)}

    def __post_init__(self) -> None:
        if not isinstance(self.layout, str) or self.layout not in _LAYOUTS:
            raise AxiscalError(f"layout must be one of {', '.join(_LAYOUTS)}, not '{self.layout}'", **self._at("layout"))
        if isinstance(self.run_labels, (str, bytes)) or not isinstance(self.run_labels, (tuple, list)) \
                or not all(isinstance(label, str) for label in self.run_labels):
            raise AxiscalError(f"run_labels must be a tuple of labels (str), not {self.run_labels!r}", **self._at("runs"))
        if self.layout == "rows" and self.reading is None:
            raise AxiscalError("layout 'rows' needs columns.reading (the reading column)", **self._at("columns.reading"))
        if self.layout == "runs":
            if not self.readings:
                raise AxiscalError("layout 'runs' needs columns.readings (one reading column per run)", **self._at("columns.readings"))
            if self.run is not None:
                raise AxiscalError("layout 'runs' takes the run from the column: drop columns.run", **self._at("columns.run"))
            if self.run_labels and len(self.run_labels) != len(self.readings):
                raise AxiscalError(
                    f"{len(self.run_labels)} run labels for {len(self.readings)} reading columns", **self._at("runs")
                )
        for name, unit in (("target", self.target_unit), ("reading", self.reading_unit)):
            if not isinstance(unit, str) or unit not in IMPORT_UNITS:
                raise AxiscalError(
                    f"units.{name}: unknown length unit '{unit}'; use one of {', '.join(IMPORT_UNITS)}", **self._at(f"units.{name}")
                )
        if not isinstance(self.kind, str) or self.kind not in _KINDS:
            raise AxiscalError(f"reading must be one of {', '.join(_KINDS)}, not '{self.kind}'", **self._at("reading"))
        if not isinstance(self.sign, int) or isinstance(self.sign, bool) or self.sign not in (1, -1):
            raise AxiscalError(f"sign must be 1 or -1, not {self.sign!r}", **self._at("sign"))
        if not isinstance(self.decimal, str) or self.decimal not in (".", ","):
            raise AxiscalError(f"decimal must be '.' or ',', not '{self.decimal}'", **self._at("decimal"))
        if self.decimal == "," and self.delimiter == ",":
            raise AxiscalError("a decimal comma needs another delimiter (';', 'tab' or 'whitespace')", **self._at("decimal"))
        if not isinstance(self.skip_lines, int) or isinstance(self.skip_lines, bool) or self.skip_lines < 0:
            raise AxiscalError(f"skip_lines must be a whole number >= 0, not {self.skip_lines!r}", **self._at("skip_lines"))
        if self.delimiter is not None and not isinstance(self.delimiter, str):
            raise AxiscalError(f"delimiter must be a str or None, not {self.delimiter!r}", **self._at("delimiter"))
        if not isinstance(self.direction_values, Mapping):
            raise AxiscalError(f"direction_values must map words to '+' or '-', not {self.direction_values!r}", **self._at("direction_values"))
        if not isinstance(self.header, bool):
            raise AxiscalError(f"header must be true or false, not {self.header!r}", **self._at("header"))
        if isinstance(self.readings, (str, bytes)) or not isinstance(self.readings, (tuple, list)):
            raise AxiscalError(f"readings must be a tuple of columns, not {self.readings!r}", **self._at("columns.readings"))
        for word, d in self.direction_values.items():
            if d not in ("+", "-"):
                raise AxiscalError(f"direction_values.{word}: map to '+' or '-', not '{d}'", **self._at(f"direction_values.{word}"))
        if self.target is None:
            raise AxiscalError("columns.target is missing (the target position column)", **self._at("columns"))
        for ref in (self.target, self.reading, self.run, self.direction, *self.readings):
            if ref is None:
                continue
            if isinstance(ref, bool) or not isinstance(ref, (str, int)):
                raise AxiscalError(f"a column is named by its header text or its number, not {ref!r}", **self._at("columns"))
            if isinstance(ref, int) and ref < 1:
                raise AxiscalError(f"column numbers start at 1, not {ref}", **self._at("columns"))
            if ref in ("+", "-"):
                continue
            if isinstance(ref, str) and not self.header:
                raise AxiscalError(f"column '{ref}': the file has no header (header = false), give its number", **self._at("header"))


class _Located:
    """A ``locate(dotted key)`` function seen as the key lines the format validation asks for."""

    def __init__(self, locate: Callable[[str], int | None]):
        self.locate = locate
        self.keys = _Keys(locate)

    def of(self, table: str, index: int = 0, key: str | None = None) -> int | None:
        return self.locate(".".join(p for p in (table, key) if p))


class _Keys(dict):
    def __init__(self, locate: Callable[[str], int | None]):
        super().__init__()
        self.locate = locate

    def get(self, item, default=None):  # type: ignore[override]
        table, _, key = item
        return self.locate(".".join(p for p in (table, key) if p)) or default


def column_map(
    settings: Mapping[str, Any], *, source: str | None = None, locate: Callable[[str], int | None] | None = None
) -> ColumnMap:
    """Build a :class:`ColumnMap` from the parsed TOML of a map file (see docs/importing.md).

    Parameters
    ----------
    settings : mapping
        The TOML content: ``layout``, ``[columns]``, ``[units]``, ``reading``, ``sign``,
        ``delimiter``, ``decimal``, ``skip_lines``, ``header``, ``[direction_values]``, ``runs``.
    source : str, optional, keyword-only
        The map file, named in errors.
    locate : callable, optional, keyword-only
        ``locate("units.target")`` -> the line of that dotted key in the map file, named in errors.

    Returns
    -------
    ColumnMap

    Raises
    ------
    AxiscalError
        On an unknown key (a typo would otherwise be ignored), a missing column, an unknown unit,
        layout, kind or delimiter.

    Examples
    --------
    >>> m = column_map({"layout": "rows", "columns": {"target": "Target", "reading": "Error"},
    ...                 "units": {"target": "mm", "reading": "um"}})
    >>> m.direction is None
    True
    """
    from axiscal.io.formats.base import validate_data
    from axiscal.io.formats.importmap import ImportMapFile

    if locate is not None and not callable(locate):
        raise AxiscalError(f"locate must be a function of a dotted key, not {locate!r}")
    lines = _Located(locate) if locate is not None else None
    settings = validate_data(ImportMapFile, settings, path=source, lines=lines).model_dump(exclude_none=True)
    columns = settings["columns"]
    units = settings.get("units", {})
    delimiter_text = settings.get("delimiter", ",")
    direction = columns.get("direction")
    if direction == "infer":
        direction = None
    run = columns.get("run")
    if run == "infer":
        run = None
    readings = columns.get("readings", ())
    if isinstance(readings, (str, int)):
        readings = (readings,)
    run_labels = tuple(str(r) for r in settings.get("runs", ()))
    return ColumnMap(
        layout=str(settings.get("layout", "rows")),
        target=columns["target"],
        reading=columns.get("reading"),
        readings=tuple(readings),
        run=run,
        direction=direction,
        target_unit=str(units.get("target", "mm")),
        reading_unit=str(units.get("reading", "um")),
        kind=str(settings.get("reading", "deviation")),
        sign=settings.get("sign", 1),
        delimiter=_DELIMITERS[delimiter_text],
        decimal=str(settings.get("decimal", ".")),
        skip_lines=settings.get("skip_lines", 0),
        header=bool(settings.get("header", True)),
        direction_values={str(k).lower(): str(v) for k, v in settings.get("direction_values", {}).items()},
        run_labels=run_labels,
        source=source,
        locate=locate,
    )


def read_column_map(path: str | Path) -> ColumnMap:
    """Read a column map TOML file.

    Parameters
    ----------
    path : str or Path
        The map file.

    Returns
    -------
    ColumnMap

    Raises
    ------
    AxiscalError
        Naming the file (and the line for malformed TOML); see :func:`column_map`.
    """
    text = read_text(path)
    lines = TomlLines(text)

    def locate(key: str) -> int | None:
        table, _, name = key.rpartition(".")
        return lines.of(table, 0, name) or lines.of(key) or lines.of(table)

    return column_map(parse_toml(text, path=path), source=str(path), locate=lambda key: locate(key) or 1)

