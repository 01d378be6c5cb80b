"""Every number the G-code writer puts in a program is one every control reads: bounded, fixed decimals, no exponent."""

from __future__ import annotations

import re

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.errors import AxiscalError
from axiscal.io.gcode import DIALECT_NAMES, ProgramWriter
from axiscal.io.gcode.writer import MAX_FEED_MM_MIN, MAX_POSITION_MM, feed_word, position_word

#: an address word as every control reads it: a letter, a sign, at most five whole digits (six for a feed), decimals
WORD = re.compile(r"^(X[+-]?\d{1,5}|F\d{1,6})(\.\d*)?$")


@pytest.mark.parametrize("dialect", DIALECT_NAMES)
@settings(max_examples=30, deadline=None)
@given(position_mm=st.floats(-MAX_POSITION_MM, MAX_POSITION_MM), feed=st.floats(1e-3, MAX_FEED_MM_MIN))
def test_every_word_written_is_fixed_point_and_bounded(dialect, position_mm, feed):
    writer = ProgramWriter(dialect)
    writer.move({"X": position_mm * 1e-3}, feed_m_per_s=feed * 1e-3 / 60)
    block = [b for b in writer.text().splitlines() if re.search(r" X[+-]?\d", b)][-1]
    words = [w for w in block.split() if w[0] in "XF" and w != "FMAX"]
    assert len(words) == 2 and all(WORD.match(w) for w in words), block


@pytest.mark.parametrize("dialect", DIALECT_NAMES)
def test_a_feed_or_position_beyond_the_words_range_is_refused(dialect):
    writer = ProgramWriter(dialect)
    with pytest.raises(AxiscalError, match="feed_mm_min must be at most 100000 mm/min"):
        writer.move({"X": 0.0}, feed_m_per_s=1e6 * 1e-3 / 60)  # was written F1000000 (and F1e+06 on the dry run)
    with pytest.raises(AxiscalError, match=r"X position in mm must be within \+/-99999.999"):
        writer.move({"X": 1e297}, feed_m_per_s=0.01)  # was a 300-digit X word
    with pytest.raises(AxiscalError, match="seconds"):
        writer.dwell(1e300)
    writer.move({"X": MAX_POSITION_MM * 1e-3}, feed_m_per_s=MAX_FEED_MM_MIN * 1e-3 / 60)  # the bounds themselves are written


def test_the_word_helpers_round_and_never_write_an_exponent():
    assert position_word("X", 1e-9) == "0.000" and position_word("X", -99999.999) == "-99999.999"
    assert feed_word(99999.9994) == "99999.999" and feed_word(0.001) == "0.001"
    with pytest.raises(AxiscalError, match="feed_mm_min must be at least 0.001 mm/min"):
        feed_word(1e-5)  # it would be written F0
