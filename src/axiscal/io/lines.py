"""Physical lines of a text file as an editor shows them: only LF, CRLF and CR end a line.

Python's ``str.splitlines`` also breaks at form feeds, U+2028 and other separators, so its line
numbers disagree with an editor's; here the line structure is computed with NumPy over the byte
positions of the line ends (no Python loop per line), so that a reader can name any line cheaply.
"""

from __future__ import annotations

import numpy as np

from axiscal.io.arguments import check_instance

__all__ = ["Lines"]

# bytes that may start a line that is blank or a comment once stripped of white space (ASCII white
# space and control characters that str.strip() removes, and every non-ASCII lead byte)
_DOUBTFUL = np.zeros(256, dtype=bool)
_DOUBTFUL[[b for b in range(128) if chr(b).isspace()]] = True
_DOUBTFUL[0x80:] = True


class Lines:
    """Start and end byte offsets of every physical line of ``data``.

    Parameters
    ----------
    data : bytes
        The file's content (UTF-8; the terminators are ASCII, so offsets never split a character).

    Attributes
    ----------
    starts, ends : numpy.ndarray of int64, shape (n,)
        Offset of each line's first byte and one past its last byte before the line end. A file
        ending with a line end has no empty line after it.

    Raises
    ------
    AxiscalError
        For ``data`` that is not bytes.

    Examples
    --------
    >>> lines = Lines(b"a\\r\\nb\\rc\\x0cd\\n")
    >>> len(lines), lines.text(2), lines.number_at(5)
    (3, 'c\\x0cd', 3)
    """

    def __init__(self, data: bytes):
        check_instance("data", data, bytes, what="the file's content (bytes)")
        self.data = data
        arr = np.frombuffer(data, dtype=np.uint8)
        if b"\r" in data:
            lf = arr == 10
            cr_alone = arr == 13
            cr_alone[:-1] &= ~lf[1:]
            last = np.flatnonzero(lf | cr_alone)  # the last byte of each line end
            crlf = np.zeros(len(last), dtype=bool)
            inner = last > 0
            crlf[inner] = (arr[last[inner]] == 10) & (arr[last[inner] - 1] == 13)
            content_end = last - crlf
        else:
            last = np.flatnonzero(arr == 10)
            content_end = last
        starts = np.concatenate(([0], last + 1))
        ends = np.concatenate((content_end, [len(arr)]))
        if starts[-1] == len(arr):
            starts, ends = starts[:-1], ends[:-1]
        self.starts = starts.astype(np.int64, copy=False)
        self.ends = ends.astype(np.int64, copy=False)

    def __len__(self) -> int:
        return len(self.starts)

    def text(self, index: int) -> str:
        """The text of line ``index`` (0-based) without its line end, decoded as UTF-8."""
        return self.data[self.starts[index] : self.ends[index]].decode("utf-8", errors="replace")

    def number_at(self, offset: int) -> int:
        """The 1-based number of the line holding byte ``offset``."""
        return max(int(np.searchsorted(self.starts, offset, side="right")), 1)

    def content(self) -> np.ndarray:
        """0-based indices of the lines that are neither blank nor comments (first non-blank ``#``).

        White space is what ``str.strip`` removes. Lines are judged by their first byte; only those
        starting with white space or a non-ASCII character are decoded and looked at in Python.
        """
        arr = np.frombuffer(self.data, dtype=np.uint8)
        nonempty = self.ends > self.starts
        first = np.zeros(len(self.starts), dtype=np.uint8)
        first[nonempty] = arr[self.starts[nonempty]]
        keep = nonempty & (first != ord("#"))
        for index in np.flatnonzero(nonempty & _DOUBTFUL[first]):
            stripped = self.text(index).strip()
            keep[index] = bool(stripped) and not stripped.startswith("#")
        return np.flatnonzero(keep)

    def count(self, byte: bytes, indices: np.ndarray) -> np.ndarray:
        """How often ``byte`` occurs in each of the lines ``indices``."""
        arr = np.frombuffer(self.data, dtype=np.uint8)
        found = np.flatnonzero(arr == ord(byte))
        return np.searchsorted(found, self.ends[indices]) - np.searchsorted(found, self.starts[indices])

    def join(self, indices: np.ndarray) -> bytes:
        """The bytes of the lines ``indices`` (sorted), each with its own line end."""
        if len(indices) and indices[-1] - indices[0] + 1 == len(indices):
            return self.data[self.starts[indices[0]] : self.ends[indices[-1]]]
        nxt = np.append(self.starts[1:], len(self.data))
        mark = np.zeros(len(self.data) + 1, dtype=np.int8)
        mark[self.starts[indices]] += 1
        mark[nxt[indices]] -= 1
        keep = np.cumsum(mark[:-1], dtype=np.int8) > 0
        return np.frombuffer(self.data, dtype=np.uint8)[keep].tobytes()
