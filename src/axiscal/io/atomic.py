"""Atomic writes: a temporary file in the target's folder, flushed to disk, then renamed over it.

A failure (no permission, disk full, an exception while the content is produced) never leaves a
half-written file and never destroys the file that was there before.
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import Any

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_instance, check_path

__all__ = ["atomic_write", "write_text"]


def atomic_write(path: str | Path, write: Callable[[Path], Any], *, make_parents: bool = True) -> Path:
    """Produce ``path`` atomically: ``write(tmp)`` fills a temporary file that then replaces ``path``.

    A link is followed (the file it points to is replaced). A device or a pipe (``/dev/null``, a
    FIFO) cannot be replaced and is written directly.

    Parameters
    ----------
    path : str or Path
        The file to produce. Its folder is created when ``make_parents`` (the default).
    write : callable
        Called with the temporary path (in the same folder, same suffix, so that writers that pick
        a format from the suffix, such as matplotlib, still do).
    make_parents : bool, keyword-only
        Create missing parent folders.

    Returns
    -------
    Path
        ``path``.

    Raises
    ------
    AxiscalError
        If the folder cannot be made or the file cannot be written; it names the file. Also for a
        ``path`` that is not a file name or a ``write`` that is not callable.
    """
    path = check_path("path", path)
    if not isinstance(make_parents, bool):
        raise AxiscalError(f"make_parents must be a bool, not {make_parents!r}")
    if not callable(write):
        raise AxiscalError(f"write must be a function that fills the file, not {write!r}")
    shown = path
    tmp: Path | None = None
    try:
        if path.is_symlink():
            path = path.resolve()  # replace the file the link points to, not the link
        if path.exists() and not path.is_file():
            if path.is_dir():
                raise AxiscalError("is a folder, not a file", path=shown)
            # a device or a pipe (/dev/null, /dev/stdout, a FIFO): nothing to replace, write to it
            write(path)
            return path
        if make_parents:
            path.parent.mkdir(parents=True, exist_ok=True)
        fd, name = tempfile.mkstemp(prefix=f".{path.name}.", suffix=path.suffix or ".tmp", dir=path.parent)
        os.close(fd)
        tmp = Path(name)
        write(tmp)
        with open(tmp, "rb+") as handle:
            os.fsync(handle.fileno())
        mode = path.stat().st_mode & 0o7777 if path.exists() else 0o666 & ~_umask()
        os.chmod(tmp, mode)
        os.replace(tmp, path)
        tmp = None
        _sync_folder(path.parent)
    except OSError as exc:
        raise AxiscalError(f"cannot write this file: {exc.strerror or exc}", path=shown) from None
    finally:
        if tmp is not None:
            try:
                tmp.unlink()
            except OSError:
                pass
    return path


def write_text(path: str | Path, text: str) -> Path:
    """Write ``text`` (UTF-8, newlines as given) to ``path`` atomically; see :func:`atomic_write`.

    Parameters
    ----------
    path : str or Path
        The file to produce.
    text : str
        Its content.

    Returns
    -------
    Path
        ``path``.

    Raises
    ------
    AxiscalError
        For a ``text`` that is not a str, or what :func:`atomic_write` raises.
    """
    check_instance("text", text, str, what="a str")
    return atomic_write(path, lambda target: target.write_bytes(text.encode("utf-8")))


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def _sync_folder(folder: Path) -> None:
    # the rename is durable once the folder's entry is on disk (POSIX; not possible on Windows)
    try:
        fd = os.open(folder, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)
