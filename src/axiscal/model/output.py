"""What the machine model writes: plain data CSVs with a JSON sidecar, and text from templates.

A data CSV is plain (header first, no comment lines; docs/formats.md); what describes it (the kind,
the sign convention, the machine file, settings) goes into the sidecar ``NAME.json`` beside it.
Multi-line text is rendered from the Jinja2 templates shipped in ``axiscal/templates``.
"""

from __future__ import annotations

import os
from abc import ABC, abstractmethod
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_instance, check_mapping, check_path, render_checked
from axiscal.io.atomic import write_text
from axiscal.io.jsonio import write_sidecar
from axiscal.io.tabular import write_csv
from axiscal.io.templates import render_template as _render

__all__ = ["SIGN_CONVENTION", "table_text", "write_table", "TableResult", "render_template"]

#: the one sign of every displacement error the model room outputs (docs/conventions.md)
SIGN_CONVENTION = "actual minus nominal, along the stated direction"


def table_text(columns: Mapping[str, np.ndarray], *, fmt: str = "{:.6f}") -> str:
    """The CSV text of equally long columns (display units already in the names and values).

    Parameters
    ----------
    columns : mapping of str to ndarray, shape (N,)
        Column name to values.
    fmt : str
        Format of every value.

    Returns
    -------
    str
        Header line, then one line per row, each ending in a newline.
    """
    check_mapping("columns", columns, what="a mapping of column names to values")
    checked = {}
    for name, values in columns.items():
        check_instance("column name", name, str)
        checked[name] = check_array(f"column {name!r}", values, ndim=1, finite=False, unit="")
    if len({v.size for v in checked.values()}) > 1:
        raise AxiscalError(f"columns must be equally long, not {', '.join(str(v.size) for v in checked.values())} values")
    check_instance("fmt", fmt, str, what="a format such as '{:.6f}'")
    try:
        fmt.format(0.0)
    except (ValueError, IndexError, KeyError):
        raise AxiscalError(f"fmt {fmt!r} is not a format of one number such as '{{:.6f}}'") from None
    return write_csv(None, checked, fmt=fmt)


def write_table(
    path: str | Path,
    columns: Mapping[str, np.ndarray],
    *,
    fmt: str = "{:.6f}",
    kind: str,
    sources: Sequence[str | Path] = (),
    sidecar: bool = True,
    **metadata: Any,
) -> Path:
    """Write a plain data CSV atomically and, unless ``sidecar=False``, its JSON sidecar.

    Parameters
    ----------
    path : str or Path
        The CSV to write (its folder is created); the sidecar is the same name ending in ``.json``.
    columns : mapping of str to ndarray, shape (N,)
        Column name to values, display units.
    fmt : str
        Format of every value.
    kind : str
        What the file holds, for the sidecar.
    sources : sequence of paths
        Input files, for the sidecar.
    sidecar : bool
        Write the sidecar (default True).
    **metadata
        Further sidecar entries; the sign convention is always recorded.

    Returns
    -------
    Path
        The CSV's path.

    Raises
    ------
    AxiscalError
        If the file cannot be written.
    """
    path = check_path("path", path)
    check_instance("kind", kind, str)
    if isinstance(sources, (str, os.PathLike)) or not isinstance(sources, Sequence):
        raise AxiscalError(f"sources must be a list of file names, not {sources!r:.40}")
    text = table_text(columns, fmt=fmt)
    path = write_text(path, text)
    if sidecar:
        write_sidecar(path, kind=kind, sources=sources, **({"sign": SIGN_CONVENTION} | metadata))
    return path


class TableResult(ABC):
    """What the model room's result objects share: their table as CSV text, or as a file with its sidecar.

    A subclass gives :meth:`columns` (display units in names and values), the class attributes
    below and, optionally, more sidecar entries in :meth:`sidecar_metadata`.

    Attributes
    ----------
    csv_format : str
        Format of every value in the CSV.
    csv_kind : str
        What the table holds, for the sidecar.
    sources : tuple of str
        Files the result was computed from, for the sidecar.
    """

    csv_format = "{:.6f}"
    csv_kind = "table"
    sources: tuple[str, ...] = ()

    @abstractmethod
    def columns(self) -> dict[str, np.ndarray]:
        """The table: column name (with its unit) to values in that unit.

        Returns
        -------
        dict of str to ndarray, shape (N,)
        """

    def sidecar_metadata(self) -> dict[str, Any]:
        """Entries of the JSON sidecar besides kind, sign and sources.

        Returns
        -------
        dict
        """
        return {}

    def csv(self) -> str:
        """The CSV text of :meth:`columns`.

        Returns
        -------
        str
            Header line, then one line per row.
        """
        return table_text(self.columns(), fmt=self.csv_format)

    def write_csv(self, path: str | Path, *, sidecar: bool = True) -> Path:
        """Write the CSV atomically and, unless ``sidecar=False``, its JSON sidecar.

        Parameters
        ----------
        path : str or Path
            The CSV file (its folder is created); the sidecar is the same name ending in ``.json``.
        sidecar : bool
            Write the sidecar (default True): kind, sign convention, sources and
            :meth:`sidecar_metadata`.

        Returns
        -------
        Path
            ``path``.

        Raises
        ------
        AxiscalError
            If the file cannot be written.
        """
        return write_table(
            path, self.columns(), fmt=self.csv_format, kind=self.csv_kind, sources=self.sources, sidecar=sidecar,
            **self.sidecar_metadata(),
        )


def render_template(template: str, /, **context: Any) -> str:
    """Render the text template ``axiscal/templates/<template>`` with ``context``.

    Parameters
    ----------
    template : str
        File name of the template, e.g. ``"model_diagonal.txt.j2"``.
    **context
        The template's variables; a variable the template uses but is not given raises.

    Returns
    -------
    str
        The rendered text.

    Raises
    ------
    jinja2.TemplateNotFound, jinja2.UndefinedError
        A template that is not shipped, or a variable it uses that is not given (program errors,
        not user mistakes).
    """
    return render_checked(_render_kept, template, **context)


def _render_kept(template: str, **context: Any) -> str:
    return _render(template, keep_trailing_newline=True, **context)
