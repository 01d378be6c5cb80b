"""The word dialects' reader: ISO 6983 / RS-274 blocks (LinuxCNC, Grbl, FANUC, SINUMERIK) and printer lines.

A block is a sequence of words, a letter and a number (ISO 6983-1); which G and M codes and which
letters a control has, what its dwell word counts and how it writes comments come from its
:class:`~axiscal.io.gcode.dialects.Dialect`. The printer firmware (Marlin, Klipper) take one G or M
command a line followed by its parameters. Circular moves (G2, G3) are read in the plane chosen by
G17, G18, G19 from the centre's offsets I, J, K (from the start point) or the radius R (negative:
the arc of more than half a turn), as the LinuxCNC G-code reference describes them; an end point
off the circle by more than 0.002 mm is refused, as LinuxCNC refuses it.
"""

from __future__ import annotations

import math
import re

from axiscal.io.gcode.blocks import PLANE_AXES, ControlState

__all__ = ["run_block"]

_MM = 1e-3
_NUMBER = r"[+-]?(?:\d+\.?\d*|\.\d+)"
_WORDS = re.compile(rf"(?:\s*(?:CR\s*=|[A-Za-z])\s*{_NUMBER})*\s*")
_WORD = re.compile(rf"(CR\s*=|[A-Za-z])\s*({_NUMBER})")
#: largest difference of the radii at the start and the end of an arc (LinuxCNC: 0.002 mm)
ARC_RADIUS_TOLERANCE_M = 0.002 * _MM

#: G codes that change nothing the reader follows (cancel cutter compensation, tool length
#: compensation, canned cycles)
_NEUTRAL_G = {"rs274": frozenset({"G40", "G49", "G80"}), "printer": frozenset()}
#: M codes that move nothing and wait for nothing (spindle, coolant; printer fan, heaters without waiting)
_NEUTRAL_M = {"rs274": frozenset({"M3", "M4", "M5", "M7", "M8", "M9"}),
              "printer": frozenset({"M400", "M104", "M140", "M106", "M107", "M204"})}
_REFUSED_G = {
    "G93": "inverse-time feed (G93) is not followed",
    "G95": "feed per revolution (G95) is not followed",
    "G65": "a macro call (G65) is not followed",
    "G66": "a macro call (G66) is not followed",
    "G28": "a return to the reference point (G28) is not followed",
    "G10": "setting offsets from the program (G10) is not followed",
    "G41": "cutter radius compensation (G41) is not followed",
    "G42": "cutter radius compensation (G42) is not followed",
    "G43": "tool length compensation (G43) is not followed",
    "G53": "a move in machine coordinates (G53) is not followed",
    "G90.1": "absolute arc centres (G90.1) are not followed",
}
_CANNED = frozenset({"G73", "G74", "G76", "G81", "G82", "G83", "G84", "G85", "G86", "G87", "G88", "G89"})
_WORK_OFFSETS = frozenset({"G54", "G55", "G56", "G57", "G58", "G59", "G54.1", "G59.1", "G59.2", "G59.3"})
_REFUSED_M = {
    "M98": "a subprogram call (M98) is not followed",
    "M99": "a subprogram return (M99) is not followed",
    "M0": "a program stop (M0) waits for the operator for an unknown time",
    "M1": "an optional stop (M1) waits for the operator for an unknown time",
    "M6": "a tool change (M6) is not followed",
    "M109": "waiting for the hot end's temperature (M109) takes an unknown time",
    "M190": "waiting for the bed's temperature (M190) takes an unknown time",
}
_PLANE = {"G17": "XY", "G18": "ZX", "G19": "YZ"}
_OFFSET_LETTER = {"X": "I", "Y": "J", "Z": "K"}


_CODES: dict[tuple[str, str], str] = {}


def _code(letter: str, raw: str) -> str:
    """``G01`` -> ``G1``, ``G91.1`` -> ``G91.1`` (remembered: a program repeats a few codes)."""
    code = _CODES.get((letter, raw))
    if code is None:
        value = float(raw)
        if not math.isfinite(value):  # a number too large for a float: named short, refused as an unknown code
            return f"{letter}{raw[:8]}... ({len(raw)} characters)"
        code = f"{letter}{int(value)}" if value == int(value) else f"{letter}{value:g}"
        if len(_CODES) < 4096:
            _CODES[(letter, raw)] = code
    return code


def _strip_comments(text: str, styles: tuple[str, ...], state: ControlState) -> tuple[str, str]:
    """``text`` without its comments, and the comments as written (parentheses and/or ';')."""
    paren = "paren" in styles
    semicolon = "semicolon" in styles
    if not ((paren and "(" in text) or (semicolon and ";" in text)):
        return text, ""
    code: list[str] = []
    comments: list[str] = []
    start = 0
    while True:
        opens = [j for j in ((text.find("(", start) if paren else -1), (text.find(";", start) if semicolon else -1)) if j >= 0]
        if not opens:
            code.append(text[start:])
            return "".join(code), " ".join(comments)
        j = min(opens)
        code.append(text[start:j])
        if text[j] == ";":
            comments.append(text[j:].rstrip())
            return "".join(code), " ".join(comments)
        close = text.find(")", j + 1)
        if close < 0:
            raise state.fail("a comment opened with '(' is not closed on its line")
        if "(" in text[j + 1:close]:
            raise state.fail("a comment inside a comment")
        comments.append(text[j:close + 1])
        start = close + 1


def run_block(text: str, state: ControlState) -> None:
    """Run one line of an RS-274 or printer dialect on ``state`` (and record it)."""
    spec = state.spec
    stripped = text.strip()
    if not stripped:
        state.record(text, None, (), "", "", None)
        return
    if stripped == "%":
        if not spec.percent:
            raise state.fail(f"'%' is not a {spec.controller} block")
        if (state.motions or state.position or state.moved) and spec.name == "linuxcnc":
            state.ended = True  # a closing % ends a LinuxCNC program; on a FANUC tape it only marks the tape's end
        state.record(text, None, (), "", "", None)
        return
    if stripped.startswith("/"):
        raise state.fail("a block skipped at the operator's switch ('/') is not followed")
    if spec.name == "fanuc" and not (state.motions or state.moved) and re.fullmatch(r"[Oo]\d{1,5}(\s*\(.*\))?", stripped):
        state.record(text, None, (), "", "", None)
        return
    code, comment = _strip_comments(stripped, spec.comments, state)
    if not code or code.isspace():
        state.record(text, None, (), "", comment, None)
        return
    if state.ended:
        raise state.fail("a block after the program end")
    if _WORDS.fullmatch(code) is None:
        bad = _WORDS.match(code).end()
        raise state.fail(f"cannot read {code[bad:].strip()[:20]!r}: not a {spec.controller} word")
    gs: list[str] = []
    ms: list[str] = []
    words: dict[str, str] = {}
    written: list[tuple[str, str]] = []
    number = ""
    for index, (letter, raw) in enumerate(_WORD.findall(code)):
        letter = letter.upper()
        if len(letter) > 1:
            if "CR" not in spec.arc_words:
                raise state.fail(f"CR= is not a word of {spec.controller}")
            letter = "CR"
        if letter == "N":
            if index or spec.syntax == "printer":
                raise state.fail("a block number (N) must come first in its block" if index else
                                 f"block numbers (N) are a host's checksum protocol, not a {spec.controller} program word")
            number = f"N{raw}"
            continue
        written.append((letter, raw))
        if letter == "G":
            gs.append(_code("G", raw))
        elif letter == "M":
            ms.append(_code("M", raw))
        elif letter in words:
            raise state.fail(f"{letter} twice in one block")
        else:
            words[letter] = raw
    if spec.syntax == "printer" and len(gs) + len(ms) != 1:
        raise state.fail(f"{spec.controller} takes one G or M command a line, with its parameters")
    motion = _modes(gs, ms, state) if gs or ms else None
    if "G4" in gs:
        _dwell(words, gs, ms, state)
        state.record(text, state.motions[-1], tuple(written), number, comment, None)
        return
    if gs and spec.set_position and not spec.set_position_codes.isdisjoint(gs):
        if len(gs) > 1 or ms or any(letter not in spec.axes for letter in words):
            raise state.fail(f"{spec.set_position[0]} takes only axis words, in a block of its own")
        state.set_coordinates(words)
        state.record(text, None, tuple(written), number, comment, None)
        return
    made = _motion(words, gs, ms, motion, state)
    state.record(text, made, tuple(written), number, comment, motion)


def _modes(gs: list[str], ms: list[str], state: ControlState) -> str | None:
    """Apply the block's mode words; return the motion G code written in it, if any."""
    spec = state.spec
    for m in ms:
        if m in _REFUSED_M:
            raise state.fail(_REFUSED_M[m])
        if m in spec.end_words:
            state.ended = True
        elif m in ("M82", "M83") and "E" in spec.axes:
            state.extruder_absolute = m == "M82"
        elif m not in _NEUTRAL_M[spec.syntax]:
            raise state.fail(f"{m} is not a {spec.controller} M code this reader follows")
    motion = None
    for g in gs:
        if g in ("G0", "G1") or (g in ("G2", "G3") and spec.arc_words):
            if motion is not None:
                raise state.fail(f"two motion words ({motion}, {g}) in one block")
            motion = g
        elif g == "G4" or g in spec.set_position:
            continue
        elif g in spec.metric_words:
            state.metres_per_unit = _MM
        elif g in spec.inch_words:
            state.metres_per_unit = 25.4 * _MM
        elif g in ("G90", "G91"):
            state.absolute = g == "G90"
            if spec.g90_sets_extruder:
                state.extruder_absolute = g == "G90"
        elif g in _PLANE and g in spec.planes:
            state.plane = _PLANE[g]
        elif g in spec.clear_position:
            state.shift.clear()
        elif g in spec.work_offset_words:
            continue
        elif g == "G94" and spec.syntax == "rs274":
            continue
        elif g in _REFUSED_G:
            raise state.fail(_REFUSED_G[g])
        elif g in _CANNED:
            raise state.fail(f"a canned cycle ({g}) is not followed")
        elif g in _WORK_OFFSETS and spec.work_offset_words:
            raise state.fail(f"work offset {g} is not followed: only {', '.join(spec.work_offset_words)},"
                             " whose offset is given to the reader")
        elif g not in _NEUTRAL_G[spec.syntax]:
            raise state.fail(f"{g} is not a {spec.controller} G code this reader follows")
    return motion


def _dwell(words: dict[str, str], gs: list[str], ms: list[str], state: ControlState) -> None:
    """Run a dwell block (G4 and its time word)."""
    spec = state.spec
    if spec.dwell_alone and (len(gs) > 1 or ms):
        raise state.fail(f"a dwell ({spec.dwell_word}) must stand in a block of its own")
    for letter in words:
        if letter in spec.refused_dwell_words:
            raise state.fail(spec.refused_dwell_words[letter])
        if letter not in spec.dwell_words:
            raise state.fail(f"{letter} is not a dwell word of {spec.controller}"
                             f" ({spec.dwell_word} takes {' or '.join(spec.dwell_words)})")
    if len(words) != 1:
        raise state.fail(f"a dwell needs one time word ({' or '.join(spec.dwell_words)})")
    (letter, raw), = words.items()
    seconds = float(raw) * spec.dwell_words[letter]
    if spec.decimal_point_needed:
        if spec.dwell_words[letter] != 1.0 and "." in raw:
            raise state.fail(f"{spec.dwell_word} {letter} counts milliseconds and takes no decimal point")
        if spec.dwell_words[letter] == 1.0 and "." not in raw:
            seconds = float(raw) * spec.implicit_increment
    state.dwell(seconds)


def _motion(words: dict[str, str], gs: list[str], ms: list[str], motion: str | None, state: ControlState):
    """Run the block's move, if it has one; return its Motion or None."""
    spec = state.spec
    arc_words = {letter: raw for letter, raw in words.items() if letter in spec.arc_words} if spec.arc_words else {}
    for letter in words:
        if letter not in spec.axes and letter != "F" and letter != "S" and letter not in arc_words:
            raise state.fail(f"{letter} is not a word of {spec.controller} this reader follows")
    if "S" in words and spec.syntax == "printer":
        raise state.fail(f"S is not a parameter of {' '.join(gs + ms)}")
    if "F" in words:
        state.set_feed(words["F"])
    targets = {letter: raw for letter, raw in words.items() if letter in spec.axes}
    if motion is not None:
        state.motion = motion
    if arc_words and state.motion not in ("G2", "G3"):
        raise state.fail(f"{', '.join(arc_words)} without a circular move (G2, G3)")
    if not targets and not arc_words:
        return None
    if spec.syntax == "printer" and motion is None:
        raise state.fail(f"axis words with no move command ({' '.join(gs + ms)})")
    if state.motion is None:
        raise state.fail("axis words before any motion mode (G0, G1)")
    if state.absolute is None:
        raise state.fail(f"a move before the distance mode is set (G90 or G91): {spec.controller}'s mode at"
                         " power-on is a setting of the machine")
    absolute = state.absolute
    end = state.target({letter: (raw, not absolute or (letter == "E" and state.extruder_relative()))
                        for letter, raw in targets.items()})
    if state.motion in ("G2", "G3"):
        return _arc(end, arc_words, state)
    kind = "feed" if state.motion == "G1" or spec.rapid_at_feed else "rapid"
    return state.move(kind, end)


def _arc(end: dict[str, float], arc_words: dict[str, str], state: ControlState):
    """A circular move to ``end`` with the centre given by I, J, K or by R (or CR=)."""
    a, b, normal = PLANE_AXES[state.plane]
    for letter in (a, b):
        if letter not in state.position:
            raise state.fail(f"an arc in the {state.plane} plane before the position of {letter} is known")
    extra = [k for k in end if k not in (a, b, normal, "E") and end[k] != state.position.get(k)]
    if extra:
        raise state.fail(f"an arc that also moves {', '.join(extra)} is not followed")
    start_a, start_b = state.position[a], state.position[b]
    end_a, end_b = end.get(a, start_a), end.get(b, start_b)
    radius_word = "CR" if "CR" in arc_words else "R"
    offsets = {_OFFSET_LETTER[axis]: axis for axis in (a, b)}
    wrong = [k for k in arc_words if k != radius_word and k not in offsets]
    if wrong:
        raise state.fail(f"{', '.join(wrong)} is not a centre offset in the {state.plane} plane"
                         f" (use {' and '.join(offsets)})")
    clockwise = state.motion == "G2"
    if radius_word in arc_words:
        if len(arc_words) > 1:
            raise state.fail("an arc takes its radius or its centre's offsets, not both")
        radius = state.length("R", arc_words[radius_word])
        da, db = end_a - start_a, end_b - start_b
        chord = math.hypot(da, db)
        if chord == 0.0:
            raise state.fail("an arc given by its radius needs an end point other than its start")
        half = chord / 2.0
        if half > abs(radius) + ARC_RADIUS_TOLERANCE_M:
            raise state.fail(f"the radius ({abs(radius) / _MM:g} mm) is shorter than half the distance to the end point")
        height = math.sqrt(max(radius * radius - half * half, 0.0))
        side = height / chord * (1.0 if clockwise == (radius > 0) else -1.0)
        centre_a = (start_a + end_a) / 2.0 + side * db
        centre_b = (start_b + end_b) / 2.0 - side * da
    else:
        if not arc_words:
            raise state.fail("an arc needs its centre's offsets (I, J, K) or its radius (R)")
        offset_a, offset_b = _OFFSET_LETTER[a], _OFFSET_LETTER[b]
        centre_a = start_a + (state.length(offset_a, arc_words[offset_a]) if offset_a in arc_words else 0.0)
        centre_b = start_b + (state.length(offset_b, arc_words[offset_b]) if offset_b in arc_words else 0.0)
        r_start = math.hypot(start_a - centre_a, start_b - centre_b)
        r_end = math.hypot(end_a - centre_a, end_b - centre_b)
        if r_start == 0.0:
            raise state.fail("an arc whose centre is its start point")
        if abs(r_end - r_start) > ARC_RADIUS_TOLERANCE_M:
            raise state.fail(f"the arc's end point is not on its circle: {r_start / _MM:.4f} mm from the centre at the"
                             f" start, {r_end / _MM:.4f} mm at the end")
    return state.move("arc", end, centre={a: centre_a, b: centre_b}, clockwise=clockwise)

