"""The pre-compensation's fast paths give what their plain references give, to the bit and to the byte.

The pieces' columns read in bulk, short pieces after the first included (:func:`axiscal.io.gcode.stream.read_pieces`),
against those read block by block, and the pieces' text written by the compiled
kernel (:mod:`axiscal.precompensation.format_kernel`) against the NumPy formatting, the path's
samples (:mod:`axiscal.precompensation.path_kernel`) and the arcs' chords laid all at once against
their NumPy references, over seeded random programs of every word dialect (plain moves with and
without G words and feeds, block numbers, arcs in every plane and helical, G91 stretches, G92, inch
blocks, dwells, comments, the extruder) cut at random lines, and over random numbers.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from axiscal.io.gcode import reader
from axiscal.io.gcode import stream
from axiscal.precompensation import rewrite_program, text as text_module

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
def test_the_pieces_read_in_bulk_are_the_pieces_read_block_by_block(seed, dialect):
    """The first piece read in bulk, so every later one too however short: the columns of the pieces read
    block by block, and the F numbers as written (looked up on the lines that have one only)."""
    pieces = _cut(_random_program(seed, dialect), seed)
    saved = reader._BULK_FROM, reader._BULK
    try:
        reader._BULK_FROM = len(reader.split_lines(pieces[0]))
        fast = list(stream.read_pieces(pieces, dialect=dialect, source="p"))
        reader._BULK = False
        slow = list(stream.read_pieces(pieces, dialect=dialect, source="p"))
    finally:
        reader._BULK_FROM, reader._BULK = saved
    assert len(fast) == len(slow)
    taken = 0
    for a, b in zip(fast, slow):
        assert (a.lines, a.line_end, a.last, a.ends_with_line_end, a.size) == (b.lines, b.line_end, b.last,
                                                                               b.ends_with_line_end, b.size)
        x, y = a.columns, b.columns
        assert (x.axes, x.first_line, x.motion_word_before) == (y.axes, y.first_line, y.motion_word_before)
        for name in ("kind", "absolute", "extruder_relative", "metres_per_unit", "motion_word", "has_e", "motion_line",
                     "end_m", "known", "start_m", "start_known", "offset_m"):
            u, v = getattr(x, name), getattr(y, name)
            assert u.dtype == v.dtype and np.array_equal(u, v, equal_nan=u.dtype.kind == "f"), name
        bulk = np.flatnonzero(x.bulk_row >= 0)
        taken += bulk.size
        for line in bulk.tolist():
            written = dict(y.general[line].words).get("F")
            assert x.feed_word[line] == written and line not in x.general
            start, stop = x.number_at[line]
            assert (f"N{a.lines[line][start:stop]}" if stop > start else "") == y.general[line].number
        assert x.general == {i: block for i, block in y.general.items() if i not in set(bulk.tolist())}
    if dialect != "fanuc":
        assert taken


def _rewritten(text, machine, dialect, compiled, **settings_):
    from axiscal.precompensation import path

    old = text_module._COMPILED, path._COMPILED
    text_module._COMPILED = path._COMPILED = compiled
    try:
        return rewrite_program(text, machine, dialect=dialect, source="p", **settings_)
    finally:
        text_module._COMPILED, path._COMPILED = old


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
    # with block numbers before some rows, as the lines of one piece write them
    numbers = [str(10 * k).zfill(k % 4) if k % 3 else "" for k in range(n)]
    data = np.frombuffer("".join(numbers).encode("ascii"), dtype=np.uint8)
    at = np.where([bool(x) for x in numbers], np.cumsum([len(x) for x in numbers]) - [len(x) for x in numbers], -1)
    prefixed = text_module._compiled_rows(codes, options, ["X", "Y", "Z"], values, places, show, e,
                                          (data, at.astype(np.int64), np.array([len(x) for x in numbers])))
    assert prefixed == [f"N{x} {row}" if x else row for x, row in zip(numbers, fast)]
    # and as Python's formatting writes them
    for row, (x, y, z), p in zip(fast, values, places):
        assert row.split()[1:4] == [f"{k}{v / 10.0 ** p + 0.0:.{p}f}" for k, v in zip("XYZ", (x, y, z))]


def _chords_one_arc_at_a_time(moves, linear, tolerance_m, max_segment_m):
    """The chords' ends of every arc as the rewriting made them before, one arc at a time: the reference."""
    import math

    from axiscal.io.gcode import PLANE_AXES

    end = moves.end
    path = moves.kind != 1
    path[0] = False
    start = np.where(path[:, None], np.vstack([end[:1], end[:-1]]), end)
    out = {}
    for number in np.flatnonzero((moves.kind == 3) & path).tolist():
        motion = moves.motion(number)
        a, b, normal = PLANE_AXES[motion.plane]
        ca, cb = motion.centre_m[a], motion.centre_m[b]
        radius = math.hypot(motion.start_m[a] - ca, motion.start_m[b] - cb)
        sweep = motion.sweep_rad
        step = min(4.0 * math.asin(math.sqrt(min(tolerance_m / 4.0 / (2.0 * radius), 1.0))), max_segment_m / radius)
        count = max(1, math.ceil(abs(sweep) / step - 1e-9))
        f = np.arange(1, count + 1) / count
        points = np.repeat(start[number][None, :], count, axis=0)
        theta = math.atan2(motion.start_m[b] - cb, motion.start_m[a] - ca) + sweep * f
        for letter, value in ((a, ca + radius * np.cos(theta)), (b, cb + radius * np.sin(theta))):
            if letter in linear:
                points[:, linear.index(letter)] = value
        if normal in linear:
            j = linear.index(normal)
            points[:, j] = start[number][j] + f * (end[number][j] - start[number][j])
        points[-1] = end[number]
        out[number] = (points, f)
    return out


def _arcs_program(rng, plane: str, axes: str) -> str:
    """Arcs by radius and by centre, both ways round, with a helical climb, in ``plane``, among straight moves."""
    a, b = {"G17": "XY", "G18": "XZ", "G19": "YZ"}[plane]
    position = {"X": 400.0, "Y": 250.0, "Z": 200.0} if axes == "XYZ" else {"X": 100.0, "Z": 100.0}
    lines = ["%", f"G21 G90 G94 {plane}", "G0 " + " ".join(f"{k}{v:.3f}" for k, v in position.items()), "G1 F900"]
    for _ in range(40):
        if a not in position or b not in position:
            break
        r = rng.uniform(0.3, 8.0)
        angle = rng.uniform(0, 2 * np.pi)
        chord = rng.uniform(0.2, 1.9) * r
        ea, eb = position[a] + chord * np.cos(angle), position[b] + chord * np.sin(angle)
        normal = next((k for k in axes if k not in (a, b)), None)
        climb = f" {normal}{position[normal] + rng.uniform(-1, 1):.4f}" if normal and rng.random() < 0.3 else ""
        g = rng.choice(["G2", "G3"])
        if rng.random() < 0.5:
            lines.append(f"{g} {a}{ea:.4f} {b}{eb:.4f}{climb} R{r:.4f}")
        else:  # the centre on the chord's bisector
            mid_a, mid_b = (position[a] + ea) / 2, (position[b] + eb) / 2
            half = chord / 2
            off = np.sqrt(max(r * r - half * half, 0.0))
            ca, cb = mid_a - off * np.sin(angle), mid_b + off * np.cos(angle)
            i_word = {"X": "I", "Y": "J", "Z": "K"}
            lines.append(f"{g} {a}{ea:.4f} {b}{eb:.4f}{climb} {i_word[a]}{ca - position[a]:.4f} {i_word[b]}{cb - position[b]:.4f}")
        if climb:
            position[normal] = float(climb.split(normal)[1])
        position[a], position[b] = float(f"{ea:.4f}"), float(f"{eb:.4f}")
        lines.append(f"G1 {a}{position[a] + 0.5:.4f}")
        position[a] = float(f"{position[a] + 0.5:.4f}")
    return "\n".join(lines + ["M2", "%"]) + "\n"


@settings(max_examples=40, deadline=None)
@given(seed=st.integers(0, 10_000), plane=st.sampled_from(["G17", "G18", "G19"]),
       machine=st.sampled_from(["xfyz", "module"]), tolerance_um=st.sampled_from([0.2, 0.5, 3.0]),
       segment_mm=st.sampled_from([0.5, 2.0, 20.0]))
def test_every_arcs_chords_are_those_of_one_arc_at_a_time(seed, plane, machine, tolerance_um, segment_mm):
    from axiscal.io.gcode import read_program
    from axiscal.precompensation.moves import Moves
    from axiscal.precompensation.path import build_pieces

    model = MACHINES[machine]
    axes = "XYZ" if machine == "xfyz" else "XZ"
    if axes == "XZ" and plane != "G18":
        plane = "G18"
    text = _arcs_program(np.random.default_rng(seed), plane, axes)
    linear = [k for k in model.letters if k not in model.rotary]
    program = read_program(text, dialect="linuxcnc")
    moves = Moves(program.columns, model, linear, [], None)
    pieces = build_pieces(moves, linear, [], tolerance_um * 1e-6, segment_mm * 1e-3, None)
    reference = _chords_one_arc_at_a_time(moves, linear, tolerance_um * 1e-6, segment_mm * 1e-3)
    assert reference
    for number, (points, f) in reference.items():
        rows = pieces.move == number
        assert np.array_equal(pieces.p1[rows], points) and np.array_equal(pieces.t1[rows], f), number


@settings(max_examples=100, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), pieces=st.integers(1, 50), columns=st.integers(1, 3),
       scale=st.sampled_from([1e-3, 1.0, 1e3]))
def test_the_compiled_samples_are_numpys(seed, pieces, columns, scale):
    from axiscal.precompensation import path

    rng = np.random.default_rng(seed)
    start, out, p0, p1 = (rng.normal(0.0, scale, (pieces, columns)) for _ in range(4))
    idx = np.flatnonzero(rng.random(pieces) < 0.7)
    counts = rng.integers(1, 9, idx.size)
    fast = path._samples(start, out, p0, p1, idx, counts)
    old = path._COMPILED
    path._COMPILED = False
    try:
        plain = path._samples(start, out, p0, p1, idx, counts)
    finally:
        path._COMPILED = old
    assert all(np.array_equal(a, b) for a, b in zip(fast, plain))
