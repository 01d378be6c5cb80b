"""Text files read whole: UTF-8 text and TOML, a bad byte or a malformed line refused naming its line."""

from __future__ import annotations

import re
from pathlib import Path

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_instance, check_path

__all__ = ["read_text", "read_checked_text", "read_toml", "parse_toml"]


def read_text(path: str | Path) -> str:
    """The text of a UTF-8 file (a byte-order mark is dropped).

    Raises
    ------
    AxiscalError
        If the file is missing or unreadable, naming it; if it is not UTF-8, naming the line of the
        first byte that is not.
    """
    return read_checked_text(check_path("path", path))


def read_checked_text(path: Path) -> str:
    """:func:`read_text` of a path a public entry has already checked (a file a checked file names).

    Parameters
    ----------
    path : Path

    Returns
    -------
    str
    """
    try:
        data = path.read_bytes()
    except FileNotFoundError:
        raise AxiscalError("file not found", path=path) from None
    except OSError as exc:
        raise AxiscalError(f"cannot read file ({exc})", path=path) from None
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        before = data[: exc.start]
        line = before.count(b"\n") + before.count(b"\r") - before.count(b"\r\n") + 1
        raise AxiscalError(f"not UTF-8 text (byte 0x{data[exc.start]:02x})", path=path, line=line) from None



def read_toml(path: str | Path) -> dict:
    """Parse a TOML file.

    Raises
    ------
    AxiscalError
        If the file is missing, unreadable or malformed, naming the file and line.
    """
    return parse_toml(read_text(path), path=path)


def parse_toml(text: str, *, path: str | Path | None = None) -> dict:
    """Parse TOML text, a malformed text refused naming its line.

    Parameters
    ----------
    text : str
        The TOML text (as :func:`read_text` returns it).
    path : str or Path, optional, keyword-only
        The file's name, for messages.

    Returns
    -------
    dict

    Raises
    ------
    AxiscalError
        For malformed TOML, naming the line (the last line for a text cut short).

    Examples
    --------
    >>> parse_toml("a = 1")
    {'a': 1}
    """
    import tomllib

    from axiscal.io.schema import check_key_depth, check_nesting, nesting_error

    check_instance("text", text, str, what="the TOML text (a str)")
    check_key_depth(text, path=path)
    try:
        return check_nesting(tomllib.loads(text), text, path=path)
    except RecursionError:  # tomllib parses nested arrays and inline tables recursively
        raise nesting_error(text, path=path) from None
    except tomllib.TOMLDecodeError as exc:
        # Python 3.11 has no lineno attribute: the line is only in the message
        found = re.search(r"\(at line (\d+)", str(exc))
        message = re.split(r" \(at (?:line|end of document)", str(exc))[0]
        if found:
            line = int(found.group(1))
        else:  # "at end of document": the last line
            line = len(re.split(r"\r\n|\r|\n", text.rstrip("\r\n"))) if "end of document" in str(exc) else None
        raise AxiscalError(f"malformed TOML: {message}", path=path, line=line) from None
