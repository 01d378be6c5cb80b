"""The fault bits of a frame: one IntFlag, values kept from the first record format."""

from __future__ import annotations

from axiscal.measurement.faults import Fault, fault_legend, fault_text


def test_fault_bits_keep_the_values_records_were_written_with():
    assert [int(f) for f in (Fault.MISSING, Fault.RANGE, Fault.POSITION, Fault.MALFORMED)] == [1, 2, 4, 256]
    assert fault_text(Fault.MALFORMED | Fault.MISSING).startswith("malformed frame")
    assert fault_text(8) == "unknown fault bits 0x8"
    assert list(fault_legend()) == ["1", "2", "4", "256"]


def test_fault_text_of_good_and_combined_frames():
    assert fault_text(0) == "ok"
    assert fault_text(Fault.MISSING | Fault.RANGE | Fault.POSITION) == "missing channel; channel out of range; position outside the error model"
