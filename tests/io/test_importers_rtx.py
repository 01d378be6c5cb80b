"""Renishaw .rtx dynamic capture: files built to the layout the public readers take (no instrument file at hand).

The header values are those of the capture published with rtx2csv (github.com/TanmayPani/rtx2csv,
``test/outputs/MagOuterDynamic1Pitch2Cyc/header.json``); the field order is RTX2CSV-Converter's
(github.com/travdt/RTX2CSV-Converter, ``RTXFileProcessor.cs``).
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from axiscal.errors import AxiscalError
from axiscal.io.importers import (
    RTX_DATA,
    RTX_EOF,
    RTX_FIELDS,
    RTX_HEADER,
    read_rtx,
    rtx_csv,
    write_rtx,
    write_rtx_csv,
)
from axiscal.units import MM, UM


def handmade(path, samples, header_lines, *, trailer=RTX_EOF):
    """Bytes laid out by hand, independently of write_rtx: CR LF header lines, float64 little-endian."""
    text = "".join(f"{line}\r\n" for line in header_lines).encode()
    path.write_bytes(RTX_HEADER + text + RTX_DATA + np.asarray(samples, "<f8").tobytes() + trailer)
    return path


HEADER = ["Filename: MagOuterDynamic1Pitch2Cyc.rtx", "Owner: CARTO-Dynamic", "Version no: 4.13.9237.28405",
          "File Type: Dynamic", "Velocity: 0", "Sample rate: 50000", "Sample no: 4", "Trigger point: 0",
          "Trigger interval: 2E-05", "Actual sample rate: 50000", "Flags: 0 1 2 0 2", "Machine: ", "Serial No: ",
          "Date: 10/02/2025 12:58:22", "By: User", "Axis: ", "Location: "]


def test_handmade_file(tmp_path):
    path = handmade(tmp_path / "c.rtx", [0.0, 0.5, 1.0, 1.5], HEADER)
    capture = read_rtx(path, unit="um")
    np.testing.assert_allclose(capture.samples_m / UM, [0.0, 0.5, 1.0, 1.5])
    np.testing.assert_allclose(capture.time_s, [0.0, 2e-5, 4e-5, 6e-5])
    assert capture.header["Date"] == "10/02/2025 12:58:22" and capture.header["Owner"] == "CARTO-Dynamic"


@pytest.mark.parametrize("trailer", [b"\r\nEOF::", b"EOF::\r\n", b"\r\nEOF::\r\n", b"EOF::", b"\r\nEOF"])
def test_both_public_trailers(tmp_path, trailer):
    """rtx2csv drops 7 bytes after the samples; RTX2CSV-Converter stops at a slot starting CR LF EOF."""
    samples = [0.0, 0.5, 1.0, 1.5]
    capture = read_rtx(handmade(tmp_path / "c.rtx", samples, HEADER, trailer=trailer), unit="um")
    np.testing.assert_allclose(capture.samples_m / UM, samples)
    assert capture.trailer == trailer


def test_real_header_shape(tmp_path):
    """The 17 fields in the converter's order, with empty values, as the published capture has them."""
    capture = read_rtx(handmade(tmp_path / "c.rtx", [1.0, 2.0, 3.0, 4.0], HEADER), unit="mm")
    assert tuple(capture.header) == RTX_FIELDS
    assert capture.header["Flags"] == "0 1 2 0 2" and capture.header["Version no"] == "4.13.9237.28405"
    assert capture.header["Machine"] == "" and capture.header["Location"] == "" and capture.header["By"] == "User"
    assert capture.sample_rate_hz == 50000.0


def test_trailer_bytes_that_look_like_samples_are_not_read(tmp_path):
    """The declared count decides: a trailer is never taken for a sample (rtx2csv's 7-byte drop)."""
    lines = [line if not line.startswith("Sample no") else "Sample no: 3" for line in HEADER]
    capture = read_rtx(handmade(tmp_path / "c.rtx", [1.0, 2.0, 3.0], lines, trailer=b"\r\nEOF::\r\n"), unit="mm")
    assert capture.samples_m.size == 3


def test_fewer_samples_than_declared_names_both_counts(tmp_path):
    """Never padded with zeros (as RTX2CSV-Converter does): refused, naming the 'Sample no' line."""
    for trailer in (RTX_EOF, b"EOF::\r\n", b""):
        path = handmade(tmp_path / "c.rtx", [1.0, 2.0, 3.0], HEADER, trailer=trailer)
        with pytest.raises(AxiscalError, match="header says 4 samples \\(Sample no\\), the file holds 3") as info:
            read_rtx(path, unit="mm")
        assert info.value.line == 1 + 1 + HEADER.index("Sample no: 4")


def test_writer_writes_the_real_layout(tmp_path):
    path = write_rtx(tmp_path / "w.rtx", [1.0, 2.0], sample_rate_hz=50000.0, unit="mm", header={"By": "User"})
    blob = path.read_bytes()
    assert blob.endswith(np.asarray([1.0, 2.0], "<f8").tobytes() + b"\r\nEOF::")
    capture = read_rtx(path, unit="mm")
    assert tuple(capture.header) == RTX_FIELDS and capture.header["Machine"] == "" and capture.header["By"] == "User"
    assert b"\r\nMachine: \r\n" in blob and capture.header["Filename"] == "w.rtx"
    old = write_rtx(tmp_path / "o.rtx", [1.0, 2.0], sample_rate_hz=1.0, unit="mm", trailer=b"EOF::\r\n")
    assert old.read_bytes().endswith(b"EOF::\r\n") and read_rtx(old, unit="mm").samples_m.size == 2
    with pytest.raises(AxiscalError, match="trailer"):
        write_rtx(tmp_path / "b.rtx", [1.0], sample_rate_hz=1.0, unit="mm", trailer=b"END")


def test_round_trip(tmp_path):
    rng = np.random.default_rng(3)
    samples = rng.normal(100.0, 0.01, 2000)
    path = write_rtx(tmp_path / "w.rtx", samples, sample_rate_hz=1000.0, unit="mm", header={"Axis": "X"})
    capture = read_rtx(path, unit="mm")
    np.testing.assert_allclose(capture.samples_m / MM, samples, rtol=1e-15)
    assert capture.header["Axis"] == "X" and capture.sample_rate_hz == 1000.0
    out = write_rtx_csv(capture, tmp_path / "w.csv")
    frame = pd.read_csv(out)
    assert list(frame.columns) == ["time_s", "reading_mm"]
    np.testing.assert_allclose(frame["reading_mm"], samples, rtol=1e-10)
    np.testing.assert_allclose(frame["time_s"], np.arange(2000) / 1000.0)
    assert (tmp_path / "w.json").exists()
    assert rtx_csv(capture).splitlines()[0] == "time_s,reading_mm"


@pytest.mark.parametrize(
    "build, message",
    [
        (lambda p: p.write_bytes(b"hello"), "does not start with 'HEADER::'"),
        (lambda p: p.write_bytes(RTX_HEADER + b"Sample rate: 10\r\n"), "no 'Data:'"),
        (lambda p: handmade(p, [1.0, 2.0, 3.0, 4.0], HEADER, trailer=b""), "trailer is missing"),
        (lambda p: handmade(p, [1.0, 2.0, 3.0, 4.0, 5.0], HEADER), "15 bytes follow them that do not start"),
        (lambda p: handmade(p, [1.0, 2.0, 3.0], HEADER), "header says 4 samples"),
        (lambda p: handmade(p, [1.0], ["Sample no: 1"]), "sample rate"),
        (lambda p: handmade(p, [1.0], ["Sample rate: 10"]), "no 'Sample no'"),
        (lambda p: handmade(p, [], ["Sample rate: 10", "Sample no: 0"]), "not a whole number"),
        (lambda p: handmade(p, [1.0], ["Sample rate: 10", "Sample no: 1", "a line without a colon"]), "not 'Key: value'"),
        (lambda p: handmade(p, [1.0, float("nan")], ["Sample rate: 10", "Sample no: 2"]), "not a finite number"),
    ],
)
def test_bad_files(tmp_path, build, message):
    path = tmp_path / "bad.rtx"
    build(path)
    with pytest.raises(AxiscalError, match=message) as info:
        read_rtx(path, unit="mm")
    assert info.value.path == str(path) and "\n" not in str(info.value)


def test_truncated_data_block(tmp_path):
    path = tmp_path / "cut.rtx"
    path.write_bytes(RTX_HEADER + b"Sample rate: 10\r\nSample no: 2\r\n" + RTX_DATA + b"\x00" * 12 + RTX_EOF)
    with pytest.raises(AxiscalError, match="header says 2 samples \\(Sample no\\), the file holds 1"):
        read_rtx(path, unit="mm")


def test_unit_required_known(tmp_path):
    with pytest.raises(AxiscalError, match="unknown length unit"):
        read_rtx(tmp_path / "x.rtx", unit="ft")
