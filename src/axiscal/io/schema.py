"""What the readers of TOML and JSON files share: where each key stands (to name its line in an
error), what counts as a number (a bool does not, nor NaN), and file names confined to a folder.

A hand-edited file gets wrong types in ways Python would silently accept (``hold_ends = "false"``
is a true string, ``True`` is an int); every reader checks its keys against its declared schema
with these helpers and names the file, the line and the key.
"""

from __future__ import annotations

import math
import re
from pathlib import Path
from typing import Any

from axiscal.errors import AxiscalError
from axiscal.io.arguments import is_real

__all__ = ["TomlLines", "finite_number", "confined_path", "MAX_NESTING", "nesting_error", "check_nesting", "check_key_depth"]

#: how deep tables, arrays and dotted keys may nest in a file read by hand-written formats (the
#: deepest format nests a few levels; deeper than this, readers and validators would recurse without end)
MAX_NESTING = 50


class TomlLines:
    """Where each table and key of a TOML text stands, so that an error can name the line.

    Parameters
    ----------
    text : str
        The TOML text.

    Examples
    --------
    >>> lines = TomlLines('name = "x"\\n[axes.X]\\nerrors = "x.csv"\\n')
    >>> lines.of("axes.X", key="errors"), lines.of("axes.X"), lines.of("", key="name")
    (3, 2, 1)
    """

    _header = re.compile(r"^\s*(\[\[?)\s*([A-Za-z0-9_.\-\"' ]+?)\s*\]\]?\s*(#.*)?$")
    _key = re.compile(r"^\s*([A-Za-z0-9_\-]+|\"[^\"]*\")\s*=")

    def __init__(self, text: str):
        self.tables: dict[tuple[str, int], int] = {}
        self.keys: dict[tuple[str, int, str], int] = {}
        counts: dict[str, int] = {}
        table, index = "", 0
        for number, line in enumerate(re.split(r"\r\n|\r|\n", text), start=1):
            found = self._header.match(line)
            if found:
                table = found.group(2).strip().replace(" ", "").replace('"', "")
                if found.group(1) == "[[":
                    index = counts.get(table, 0)
                    counts[table] = index + 1
                else:
                    index = 0
                self.tables[(table, index)] = number
                continue
            found = self._key.match(line)
            if found:
                self.keys.setdefault((table, index, found.group(1).strip('"')), number)

    def of(self, table: str, index: int = 0, key: str | None = None) -> int | None:
        """The line of ``key`` in ``[table]`` (the ``index``-th for an array of tables), else of the
        table's header (or of its first sub-table's, for a table made only by sub-tables), else None.

        Parameters
        ----------
        table : str
            Dotted table name (``""`` for the top level).
        index : int
            Which ``[[table]]``.
        key : str, optional

        Returns
        -------
        int or None
        """
        if key is not None:
            found = self.keys.get((table, index, key))
            if found is not None:
                return found
            dotted = key.split(".")
            if len(dotted) > 1:
                return self.of(".".join([table, *dotted[:-1]]).strip("."), index, dotted[-1])
        found = self.tables.get((table, index))
        if found is None and table:  # a table made only by its sub-tables ([a.b] makes a): the first of them
            found = min((n for (t, _), n in self.tables.items() if t.startswith(table + ".")), default=None)
        return found


def _is(kind: str, value: Any) -> bool:
    if kind == "number":
        return is_real(value) and math.isfinite(value)
    raise ValueError(kind)


def finite_number(value: Any) -> bool:
    """True for an int or float that is finite (a bool is not a number here).

    Parameters
    ----------
    value : object

    Returns
    -------
    bool
    """
    return _is("number", value)


def confined_path(base: str | Path, name: str) -> Path:
    """The file ``name`` relative to the folder ``base``, refused when it leaves it.

    Parameters
    ----------
    base : str or Path
        The folder of the file that names ``name`` (a machine file's folder).
    name : str
        The file name as written.

    Returns
    -------
    Path
        The resolved path inside ``base``.

    Raises
    ------
    AxiscalError
        For an absolute name or one that leaves ``base`` (``..``, a link pointing out); the
        message names neither the target's content nor anything read from it.
    """
    base = Path(base).resolve()
    candidate = Path(name)
    if candidate.is_absolute():
        raise AxiscalError(f"'{name}' is an absolute path: name files relative to the folder of the file that names them")
    resolved = (base / candidate).resolve()
    if not resolved.is_relative_to(base):
        raise AxiscalError(f"'{name}' leaves the folder of the file that names it ({base})")
    return resolved


def _deep_line(text: str) -> int | None:
    """The first line whose arrays, inline tables and dotted key alone nest deeper than :data:`MAX_NESTING`, else None."""
    depth = 0
    for number, line in enumerate(re.split(r"\r\n|\r|\n", text), start=1):
        key = line.split("=", 1)[0] if "=" in line else line if line.lstrip().startswith("[") and depth == 0 else ""
        dots = key.count(".")
        if depth + dots > MAX_NESTING:
            return number
        for bracket in line.translate(_NOT_BRACKETS):
            depth += (bracket in "[{") - (bracket in "]}")
            if depth + dots > MAX_NESTING:
                return number
    return None


_NOT_BRACKETS = {c: None for c in range(128) if chr(c) not in "[]{}"}


def check_key_depth(text: str, *, path: str | Path | None = None) -> None:
    """Refuse a TOML text with a dotted key or table name of more than :data:`MAX_NESTING` parts, before it is parsed.

    Python's TOML parser takes time growing with the square of a dotted key's length (a 5,000-part
    key: seconds), so such a key is refused by its text alone.

    Parameters
    ----------
    text : str
        The TOML text.
    path : str or Path, optional, keyword-only
        The file, named in the error.

    Raises
    ------
    AxiscalError
        Naming the line of the first such key.
    """
    for number, line in enumerate(re.split(r"\r\n|\r|\n", text), start=1):
        key = line.split("=", 1)[0]
        if key.count(".") <= MAX_NESTING:
            continue
        key = _QUOTED.sub("q", key).strip()
        if ("=" in line or key.startswith("[")) and _DOTTED.fullmatch(key.strip("[] \t")) and key.count(".") > MAX_NESTING:
            raise AxiscalError(f"nested more than {MAX_NESTING} levels deep (arrays, tables or dotted keys inside each"
                               " other)", path=path, line=number)


_QUOTED = re.compile(r"\"(?:[^\"\\]|\\.)*\"|'[^']*'")
#: a dotted key: bare or quoted parts (quotes replaced by ``q``) joined by dots (prose with dot leaders is not one)
_DOTTED = re.compile(r"[A-Za-z0-9_\-]+(?:[ \t]*\.[ \t]*[A-Za-z0-9_\-]+)*")


def nesting_error(text: str, *, path: str | Path | None = None) -> AxiscalError:
    """The error for a text nested deeper than :data:`MAX_NESTING`, naming the line where it goes too deep (when found).

    Parameters
    ----------
    text : str
        The file's text.
    path : str or Path, optional, keyword-only
        The file, named in the error.

    Returns
    -------
    AxiscalError
    """
    return AxiscalError(f"nested more than {MAX_NESTING} levels deep (arrays, tables or dotted keys inside each other)",
                        path=path, line=_deep_line(text))


def check_nesting(data: Any, text: str, *, path: str | Path | None = None) -> Any:
    """``data`` (parsed TOML or JSON) when its tables and arrays nest at most :data:`MAX_NESTING` deep.

    Parameters
    ----------
    data : object
        The parsed file: dicts, lists and plain values.
    text : str
        The file's text (to find the line of an error).
    path : str or Path, optional, keyword-only
        The file, named in the error.

    Returns
    -------
    object
        ``data`` itself.

    Raises
    ------
    AxiscalError
        For deeper nesting (a 5,000-deep dotted key parses, but every reader after it would
        recurse without end), naming the line where it goes too deep.
    """
    pending = [(data, 0)]
    while pending:
        value, depth = pending.pop()
        items = value.values() if isinstance(value, dict) else value if isinstance(value, list) else ()
        for item in items:
            if isinstance(item, (dict, list)):
                if depth + 1 > MAX_NESTING:
                    raise nesting_error(text, path=path)
                pending.append((item, depth + 1))
    return data
