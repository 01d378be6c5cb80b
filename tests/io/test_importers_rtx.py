"""Renishaw .rtx dynamic capture: files built to the layout rtx2csv describes (no instrument file at hand)."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from axiscal.errors import AxiscalError
from axiscal.io.importers import (
    RTX_DATA,
    RTX_EOF,
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


HEADER = ["Owner: CARTO-Dynamic", "Version no: 4.13", "File Type: Dynamic", "Sample rate: 50000",
          "Sample no: 4", "Trigger point: 0", "Actual sample rate: 50000", "Date: 10/02/2025 12:58:22"]


def test_handmade_file(tmp_path):
    path = handmade(tmp_path / "c.rtx", [0.0, 0.5, 1.0, 1.5], HEADER)
    capture = read_rtx(path, unit="um")
    np.testing.assert_allclose(capture.samples_m / UM, [0.0, 0.5, 1.0, 1.5])
    np.testing.assert_allclose(capture.time_s, [0.0, 2e-5, 4e-5, 6e-5])
    assert capture.header["Date"] == "10/02/2025 12:58:22" and capture.header["Owner"] == "CARTO-Dynamic"


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
        (lambda p: handmade(p, [1.0, 2.0, 3.0, 4.0], HEADER, trailer=b""), "EOF::"),
        (lambda p: handmade(p, [1.0, 2.0, 3.0], HEADER), "header says 4 samples"),
        (lambda p: handmade(p, [1.0], ["Sample no: 1"]), "sample rate"),
        (lambda p: handmade(p, [1.0], ["Sample rate: 10", "a line without a colon"]), "not 'Key: value'"),
        (lambda p: handmade(p, [1.0, float("nan")], ["Sample rate: 10"]), "not a finite number"),
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
    path.write_bytes(RTX_HEADER + b"Sample rate: 10\r\n" + RTX_DATA + b"\x00" * 12 + RTX_EOF)
    with pytest.raises(AxiscalError, match="whole number of 8-byte samples"):
        read_rtx(path, unit="mm")


def test_unit_required_known(tmp_path):
    with pytest.raises(AxiscalError, match="unknown length unit"):
        read_rtx(tmp_path / "x.rtx", unit="ft")
