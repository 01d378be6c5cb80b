"""Atomic writes: a temporary file in the target's folder, flushed to disk, then renamed over it.

A failure (no permission, disk full, an exception while the content is produced) never leaves a
half-written file and never destroys the file that was there before.
"""

from __future__ import annotations

import os
import re
import tempfile
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_instance, check_path

__all__ = ["atomic_write", "write_text", "remove_stale_temporaries"]

#: a temporary file left by an earlier release (no process id in its name) is stale after this long, s
LEGACY_STALE_S = 3600.0


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
        fd, name = tempfile.mkstemp(prefix=f".{path.name}.{os.getpid()}-", suffix=path.suffix or ".tmp", dir=path.parent)
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


def remove_stale_temporaries(path: str | Path) -> list[Path]:
    """Remove the temporary files that writes of ``path`` killed before their end left beside it.

    :func:`atomic_write` names its temporary ``.<name>.<process id>-<random><suffix>`` in the
    target's folder; a run killed (SIGKILL, power loss) before the rename leaves it there. Such a file
    is removed when its process is no longer running; a temporary of a process still running (a
    write of the same file under way) is left alone. A temporary of an earlier release (no process
    id in its name) is removed once it is older than :data:`LEGACY_STALE_S`.

    Parameters
    ----------
    path : str or Path
        The file whose stale temporaries are removed (it need not exist).

    Returns
    -------
    list of Path
        The files removed.

    Raises
    ------
    AxiscalError
        For a ``path`` that is not a file name.
    """
    path = check_path("path", path)
    if path.is_symlink():
        path = path.resolve()
    folder = path.parent
    suffix = re.escape(path.suffix or ".tmp")
    ours = re.compile(rf"\.{re.escape(path.name)}\.(?:(\d+)-)?[a-z0-9_]{{8}}{suffix}")
    removed: list[Path] = []
    try:
        names = [entry for entry in os.scandir(folder) if entry.name.startswith(f".{path.name}.")]
    except OSError:
        return removed
    now = time.time()
    for entry in names:
        found = ours.fullmatch(entry.name)
        if found is None:
            continue
        try:
            if not entry.is_file(follow_symlinks=False):
                continue
            if found.group(1) is not None:
                if _running(int(found.group(1))):
                    continue
            elif now - entry.stat(follow_symlinks=False).st_mtime < LEGACY_STALE_S:
                continue
            os.unlink(entry.path)
            removed.append(Path(entry.path))
        except OSError:
            continue
    return removed


def _running(pid: int) -> bool:
    """Whether a process ``pid`` is running here (another user's process counts)."""
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (OverflowError, ValueError):  # a number no process has
        return False
    except OSError:  # not ours to signal: running
        return True
    return True


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
