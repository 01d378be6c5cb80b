"""JSON output: plain values (NaN becomes null), atomic files, and the sidecar beside a data CSV.

A data CSV that axiscal writes is plain (header first, no comment lines); what describes it (the
method, the units, the source files, the axiscal version) is written beside it as ``NAME.json``.
"""

from __future__ import annotations

import json
import math
from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_instance, check_path
from axiscal.io.atomic import write_text
from axiscal.version import __version__

__all__ = ["to_plain", "dumps", "write_json", "read_json", "json_line", "sidecar_path", "write_sidecar", "named_from"]


def to_plain(value: Any) -> Any:
    """``value`` with NumPy scalars and arrays turned into Python ones, non-finite floats into None."""
    if isinstance(value, Mapping):
        return {str(k): to_plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [to_plain(v) for v in value]
    if isinstance(value, np.ndarray):
        return [to_plain(v) for v in value.tolist()]
    if isinstance(value, (np.floating, float)):
        value = float(value)
        return value if math.isfinite(value) else None
    if isinstance(value, np.integer):
        return int(value)
    if isinstance(value, np.bool_):
        return bool(value)
    if isinstance(value, Path):
        return str(value)
    return value


def dumps(payload: Any) -> str:
    """The JSON text of ``payload`` (indented, ending in a newline); NaN and infinities are null.

    Raises
    ------
    AxiscalError
        For a payload holding a value JSON cannot write (an object, a set, bytes, a complex number).
    """
    try:
        return json.dumps(to_plain(payload), indent=2, ensure_ascii=False) + "\n"
    except (TypeError, ValueError) as exc:
        raise AxiscalError(f"payload holds a value JSON cannot write ({exc})") from None


def write_json(path: str | Path, payload: Any) -> Path:
    """Write ``payload`` as JSON to ``path`` atomically.

    Raises
    ------
    AxiscalError
        For a payload JSON cannot write, a ``path`` that is not a file name, a file that cannot
        be written.
    """
    return write_text(path, dumps(payload))


def json_line(text: str, *keys: str) -> int | None:
    """The line of a key path (``"channels", "x_psd_y_um", "gain"``) in a JSON text, so an error can name it.

    Each key is looked for after the one before, as ``"key":``; the line of the deepest key found
    is returned (None when not even the first is there). Exact for files where a key path is
    spelled once in order, as axiscal writes them.

    Parameters
    ----------
    text : str
        The JSON text.
    *keys : str
        The path of object keys.

    Returns
    -------
    int or None

    Raises
    ------
    AxiscalError
        For a ``text`` that is not a str.

    Examples
    --------
    >>> json_line('{\n  "a": {\n    "b": 1,\n    "c": 2\n  }\n}', "a", "c")
    4
    """
    import re

    check_instance("text", text, str, what="the JSON text (a str)")
    at, found = 0, None
    for key in keys:
        match = re.compile(re.escape(json.dumps(str(key), ensure_ascii=False)) + r"\s*:").search(text, at)
        if match is None:
            break
        at, found = match.end(), match.start()
    return None if found is None else text.count("\n", 0, found) + 1


def read_json(path: str | Path) -> Any:
    """Parse a JSON file; a missing or malformed file raises AxiscalError naming the line.

    Raises
    ------
    AxiscalError
        For a ``path`` that is not a file name, a missing or unreadable file, malformed JSON.
    """
    from axiscal.io.tabular import read_text

    from axiscal.io.schema import check_nesting, nesting_error

    text = read_text(path)
    try:
        return check_nesting(json.loads(text), text, path=path)
    except RecursionError:  # json parses nested arrays and objects recursively
        raise nesting_error(text, path=path) from None
    except json.JSONDecodeError as exc:
        raise AxiscalError(f"malformed JSON: {exc.msg}", path=path, line=exc.lineno) from None


def sidecar_path(csv_path: str | Path) -> Path:
    """``NAME.json`` beside ``NAME.csv``.

    Raises
    ------
    AxiscalError
        For a ``csv_path`` that is not a file name.
    """
    return check_path("csv_path", csv_path).with_suffix(".json")


def write_sidecar(
    csv_path: str | Path,
    *,
    kind: str,
    units: Mapping[str, str] | None = None,
    sources: Sequence[str | Path] = (),
    **metadata: Any,
) -> Path:
    """Write the JSON sidecar of a data CSV: what it is, its columns' units, its sources.

    Parameters
    ----------
    csv_path : str or Path
        The CSV the sidecar describes; the sidecar is ``csv_path`` with the suffix ``.json``.
    kind : str, keyword-only
        What the file holds, e.g. ``"separation"`` or ``"positioning plan"``.
    units : mapping, keyword-only
        Column name to unit, where the name alone does not say it.
    sources : sequence of paths, keyword-only
        The input files the CSV was computed from.
    **metadata
        Anything else worth keeping (method, settings, counts).

    Returns
    -------
    Path
        The sidecar's path.

    Raises
    ------
    AxiscalError
        For a ``csv_path`` that is not a file name, an empty ``kind``, ``units`` that is not a
        mapping or ``sources`` that is not a sequence of names; or when the file cannot be written.
    """
    csv_path = check_path("csv_path", csv_path)
    if not isinstance(kind, str) or not kind.strip():
        raise AxiscalError(f"kind must say what the file holds (a str), not {kind!r}")
    if units is not None and not isinstance(units, Mapping):
        raise AxiscalError(f"units must map column names to units, not {type(units).__name__}")
    if isinstance(sources, (str, bytes, Path)) or not isinstance(sources, Iterable):
        raise AxiscalError(f"sources must be a sequence of file names, not {sources!r}")
    payload: dict[str, Any] = {"kind": kind, "file": csv_path.name, "axiscal_version": __version__}
    if units:
        payload["units"] = dict(units)
    if sources:
        payload["sources"] = [str(s) for s in sources]
    payload.update(metadata)
    return write_json(sidecar_path(csv_path), payload)


def named_from(path: str | Path, beside: str | Path) -> str:
    """How a sidecar beside ``beside`` names ``path``: relative to ``beside``'s folder when it lies
    within it (so a folder moved elsewhere still names its own files), else as it was given.

    Parameters
    ----------
    path : str or Path
        The file named (a source, a program).
    beside : str or Path
        The file whose sidecar names it.

    Returns
    -------
    str

    Examples
    --------
    >>> named_from("/data/run/x.ngc", "/data/run/recording.csv")
    'x.ngc'
    """
    try:
        return str(Path(path).resolve().relative_to(Path(beside).resolve().parent))
    except ValueError:
        return str(path)
