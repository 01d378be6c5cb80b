"""An instrument's export read through a column map (:mod:`axiscal.io.importers.columnmap`) into
the readings of a positioning test, and written as axiscal's positioning CSV (``target_mm``,
``run``, ``direction``, ``deviation_um``; deviation = position reached - target, ISO 230-2 clause 2.11).
"""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_instance, check_path
from axiscal.io.atomic import write_text
from axiscal.io.importers.columnmap import (
    _DIRECTION_WORDS,
    IMPORT_UNITS,
    POSITIONING_COLUMNS,
    ColumnMap,
    read_column_map,
)
from axiscal.io.jsonio import write_sidecar
from axiscal.io.tabular import read_text
from axiscal.units import MM, UM

__all__ = ["ImportedReadings", "import_readings", "positioning_csv", "write_positioning_csv"]


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
