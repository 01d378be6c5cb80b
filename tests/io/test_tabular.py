"""The CSV reader: errors name file and physical line; values are finite floats; parity with the old reader."""

from __future__ import annotations

import csv
import math
import os
import re

import numpy as np
import pandas as pd
import pytest
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st

from axiscal.errors import AxiscalError
from axiscal.io.tabular import CsvTable, parse_csv, read_csv, write_csv


def test_reads_numbers_skipping_comments_and_blank_lines():
    table = parse_csv(["# made by hand", "position_mm, EXX_um", "", "0, 1.5", "10, -2"])
    assert table.header == ("position_mm", "EXX_um")
    np.testing.assert_array_equal(table.numeric("EXX_um"), [1.5, -2.0])
    assert table.lines == (4, 5)
    assert table.rows == (("0", "1.5"), ("10", "-2"))
    assert table.header_line == 2 and len(table) == 2


@pytest.mark.parametrize(
    "lines, message, line",
    [
        (["a,b", "1,x"], "'x' is not a number", 2),
        (["a,b", "1,nan"], "not a finite number", 2),
        (["a,b", "1,2,3"], "3 cells where the header has 2", 2),
        (["a,b", "1"], "1 cells where the header has 2", 2),
        (["a,b", "1,2", "3,4,5"], "3 cells where the header has 2", 3),
        (["a,b", "1,2", "", "# c", "3"], "1 cells where the header has 2", 5),
        (["a,a", "1,2"], "appears twice", 1),
        (["a,", "1,2"], "empty column name", 1),
        (["a,b"], "0 data rows", 1),
        ([], "empty file", 1),
    ],
)
def test_errors_name_the_line(lines, message, line):
    with pytest.raises(AxiscalError) as info:
        table = parse_csv(lines, path="f.csv")
        table.numeric("b")
    assert message in str(info.value)
    assert info.value.line == line
    assert str(info.value).startswith(f"f.csv:{line}: ")


def test_missing_column_and_missing_file(tmp_path):
    with pytest.raises(AxiscalError, match="missing column 'c'") as info:
        parse_csv(["# x", "a,b", "1,2"]).numeric("c")
    assert info.value.line == 2
    with pytest.raises(AxiscalError, match="file not found"):
        read_csv(tmp_path / "nope.csv")


@pytest.mark.parametrize(
    "data",
    [
        b"# note\n\nx_mm,y_um\n1,2\n\n# mid\n3,4\n",  # comments and blank lines above and between
        b"\xef\xbb\xbf# note\r\n\r\nx_mm,y_um\r\n1,2\r\n\r\n# mid\r\n3,4\r\n",  # BOM and CRLF
        b"# note\r\rx_mm,y_um\r1,2\r\r# mid\r3,4",  # CR only, no final line end
        b"  # note\n \t \nx_mm , y_um \n 1 , 2\n\n   # mid\n3,4 \n",  # indented comments, padded cells
    ],
)
def test_line_numbers_count_every_physical_line(tmp_path, data):
    path = tmp_path / "f.csv"
    path.write_bytes(data)
    table = read_csv(path)
    assert table.header == ("x_mm", "y_um") and table.header_line == 3
    assert table.lines == (4, 7)
    np.testing.assert_array_equal(table.numeric("y_um"), [2.0, 4.0])


def test_form_feed_and_line_separator_do_not_end_a_line(tmp_path):
    path = tmp_path / "f.csv"
    path.write_bytes("a,b\n1,2\x0c\n3,4\u2028x\n5,6\n".encode())
    table = read_csv(path)
    assert table.lines == (2, 3, 4) and table.text("b") == ["2", "4\u2028x", "6"]
    with pytest.raises(AxiscalError, match=r"'4\\u2028x' is not a number") as info:
        table.numeric("b")
    assert info.value.line == 3


@pytest.mark.parametrize("cell, value", [("-1.5", -1.5), ("+.5", 0.5), ("1.", 1.0), ("2E-3", 2e-3), ("1e+5", 1e5), ("007", 7.0), (" 3 ", 3.0)])
def test_number_grammar_accepts_plain_decimals(cell, value):
    assert parse_csv(["a", cell, "0"]).numeric("a")[0] == value


@pytest.mark.parametrize(
    "cell, problem",
    [
        ("1_000", "'1_000' is not a number"),
        ("\uff11\uff12", "'\uff11\uff12' is not a number"),  # full-width digits
        ("\u0661", "'\u0661' is not a number"),  # Arabic-Indic digit
        ("0x1F", "'0x1F' is not a number"),
        ("nan", "nan is not a finite number"),
        ("-inf", "-inf is not a finite number"),
        ("Infinity", "Infinity is not a finite number"),
        ("1e500", "1e500 is not a finite number"),
        ("", "'' is not a number"),
        ("1e", "'1e' is not a number"),
        (".", "'.' is not a number"),
        ("True", "'True' is not a number"),
        ("1,5", None),  # two cells with a comma delimiter
    ],
)
def test_number_grammar_refuses_the_rest_with_column_cell_and_line(cell, problem):
    lines = ["# c", "a,b", "0,1", f"2,{cell}" if problem else "2,1,5"]
    with pytest.raises(AxiscalError) as info:
        parse_csv(lines, path="f.csv").numeric("b")
    assert info.value.line == 4
    assert problem is None or str(info.value) == f"f.csv:4: column 'b': {problem}"


def test_big_integers_and_empty_cells():
    table = parse_csv(["a,b", "999999999999,", "1,2"])
    np.testing.assert_array_equal(table.numeric("a"), [999999999999.0, 1.0])
    np.testing.assert_array_equal(table.numeric("b", allow_empty=True), [np.nan, 2.0])
    with pytest.raises(AxiscalError, match="'' is not a number"):
        table.numeric("b")


@pytest.mark.parametrize("sep", [";", "\t"])
def test_semicolon_or_tab_header_chooses_delimiter_and_allows_decimal_comma(sep):
    table = parse_csv([f"position_mm{sep}EXX_µm{sep}note", f"0{sep}1,5{sep}a, b", f"10,0{sep}-2.25{sep}c"])
    assert table.header == ("position_mm", "EXX_um", "note")
    np.testing.assert_array_equal(table.numeric("position_mm"), [0.0, 10.0])
    np.testing.assert_array_equal(table.numeric("EXX_um"), [1.5, -2.25])
    assert table.text("note") == ["a, b", "c"]
    with pytest.raises(AxiscalError, match="'1,5,3' is not a number"):
        parse_csv([f"a{sep}b", f"1,5,3{sep}2"]).numeric("a")


def test_micro_sign_and_greek_mu_read_as_u():
    assert parse_csv(["x_\u03bcm,a_\u00b5rad", "1,2"]).header == ("x_um", "a_urad")
    with pytest.raises(AxiscalError, match="'x_um' appears twice"):
        parse_csv(["x_um,x_\u00b5m", "1,2"])


def test_quoted_cells_within_a_line():
    table = parse_csv(['a,note', '"1.5","x, y"', '2,"say ""hi"""'])
    np.testing.assert_array_equal(table.numeric("a"), [1.5, 2.0])
    assert table.text("note") == ["x, y", 'say "hi"']
    with pytest.raises(AxiscalError, match="cannot split into cells") as info:
        parse_csv(["a,note", '1,"open', 'still",2'], path="f.csv")
    assert info.value.line == 2


def test_long_cells_read_or_refused_cleanly():
    long = "9" * 200_000
    table = parse_csv(["a,b", f"1,{long[:-1]}.5"])
    assert table.text("b")[0].endswith("9.5")
    with pytest.raises(AxiscalError, match="is not a finite number"):  # a real number, too big for a float
        table.numeric("b")
    quoted = parse_csv(["a,b", f'1,"{long}"'], path="f.csv")  # quoted, it is read whole too
    assert quoted.text("b") == [long]


def test_nul_and_bad_utf8_name_their_line(tmp_path):
    path = tmp_path / "f.csv"
    path.write_bytes(b"a,b\n1,2\n3,\x004\n")
    with pytest.raises(AxiscalError, match="NUL") as info:
        read_csv(path)
    assert info.value.line == 3
    path.write_bytes(b"a,b\r1,2\r3,\xff4\r")
    with pytest.raises(AxiscalError, match="not UTF-8") as info:
        read_csv(path)
    assert info.value.line == 3


def test_rows_lines_and_text_of_a_large_file_agree(tmp_path):
    n = 5000
    x = np.arange(n) * 0.25
    path = tmp_path / "p.csv"
    write_csv(path, {"position_mm": x, "run": [str(k % 3) for k in range(n)]}, fmt="{:.2f}")
    table = read_csv(path)
    assert len(table) == n and table.lines[-1] == n + 1 and table.line_of(10) == 12
    assert table.rows[3] == ("0.75", "0")
    assert table.text("position_mm")[:2] == ["0.00", "0.25"]  # as written, not as parsed
    np.testing.assert_array_equal(table.numeric("position_mm"), x)
    np.testing.assert_array_equal(table.numeric("run"), np.arange(n) % 3)


def test_a_table_made_by_hand_still_works():
    table = CsvTable("f.csv", ("a", "b"), (("1", "x"),), (3,))
    assert table.header_line == 2 and table.lines == (3,) and table.text("b") == ["x"]
    np.testing.assert_array_equal(table.numeric("a"), [1.0])


def test_a_value_beyond_any_physical_one_is_refused():
    table = parse_csv(["a,b", "1,2", "1e308,3", "99999999999999999999,4"])
    with pytest.raises(AxiscalError, match="beyond any physical value") as caught:
        table.numeric("a")
    assert caught.value.line == 3


@given(st.lists(st.floats(min_value=-1e12, max_value=1e12), min_size=1, max_size=20))
def test_write_then_read_round_trip(values):
    text = write_csv(None, {"x_mm": values}, fmt="{:.17g}")
    back = parse_csv(text.splitlines()).numeric("x_mm")
    np.testing.assert_array_equal(back, np.asarray(values, dtype=float))


def test_write_csv_is_atomic_and_plain(tmp_path):
    path = tmp_path / "out.csv"
    path.write_text("old\n")
    text = write_csv(path, {"position_mm": [0.0, 1.5], "EXX_um": [2.0, -3.25], "run": ["a", "b"]}, fmt={"EXX_um": "{:.3f}"})
    assert path.read_text() == text == "position_mm,EXX_um,run\n0.000000,2.000,a\n1.500000,-3.250,b\n"
    frame = pd.read_csv(path)
    assert list(frame.columns) == ["position_mm", "EXX_um", "run"] and frame["EXX_um"].tolist() == [2.0, -3.25]
    assert sorted(os.listdir(tmp_path)) == ["out.csv"]
    with pytest.raises(AxiscalError, match="is a folder"):
        write_csv(tmp_path, {"a": [1.0]})


# ---- a plain, slow reference reader of the contract in docs/formats.md
# one way to split every number (a digit run, then a point and its digits): no backtracking over a long run
REF_NUMBER = re.compile(r"[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?")
REF_NUMBER_COMMA = re.compile(r"[+-]?(?:[0-9]+(?:[.,][0-9]*)?|[.,][0-9]+)(?:[eE][+-]?[0-9]+)?")


class Refused(Exception):
    def __init__(self, line: int):
        super().__init__(line)
        self.line = line


def physical_lines(data: bytes) -> list[bytes]:
    """Lines as an editor shows them: only LF, CRLF and CR end one."""
    parts = re.split(rb"\r\n|\r|\n", data)
    if parts and parts[-1] == b"":
        parts.pop()
    return parts


#: what the reader strips a cell of (ASCII blanks within a line; not \x1c-\x1f, which str.strip also takes)
BLANKS = " \t\v\f"


def reference_read(data: bytes, min_rows: int = 1):
    """(header, rows, line numbers, delimiter) or Refused(line)."""
    if data.startswith(b"\xef\xbb\xbf"):
        data = data[3:]
    raw = physical_lines(data)
    for number, line in enumerate(raw, start=1):
        if b"\0" in line:
            raise Refused(number)
    text = []
    for number, line in enumerate(raw, start=1):
        try:
            text.append(line.decode("utf-8"))
        except UnicodeDecodeError:
            raise Refused(number) from None
    kept = [(n, line) for n, line in enumerate(text, start=1) if line.strip() and not line.strip().startswith("#")]
    if not kept:
        raise Refused(1)
    header_line, header_text = kept[0]
    delimiter = next((d for d in (",", ";", "\t") if d in header_text), ",")

    def split(number: int, line: str) -> list[str]:
        if '"' not in line:
            return [c.strip(BLANKS) for c in line.split(delimiter)]
        try:
            return [c.strip(BLANKS) for c in next(csv.reader([line], delimiter=delimiter, strict=True), [""])]
        except csv.Error:
            raise Refused(number) from None

    header = []
    for name in split(header_line, header_text):
        stem, sep, unit = name.rpartition("_")
        if sep and unit[:1] in ("\u00b5", "\u03bc"):
            name = f"{stem}_u{unit[1:]}"
        if not name or name in header:
            raise Refused(header_line)
        header.append(name)
    rows, numbers = [], []
    for k, (number, line) in enumerate(kept[1:]):
        if k == 0 and line.startswith("\ufeff"):
            line = line[1:]  # a byte-order mark opening the first data line is dropped, as one opening the file
        cells = split(number, line)
        if len(cells) != len(header):
            raise Refused(number)
        rows.append(tuple(cells))
        numbers.append(number)
    if len(rows) < min_rows:
        raise Refused(header_line)
    return tuple(header), tuple(rows), tuple(numbers), delimiter


def reference_numeric(rows, numbers, column: int, delimiter: str, allow_empty: bool = False) -> list[float]:
    """The column as floats, or Refused(line) at its first cell that is not a finite number of at
    most 1e12 in magnitude."""
    grammar = REF_NUMBER if delimiter == "," else REF_NUMBER_COMMA
    out = []
    for row, number in zip(rows, numbers):
        cell = row[column]
        if cell == "" and allow_empty:
            out.append(math.nan)
            continue
        if not grammar.fullmatch(cell):
            raise Refused(number)
        value = float(cell.replace(",", "."))
        if not math.isfinite(value) or abs(value) > 1e12:  # beyond any physical value (io.tabular.MAX_MAGNITUDE)
            raise Refused(number)
        out.append(value)
    return out


# ---- mutated files: an AxiscalError with the file and a line, or the reference reader's parse


@st.composite
def valid_files(draw) -> bytes:
    names = draw(st.lists(st.sampled_from(["position_mm", "EXX_um", "EAX_urad", "t_s", "run", "a_\u00b5m"]), min_size=1, max_size=4, unique=True))
    sep = draw(st.sampled_from([",", ",", ";", "\t"]))
    end = draw(st.sampled_from(["\n", "\r\n", "\r"]))
    fmt = draw(st.sampled_from(["{:.6f}", "{:g}", "{:.3e}", "{:.0f}", "{!r}"]))
    values = draw(st.lists(st.floats(-1e6, 1e6, allow_nan=False), min_size=0, max_size=8 * len(names)))
    lines = [f"# {draw(st.text(max_size=10))}"] * draw(st.integers(0, 2)) + [sep.join(names)]
    for k in range(len(values) // len(names)):
        cells = [fmt.format(v) for v in values[k * len(names) : (k + 1) * len(names)]]
        if sep != ",":
            cells = [c.replace(".", ",") if draw(st.booleans()) else c for c in cells]
        lines.append(sep.join(cells))
        if draw(st.integers(0, 9)) == 0:
            lines.append(draw(st.sampled_from(["", "  ", "# between", "\t# x"])))
    bom = "\ufeff" if draw(st.booleans()) else ""
    return (bom + end.join(lines) + (end if draw(st.booleans()) else "")).encode("utf-8")


INSERTS = [b",", b";", b"\t", b'"', b"\0", b"\xef\xbb\xbf", b"\r", b"\n", b"\r\n", b"#", b" ", b"\x0c", "\u2028".encode(),
           b"\xff", b"_", b"nan", b"e", b".", b"-", "\uff11".encode(), b'"x,y"', b"9" * 140_000]


@st.composite
def mutated_files(draw) -> bytes:
    data = bytearray(draw(valid_files()))
    for _ in range(draw(st.integers(0, 3))):
        at = draw(st.integers(0, len(data)))
        kind = draw(st.sampled_from(["flip", "truncate", "insert", "insert"]))
        if kind == "flip" and at < len(data):
            data[at] ^= draw(st.integers(1, 255))
        elif kind == "truncate":
            del data[at:]
        else:
            data[at:at] = draw(st.sampled_from(INSERTS))
    return bytes(data)


@settings(max_examples=int(os.environ.get("FUZZ_EXAMPLES", "400")), deadline=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
@given(mutated_files(), st.integers(0, 2))
def test_mutated_files_give_a_located_error_or_the_reference_parse(tmp_path_factory, data, min_rows):
    path = tmp_path_factory.mktemp("fuzz") / "f.csv"
    path.write_bytes(data)
    try:
        expected = reference_read(data, min_rows)
    except Refused as refused:
        expected = refused
    try:
        table = read_csv(path, min_rows=min_rows)
    except AxiscalError as exc:
        assert exc.path == str(path) and isinstance(exc.line, int) and exc.line >= 1
        assert isinstance(expected, Refused), f"refused a file the reference reads: {exc}"
        assert exc.line == expected.line, str(exc)
        event(f"refused: {exc.message.split(':')[0][:30]}")
        return
    event("read")
    assert not isinstance(expected, Refused), "read a file the reference refuses"
    header, rows, numbers, delimiter = expected
    assert (table.header, table.lines, len(table)) == (header, numbers, len(rows))
    assert table.rows == rows
    for i, name in enumerate(header):
        for allow_empty in (False, True):
            try:
                want = reference_numeric(rows, numbers, i, delimiter, allow_empty)
            except Refused as refused:
                with pytest.raises(AxiscalError) as info:
                    table.numeric(name, allow_empty=allow_empty)
                assert info.value.line == refused.line and info.value.path == str(path)
            else:
                np.testing.assert_array_equal(table.numeric(name, allow_empty=allow_empty), want)


def test_replace_gives_a_table_of_chosen_rows():
    import dataclasses

    table = parse_csv(["a;b", "1;2,5", "# x", "3;4,5"])
    kept = dataclasses.replace(table, rows=table.rows[1:], lines=table.lines[1:])
    assert kept.rows == (("3", "4,5"),) and kept.lines == (4,) and len(kept) == 1
    np.testing.assert_array_equal(kept.numeric("b"), [4.5])
    with pytest.raises(dataclasses.FrozenInstanceError):
        table.path = "other"  # type: ignore[misc]


def test_a_file_rewritten_while_read_is_parsed_from_the_bytes_read_first(tmp_path, monkeypatch):
    import axiscal.io.tabular as tabular

    path = tmp_path / "f.csv"
    path.write_text("# c\na,b\n1,2\n3,4\n")
    stamps = iter([(1, 1, 1), (2, 2, 2)])
    real_read_bytes = type(path).read_bytes

    def read_then_rewrite(self):
        data = real_read_bytes(self)
        self.write_text("# c\na,b\n5,6\n7,8\n")  # same rows, other values
        return data

    monkeypatch.setattr(tabular, "_stamp", lambda _: next(stamps))
    monkeypatch.setattr(type(path), "read_bytes", read_then_rewrite)
    table = read_csv(path)
    np.testing.assert_array_equal(table.numeric("a"), [1.0, 3.0])


def test_a_control_character_is_not_stripped_from_a_number(tmp_path):
    # str.strip() takes \x1c-\x1f as white space: "\x1d.890" (a damaged "-2.890") must not read as 0.890
    path = tmp_path / "f.csv"
    path.write_bytes(b"position_mm,EXX_um\n0,\x1d.890\n1,2\n")
    with pytest.raises(AxiscalError, match=r"'\\x1d\.890' is not a number") as info:
        read_csv(path).numeric("EXX_um")
    assert info.value.line == 2


@pytest.mark.parametrize("rows", [b"1,2,\n3,4\n", b"1,2\n3,4,\n", b"1,2\n3,4,,\n"])
def test_a_row_with_an_extra_empty_cell_is_refused_on_every_path(tmp_path, rows):
    # pandas drops trailing empty cells past the header's width; the plain-number path must not
    path = tmp_path / "f.csv"
    path.write_bytes(b"position_mm,EXX_um\n" + rows)
    with pytest.raises(AxiscalError, match="3 cells where the header has 2|4 cells where the header has 2"):
        read_csv(path).numeric("EXX_um")


@pytest.mark.parametrize("ended", ["every row", "the first half"])
def test_an_extra_empty_cell_is_refused_in_a_file_pandas_reads_in_threads(tmp_path, ended):
    # over 5 MB of rows, pandas parses the file in pieces, each dropping its own rows' trailing
    # empty cells; the delimiters counted over the whole body still refuse the first such row
    rows = 400_000
    last = rows if ended == "every row" else rows // 2
    text = "position_mm,EXX_um\n" + "".join(
        f"{k * 0.0025:.6f},{k * 1e-6:.6f}{',' if k < last else ''}\n" for k in range(rows)
    )
    path = tmp_path / "large.csv"
    path.write_text(text)
    assert path.stat().st_size > 5 * 1024 * 1024
    with pytest.raises(AxiscalError, match="3 cells where the header has 2") as info:
        read_csv(path)
    assert info.value.line == 2
