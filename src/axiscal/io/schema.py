"""Checking TOML and JSON input against one declared schema per format, naming the key and line.

A hand-edited file gets wrong types in ways Python would silently accept: ``hold_ends = "false"``
(a non-empty string is true), ``tool_mm = [true, 0, 0]`` (a bool is an int), a number written as a
string. Each format declares its keys once as :class:`Field` entries and :func:`check_table`
refuses anything else with one :class:`~axiscal.errors.AxiscalError` naming the file, the line and
the key.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from axiscal.errors import AxiscalError

__all__ = ["TomlLines", "Field", "check_table", "finite_number", "confined_path"]


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
        table's header, else None.

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
        return self.tables.get((table, index))


@dataclass(frozen=True)
class Field:
    """One key of a format.

    Attributes
    ----------
    kind : str
        ``"str"``, ``"bool"``, ``"number"`` (finite int or float, not bool), ``"int"``,
        ``"vector3"`` (a list of three numbers), ``"table"`` or ``"any"``.
    required : bool
        Whether the key must be there.
    choices : tuple of str
        The allowed values of a ``"str"`` key (empty: any text).
    check : callable, optional
        Called with the value after the type check; returns an error message or None.
    """

    kind: str
    required: bool = False
    choices: tuple[str, ...] = ()
    check: Callable[[Any], str | None] | None = None


_KIND_NAMES = {
    "str": "a text in quotes",
    "bool": "true or false",
    "number": "a number",
    "int": "a whole number",
    "vector3": "a list of 3 numbers, e.g. [0.0, -40.0, 0.0]",
    "table": "a table",
}


def _is(kind: str, value: Any) -> bool:
    if kind == "any":
        return True
    if kind == "str":
        return isinstance(value, str)
    if kind == "bool":
        return isinstance(value, bool)
    if kind == "number":
        return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)
    if kind == "int":
        return isinstance(value, int) and not isinstance(value, bool)
    if kind == "vector3":
        return isinstance(value, list) and len(value) == 3 and all(_is("number", v) for v in value)
    if kind == "table":
        return isinstance(value, Mapping)
    raise ValueError(kind)


def _show(value: Any) -> str:
    text = repr(value)
    return text if len(text) <= 40 else text[:37] + "..."


def check_table(
    data: Any,
    fields: Mapping[str, Field],
    *,
    where: str,
    source: str | Path | None = None,
    lines: TomlLines | None = None,
    table: str = "",
    index: int = 0,
) -> dict[str, Any]:
    """Check one table of a TOML or JSON file against its declared fields.

    Parameters
    ----------
    data : mapping
        The parsed table.
    fields : mapping of str to Field
        The keys the table may carry.
    where : str
        How messages name the table (``"[axes.X]"``, ``"the machine file"``).
    source : str or Path, keyword-only
        The file, for messages.
    lines : TomlLines, keyword-only
        To name the line of a key.
    table, index : keyword-only
        The table's dotted name and array index in ``lines``.

    Returns
    -------
    dict
        ``data`` as a plain dict, every value checked.

    Raises
    ------
    AxiscalError
        An unknown key, a missing required key, a value of the wrong type or out of its choices,
        naming the file, the line and the key.
    """

    def fail(message: str, key: str | None = None) -> AxiscalError:
        line = lines.of(table, index, key) if lines is not None else None
        return AxiscalError(message, path=source, line=line)

    if not isinstance(data, Mapping):
        raise fail(f"{where} must be a table")
    for key, value in data.items():
        field = fields.get(key)
        if field is None:
            raise fail(f"{where}: unknown key '{key}' (known: {', '.join(fields)})", key)
        if not _is(field.kind, value):
            raise fail(f"{where} {key} must be {_KIND_NAMES.get(field.kind, field.kind)}, not {_show(value)}", key)
        if field.choices and value not in field.choices:
            raise fail(f"{where} {key} must be one of {', '.join(field.choices)}, not {_show(value)}", key)
        if field.check is not None:
            problem = field.check(value)
            if problem:
                raise fail(f"{where} {key}: {problem}", key)
    for key, field in fields.items():
        if field.required and key not in data:
            raise fail(f"{where} needs '{key}'")
    return dict(data)


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
