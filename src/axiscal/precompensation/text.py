"""The text of a pre-compensated program: each rewritten block's pieces in the dialect's words, the rest as it was.

Positions are written with 0.1 um resolution (:data:`PLACES` decimals: 4 in mm, 6 in inch), in the
block's units, distance mode and frame (work offset and G92); a block's number, its other words and
its comment go on its first piece; a G92 met where the control stands at a corrected point is moved
by the correction there. One formatting pass per axis over all the pieces keeps 10^5 lines fast.
"""

from __future__ import annotations

import numpy as np

from axiscal.io.gcode import Program, decimal, split_lines

__all__ = ["PLACES", "program_text"]

#: decimals written for a position, per program unit (0.1 um either way)
PLACES = {"mm": 4, "inch": 6}
_MM = 1e-3
_ARC_WORDS = frozenset({"I", "J", "K", "R", "CR"})
_MOTION = frozenset({"G0", "G1", "G2", "G3"})


def _sanitize_comment(text: str, style: str) -> str:
    return f"({text.replace('(', '[').replace(')', ']')})" if style == "paren" else f"; {text}"


def _formatted(values: np.ndarray, places: np.ndarray) -> list[str]:
    """Numbers with ``places`` decimals each (4 or 6), never ``-0``."""
    values = values + 0.0
    out = np.empty(values.shape, dtype=object)
    for count in np.unique(places):
        rows = places == count
        out[rows] = np.char.mod(f"%.{int(count)}f", np.round(values[rows], int(count)) + 0.0)
    return out.tolist()


def program_text(program: Program, moves, pieces, verbatim, linear, rotary, text: str, header: str) -> tuple[str, int]:
    """The output program's text and the number of moves written anew.

    ``moves`` and ``pieces`` are the rewriting's moves and pieces (:mod:`axiscal.precompensation.program`);
    ``verbatim`` says per move whether it is written as it was.
    """
    spec = program.dialect
    lines = split_lines(text)
    n = pieces.move.size
    first = np.r_[0, np.flatnonzero(np.diff(pieces.move)) + 1] if n else np.zeros(0, dtype=np.int64)
    stop = np.r_[first[1:], n] if n else np.zeros(0, dtype=np.int64)
    offset, per_unit = moves.offset[pieces.move], moves.per_unit[pieces.move]
    places = np.where(per_unit == _MM, PLACES["mm"], PLACES["inch"])
    scale = (10.0 ** places / per_unit)[:, None]
    out_at = np.where(verbatim[pieces.move][:, None], pieces.p1, pieces.command)
    before = np.vstack([pieces.p0[:1], out_at[:-1]]) if n else out_at
    now = np.rint((out_at - offset) * scale)
    absolute = np.array([program.blocks[i].absolute for i in moves.index], dtype=bool)[pieces.move] if n else np.zeros(0, bool)
    value = np.where(absolute[:, None], now, now - np.rint((before - offset) * scale)) / 10.0 ** places[:, None]
    columns = [[letter + v for v in _formatted(value[:, j], places)] for j, letter in enumerate(linear)] if n else []
    body = list(map(" ".join, zip(*columns)))
    extruder = _extruder_text(program, moves, pieces, places) if n else None
    with_e = body if extruder is None else [f"{b} E{e}" for b, e in zip(body, extruder)]
    move_of_block = {index: number for number, index in enumerate(moves.index)}
    out: list[str] = []
    rewritten = 0
    here = program_here = None
    for index, block in enumerate(program.blocks):
        number = move_of_block.get(index)
        if number is None:
            if here is not None and _sets_position(block, spec):
                out.append(_shifted(block, spec, here - program_here, linear, lines[index]))
            else:
                out.append(lines[index])
            continue
        last = stop[number] - 1
        here, program_here = out_at[last], pieces.p1[last]
        if verbatim[number]:
            out.append(lines[index])
            continue
        rewritten += 1
        word = spec.rapid_word if block.motion.kind == "rapid" and not spec.rapid_at_feed else spec.feed_word
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
        words = with_e if extruder is not None and any(letter == "E" for letter, _ in block.words) else body
        k = first[number]
        parts = ([block.number] if block.number else []) + head + [word, words[k]] + rotary_words + tail
        out.append(" ".join(parts + ([block.comment] if block.comment else [])))
        if stop[number] > k + 1:
            out.extend([f"{word} {words[j]}" for j in range(k + 1, stop[number])])
    at = 0
    while at < len(out) and (out[at].strip() == "%" or (spec.name == "fanuc" and out[at].strip()[:1] in "Oo" and out[at].strip())):
        at += 1
    out.insert(at, _sanitize_comment(header, spec.comment_style))
    end = program.line_end
    return end.join(out) + (end if text.endswith(("\n", "\r")) else ""), rewritten


def _extruder_text(program: Program, moves, pieces, places) -> list[str] | None:
    """The E word of every piece (absolute or relative as the block is), shared out along the move."""
    motions = moves.motions
    if not any("E" in m.end_m for m in motions):
        return None
    e_end = np.array([m.end_m.get("E", 0.0) for m in motions])[pieces.move]
    e_start = np.array([m.start_m.get("E", 0.0) for m in motions])[pieces.move]
    blocks = [program.blocks[i] for i in moves.index]
    shift = np.array([b.offset_m.get("E", 0.0) for b in blocks])[pieces.move]
    relative = np.array([b.extruder_relative for b in blocks], dtype=bool)[pieces.move]
    per_unit = np.array([b.metres_per_unit for b in blocks])[pieces.move]
    at_end = e_start + pieces.t1 * (e_end - e_start)
    at_start = e_start + pieces.t0 * (e_end - e_start)
    value = np.where(relative, at_end - at_start, at_end - shift) / per_unit
    return _formatted(value, np.full(value.size, 5))


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
