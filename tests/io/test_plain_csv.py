"""The CSV reader's fast path: a file of plain numbers gives the same table as the strict reading of its bytes."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from axiscal.errors import AxiscalError
from axiscal.io.plain_csv import HEAD, read_plain, stamp
from axiscal.io.tabular import MAX_MAGNITUDE, _parse, read_csv

SETTINGS = settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])

NUMBERS = st.sampled_from(["0", "-0", "1.5", "-2.25", "+7", ".5", "5.", "1e-3", "2E3", "  3.25 ", "12345678.901234",
                           "1e12", "-1e12", "42"])
ODD = st.sampled_from(["", " ", "x", "nan", "inf", "1e13", "1_000", "0x1F", "#", "\"1\"", "1e", "\uff11", "\x00",
                       "\u00b5", "1;2", "1,2", "\t"])


def same_table(fast, strict):
    """The two readings agree on everything a caller can ask."""
    assert fast.header == strict.header
    assert fast.header_line == strict.header_line
    assert len(fast) == len(strict)
    assert fast.lines == strict.lines
    assert [fast.line_of(k) for k in range(len(fast))] == list(strict.lines)
    for name in fast.header:
        np.testing.assert_array_equal(fast.numeric(name), strict.numeric(name))
        assert fast.text(name) == strict.text(name)
    assert fast.rows == strict.rows


@st.composite
def plain_files(draw):
    """A header and rows of numbers, with any delimiter, line end, byte-order mark and preamble."""
    width = draw(st.integers(1, 4))
    delimiter = draw(st.sampled_from([",", ";", "\t"])) if width > 1 else ","
    end = draw(st.sampled_from(["\n", "\r\n", "\r"]))
    rows = draw(st.lists(st.lists(NUMBERS, min_size=width, max_size=width), min_size=1, max_size=30))
    if delimiter != ",":  # a decimal comma (pandas then reads no decimal point: those files take the strict reader)
        rows = [[cell.replace(".", ",") for cell in row] for row in rows]
    preamble = draw(st.lists(st.sampled_from(["# made by hand", "", "   ", "  # note µm"]), max_size=3))
    header = delimiter.join(f"c{k}_mm" for k in range(width))
    lines = [*preamble, header, *(delimiter.join(row) for row in rows)]
    text = end.join(lines) + (end if draw(st.booleans()) else "")
    bom = b"\xef\xbb\xbf" if draw(st.booleans()) else b""
    return bom + text.encode()


@SETTINGS
@given(plain_files())
def test_a_plain_file_reads_as_the_strict_reader_reads_it(tmp_path, data):
    path = tmp_path / "plain.csv"
    path.write_bytes(data)
    table = read_csv(path)
    lone_cr = b"\r" in data.replace(b"\r\n", b"")
    assert bool(table._checked) != lone_cr  # read by the fast path, unless a line ends with a lone CR
    same_table(table, _parse(data, str(path), 1))


@SETTINGS
@given(plain_files(), st.data())
def test_anything_not_plain_is_left_to_the_strict_reader(tmp_path, data, draw):
    """One odd cell or line anywhere: the fast path declines, and read_csv answers as the strict reading."""
    text = data.decode("utf-8-sig")
    lines = text.splitlines(keepends=True)
    k = draw.draw(st.integers(0, len(lines)))
    odd = draw.draw(ODD)
    if draw.draw(st.booleans()) and k < len(lines) and not lines[k].lstrip().startswith("#"):
        line = lines[k]
        body = line.rstrip("\r\n")
        cut = draw.draw(st.integers(0, len(body)))
        lines[k] = body[:cut] + odd + body[cut:] + line[len(body):]
    else:
        lines.insert(k, odd + "\n")
    mutated = "".join(lines).encode()
    path = tmp_path / "odd.csv"
    path.write_bytes(mutated)
    try:
        strict = _parse(mutated, str(path), 1)
        columns = {name: strict.numeric(name) for name in strict.header}
    except AxiscalError as exc:
        with pytest.raises(AxiscalError) as info:
            fast = read_csv(path)
            for name in fast.header:
                fast.numeric(name)
        assert str(info.value) == str(exc)
        return
    fast = read_csv(path)
    same_table(fast, strict)
    for name, values in columns.items():
        np.testing.assert_array_equal(fast.numeric(name), values)


def test_a_large_file_of_numbers_is_read_by_pandas_with_each_row_on_its_line(tmp_path):
    rng = np.random.default_rng(0)
    values = rng.normal(size=(200_000, 2)) * 100
    text = "# note\nposition_mm,deviation_um\n" + "\n".join(f"{a:.6f},{b:.6f}" for a, b in values) + "\n"
    path = tmp_path / "large.csv"
    path.write_text(text)
    table = read_csv(path)
    assert table._checked and table.header_line == 2 and table.line_of(199_999) == 200_002
    np.testing.assert_allclose(table.numeric("deviation_um"), values[:, 1], atol=5e-7)


@pytest.mark.parametrize("data", [
    b"a,b\n1,2\n3,4\n\n",  # a blank line after the rows
    b"a,b\n1,2\n# note\n3,4\n",  # a comment among the rows
    b"a,b\n1,\"2\"\n",  # a quote
    b"a,b\n1,2\x003\n",  # a NUL byte
    b"a,b\n1,2\n3,nan\n",  # not finite
    b"a,b\n1,2\n3,1e13\n",  # beyond any physical value
    b"a,b\n1,2\n3,\xc2\xb5\n",  # not ASCII after the header
    b"a,b\n1,2\n3\n",  # a short row
    b"a,b\n1,2\n3,4,5\n",  # a long row
    b"a,b\n",  # no data rows
])
def test_the_fast_path_declines_what_is_not_plain(tmp_path, data):
    path = tmp_path / "f.csv"
    path.write_bytes(data)
    assert read_plain(data, path, stamp(path), MAX_MAGNITUDE) is None


def test_a_file_rewritten_while_read_is_declined(tmp_path):
    path = tmp_path / "f.csv"
    path.write_bytes(b"a,b\n1,2\n")
    before = stamp(path)
    path.write_bytes(b"a,b\n1,2\n3,4\n")
    assert read_plain(b"a,b\n1,2\n", path, before, MAX_MAGNITUDE) is None


def test_a_header_past_the_first_64_kib_is_left_to_the_strict_reader(tmp_path):
    data = b"# long preamble\n" * 5000 + b"a,b\n1,2\n"
    path = tmp_path / "f.csv"
    path.write_bytes(data)
    assert read_plain(data[:HEAD], path, stamp(path), MAX_MAGNITUDE) is None
    table = read_csv(path)
    assert table.header_line == 5001 and table.numeric("b").tolist() == [2.0]


def test_rows_ended_by_any_line_end_keep_their_lines(tmp_path):
    """LF, CRLF and lone CR mixed among the rows of a file large enough for pandas' threads."""
    rng = np.random.default_rng(4)
    ends = rng.choice(["\n", "\r\n", "\r"], 150_000)
    text = "# x\r\nposition_mm,deviation_um\n" + "".join(f"{k},{k * 0.25}{end}" for k, end in enumerate(ends))
    path = tmp_path / "ends.csv"
    path.write_bytes(text.encode())
    table = read_csv(path)
    assert table._checked and len(table) == 150_000 and table.line_of(149_999) == 150_002
    np.testing.assert_array_equal(table.numeric("position_mm"), np.arange(150_000))
    assert table.text("deviation_um")[:3] == ["0.0", "0.25", "0.5"]


def test_the_text_of_a_file_changed_since_it_was_read_is_refused(tmp_path):
    path = tmp_path / "f.csv"
    path.write_bytes(b"a,b\n1,2\n3,4\n")
    table = read_csv(path)
    assert table.numeric("b").tolist() == [2.0, 4.0]
    path.write_bytes(b"a,b\n1,2\n3,4\n5,6\n")
    with pytest.raises(AxiscalError, match="changed while it was being read") as info:
        table.text("b")
    assert info.value.path == str(path) or str(path) in str(info.value)
