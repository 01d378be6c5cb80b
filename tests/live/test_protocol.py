"""The line protocol of the live TCP/serial sources (docs/live.md): decoding, headers, faults, round trips."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.live.protocol import FrameBatch, LineDecoder, encode_lines, header_line

CHANNELS = ("a_mm", "b_um", "c_um")


def test_lines_without_header_are_t_s_then_the_channels_in_order():
    batch = LineDecoder(CHANNELS).feed(b"0.1,1,2,3\n0.2,4,5,6\n")
    np.testing.assert_array_equal(batch.t_s, [0.1, 0.2])
    np.testing.assert_array_equal(batch.values, [[1, 2, 3], [4, 5, 6]])
    assert not batch.malformed.any()


def test_a_line_split_across_reads_is_decoded_once_complete():
    decoder = LineDecoder(CHANNELS)
    assert len(decoder.feed(b"0.1,1,2")) == 0
    batch = decoder.feed(b",3\n0.2,4")
    np.testing.assert_array_equal(batch.values, [[1, 2, 3]])
    assert len(decoder.flush()) == 1


def test_header_reorders_columns_leaves_channels_out_and_ignores_unknown_ones():
    decoder = LineDecoder(CHANNELS)
    batch = decoder.feed(b"0.1,1,2,3\nt_s,c_um,a_mm,other\n0.2,30,10,99\n")
    np.testing.assert_array_equal(batch.values[0], [1, 2, 3])
    np.testing.assert_array_equal(batch.values[1], [10, np.nan, 30])
    assert decoder.ignored_columns == ("other",)
    decoder.reset()
    np.testing.assert_array_equal(decoder.feed(b"0.3,1,2,3\n").values, [[1, 2, 3]])


def test_a_line_with_more_fields_than_columns_is_kept_as_a_malformed_frame():
    decoder = LineDecoder(CHANNELS)
    batch = decoder.feed(b"0.1,1,2,3\n7,0.2,4,5,6\n0.3,1,2\n")  # a counter in front shifts every field
    np.testing.assert_array_equal(batch.t_s, [0.1, 7.0, 0.3])
    np.testing.assert_array_equal(batch.malformed, [False, True, False])
    np.testing.assert_array_equal(batch.values[2], [1, 2, np.nan])  # too few fields: the last channel is missing


def test_a_header_with_t_s_anywhere_is_a_header_not_a_malformed_frame():
    decoder = LineDecoder(CHANNELS)
    batch = decoder.feed(b"b_um,t_s,a_mm,c_um\n2,0.1,1,3\n")
    np.testing.assert_array_equal(batch.t_s, [0.1])
    np.testing.assert_array_equal(batch.values, [[1, 2, 3]])
    assert not batch.malformed.any() and decoder.lines == 1


def test_bad_cells_are_missing_channels_and_a_bad_time_marks_the_frame_malformed():
    decoder = LineDecoder(CHANNELS)
    text = b"# a comment\n\n0.1,1,,3\n0.2,x,2,inf\n0.3,1\nnot-a-time,1,2,3\n0.5,1,2,3,4,5\r\n"
    batch = decoder.feed(text)
    assert len(batch) == 5
    np.testing.assert_array_equal(batch.values[0], [1, np.nan, 3])
    np.testing.assert_array_equal(batch.values[1], [np.nan, 2, np.nan])
    np.testing.assert_array_equal(batch.values[2], [1, np.nan, np.nan])
    np.testing.assert_array_equal(batch.malformed, [False, False, False, True, True])  # the last has two fields too many
    np.testing.assert_array_equal(batch.values[4], [1, 2, 3])
    assert decoder.malformed_lines == 2 and decoder.lines == 5


def test_frames_mapping_has_t_s_and_every_channel():
    batch = FrameBatch.from_frames({"t_s": np.array([0.0, 1.0]), "a_mm": np.array([1.0, 2.0])}, CHANNELS)
    frames = batch.frames(CHANNELS)
    assert set(frames) == {"t_s", *CHANNELS}
    assert np.isnan(frames["b_um"]).all()


@settings(max_examples=60, deadline=None)
@given(
    table=st.lists(
        st.lists(st.floats(allow_nan=False, allow_infinity=False, width=64), min_size=4, max_size=4), min_size=1, max_size=30
    ),
    cuts=st.lists(st.integers(min_value=0, max_value=4000), max_size=6),
    with_header=st.booleans(),
)
def test_encode_then_decode_in_any_chunking_gives_the_frames_back(table, cuts, with_header):
    values = np.array(table)
    data = (header_line(CHANNELS) if with_header else b"") + encode_lines(values[:, 0], values[:, 1:])
    decoder = LineDecoder(CHANNELS)
    edges = sorted({min(c, len(data)) for c in cuts} | {0, len(data)})
    batches = [decoder.feed(data[a:b]) for a, b in zip(edges[:-1], edges[1:])]
    batch = FrameBatch.concatenate([b for b in batches if len(b)], len(CHANNELS))
    np.testing.assert_array_equal(batch.t_s, values[:, 0])
    np.testing.assert_array_equal(batch.values, values[:, 1:])


def test_a_line_longer_than_the_limit_is_one_malformed_frame_and_the_decoder_resynchronises():
    decoder = LineDecoder(CHANNELS, max_line_bytes=64)
    chunk = b"7" * 4096
    got = [decoder.feed(b"0.1,1,2,3\n" + chunk)]
    for _ in range(1000):  # 4 MB without a line end: nothing of it is kept
        got.append(decoder.feed(chunk))
        assert len(decoder._pending) <= 64
    got.append(decoder.feed(b"7777\n0.2,4,5,6\n"))
    batch = FrameBatch.concatenate(got, len(CHANNELS))
    np.testing.assert_array_equal(batch.t_s, [0.1, np.nan, 0.2])
    np.testing.assert_array_equal(batch.malformed, [False, True, False])
    np.testing.assert_array_equal(batch.values[2], [4, 5, 6])
    assert decoder.overlong_lines == 1 and decoder.malformed_lines == 1


def test_an_overlong_line_inside_one_chunk_is_one_malformed_frame():
    decoder = LineDecoder(CHANNELS, max_line_bytes=64)
    batch = decoder.feed(b"0.1,1,2,3\n" + b"1," * 100 + b"\n0.2,4,5,6\n")
    np.testing.assert_array_equal(batch.malformed, [False, True, False])
    assert batch.t_s[2] == 0.2


@pytest.mark.parametrize("end", [b"\r", b"\r\n", b"\n"])
def test_every_line_end_reads_the_same_frames(end):
    text = end.join([b"t_s,a_mm,b_um,c_um", b"0.1,1,2,3", b"0.2,4,5,6", b""])
    decoder = LineDecoder(CHANNELS)
    batch = FrameBatch.concatenate([decoder.feed(text[k : k + 3]) for k in range(0, len(text), 3)], len(CHANNELS))
    np.testing.assert_array_equal(batch.t_s, [0.1, 0.2])
    np.testing.assert_array_equal(batch.values, [[1, 2, 3], [4, 5, 6]])
    assert not batch.malformed.any()


@settings(max_examples=60, deadline=None)
@given(cuts=st.lists(st.integers(0, 400), max_size=12), long=st.integers(0, 200))
def test_the_frames_do_not_depend_on_how_the_bytes_are_cut(cuts, long):
    """However the stream is split into reads, the decoded frames are the same (an overlong line included)."""
    text = b"0.1,1,2,3\r\n" + b"5" * long + b"\n0.2,4,5,6\r0.3,7,8,9\n"
    whole = LineDecoder(CHANNELS, max_line_bytes=50).feed(text)
    decoder = LineDecoder(CHANNELS, max_line_bytes=50)
    bounds = sorted({0, len(text), *(c % (len(text) + 1) for c in cuts)})
    parts = FrameBatch.concatenate([decoder.feed(text[a:b]) for a, b in zip(bounds, bounds[1:])], len(CHANNELS))
    np.testing.assert_array_equal(parts.t_s, whole.t_s)
    np.testing.assert_array_equal(parts.malformed, whole.malformed)
    assert len(whole) == (4 if long else 3)
