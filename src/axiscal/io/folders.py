"""Atomic folders: an output folder built beside its destination, then swapped into place whole.

A run killed at any moment leaves the destination as it was (the earlier output, whole) or as the
new one (whole), never a mix of the two. On Linux the swap is one ``renameat2(RENAME_EXCHANGE)``;
elsewhere the old folder is renamed aside and the new one into place (a run killed between the two
renames leaves the earlier output in a hidden folder beside). The temporary folders of a run that
was killed are removed by the next run that writes the same destination.
"""

from __future__ import annotations

import ctypes
import errno
import os
import shutil
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import TypeVar

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_instance, check_path
from axiscal.io.atomic import _running, _sync_folder, _umask

__all__ = ["atomic_folder", "stale_temporaries"]

T = TypeVar("T")
_TAG = "axiscal"


def _prefix(path: Path) -> str:
    return f".{path.name}.{_TAG}-"


def stale_temporaries(path: str | Path) -> list[Path]:
    """The temporary folders left beside ``path`` by runs that were killed while writing it.

    Parameters
    ----------
    path : str or Path
        An output folder written by :func:`atomic_folder`.

    Returns
    -------
    list of Path
        Hidden folders ``.NAME.axiscal-PID-*`` beside ``path`` whose process is no longer running,
        sorted.

    Raises
    ------
    AxiscalError
        For a ``path`` that is not a file name.
    """
    path = check_path("path", path)
    prefix = _prefix(path)
    try:
        entries = list(path.parent.iterdir())
    except OSError:
        return []
    found = []
    for entry in entries:
        if not entry.name.startswith(prefix):
            continue
        pid = entry.name[len(prefix):].split("-", 1)[0]
        if pid.isdigit() and int(pid) != os.getpid() and not _running(int(pid)):
            found.append(entry)
    return sorted(found)


def _remove(path: Path) -> None:
    if path.is_dir() and not path.is_symlink():
        shutil.rmtree(path, ignore_errors=True)
    else:
        try:
            path.unlink()
        except OSError:
            pass


def _exchange(a: Path, b: Path) -> bool:
    """Swap two paths in one step (Linux renameat2); False where the system cannot."""
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        renameat2 = libc.renameat2
    except (OSError, AttributeError):
        return False
    renameat2.argtypes = [ctypes.c_int, ctypes.c_char_p, ctypes.c_int, ctypes.c_char_p, ctypes.c_uint]
    renameat2.restype = ctypes.c_int
    at_fdcwd, rename_exchange = -100, 2
    if renameat2(at_fdcwd, os.fsencode(a), at_fdcwd, os.fsencode(b), rename_exchange) == 0:
        return True
    code = ctypes.get_errno()
    if code in (errno.EINVAL, errno.ENOSYS, errno.ENOTSUP, errno.EOPNOTSUPP):
        return False
    raise OSError(code, os.strerror(code), str(b))


def _sync_tree(folder: Path) -> None:
    for entry in [folder, *folder.rglob("*")]:
        if entry.is_symlink():
            continue
        try:
            fd = os.open(entry, os.O_RDONLY)
        except OSError:
            continue
        try:
            os.fsync(fd)
        except OSError:
            pass
        finally:
            os.close(fd)


def atomic_folder(path: str | Path, fill: Callable[[Path], T], *, marker: str | None = None) -> T:
    """Produce the folder ``path`` atomically: ``fill(tmp)`` fills a folder beside it, then swapped in.

    Parameters
    ----------
    path : str or Path
        The output folder; replaced as a whole when it exists. Its parent is created.
    fill : callable
        Called with the temporary folder (empty, beside ``path``); writes everything there. What it
        returns is returned.
    marker : str, keyword-only
        A file every output of this kind holds (``identify.json``): an existing folder that is not
        empty and holds no such file is refused rather than replaced.

    Returns
    -------
    object
        What ``fill`` returned.

    Raises
    ------
    AxiscalError
        For a ``path`` that is a file or a folder of something else, or a folder that cannot be
        written (naming it); ``path`` is then as it was. What ``fill`` raises is raised after the
        temporary folder is removed.
    """
    path = check_path("path", path)
    if not callable(fill):
        raise AxiscalError(f"fill must be a function that fills the folder, not {fill!r}")
    if marker is not None:
        check_instance("marker", marker, str, what="a file name")
    if path.is_symlink():
        path = path.resolve()  # replace the folder the link points to, not the link
    if path.exists():
        if not path.is_dir():
            raise AxiscalError("exists and is not a folder", path=path)
        if marker is not None and not (path / marker).is_file() and any(path.iterdir()):
            raise AxiscalError(f"holds files that are not an earlier output of this command (no {marker}): "
                               "give a new or an empty folder", path=path)
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        for stale in stale_temporaries(path):
            _remove(stale)
        staging = Path(tempfile.mkdtemp(prefix=f"{_prefix(path)}{os.getpid()}-", dir=path.parent))
    except OSError as exc:
        raise AxiscalError(f"cannot make the folder: {exc.strerror or exc}", path=path) from None
    try:
        result = fill(staging)
        os.chmod(staging, 0o777 & ~_umask())
        _sync_tree(staging)
        if path.is_dir() and not path.is_symlink():
            if _exchange(staging, path):
                _remove(staging)  # it holds the earlier output now
            else:
                aside = Path(tempfile.mkdtemp(prefix=f"{_prefix(path)}{os.getpid()}-old-", dir=path.parent))
                os.replace(path, aside / "previous")
                try:
                    os.replace(staging, path)
                except OSError:
                    os.replace(aside / "previous", path)
                    raise
                _remove(aside)
        else:
            os.replace(staging, path)
        _sync_folder(path.parent)
    except OSError as exc:
        _remove(staging)
        raise AxiscalError(f"cannot write the folder: {exc.strerror or exc}", path=path) from None
    except BaseException:
        _remove(staging)
        raise
    return result
