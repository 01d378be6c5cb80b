"""Reading and writing the project's CSV files, with errors that name the file and the line.

Readers validate once, at the boundary: every value a caller gets back is a finite float (or a
stripped string for text columns). Lines starting with ``#`` and blank lines are skipped, but line
numbers in errors are those of the file as a person sees it (the header is line 1 when it is the
first line).
"""

from __future__ import annotations

import csv
import math
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from axiscal.errors import AxiscalError

__all__ = ["CsvTable", "read_csv", "read_text", "parse_csv", "write_csv", "read_toml"]


@dataclass(frozen=True)
class CsvTable:
    """A parsed CSV file: header, the raw cells of each data row, and each row's line number."""

    path: str
    header: tuple[str, ...]
    rows: tuple[tuple[str, ...], ...]
    lines: tuple[int, ...]
    _index: dict[str, int] = field(repr=False, compare=False, default_factory=dict)

    def __post_init__(self) -> None:
        self._index.update({name: i for i, name in enumerate(self.header)})

    def __len__(self) -> int:
        return len(self.rows)

    def has(self, name: str) -> bool:
        return name in self._index

    def require(self, *names: str) -> None:
        """Raise naming the first missing column."""
        for name in names:
            if name not in self._index:
                raise AxiscalError(
                    f"missing column '{name}' (columns are: {', '.join(self.header)})", path=self.path, line=self.header_line
                )

    @property
    def header_line(self) -> int:
        return self.lines[0] - 1 if self.lines else 1

    def text(self, name: str) -> list[str]:
        """The stripped cells of column ``name``."""
        self.require(name)
        i = self._index[name]
        return [row[i] for row in self.rows]

    def numeric(self, name: str, *, allow_empty: bool = False) -> np.ndarray:
        """Column ``name`` as finite floats; an empty cell is NaN only when ``allow_empty``."""
        self.require(name)
        i = self._index[name]
        out = np.empty(len(self.rows))
        for k, row in enumerate(self.rows):
            cell = row[i]
            if cell == "" and allow_empty:
                out[k] = math.nan
                continue
            try:
                value = float(cell)
            except ValueError:
                raise AxiscalError(f"column '{name}': '{cell}' is not a number", path=self.path, line=self.lines[k]) from None
            if not math.isfinite(value):
                raise AxiscalError(f"column '{name}': {cell} is not a finite number", path=self.path, line=self.lines[k])
            out[k] = value
        return out


def read_csv(path: str | Path, *, min_rows: int = 1) -> CsvTable:
    """Read a CSV file with a header row; cells are stripped of white space.

    Raises
    ------
    AxiscalError
        If the file is missing or unreadable, has no header, has a row with a different number of
        cells than the header, a repeated column name, or fewer than ``min_rows`` data rows.
    """
    text = read_text(path)
    return parse_csv(text.splitlines(), path=str(path), min_rows=min_rows)


def read_text(path: str | Path) -> str:
    """The text of a UTF-8 file (a byte-order mark is dropped); a missing or unreadable file raises
    AxiscalError naming it."""
    path = Path(path)
    try:
        return path.read_text(encoding="utf-8-sig")
    except FileNotFoundError:
        raise AxiscalError("file not found", path=path) from None
    except (OSError, UnicodeDecodeError) as exc:
        raise AxiscalError(f"cannot read file ({exc})", path=path) from None


def parse_csv(lines: Iterable[str], *, path: str = "<input>", min_rows: int = 1) -> CsvTable:
    """Parse CSV text given as lines (see :func:`read_csv`)."""
    header: tuple[str, ...] | None = None
    rows: list[tuple[str, ...]] = []
    numbers: list[int] = []
    header_line = 1
    kept = [(n, line) for n, line in enumerate(lines, start=1) if line.strip() and not line.strip().startswith("#")]
    # one reader over all kept lines (a line holds one record: quoted newlines are not supported)
    for (lineno, _), raw in zip(kept, csv.reader(line for _, line in kept)):
        cells = tuple(c.strip() for c in raw)
        if header is None:
            header, header_line = cells, lineno
            seen: set[str] = set()
            for name in header:
                if not name:
                    raise AxiscalError("empty column name in header", path=path, line=lineno)
                if name in seen:
                    raise AxiscalError(f"column '{name}' appears twice", path=path, line=lineno)
                seen.add(name)
            continue
        if len(cells) != len(header):
            raise AxiscalError(f"{len(cells)} cells where the header has {len(header)}", path=path, line=lineno)
        rows.append(cells)
        numbers.append(lineno)
    if header is None:
        raise AxiscalError("empty file: expected a header row", path=path)
    if len(rows) < min_rows:
        raise AxiscalError(f"{len(rows)} data rows; at least {min_rows} needed", path=path, line=header_line)
    return CsvTable(path=path, header=header, rows=tuple(rows), lines=tuple(numbers))


def write_csv(
    path: str | Path | None,
    columns: Mapping[str, Sequence[float] | np.ndarray],
    *,
    fmt: str | Mapping[str, str] = "{:.6f}",
    comments: Sequence[str] = (),
) -> str:
    """Write columns (all the same length) as CSV; return the text. ``path=None`` only returns it.

    ``fmt`` is one format for every column or a mapping from column name to format; non-float
    values (strings) are written as they are.
    """
    names = list(columns)
    n = len(next(iter(columns.values()))) if names else 0
    out = [f"# {c}" for c in comments]
    out.append(",".join(names))
    for k in range(n):
        cells = []
        for name in names:
            value = columns[name][k]
            f = fmt.get(name, "{:.6f}") if isinstance(fmt, Mapping) else fmt
            cells.append(value if isinstance(value, str) else f.format(float(value)))
        out.append(",".join(cells))
    text = "\n".join(out) + "\n"
    if path is not None:
        Path(path).write_text(text, encoding="utf-8")
    return text


def read_toml(path: str | Path) -> dict:
    """Parse a TOML file; a missing, unreadable or malformed file raises AxiscalError naming the line."""
    import re
    import tomllib

    text = read_text(path)
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        # Python 3.11 has no lineno attribute: the line is only in the message
        found = re.search(r"\(at line (\d+)", str(exc))
        message = str(exc).split(" (at line")[0]
        raise AxiscalError(f"malformed TOML: {message}", path=path, line=int(found.group(1)) if found else None) from None
