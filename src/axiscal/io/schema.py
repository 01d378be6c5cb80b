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

__all__ = ["TomlLines", "finite_number", "confined_path"]


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
