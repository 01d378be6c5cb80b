"""The bulk reading of plain straight moves gives what the block-by-block reader gives, to the bit.

A program's plain lines (``G1 X1 Y2 F600``) are read in bulk with NumPy; every other line block by
block. Against the reader with the bulk path off (``reader._BULK = False``), over seeded and
hypothesis-drawn programs mixing plain lines with everything that changes the state around them
(units, distance mode, G92, arcs, comments, dwells, extruder modes, bad lines), the blocks, the
motions, the columns and the errors are the same.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from axiscal.errors import AxiscalError
from axiscal.io.gcode import reader
from axiscal.io.gcode.columns import program_columns

WORD_DIALECTS = ["linuxcnc", "grbl", "sinumerik", "marlin", "klipper"]
NUMBER = st.one_of(
    st.integers(-99999, 99999).map(str),
    st.builds(lambda a, b: f"{a}.{b}", st.integers(-9999, 9999), st.integers(0, 999999)),
    st.sampled_from(["-0", "+1.5", ".5", "-.25", "1.", "007", "12345678901234567.5", "0.000000000000000000000001",
                     "1" * 30, "-0.0"]),
)


@pytest.fixture(autouse=True)
def bulk_from_the_first_line(monkeypatch):
    """Read every program of these tests in bulk, however short (the reader reads short ones block by block)."""
    monkeypatch.setattr(reader, "_BULK_FROM", 0)


def _read(text: str, dialect: str, bulk: bool):
    old = reader._BULK
    reader._BULK = bulk
    try:
        return reader.read_program(text, dialect=dialect, source="p.ngc")
    except AxiscalError as error:
        return ("error", str(error), error.line)
    finally:
        reader._BULK = old


def _same(text: str, dialect: str) -> None:
    fast, slow = _read(text, dialect, True), _read(text, dialect, False)
    if isinstance(slow, tuple) or isinstance(fast, tuple):
        assert fast == slow
        return
    assert fast.blocks == slow.blocks
    assert fast.motions == slow.motions
    for block_fast, block_slow in zip(fast.blocks, slow.blocks):  # key order too (a reader names the first)
        assert list(block_fast.offset_m) == list(block_slow.offset_m)
        if block_fast.motion is not None:
            assert list(block_fast.motion.end_m) == list(block_slow.motion.end_m)
    a, b = fast.columns, program_columns(slow)
    assert a.axes == b.axes
    for name in ("kind", "absolute", "extruder_relative", "metres_per_unit", "motion_word", "known"):
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name), err_msg=name)
    for name in ("motion_line", "end_m", "start_m", "start_known", "offset_m"):
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name), err_msg=name)


def _line(rng: np.random.Generator, dialect: str) -> str:
    """One line: mostly plain moves in many spellings, sometimes anything that changes the state."""
    axes = {"marlin": "XYZE", "klipper": "XYZE", "grbl": "XYZ"}.get(dialect, "XYZA")
    number = lambda: rng.choice([f"{rng.uniform(-500, 500):.{rng.integers(0, 7)}f}", str(rng.integers(-50, 50)),
                                 f"{rng.uniform(-1, 1):.3f}".replace("0.", "."), "0"])
    r = rng.random()
    if r < 0.7:
        letters = [k for k in axes if rng.random() < 0.6] or [axes[0]]
        if rng.random() < 0.1:
            rng.shuffle(letters)  # out of order: the block reader's
        words = [f"{k}{' ' if rng.random() < 0.2 else ''}{number()}" for k in letters]
        if rng.random() < 0.5 or dialect in ("marlin", "klipper"):
            words.insert(0, rng.choice(["G1", "G0", "G01", "G00", "g1"]))
        if rng.random() < 0.1:
            words.append(f"F{rng.choice(['600', '1500.5', '0', '-5', '.5'])}")
        sep = rng.choice([" ", "", "\t", "  "])
        line = sep.join(words)
        if rng.random() < 0.05:
            line = " " + line + " "
        return line
    extras = {
        "linuxcnc": ["G20", "G21", "G90", "G91", "G92 X1 Y2", "G92.1", "G2 X1 Y1 R5", "G3 X0 Y0 I1 J0", "(comment)",
                     "G4 P0.5", "F800", "X1 2", "X1Y2 ; tail", "N10 G1 X1", "G1 X1 S100", "G18", "",
                     "G17", "G1 X1 Y1 A5 F100"],
        "grbl": ["G20", "G21", "G90", "G91", "G2 X1 Y1 R5", "(comment)", "G4 P0.5", "F800", "X1 2", "", "G92 X0"],
        "sinumerik": ["G70", "G71", "G90", "G91", "G2 X1 Y1 CR=5", "; note", "G4 F1", "F800", "X1 2", ""],
        "marlin": ["G20", "G21", "G90", "G91", "M82", "M83", "G92 E0", "G2 X1 Y1 R5", "; note", "G4 P500", "G1 F800",
                   "G1 X1 2", ""],
        "klipper": ["G90", "G91", "M82", "M83", "G92 E0", "G2 X1 Y1 I1 J0", "; note", "G4 P500", "G1 F800", ""],
    }[dialect]
    return str(rng.choice(extras))


@pytest.mark.parametrize("dialect", WORD_DIALECTS)
@pytest.mark.parametrize("seed", range(6))
def test_seeded_programs_read_the_same_in_bulk_and_block_by_block(dialect, seed):
    rng = np.random.default_rng(seed)
    start = {"linuxcnc": ["G21 G90 G94", "G0 X0 Y0 Z0 A0", "G1 F600"], "grbl": ["G21 G90", "G0 X0 Y0 Z0", "G1 F600"],
             "sinumerik": ["G71 G90", "G0 X0 Y0 Z0 A0", "G1 F600"], "marlin": ["G21", "G90", "G1 X0 Y0 Z0 F600"],
             "klipper": ["G90", "G1 X0 Y0 Z0 F600"]}[dialect]
    lines = start + [_line(rng, dialect) for _ in range(400)]
    ending = {"linuxcnc": ["M2"], "sinumerik": ["M30"], "grbl": ["M2"]}.get(dialect, [])
    # the program as drawn stops at its first bad line; each bad line is compared, then dropped,
    # until the whole program reads
    for _ in range(200):
        text = "\n".join(lines + ending) + "\n"
        _same(text, dialect)
        read = _read(text, dialect, False)
        if not isinstance(read, tuple):
            break
        del lines[read[2] - 1]
    assert not isinstance(read, tuple) and len(read.motions) > 150


@settings(max_examples=150, deadline=None)
@given(dialect=st.sampled_from(WORD_DIALECTS), numbers=st.lists(NUMBER, min_size=1, max_size=12),
       ending=st.sampled_from(["\n", "\r\n", "\r"]), g=st.sampled_from(["", "G1 ", "G0 ", "G01 "]))
def test_plain_lines_with_any_number_read_the_same(dialect, numbers, ending, g):
    head = {"linuxcnc": "G21 G90\nG1 X0 Y0 Z0 F600", "grbl": "G21 G90\nG1 X0 Y0 Z0 F600", "sinumerik": "G71 G90\nG1 X0 Y0 Z0 F600",
            "marlin": "G21\nG90\nG1 X0 Y0 Z0 F600", "klipper": "G90\nG1 X0 Y0 Z0 F600"}[dialect]
    letters = "XYZ"
    lines = head.split("\n") + [f"{g or 'G1 '}{letters[i % 3]}{n}" if dialect in ("marlin", "klipper") else f"{g}{letters[i % 3]}{n}"
                                for i, n in enumerate(numbers)]
    _same(ending.join(lines) + ending, dialect)


def test_a_plain_line_is_parsed_as_float_parses_it():
    numbers = ["0.1", "0.7", "1.0000001", "123456.789012", "-0.0001", "99999.99999", "3.14159265358979",
               "0.30000000000000004", "1e5"]
    for n in numbers[:-1]:
        program = reader.read_program(f"G21 G90\nG1 X0 F600\nG1 X{n}\nM2\n", dialect="linuxcnc")
        assert program.motions[-1].end_m["X"] == float(n) * 1e-3
        assert program.columns.end_m[-1, 0] == float(n) * 1e-3


@pytest.mark.parametrize("dialect", ["linuxcnc", "sinumerik", "fanuc", "marlin"])
@pytest.mark.parametrize("seed", range(3))
def test_numbered_blocks_and_fanuc_read_the_same_in_bulk_and_block_by_block(dialect, seed):
    """Block numbers on most lines (N10, n20, N 30, N-4, N1.5) and FANUC's numbers with and without
    their point: the plain ones read in bulk, the rest block by block, the same blocks either way."""
    rng = np.random.default_rng(100 + seed)
    start = {"linuxcnc": ["G21 G90 G94", "G0 X0 Y0 Z0 A0", "G1 F600"], "sinumerik": ["G71 G90", "G0 X0 Y0 Z0 A0", "G1 F600"],
             "fanuc": ["%", "O0001", "G21", "G90 G94", "G00 X0. Y0. Z0. A0.", "G01 F600."],
             "marlin": ["G21", "G90", "G1 X0 Y0 Z0 F600"]}[dialect]
    like = "marlin" if dialect == "marlin" else "linuxcnc"
    lines = list(start)
    for k in range(400):
        line = _line(rng, like)
        if dialect == "fanuc" and rng.random() < 0.8:
            line = line.replace("G92.1", "G92 X0")
            line = " ".join(word + "." if word[:1] in "XYZA" and "." not in word and word[1:].lstrip("-").isdigit()
                            else word for word in line.split(" "))
        if rng.random() < 0.6:
            line = rng.choice([f"N{10 * k} ", f"n{k}", f"N {k} ", "N-4 ", "N1.5 "]) + line
        lines.append(line)
    ending = {"linuxcnc": ["M2"], "sinumerik": ["M30"], "fanuc": ["M30", "%"]}.get(dialect, [])
    for _ in range(300):
        text = "\n".join(lines + ending) + "\n"
        _same(text, dialect)
        read = _read(text, dialect, False)
        if not isinstance(read, tuple):
            break
        del lines[read[2] - 1]
    assert not isinstance(read, tuple) and len(read.motions) > 100
    if dialect != "marlin":
        assert any(block.number for block in read.blocks)
