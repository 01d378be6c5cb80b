"""Renishaw dynamic capture files (``.rtx``): read them into a time series, and write them (for tests).

Layout as the two public readers take it (rtx2csv, github.com/TanmayPani/rtx2csv, ``rtx_to_csv.py``;
RTX2CSV-Converter, github.com/travdt/RTX2CSV-Converter, ``RTXFileProcessor.cs``): the text line
``HEADER::``, then the 17 ``Key: value`` lines of :data:`RTX_FIELDS` (a value may be empty:
``Machine: ``), the line ``Data:``, ``Sample no`` samples as little-endian IEEE 754 float64, and a
trailer; lines end in CR LF. rtx2csv drops the 7 bytes after the samples, whatever they hold;
RTX2CSV-Converter reads ``Sample no`` doubles and takes an 8-byte slot starting ``\\r\\nEOF`` as the
end. The trailer of a file from the instrument is most likely ``\\r\\nEOF::`` (:data:`RTX_EOF`); the
reader takes the declared number of samples and accepts any trailer starting ``\\r\\nEOF`` or
``EOF``. Sample k is taken at ``k / Actual sample rate`` seconds. The header does not state the unit
of the samples: the caller gives it. No file from the instrument was at hand: the reader is tested
with files built to this layout, with the header values of a published capture.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_mapping, check_number, check_path
from axiscal.io.arguments import check_instance
from axiscal.io.atomic import atomic_write, write_text
from axiscal.io.importers.columnmap import IMPORT_UNITS
from axiscal.io.jsonio import write_sidecar
from axiscal.io.tabular import parse_number

__all__ = [
    "RTX_HEADER",
    "RTX_DATA",
    "RTX_EOF",
    "RTX_TRAILERS",
    "RTX_FIELDS",
    "RtxCapture",
    "read_rtx",
    "write_rtx",
    "rtx_csv",
    "write_rtx_csv",
]

RTX_HEADER = b"HEADER::\r\n"
RTX_DATA = b"Data:\r\n"
RTX_EOF = b"\r\nEOF::"
"""The trailer :func:`write_rtx` writes after the samples (7 bytes, as rtx2csv drops)."""
RTX_TRAILERS = (b"\r\nEOF", b"EOF")
"""How a trailer the reader accepts starts."""
RTX_FIELDS = (
    "Filename",
    "Owner",
    "Version no",
    "File Type",
    "Velocity",
    "Sample rate",
    "Sample no",
    "Trigger point",
    "Trigger interval",
    "Actual sample rate",
    "Flags",
    "Machine",
    "Serial No",
    "Date",
    "By",
    "Axis",
    "Location",
)
"""The header fields of a capture, in the order RTX2CSV-Converter reads them."""
_LONGEST_TRAILER = len(b"\r\nEOF::\r\n")
_RATE_KEYS = ("Actual sample rate", "Sample rate")


@dataclass(frozen=True)
class RtxCapture:
    """A dynamic capture: equally spaced samples of one reading.

    Attributes
    ----------
    samples_m : ndarray, shape (n,)
        The readings, metres.
    sample_rate_hz : float
        Samples per second (the header's ``Actual sample rate``, else ``Sample rate``).
    header : dict of str to str
        Every ``Key: value`` line of the header, as text, in the file's order (the fields of
        :data:`RTX_FIELDS` and any other; an empty value is ``""``).
    unit : str
        The unit the samples were stored in (``nm``, ``um``, ``mm``, ``m`` or ``in``).
    source : str
        The file read.
    trailer : bytes
        The bytes after the samples (``b"\\r\\nEOF::"`` in a file from the instrument).
    """

    samples_m: np.ndarray
    sample_rate_hz: float
    header: Mapping[str, str] = field(default_factory=dict)
    unit: str = "mm"
    source: str = ""
    trailer: bytes = RTX_EOF

    @property
    def time_s(self) -> np.ndarray:
        """Time of each sample from the first, seconds (k / sample rate)."""
        return np.arange(len(self.samples_m)) / self.sample_rate_hz


def _unit_factor(unit: str, path: str | None = None) -> float:
    if not isinstance(unit, str) or unit not in IMPORT_UNITS:
        raise AxiscalError(f"unknown length unit '{unit}' for the samples; use one of {', '.join(IMPORT_UNITS)}", path=path)
    return IMPORT_UNITS[unit]


def read_rtx(path: str | Path, *, unit: str) -> RtxCapture:
    """Read a Renishaw ``.rtx`` dynamic capture file.

    Parameters
    ----------
    path : str or Path
        The file.
    unit : str, keyword-only
        Unit of the stored samples (the file does not say): ``nm``, ``um``, ``mm``, ``m`` or ``in``.

    Returns
    -------
    RtxCapture

    Raises
    ------
    AxiscalError
        Naming the file (and the header line where there is one): no ``HEADER::`` start, a header
        line that is not ``Key: value``, no ``Data:`` marker, no ``Sample no`` or one that is not a
        whole number of 1 or more, fewer samples than ``Sample no`` declares (both counts named;
        nothing is padded), bytes after the samples that do not start ``\\r\\nEOF`` or ``EOF``
        (or none at all), a missing or non-positive sample rate, or a non-finite sample.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> f = pathlib.Path(tempfile.mkdtemp()) / "c.rtx"
    >>> _ = write_rtx(f, [0.0, 0.001, 0.002], sample_rate_hz=1000.0, unit="mm")
    >>> read_rtx(f, unit="mm").time_s.tolist()
    [0.0, 0.001, 0.002]
    """
    path = check_path("path", path)
    factor = _unit_factor(unit)
    source = str(path)
    try:
        blob = path.read_bytes()
    except FileNotFoundError:
        raise AxiscalError("file not found", path=path) from None
    except OSError as exc:
        raise AxiscalError(f"cannot read file ({exc.strerror or exc})", path=path) from None
    if not blob.startswith(RTX_HEADER):
        raise AxiscalError("not an .rtx capture: it does not start with 'HEADER::'", path=source, line=1)
    data_at = blob.find(b"\r\n" + RTX_DATA)
    if data_at < 0:
        last = blob.count(b"\r\n") + 1
        raise AxiscalError("no 'Data:' line after the header", path=source, line=last)
    header_text = blob[len(RTX_HEADER) : data_at + 2]
    header: dict[str, str] = {}
    where: dict[str, int] = {}  # header key -> its line
    try:
        lines = header_text.decode("utf-8").split("\r\n")
    except UnicodeDecodeError as exc:
        line = header_text[: exc.start].count(b"\r\n") + 2
        raise AxiscalError("the header is not text", path=source, line=line) from None
    for number, line in enumerate(lines[:-1], start=2):
        if not line.strip() or line.rstrip().endswith("::"):
            continue  # a blank line or a section marker ("NAME::")
        key, sep, value = line.partition(":")
        if not sep or not key.strip():
            raise AxiscalError(f"header line '{line}' is not 'Key: value'", path=source, line=number)
        header.setdefault(key.strip(), value.strip())
        where.setdefault(key.strip(), number)
    data_line = len(lines) + 1
    body = memoryview(blob)[data_at + 2 + len(RTX_DATA) :]
    if "Sample no" not in header:
        raise AxiscalError("no 'Sample no' in the header: the number of samples is not known", path=source, line=data_line)
    expected = parse_number(header["Sample no"])
    if expected is None or expected != int(expected) or expected < 1:
        raise AxiscalError(f"'Sample no' is '{header['Sample no']}', not a whole number of samples (1 or more)",
                           path=source, line=where["Sample no"])
    count = int(expected)
    trailer = bytes(body[8 * count :]) if len(body) >= 8 * count else b""
    if not trailer.startswith(RTX_TRAILERS):
        held = _samples_held(body)
        if held < count:
            raise AxiscalError(f"the header says {count} samples (Sample no), the file holds {held}: it is cut short",
                               path=source, line=where["Sample no"])
        if not trailer:
            problem = "nothing follows them: the 'EOF' trailer is missing, the file is cut short"
        else:
            problem = f"{len(trailer)} bytes follow them that do not start '\\r\\nEOF' or 'EOF'"
        raise AxiscalError(f"after the {count} samples of the header (Sample no), {problem}", path=source,
                           line=where["Sample no"])
    samples = np.frombuffer(body[: 8 * count], dtype="<f8").astype(float)
    rate = None
    for key in _RATE_KEYS:
        if key in header:
            rate = parse_number(header[key])
            if rate is None or rate <= 0:
                raise AxiscalError(f"'{key}' is '{header[key]}', not a positive number", path=source, line=where[key])
            break
    if rate is None:
        raise AxiscalError("no 'Actual sample rate' or 'Sample rate' in the header", path=source, line=data_line)
    bad = np.flatnonzero(~np.isfinite(samples))
    if bad.size:
        raise AxiscalError(f"sample {bad[0]} is not a finite number", path=source, line=data_line)
    return RtxCapture(samples_m=samples * factor, sample_rate_hz=rate, header=header, unit=unit, source=source,
                      trailer=trailer)


def _samples_held(body: memoryview) -> int:
    """Whole samples before a trailer (``EOF`` or CR LF ``EOF`` in the last bytes), else in the whole body."""
    tail_at = max(0, len(body) - _LONGEST_TRAILER)
    found = bytes(body[tail_at:]).rfind(b"EOF")
    if found < 0:
        return len(body) // 8
    start = tail_at + found
    if start >= 2 and bytes(body[start - 2 : start]) == b"\r\n":
        start -= 2
    return start // 8


def write_rtx(
    path: str | Path,
    samples: np.ndarray | list[float],
    *,
    sample_rate_hz: float,
    unit: str,
    header: Mapping[str, str] | None = None,
    trailer: bytes = RTX_EOF,
) -> Path:
    """Write an ``.rtx`` capture in the layout :func:`read_rtx` reads (atomically).

    Parameters
    ----------
    path : str or Path
        The file to write.
    samples : array_like, shape (n,)
        The readings, in ``unit`` (written as they are, little-endian float64).
    sample_rate_hz : float, keyword-only
        Written as ``Sample rate`` and ``Actual sample rate``.
    unit : str, keyword-only
        Unit of ``samples`` (checked; the format itself does not record it).
    header : mapping, optional, keyword-only
        Values of the fields of :data:`RTX_FIELDS` (``Owner``, ``Date``, ``Axis`` ...) and further
        ``Key: value`` lines. The 17 fields are written in their order, empty where nothing is
        known (``Machine: ``); further keys follow them.
    trailer : bytes, keyword-only
        The bytes after the samples: ``b"\\r\\nEOF::"`` (:data:`RTX_EOF`, the default) or another
        trailer starting ``\\r\\nEOF`` or ``EOF``.

    Returns
    -------
    Path
        ``path``.

    Raises
    ------
    AxiscalError
        For a non-positive rate, an unknown unit, a header key holding ':' or a key or value holding
        a line break, or a trailer that does not start ``\\r\\nEOF`` or ``EOF``.
    """
    path = check_path("path", path)
    _unit_factor(unit)
    sample_rate_hz = check_number("sample_rate_hz", sample_rate_hz, positive=True)
    values = check_array("samples", samples, ndim=1).astype("<f8")
    if header is not None:
        check_mapping("header", header)
        if not all(isinstance(key, str) for key in header):
            raise AxiscalError(f"header must map keys (str) to values, not {dict(header)!r}")
    check_instance("trailer", trailer, bytes)
    if not trailer.startswith(RTX_TRAILERS):
        raise AxiscalError(f"trailer must start with b'\\r\\nEOF' or b'EOF', not {trailer!r}")
    lines = dict.fromkeys(RTX_FIELDS, "")
    lines.update({
        "Filename": path.name,
        "Owner": "axiscal",
        "Velocity": "0",
        "Sample rate": f"{sample_rate_hz:g}",
        "Sample no": str(values.size),
        "Trigger point": "0",
        "Trigger interval": f"{1.0 / sample_rate_hz:g}",
        "Actual sample rate": f"{sample_rate_hz:g}",
        "Flags": "0 0 0 0 0",
        **dict(header or {}),
    })
    for key, value in lines.items():
        if ":" in key or "\r" in key or "\n" in key or "\r" in str(value) or "\n" in str(value):
            raise AxiscalError(f"header entry {key!r} cannot be written as one 'Key: value' line")
    text = "".join(f"{key}: {value}\r\n" for key, value in lines.items())
    blob = RTX_HEADER + text.encode("utf-8") + RTX_DATA + values.tobytes() + trailer
    return atomic_write(path, lambda target: target.write_bytes(blob))


def rtx_csv(capture: RtxCapture) -> str:
    """The time series CSV of a capture: ``time_s`` and ``reading_<unit>`` (the unit it was stored in).

    Parameters
    ----------
    capture : RtxCapture

    Returns
    -------
    str
        Plain CSV text, header first.
    """
    factor = _unit_factor(capture.unit)
    column = f"reading_{capture.unit}"
    rows = [f"time_s,{column}"]
    rows += [f"{t:.12g},{v:.12g}" for t, v in zip(capture.time_s, capture.samples_m / factor)]
    return "\n".join(rows) + "\n"


def write_rtx_csv(capture: RtxCapture, path: str | Path) -> Path:
    """Write the time series CSV of a capture (atomically) and its JSON sidecar with the capture's header.

    Parameters
    ----------
    capture : RtxCapture
    path : str or Path
        The CSV to write.

    Returns
    -------
    Path
        ``path``.

    Raises
    ------
    AxiscalError
        For a capture that is not an :class:`RtxCapture`, or a file that cannot be written.
    """
    check_instance("capture", capture, RtxCapture, what="an RtxCapture (what read_rtx returns)")
    path = check_path("path", path)
    text = rtx_csv(capture)
    write_text(path, text)
    write_sidecar(
        path,
        kind="dynamic capture (rtx)",
        units={"time_s": "s", f"reading_{capture.unit}": capture.unit},
        sources=[capture.source] if capture.source else [],
        sample_rate_hz=capture.sample_rate_hz,
        samples=len(capture.samples_m),
        rtx_header=dict(capture.header),
    )
    return Path(path)
