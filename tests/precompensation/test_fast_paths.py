"""The pre-compensation's fast paths give what their plain references give, to the bit and to the byte.

The columns built for the pieces (:mod:`axiscal.precompensation.reading`) against the reader's
own (:func:`axiscal.io.gcode.stream.read_pieces`), and the pieces' text written by the compiled
kernel (:mod:`axiscal.precompensation.format_kernel`) against the NumPy formatting, over seeded
random programs of every word dialect (plain moves with and without G words and feeds, block
numbers, arcs, G91 stretches, G92, inch blocks, dwells, comments, the extruder) cut at random
lines, and over random numbers.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from axiscal.io.gcode import reader
from axiscal.io.gcode import stream
from axiscal.precompensation import rewrite_program, text as text_module
from axiscal.precompensation import reading

from .machines import machines
from .test_bulk import _program
from .test_streaming import bulging, kept_and_bulging

MACHINES = machines()
DIALECTS = ["linuxcnc", "grbl", "sinumerik", "fanuc", "marlin", "klipper"]


@pytest.fixture(autouse=True)
def bulk_from_the_first_line(monkeypatch):
    """Read every piece's plain lines in bulk, however short."""
    monkeypatch.setattr(reader, "_BULK_FROM", 0)


def _random_program(seed: int, dialect: str) -> str:
    rng = np.random.default_rng(seed)
    if dialect == "fanuc" or rng.random() < 0.4:
        return kept_and_bulging(rng, dialect, lines=120)
    return _program(rng, dialect, rotary=False)


def _cut(text: str, seed: int) -> list[str]:
    lines = text.splitlines(keepends=True)
    rng = np.random.default_rng(seed)
    cuts = np.sort(rng.choice(np.arange(1, len(lines)), size=min(4, len(lines) - 1), replace=False))
    return ["".join(lines[a:b]) for a, b in zip(np.r_[0, cuts], np.r_[cuts, len(lines)])]


def _same_columns(mine, theirs) -> None:
    for field in dataclasses.fields(theirs):
        a, b = getattr(mine, field.name), getattr(theirs, field.name)
        if isinstance(b, np.ndarray):
            assert a.dtype == b.dtype and a.shape == b.shape, field.name
            assert np.array_equal(a, b, equal_nan=a.dtype.kind == "f"), field.name
        elif field.name == "general":
            assert a.keys() == b.keys() and all(a[k] == b[k] for k in b), field.name
        else:
            assert a == b, field.name


@settings(max_examples=30, deadline=None)
@given(seed=st.integers(0, 10_000), dialect=st.sampled_from(DIALECTS))
def test_the_pieces_columns_are_the_readers(seed, dialect):
    pieces = _cut(_random_program(seed, dialect), seed)
    mine = list(reading.read_pieces(pieces, dialect=dialect, source="p"))
    theirs = list(stream.read_pieces(pieces, dialect=dialect, source="p"))
    assert len(mine) == len(theirs)
    for a, b in zip(mine, theirs):
        assert (a.lines, a.line_end, a.last, a.ends_with_line_end, a.size) == (b.lines, b.line_end, b.last,
                                                                               b.ends_with_line_end, b.size)
        _same_columns(a.columns, b.columns)


def _rewritten(text, machine, dialect, compiled, **settings_):
    old = text_module._COMPILED
    text_module._COMPILED = compiled
    try:
        return rewrite_program(text, machine, dialect=dialect, source="p", **settings_)
    finally:
        text_module._COMPILED = old


@settings(max_examples=30, deadline=None)
@given(seed=st.integers(0, 10_000), dialect=st.sampled_from(DIALECTS))
def test_the_compiled_text_is_numpys(seed, dialect):
    text = _random_program(seed, dialect)
    bulged = "G1 X500. Y300. Z300." in text
    machine = bulging() if bulged else MACHINES["xfyz"]
    kwargs = {"tolerance_m": 0.3e-6, "max_segment_m": 20e-3} if bulged else {}
    fast, plain = _rewritten(text, machine, dialect, True, **kwargs), _rewritten(text, machine, dialect, False, **kwargs)
    assert fast == plain
    assert fast.rewritten > 0


@settings(max_examples=200, deadline=None)
@given(counts=st.lists(st.tuples(st.integers(-10**15 + 1, 10**15 - 1), st.integers(-10**9, 10**9),
                                 st.integers(-10**15 + 1, 10**15 - 1)), min_size=1, max_size=20),
       inch=st.lists(st.booleans(), min_size=20, max_size=20),
       extruder=st.lists(st.one_of(st.none(), st.integers(-10**15 + 1, 10**15 - 1)), min_size=20, max_size=20),
       rapid=st.lists(st.booleans(), min_size=20, max_size=20))
def test_every_number_is_written_as_numpy_writes_it(counts, inch, extruder, rapid):
    n = len(counts)
    values = np.array(counts, dtype=float)
    places = np.where(inch[:n], 6, 4)
    show = np.array([e is not None for e in extruder[:n]])
    e = np.array([0.0 if v is None else float(v) for v in extruder[:n]])
    codes = np.array(rapid[:n], dtype=np.int64)
    options = ["G01", "G0"]
    fast = text_module._compiled_rows(codes, options, ["X", "Y", "Z"], values, places, show, e)
    fields = [text_module._choice(codes, options)]
    for j, letter in enumerate("XYZ"):
        fields.append(text_module._literal(f" {letter}", n))
        fields.append(text_module._fixed(values[:, j], places))
    fields.append(text_module._literal(" E", n, show))
    fields.append(text_module._fixed(e, np.full(n, 5), show))
    assert fast == text_module._rows(fields)
    # and as Python's formatting writes them
    for row, (x, y, z), p in zip(fast, values, places):
        assert row.split()[1:4] == [f"{k}{v / 10.0 ** p + 0.0:.{p}f}" for k, v in zip("XYZ", (x, y, z))]
