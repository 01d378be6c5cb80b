"""The text of a pre-compensated program: each rewritten block's pieces in the dialect's words, the rest as it was.

Positions are written with 0.1 um resolution (:data:`PLACES` decimals: 4 in mm, 6 in inch), in the
block's units, distance mode and frame (work offset and G92); a block's number, its other words and
its comment go on its first piece; a G92 met where the control stands at a corrected point is moved
by the correction there. One formatting pass per axis over all the pieces keeps 10^5 lines fast.
"""

from __future__ import annotations

from itertools import repeat
from operator import is_not

import numpy as np

from axiscal.io.gcode import decimal
from axiscal.io.gcode.fast import plain_words

__all__ = ["PLACES", "program_lines", "header_at", "header_line"]

#: decimals written for a position, per program unit (0.1 um either way)
PLACES = {"mm": 4, "inch": 6}
_MM = 1e-3
_ARC_WORDS = frozenset({"I", "J", "K", "R", "CR"})
_MOTION = frozenset({"G0", "G1", "G2", "G3"})


def _sanitize_comment(text: str, style: str) -> str:
    return f"({text.replace('(', '[').replace(')', ']')})" if style == "paren" else f"; {text}"


def program_lines(spec, lines: list[str], moves, pieces, verbatim, output, linear, rotary, end: str) -> tuple[list[str], int]:
    """The output lines of ``lines`` (one str per input line; a move cut into pieces is several lines
    joined by ``end``), no header, and the number of moves written anew.

    ``moves`` and ``pieces`` are the rewriting's moves and pieces (:mod:`axiscal.precompensation.program`);
    ``verbatim`` says per move whether it is written as it was, ``output`` whether its line is wanted.
    """
    columns = moves.columns
    n = pieces.move.size
    first = np.r_[0, np.flatnonzero(np.diff(pieces.move)) + 1] if n else np.zeros(0, dtype=np.int64)
    stop = np.r_[first[1:], n] if n else np.zeros(0, dtype=np.int64)
    out_at = np.where(verbatim[pieces.move][:, None], pieces.p1, pieces.command)
    rewritten = np.flatnonzero(~verbatim & output)
    rows = np.flatnonzero(np.repeat(~verbatim & output, np.diff(np.r_[first, n])))  # the pieces written anew
    at_row = np.full(n, -1, dtype=np.int64)
    at_row[rows] = np.arange(rows.size)
    rapid = (moves.kind == 1) & (not spec.rapid_at_feed)
    bulk_row = columns.bulk_row[moves.index]
    has_e = columns.has_e[moves.index] if "E" in columns.axes else np.zeros(len(moves), dtype=bool)
    bulk = rewritten[bulk_row[rewritten] >= 0]
    plan = _bulk_plan(lines, moves, bulk, first, stop, at_row, rotary) if bulk.size else None
    prefix = _numbers(lines, plan, columns.number_at, rows.size) if plan is not None and _COMPILED else None
    piece_text = _piece_rows(moves, pieces, rows, out_at, linear, rapid, spec, has_e, prefix) if rows.size else []
    out = np.array(lines, dtype=object)
    piece_text = np.array(piece_text, dtype=object)
    if plan is not None:
        _bulk_text(out, lines, moves, bulk, first, stop, at_row, piece_text, end, plan, prefix is not None)
    for number in rewritten[bulk_row[rewritten] < 0].tolist():
        index = int(moves.index[number])
        block = columns.general[index]
        head, tail, rotary_words = [], [], []
        for letter, raw in block.words:
            if letter in spec.axes:
                if letter in rotary:
                    rotary_words.append(f"{letter}{raw}")
            elif letter == "G":
                if _g(raw) not in _MOTION:
                    head.append(f"G{raw}")
            elif letter not in _ARC_WORDS:
                tail.append(f"{letter}{raw}")
        k = first[number]
        parts = ([block.number] if block.number else []) + head + [piece_text[at_row[k]]] + rotary_words + tail
        texts = [" ".join(parts + ([block.comment] if block.comment else []))]
        texts += piece_text[at_row[k] + 1:at_row[k] + stop[number] - k].tolist()
        out[index] = end.join(texts)
    # a G92 met where the control stands at a corrected point
    if spec.set_position:
        for index, block in columns.general.items():
            if block.motion is None and _sets_position(block, spec):
                k = int(np.searchsorted(moves.index, index)) - 1
                if k >= 0:
                    last = stop[k] - 1
                    out[index] = _shifted(block, spec, out_at[last] - pieces.p1[last], linear, out[index])
    return out.tolist(), int(rewritten.size)


def header_at(spec, lines: list[str]) -> int:
    """Where the header comment goes among ``lines``: after the tape's '%' and a FANUC program number."""
    at = 0
    while at < len(lines) and (lines[at].strip() == "%" or (spec.name == "fanuc" and lines[at].strip()[:1] in "Oo"
                                                            and lines[at].strip())):
        at += 1
    return at


def header_line(spec, header: str) -> str:
    """The header comment in the dialect's comment syntax."""
    return _sanitize_comment(header, spec.comment_style)


def _piece_rows(moves, pieces, rows, out_at, linear, rapid, spec, has_e, prefix=None) -> list[str]:
    """The text of each piece ``rows``: its motion word and its positions (and E), in the block's units
    and distance mode, 0.1 um resolution; ``prefix`` (from :func:`_numbers`): the block numbers some rows
    are written after, by the compiled kernel (the others leave them to :func:`_bulk_text`)."""
    move = pieces.move[rows]
    offset, per_unit = moves.offset[move], moves.per_unit[move]
    places = np.where(per_unit == _MM, PLACES["mm"], PLACES["inch"])
    scale = (10.0 ** places / per_unit)[:, None]
    before = np.vstack([pieces.p0[:1], out_at[:-1]])[rows]
    now = np.rint((out_at[rows] - offset) * scale)
    absolute = moves.absolute[move]
    counts = np.where(absolute[:, None], now, now - np.rint((before - offset) * scale))
    if not np.all(np.abs(counts) < 1e15):  # beyond the digits a double holds exactly: Python's formatting
        return _piece_rows_slow(moves, pieces, rows, counts, places, linear, rapid, spec, has_e, prefix)
    codes = rapid[move].astype(np.int64)
    if has_e.any():
        e = _extruder_counts(moves, pieces, rows)
        show = has_e[move]
    else:
        e, show = np.zeros(rows.size), np.zeros(rows.size, dtype=bool)
    if _COMPILED and np.all(np.abs(e) < 1e15):
        return _compiled_rows(codes, [spec.feed_word, spec.rapid_word], linear, counts, places, show, e, prefix)
    if prefix is not None:
        return _piece_rows_slow(moves, pieces, rows, counts, places, linear, rapid, spec, has_e, prefix)
    fields = [_choice(codes, [spec.feed_word, spec.rapid_word])]
    for j, letter in enumerate(linear):
        fields.append(_literal(f" {letter}", rows.size))
        fields.append(_fixed(counts[:, j], places))
    if show.any():
        fields.append(_literal(" E", rows.size, show))
        fields.append(_fixed(e, np.full(rows.size, 5), show))
    return _rows(fields)


#: whether the pieces' text is written by the compiled kernel (False: in NumPy, the reference)
_COMPILED = True


def _compiled_rows(codes, options, linear, counts, places, show, e, prefix=None) -> list[str]:
    """:func:`_piece_rows`'s text written by :func:`axiscal.precompensation.format_kernel.piece_text`."""
    from axiscal.precompensation import format_kernel  # numba takes a moment to load

    width = max(len(o) for o in options)
    words = np.zeros((len(options), width), dtype=np.uint8)
    for k, option in enumerate(options):
        words[k, :len(option)] = np.frombuffer(option.encode("ascii"), dtype=np.uint8)
    length = np.array([len(o) for o in options], dtype=np.int64)
    letters = np.frombuffer("".join(linear).encode("ascii"), dtype=np.uint8).copy()
    if prefix is None:
        prefix = (np.zeros(0, dtype=np.uint8), np.full(codes.size, -1, dtype=np.int64), np.zeros(codes.size, dtype=np.int64))
    data = format_kernel.piece_text(codes, words, length, letters, np.ascontiguousarray(counts, dtype=np.float64),
                                    places.astype(np.int64), show, np.ascontiguousarray(e, dtype=np.float64), *prefix)
    return data.tobytes().decode("ascii").split("\n")[:-1]


def _piece_rows_slow(moves, pieces, rows, counts, places, linear, rapid, spec, has_e, prefix=None) -> list[str]:
    """:func:`_piece_rows` one number at a time (for positions beyond 10^15 counts)."""
    move = pieces.move[rows]
    e = _extruder_counts(moves, pieces, rows) if has_e.any() else None
    out = []
    for i in range(rows.size):
        p = int(places[i])
        words = [spec.rapid_word if rapid[move[i]] else spec.feed_word]
        if prefix is not None and prefix[1][i] >= 0:
            start = int(prefix[1][i])
            words.insert(0, "N" + prefix[0][start:start + int(prefix[2][i])].tobytes().decode("ascii"))
        words += [f"{letter}{counts[i, j] / 10.0 ** p + 0.0:.{p}f}" for j, letter in enumerate(linear)]
        if e is not None and has_e[move[i]]:
            words.append(f"E{e[i] / 1e5 + 0.0:.5f}")
        out.append(" ".join(words))
    return out


_POW = 10 ** np.arange(19, dtype=np.int64)


def _literal(text: str, count: int, show: np.ndarray | None = None):
    chars = np.frombuffer(text.encode("ascii"), dtype=np.uint8)
    valid = np.ones((count, chars.size), dtype=bool) if show is None else np.repeat(show[:, None], chars.size, axis=1)
    return np.broadcast_to(chars, (count, chars.size)), valid


def _choice(codes: np.ndarray, options: list[str]):
    width = max(len(o) for o in options)
    table = np.zeros((len(options), width), dtype=np.uint8)
    valid = np.zeros((len(options), width), dtype=bool)
    for k, option in enumerate(options):
        table[k, :len(option)] = np.frombuffer(option.encode("ascii"), dtype=np.uint8)
        valid[k, :len(option)] = True
    return table[codes], valid[codes]


def _fixed(counts: np.ndarray, places: np.ndarray, show: np.ndarray | None = None):
    """``counts / 10**places`` written with ``places`` decimals (the digits of ``counts``), never ``-0``."""
    ints = counts.astype(np.int64)
    negative = ints < 0
    magnitude = np.abs(ints)
    p = places.astype(np.int64)
    whole, fraction = magnitude // _POW[p], magnitude % _POW[p]
    top = int(whole.max(initial=0))
    width = len(str(top))
    columns = [(np.full(ints.size, ord("-"), dtype=np.uint8), negative)]
    for c in range(width - 1, -1, -1):
        columns.append((((whole // _POW[c]) % 10 + 48).astype(np.uint8), (whole >= _POW[c]) | (c == 0)))
    columns.append((np.full(ints.size, ord("."), dtype=np.uint8), p > 0))
    for k in range(int(p.max(initial=0))):
        inside = k < p
        digit = (fraction // _POW[np.maximum(p - 1 - k, 0)]) % 10
        columns.append(((digit + 48).astype(np.uint8), inside))
    chars = np.column_stack([c for c, _ in columns])
    valid = np.column_stack([v for _, v in columns])
    if show is not None:
        valid &= show[:, None]
    return chars, valid


def _rows(fields) -> list[str]:
    """One line of text per row of the fields (each a pair of chars and valid masks), joined in order."""
    count = fields[0][0].shape[0]
    fields = list(fields) + [(np.full((count, 1), 10, dtype=np.uint8), np.ones((count, 1), dtype=bool))]
    chars = np.concatenate([np.asarray(c) for c, _ in fields], axis=1)
    valid = np.concatenate([v for _, v in fields], axis=1)
    return chars[valid].tobytes().decode("ascii").split("\n")[:-1]


def _bulk_plan(texts, moves, numbers, first, stop, at_row, rotary):
    """How the moves ``numbers`` read in bulk are written: their lines, their first piece's row, the words
    (rotary, F) written after it, whether they have a block number, and which are one piece and no more
    words (``plain``)."""
    columns = moves.columns
    lines = moves.index[numbers]
    head = np.asarray(at_row[first[numbers]])
    single = stop[numbers] - first[numbers] == 1
    extra: dict[int, list[str]] = {}
    if rotary:
        for j, line in enumerate(lines.tolist()):
            written = dict(plain_words(texts[line]))
            for letter in rotary:
                if letter in written:
                    extra.setdefault(j, []).append(f"{letter}{written[letter]}")
    feed_word = columns.feed_word
    fed = np.fromiter(map(is_not, feed_word, repeat(None)), dtype=bool, count=len(feed_word))
    for j in np.flatnonzero(fed[lines]).tolist():
        extra.setdefault(j, []).append(f"F{feed_word[lines[j]]}")
    numbered = columns.number_at[lines, 1] > 0
    plain = single.copy()
    if extra:
        plain[list(extra)] = False
    return lines, head, extra, numbered, plain


def _numbers(texts, plan, number_at, rows: int):
    """The block numbers of the lines of one piece and no more words, for the kernel to write before
    their piece: (the lines' ASCII bytes, per row where its number starts in them or -1, its length);
    None when there are none, or the lines are not ASCII."""
    lines, head, _, numbered, plain = plan
    only = plain & numbered
    if not only.any():
        return None
    joined = "\n".join(texts)
    if not joined.isascii():
        return None
    data = np.frombuffer(joined.encode("ascii"), dtype=np.uint8)
    length = np.fromiter(map(len, texts), dtype=np.int64, count=len(texts))
    starts = np.cumsum(length + 1) - length - 1
    which = lines[only]
    at = np.full(rows, -1, dtype=np.int64)
    size = np.zeros(rows, dtype=np.int64)
    at[head[only]] = starts[which] + number_at[which, 0]
    size[head[only]] = number_at[which, 1] - number_at[which, 0]
    return data, at, size


def _bulk_text(out, texts, moves, numbers, first, stop, at_row, piece_text, end, plan, prefixed: bool) -> None:
    """Write the moves ``numbers`` read in bulk (block number, G0/G1, axis words, F) as ``plan``
    (:func:`_bulk_plan`) says: the block number, the pieces' text, the rotary words and F as written on
    the first. ``out`` and ``piece_text`` are object arrays: the lines of one piece and no more words are
    put in place all at once (``prefixed``: their rows hold their block numbers already)."""
    columns = moves.columns
    lines, head, extra, numbered, plain = plan
    at = columns.number_at
    only = plain & numbered  # a block number and one piece: the number, then the piece
    if only.any() and not prefixed:
        which = lines[only]
        out[which] = np.array([f"N{texts[line][start:stop_at]} {row}" for line, row, start, stop_at
                               in zip(which.tolist(), piece_text[head[only]].tolist(), at[which, 0].tolist(),
                                      at[which, 1].tolist())], dtype=object)
    alone = plain & (~numbered | prefixed)
    out[lines[alone]] = piece_text[head[alone]]
    for j in np.flatnonzero(~plain).tolist():
        number = numbers[j]
        line = int(lines[j])
        k = first[number]
        start, stop_at = at[line]
        row = int(at_row[k])
        text = " ".join(([f"N{texts[line][start:stop_at]}"] if stop_at > start else []) + [piece_text[row]]
                        + extra.get(j, []))
        if stop[number] > k + 1:
            text = end.join([text] + piece_text[row + 1:row + stop[number] - k].tolist())
        out[line] = text


def _extruder_counts(moves, pieces, rows) -> np.ndarray:
    """The E word of every piece ``rows`` (absolute or relative as the block is), shared out along the
    move, in hundred-thousandths of the program unit."""
    columns = moves.columns
    move = pieces.move[rows]
    e_end, e_start, shift = (values[move] for values in moves.extruder())
    relative = columns.extruder_relative[moves.index][move]
    per_unit = columns.metres_per_unit[moves.index][move]
    at_end = e_start + pieces.t1[rows] * (e_end - e_start)
    at_start = e_start + pieces.t0[rows] * (e_end - e_start)
    value = np.where(relative, at_end - at_start, at_end - shift) / per_unit
    return np.rint(value * 1e5) + 0.0


def _sets_position(block, spec) -> bool:
    return any(letter == "G" and _g(raw) in spec.set_position for letter, raw in block.words)


def _shifted(block, spec, difference: np.ndarray, linear, line: str) -> str:
    """A G92 block with its coordinates moved by ``difference`` (metres per linear axis): the control
    stands at the pre-compensated point, so the coordinates it gives that point are moved by the
    correction there, and the program's frame stays where the programmer put it."""
    places = PLACES["mm"] if block.metres_per_unit == _MM else PLACES["inch"]
    half = 0.5 * 10.0 ** -places * block.metres_per_unit
    if not np.any(np.abs(difference) >= half):
        return line
    words = []
    for letter, raw in block.words:
        if letter in linear:
            value = float(raw) * (spec.implicit_increment if spec.decimal_point_needed and "." not in raw else 1.0)
            value += difference[linear.index(letter)] / block.metres_per_unit
            words.append(f"{letter}{decimal(value, places, point=spec.decimal_point_needed)}")
        else:
            words.append(f"{letter}{raw}")
    return " ".join(([block.number] if block.number else []) + words + ([block.comment] if block.comment else []))


def _g(raw: str) -> str:
    value = float(raw)
    return f"G{int(value)}" if value == int(value) else f"G{value:g}"
