"""A column map: read any instrument's CSV or text export of a positioning test into axiscal's positioning CSV.

No standard describes these exports; the map (a small TOML file, see docs/importing.md) states
where each quantity is and in which unit, so that the import is a declared, checked conversion
rather than a retyping. The result follows the columns of ISO 230-2 test data that
:func:`axiscal.positioning.read_positioning_run` reads: ``target_mm``, ``run``, ``direction``,
``deviation_um`` (deviation = position reached - target, ISO 230-2 clause 2.11).
"""

from __future__ import annotations

import csv
import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_path
from axiscal.io.arguments import check_instance
from axiscal.io.atomic import write_text
from axiscal.io.jsonio import write_sidecar
from axiscal.io.schema import TomlLines
from axiscal.io.tabular import parse_toml, read_text
from axiscal.units import LENGTH_UNITS, MM, UM

__all__ = [
    "INCH",
    "IMPORT_UNITS",
    "POSITIONING_COLUMNS",
    "ColumnMap",
    "ImportedReadings",
    "column_map",
    "read_column_map",
    "import_readings",
    "positioning_csv",
    "write_positioning_csv",
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
_KNOWN = {
    "top": {"layout", "delimiter", "decimal", "skip_lines", "header", "reading", "sign", "columns", "units",
            "direction_values", "runs"},
    "columns": {"target", "reading", "run", "direction", "readings"},
    "units": {"target", "reading"},
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


@dataclass(frozen=True)
class ImportedReadings:
    """Readings of a positioning test, one entry per reading, in SI.

    Attributes
    ----------
    targets_m : ndarray, shape (n,)
        Target position of each reading, metres.
    deviations_m : ndarray, shape (n,)
        Position reached minus target, metres.
    runs : tuple of str
        Run label of each reading.
    directions : tuple of str
        ``"+"`` or ``"-"`` for each reading.
    lines : tuple of int
        Line of the source file each reading came from.
    source : str
        The file read.
    """

    targets_m: np.ndarray
    deviations_m: np.ndarray
    runs: tuple[str, ...]
    directions: tuple[str, ...]
    lines: tuple[int, ...]
    source: str

    def __len__(self) -> int:
        return len(self.runs)


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


def _split_lines(text: str, cmap: ColumnMap) -> list[tuple[int, list[str]]]:
    lines = text.splitlines()
    out = []
    numbered = [(n, line) for n, line in enumerate(lines, start=1) if n > cmap.skip_lines and line.strip()]
    if cmap.delimiter is None:
        return [(n, line.split()) for n, line in numbered]
    reader = csv.reader((line for _, line in numbered), delimiter=cmap.delimiter)
    for (n, _), cells in zip(numbered, reader):
        out.append((n, [c.strip() for c in cells]))
    return out


def _index(ref: str | int, header: list[str] | None, *, what: str, path: str, line: int) -> int:
    if isinstance(ref, int):
        return ref - 1
    assert header is not None
    try:
        return header.index(ref)
    except ValueError:
        raise AxiscalError(
            f"the map names the {what} column '{ref}', which the file does not have (columns are: {', '.join(header)})",
            path=path,
            line=line,
        ) from None


def _number(cell: str, cmap: ColumnMap, *, what: str, path: str, line: int) -> float:
    text = cell.strip()
    if cmap.decimal == ",":
        if "." in text:
            raise AxiscalError(f"{what}: '{cell}' has a '.' in a file with a decimal comma", path=path, line=line)
        text = text.replace(",", ".")
    try:
        value = float(text)
    except ValueError:
        raise AxiscalError(f"{what}: '{cell}' is not a number", path=path, line=line) from None
    if not math.isfinite(value):
        raise AxiscalError(f"{what}: '{cell}' is not a finite number", path=path, line=line)
    return value


def _direction(cell: str, cmap: ColumnMap, *, path: str, line: int) -> str:
    word = cell.strip().lower()
    d = cmap.direction_values.get(word) or _DIRECTION_WORDS.get(word)
    if d is None:
        raise AxiscalError(
            f"direction: '{cell}' is not a direction (known: +, -, up, down, forward, reverse; add others under"
            " [direction_values] in the map)",
            path=path,
            line=line,
        )
    return d


def _infer_directions(targets: list[float]) -> list[str]:
    """The direction of the move that reached each reading; at a repeated target (a turning point, or
    the first reading) that of the next move."""
    steps = [b - a for a, b in zip(targets, targets[1:])]
    out = []
    for k in range(len(targets)):
        step = steps[k - 1] if k > 0 else 0.0
        if step == 0:
            step = next((s for s in steps[k:] if s != 0), 0.0)
        out.append("-" if step < 0 else "+")
    return out


def _infer_runs(directions: list[str], targets: list[float]) -> list[str]:
    """A new run starts where the direction turns from - to +, or (one direction only) the target turns back."""
    both = len(set(directions)) == 2
    run, out = 1, []
    for k, d in enumerate(directions):
        if k > 0:
            if both and directions[k - 1] == "-" and d == "+":
                run += 1
            elif not both and d == directions[k - 1] and (targets[k] - targets[k - 1]) * (1 if d == "+" else -1) < 0:
                run += 1
        out.append(str(run))
    return out


def import_readings(cmap: ColumnMap | str | Path, path: str | Path) -> ImportedReadings:
    """Read an instrument's export with a column map.

    Parameters
    ----------
    cmap : ColumnMap or str or Path
        The map, or the path of its TOML file.
    path : str or Path
        The instrument's CSV or text export.

    Returns
    -------
    ImportedReadings
        One entry per reading, SI units, deviations = position reached - target.

    Raises
    ------
    AxiscalError
        Naming the file and line: a column the map names that the file does not have, a row too
        short, a cell that is not a number, an unknown direction word, a file with no readings,
        or a (target, run, direction) read twice.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> _ = (folder / "x.csv").write_text("Target;Run 1\\n0;0,5\\n10;1,5\\n10;1,0\\n0;0,0\\n")
    >>> m = column_map({"layout": "runs", "delimiter": ";", "decimal": ",",
    ...                 "columns": {"target": "Target", "readings": ["Run 1"]}})
    >>> r = import_readings(m, folder / "x.csv")
    >>> r.directions
    ('+', '+', '-', '-')
    """
    if not isinstance(cmap, ColumnMap):
        cmap = read_column_map(check_path("cmap", cmap))
    source = str(check_path("path", path))
    rows = _split_lines(read_text(path), cmap)
    header: list[str] | None = None
    header_line = cmap.skip_lines + 1
    if cmap.header:
        if not rows:
            raise AxiscalError("empty file: expected a header line", path=source, line=max(1, cmap.skip_lines + 1))
        header_line, header = rows[0]
        rows = rows[1:]
    if not rows:
        raise AxiscalError("no readings after the header", path=source, line=header_line)

    def idx(ref: str | int, what: str) -> int:
        return _index(ref, header, what=what, path=source, line=header_line)

    fixed = cmap.direction if cmap.direction in ("+", "-") else None

    def cell(cells: list[str], i: int, what: str, line: int) -> str:
        if i >= len(cells):
            raise AxiscalError(f"{what}: the line has {len(cells)} cells, column {i + 1} is missing", path=source, line=line)
        return cells[i]

    target_factor = IMPORT_UNITS[cmap.target_unit]
    reading_factor = IMPORT_UNITS[cmap.reading_unit] * cmap.sign
    i_target = idx(cmap.target, "target")
    # one record per reading: (run or None, direction or None, target, value, line)
    records: list[tuple[str | None, str | None, float, float, int]] = []
    if cmap.layout == "rows":
        i_reading = idx(cmap.reading, "reading")  # type: ignore[arg-type]
        i_run = None if cmap.run is None else idx(cmap.run, "run")
        i_dir = None if cmap.direction is None or fixed else idx(cmap.direction, "direction")
        for line, cells in rows:
            t = _number(cell(cells, i_target, "target", line), cmap, what="target", path=source, line=line)
            v = _number(cell(cells, i_reading, "reading", line), cmap, what="reading", path=source, line=line)
            r = None if i_run is None else cell(cells, i_run, "run", line).strip()
            if r == "":
                raise AxiscalError("run: empty run identifier", path=source, line=line)
            d = fixed if i_dir is None else _direction(cell(cells, i_dir, "direction", line), cmap, path=source, line=line)
            records.append((r, d, t, v, line))
    else:
        labels = cmap.run_labels or tuple(str(k + 1) for k in range(len(cmap.readings)))
        i_dir = None if cmap.direction is None or fixed else idx(cmap.direction, "direction")
        indices = [idx(ref, "reading") for ref in cmap.readings]
        for label, i_reading in zip(labels, indices):
            for line, cells in rows:
                t = _number(cell(cells, i_target, "target", line), cmap, what="target", path=source, line=line)
                raw = cell(cells, i_reading, "reading", line)
                if raw.strip() == "":
                    continue  # a run with fewer readings (the software leaves the cell empty)
                v = _number(raw, cmap, what="reading", path=source, line=line)
                d = fixed if i_dir is None else _direction(cell(cells, i_dir, "direction", line), cmap, path=source, line=line)
                records.append((label, d, t, v, line))
        if not records:
            raise AxiscalError("no readings: every reading cell is empty", path=source, line=header_line)

    # infer directions within each run (or over the whole file when runs are inferred too)
    if any(d is None for _, d, _, _, _ in records):
        groups: dict[str | None, list[int]] = {}
        for k, (r, *_rest) in enumerate(records):
            groups.setdefault(r, []).append(k)
        directions = [""] * len(records)
        for members in groups.values():
            inferred = _infer_directions([records[k][2] for k in members])
            for k, d in zip(members, inferred):
                directions[k] = d
        records = [(r, directions[k], t, v, line) for k, (r, _, t, v, line) in enumerate(records)]
    if any(r is None for r, *_ in records):
        runs = _infer_runs([d for _, d, _, _, _ in records], [t for _, _, t, _, _ in records])  # type: ignore[misc]
        records = [(runs[k], d, t, v, line) for k, (_, d, t, v, line) in enumerate(records)]

    targets = np.array([t for _, _, t, _, _ in records]) * target_factor
    values = np.array([v for _, _, _, v, _ in records]) * reading_factor
    deviations = values - targets if cmap.kind == "position" else values
    seen: dict[tuple[float, str, str], int] = {}
    for k, (r, d, _, _, line) in enumerate(records):
        key = (float(targets[k]), str(r), str(d))
        if key in seen:
            raise AxiscalError(
                f"target {targets[k] / MM:g} mm, run {r}, direction {d} is read twice (first on line {seen[key]});"
                " check the run and direction columns of the map",
                path=source,
                line=line,
            )
        seen[key] = line
    return ImportedReadings(
        targets_m=targets,
        deviations_m=deviations,
        runs=tuple(str(r) for r, *_ in records),
        directions=tuple(str(d) for _, d, *_ in records),
        lines=tuple(line for *_, line in records),
        source=source,
    )


def positioning_csv(readings: ImportedReadings) -> str:
    """The text of the positioning CSV (``target_mm,run,direction,deviation_um``), sorted by run, direction, target.

    Parameters
    ----------
    readings : ImportedReadings

    Returns
    -------
    str
        Plain CSV: the header on the first line, no comment lines.
    """
    order = sorted(
        range(len(readings)),
        key=lambda k: (_run_key(readings.runs[k]), readings.directions[k] == "-",
                       readings.targets_m[k] * (1 if readings.directions[k] == "+" else -1)),
    )
    lines = [",".join(POSITIONING_COLUMNS)]
    for k in order:
        lines.append(
            f"{readings.targets_m[k] / MM:.6f},{readings.runs[k]},{readings.directions[k]},{readings.deviations_m[k] / UM:.4f}"
        )
    return "\n".join(lines) + "\n"


def _run_key(label: str) -> tuple[int, float, str]:
    try:
        return (0, float(label), label)
    except ValueError:
        return (1, 0.0, label)


def write_positioning_csv(
    readings: ImportedReadings, path: str | Path, *, map_path: str | Path | None = None
) -> Path:
    """Write the positioning CSV atomically, and its JSON sidecar (``NAME.json``) naming the sources.

    Parameters
    ----------
    readings : ImportedReadings
    path : str or Path
        The CSV to write.
    map_path : str or Path, optional, keyword-only
        The column map used, recorded in the sidecar.

    Returns
    -------
    Path
        ``path``.

    Raises
    ------
    AxiscalError
        If the file cannot be written, or for readings that are not :class:`ImportedReadings`.
    """
    check_instance("readings", readings, ImportedReadings, what="ImportedReadings (what import_readings returns)")
    path = check_path("path", path)
    if map_path is not None:
        check_path("map_path", map_path)
    write_text(path, positioning_csv(readings))
    sources = [readings.source] + ([str(map_path)] if map_path is not None else [])
    runs = sorted(set(readings.runs), key=_run_key)
    write_sidecar(
        path,
        kind="positioning readings (imported)",
        units={"target_mm": "mm", "deviation_um": "um"},
        sources=sources,
        readings=len(readings),
        runs=runs,
        directions=sorted(set(readings.directions)),
    )
    return Path(path)
