"""The G-code reader: a program's moves and dwells, in SI, as the dialect's control would run them.

What each word means is taken from the dialect's description (:mod:`axiscal.io.gcode.dialects`):
the dwell's letter and unit, the units words, the comment syntax, the program end. The reader
follows a subset of ISO 6983 / RS-274 (LinuxCNC, Grbl, FANUC, SINUMERIK), the one-command-a-line
printer firmware (Marlin, Klipper) and HEIDENHAIN's conversational blocks; a block it cannot follow
(a word it does not know, a macro, a subprogram call, a canned cycle, a move before the units are
set) is refused with an :class:`~axiscal.errors.AxiscalError` naming the source and the line,
never skipped.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_instance
from axiscal.io.gcode.dialects import Dialect, dialect as find_dialect

__all__ = ["Motion", "program_motions", "split_lines", "MM_PER_INCH"]

MM_PER_INCH = 25.4
_MM = 1e-3
_ROTARY = frozenset("ABC")
_DEG = math.pi / 180.0

_LINE_END = re.compile(r"\r\n|\r|\n")
_NUMBER = r"[+-]?(?:\d+\.?\d*|\.\d+)"
_WORDS = re.compile(rf"(?:\s*[A-Za-z]\s*{_NUMBER})*\s*")
_WORD = re.compile(rf"([A-Za-z])\s*({_NUMBER})")

#: G codes that change nothing the reader follows (cancel cutter compensation, tool length
#: compensation, canned cycles; select a plane for arcs)
_NEUTRAL_G = {"rs274": frozenset({"G17", "G18", "G19", "G40", "G49", "G80"}), "printer": frozenset()}
#: M codes that move nothing and wait for nothing (spindle, coolant; printer fan, heaters without waiting)
_NEUTRAL_M = {"rs274": frozenset({"M3", "M4", "M5", "M7", "M8", "M9"}),
              "printer": frozenset({"M400", "M104", "M140", "M106", "M107", "M204"})}
_REFUSED_G = {
    "G93": "inverse-time feed (G93) is not followed",
    "G95": "feed per revolution (G95) is not followed",
    "G65": "a macro call (G65) is not followed",
    "G66": "a macro call (G66) is not followed",
    "G28": "a return to the reference point (G28) is not followed",
}
_REFUSED_M = {
    "M98": "a subprogram call (M98) is not followed",
    "M99": "a subprogram return (M99) is not followed",
    "M0": "a program stop (M0) waits for the operator for an unknown time",
    "M1": "an optional stop (M1) waits for the operator for an unknown time",
    "M6": "a tool change (M6) is not followed",
}


@dataclass(frozen=True)
class Motion:
    """One move or dwell of a program, as the control runs it.

    Attributes
    ----------
    line : int
        1-based line of the program text the block is on.
    kind : {"rapid", "feed", "dwell"}
        A rapid move, a move at the programmed feed, or a dwell.
    end_m : Mapping[str, float]
        Absolute position, in the program's coordinates, of every axis programmed so far after the
        block: metres for linear axes, radians for rotary axes (A, B, C).
    feed_m_per_s : float or None
        The programmed feed (metres per second along the path) of a "feed" move; None for a rapid
        move and a dwell.
    dwell_s : float
        Seconds of a "dwell"; 0.0 for a move.
    """

    line: int
    kind: str
    end_m: Mapping[str, float]
    feed_m_per_s: float | None
    dwell_s: float


def split_lines(text: str) -> list[str]:
    """The lines of ``text`` as an editor numbers them: only LF, CRLF and CR end a line.

    Parameters
    ----------
    text : str

    Returns
    -------
    list of str
        Without their line ends; a text ending with a line end has no empty line after it.

    Examples
    --------
    >>> split_lines("G1 X1\\r\\nG4 P1\\n")
    ['G1 X1', 'G4 P1']
    """
    lines = _LINE_END.split(text)
    if lines and lines[-1] == "":
        lines.pop()
    return lines


class _Program:
    """The state of the control while it reads a program: units, distance mode, feed, position."""

    def __init__(self, spec: Dialect, source: str | None):
        self.spec = spec
        self.source = source
        self.line = 0
        self.metres_per_unit: float | None = {"mm": _MM, None: None}[spec.default_units]
        self.absolute: bool | None = {"absolute": True, None: None}[spec.default_distance]
        self.feed: float | None = None
        self.motion: str | None = None
        self.position: dict[str, float] = {}
        self.ended = False
        self.motions: list[Motion] = []

    def fail(self, message: str) -> AxiscalError:
        return AxiscalError(message, path=self.source, line=self.line)

    def inch(self) -> bool:
        return self.metres_per_unit is not None and self.metres_per_unit != _MM

    def length(self, letter: str, raw: str, *, implicit: bool) -> float:
        """The SI value of an axis word: metres (linear) or radians (A, B, C)."""
        value = float(raw)
        if implicit and self.spec.decimal_point_needed and "." not in raw:
            value *= self.spec.implicit_increment * (0.1 if self.inch() and letter not in _ROTARY else 1.0)
        if letter in _ROTARY:
            return value * _DEG
        if self.metres_per_unit is None:
            raise self.fail(f"a move before the units are set ({' or '.join(self.spec.metric_words + self.spec.inch_words)}):"
                            f" {self.spec.controller}'s units at power-on are a setting of the machine")
        return value * self.metres_per_unit

    def move(self, kind: str, targets: dict[str, tuple[str, bool]], *, implicit: bool = True) -> None:
        """Move to ``targets`` (letter -> (number text, incremental)) and record the motion."""
        for letter, (raw, incremental) in targets.items():
            value = self.length(letter, raw, implicit=implicit)
            if incremental:
                if letter not in self.position:
                    raise self.fail(f"an incremental move of {letter} before its position is known")
                value += self.position[letter]
            self.position[letter] = value
        if kind == "feed" and self.feed is None:
            raise self.fail("a feed move before any feed (F) is programmed")
        feed = self.feed if kind == "feed" else None
        self.motions.append(Motion(self.line, kind, MappingProxyType(dict(self.position)), feed, 0.0))

    def dwell(self, seconds: float) -> None:
        if not seconds >= 0.0:
            raise self.fail(f"a negative dwell ({seconds:g} s)")
        self.motions.append(Motion(self.line, "dwell", MappingProxyType(dict(self.position)), None, seconds))

    def set_feed(self, raw: str) -> None:
        per_minute = float(raw)
        if not per_minute > 0.0:
            raise self.fail(f"the feed must be positive, got F{raw}")
        if self.metres_per_unit is None:
            raise self.fail(f"a feed before the units are set ({' or '.join(self.spec.metric_words + self.spec.inch_words)})")
        self.feed = per_minute * self.metres_per_unit / 60.0


def _strip_comments(text: str, styles: tuple[str, ...], program: _Program) -> str:
    """``text`` without its comments (parentheses and/or ';' to the end of the line)."""
    paren = "paren" in styles
    semicolon = "semicolon" in styles
    if not ((paren and "(" in text) or (semicolon and ";" in text)):
        return text
    code: list[str] = []
    start = 0
    while True:
        opens = [j for j in ((text.find("(", start) if paren else -1), (text.find(";", start) if semicolon else -1)) if j >= 0]
        if not opens:
            code.append(text[start:])
            return "".join(code)
        j = min(opens)
        code.append(text[start:j])
        if text[j] == ";":
            return "".join(code)
        close = text.find(")", j + 1)
        if close < 0:
            raise program.fail("a comment opened with '(' is not closed on its line")
        if "(" in text[j + 1:close]:
            raise program.fail("a comment inside a comment")
        start = close + 1


def _code(letter: str, raw: str) -> str:
    value = float(raw)
    return f"{letter}{int(value)}" if value == int(value) else f"{letter}{value:g}"


def _rs274_block(text: str, program: _Program) -> None:
    """Run one block of an RS-274 or printer dialect."""
    spec = program.spec
    stripped = text.strip()
    if not stripped:
        return
    if stripped == "%":
        if not spec.percent:
            raise program.fail(f"'%' is not a {spec.controller} block")
        if program.motions or program.position:
            program.ended = True
        return
    if stripped.startswith("/"):
        raise program.fail("a block skipped at the operator's switch ('/') is not followed")
    if spec.name == "fanuc" and not program.motions and re.fullmatch(r"[Oo]\d{1,5}(\s*\(.*\))?", stripped):
        return
    code = _strip_comments(stripped, spec.comments, program)
    if not code.strip():
        return
    if program.ended:
        raise program.fail("a block after the program end")
    if _WORDS.fullmatch(code) is None:
        bad = _WORDS.match(code).end()
        raise program.fail(f"cannot read {code[bad:].strip()[:20]!r}: not a {spec.controller} word")
    gs: list[str] = []
    ms: list[str] = []
    words: dict[str, str] = {}
    for index, (letter, raw) in enumerate(_WORD.findall(code)):
        letter = letter.upper()
        if letter == "N":
            if index or spec.syntax == "printer":
                raise program.fail("a block number (N) must come first in its block" if index else
                                   f"block numbers (N) are a host's checksum protocol, not a {spec.controller} program word")
            continue
        if letter == "G":
            gs.append(_code("G", raw))
        elif letter == "M":
            ms.append(_code("M", raw))
        elif letter in words:
            raise program.fail(f"{letter} twice in one block")
        else:
            words[letter] = raw
    if spec.syntax == "printer":
        if len(gs) + len(ms) != 1:
            raise program.fail(f"{spec.controller} takes one G or M command a line, with its parameters")
    for m in ms:
        if m in _REFUSED_M:
            raise program.fail(_REFUSED_M[m])
        if m in spec.end_words:
            program.ended = True
        elif m in ("M82", "M83") and spec.syntax == "printer":
            raise program.fail("extruder modes (M82, M83) are not followed")
        elif m not in _NEUTRAL_M[spec.syntax]:
            raise program.fail(f"{m} is not a {spec.controller} M code this reader follows")
    motion = None
    dwell = False
    for g in gs:
        if g in ("G0", "G1"):
            motion = g
        elif g == "G4":
            dwell = True
        elif g in spec.metric_words:
            program.metres_per_unit = _MM
        elif g in spec.inch_words:
            program.metres_per_unit = MM_PER_INCH * _MM
        elif g in ("G90", "G91"):
            program.absolute = g == "G90"
        elif g == "G94" and spec.syntax == "rs274":
            continue
        elif g in _REFUSED_G:
            raise program.fail(_REFUSED_G[g])
        elif g not in _NEUTRAL_G[spec.syntax]:
            raise program.fail(f"{g} is not a {spec.controller} G code this reader follows")
    if dwell:
        _dwell(words, gs, ms, program)
        return
    if "E" in words:
        raise program.fail("extruder moves (E) are not followed")
    for letter in words:
        if letter not in spec.axes and letter not in "FS":
            raise program.fail(f"{letter} is not a word of {spec.controller} this reader follows")
    if "S" in words and spec.syntax == "printer" and not ms:
        raise program.fail(f"S is not a parameter of {' '.join(gs)}")
    if "F" in words:
        program.set_feed(words["F"])
    targets = {letter: raw for letter, raw in words.items() if letter in spec.axes}
    if motion is not None:
        program.motion = motion
    if not targets:
        return
    if spec.syntax == "printer" and motion is None:
        raise program.fail(f"axis words with no move command ({' '.join(gs + ms)})")
    if program.motion is None:
        raise program.fail("axis words before any motion mode (G0 or G1)")
    if program.absolute is None:
        raise program.fail(f"a move before the distance mode is set (G90 or G91): {spec.controller}'s mode at"
                           " power-on is a setting of the machine")
    kind = "feed" if program.motion == "G1" or spec.rapid_at_feed else "rapid"
    program.move(kind, {letter: (raw, not program.absolute) for letter, raw in targets.items()})


def _dwell(words: dict[str, str], gs: list[str], ms: list[str], program: _Program) -> None:
    """Run a dwell block (G4 and its time word)."""
    spec = program.spec
    if spec.dwell_alone and (len(gs) > 1 or ms):
        raise program.fail(f"a dwell ({spec.dwell_word}) must stand in a block of its own")
    for letter in words:
        if letter in spec.refused_dwell_words:
            raise program.fail(spec.refused_dwell_words[letter])
        if letter not in spec.dwell_words:
            raise program.fail(f"{letter} is not a dwell word of {spec.controller}"
                               f" ({spec.dwell_word} takes {' or '.join(spec.dwell_words)})")
    if len(words) != 1:
        raise program.fail(f"a dwell needs one time word ({' or '.join(spec.dwell_words)})")
    (letter, raw), = words.items()
    seconds = float(raw) * spec.dwell_words[letter]
    if spec.decimal_point_needed:
        if spec.dwell_words[letter] != 1.0 and "." in raw:
            raise program.fail(f"{spec.dwell_word} {letter} counts milliseconds and takes no decimal point")
        if spec.dwell_words[letter] == 1.0 and "." not in raw:
            seconds = float(raw) * spec.implicit_increment
    program.dwell(seconds)


_HH_BLOCK = re.compile(r"\s*(\d+)\s*(.*?)\s*")
_HH_PGM = re.compile(r"(BEGIN|END)\s+PGM\s+(\S+)\s+(MM|INCH)", re.IGNORECASE)
_HH_DWELL_DEF = re.compile(r"CYCL\s+DEF\s+9\.0(\s.*)?", re.IGNORECASE)
_HH_DWELL = re.compile(rf"CYCL\s+DEF\s+9\.1\s+\S+\s+({_NUMBER})", re.IGNORECASE)
_HH_AXIS = re.compile(rf"(I?)([A-Z])({_NUMBER})")


def _heidenhain_block(text: str, program: _Program, state: dict) -> None:
    """Run one numbered block of a HEIDENHAIN conversational program."""
    if not text.strip():
        return
    match = _HH_BLOCK.fullmatch(text)
    if match is None:
        raise program.fail("a conversational block starts with its block number")
    body = match.group(2)
    if body.startswith(";") or body.startswith("*"):
        return
    body = body.split(";", 1)[0].strip()
    if program.ended:
        raise program.fail("a block after END PGM")
    pgm = _HH_PGM.fullmatch(body)
    if state.get("name") is None:
        if pgm is None or pgm.group(1).upper() != "BEGIN":
            raise program.fail("a conversational program starts with BEGIN PGM name MM")
        if pgm.group(3).upper() == "INCH":
            raise program.fail("inch programs (BEGIN PGM ... INCH) are not read")
        state["name"] = pgm.group(2)
        program.metres_per_unit = _MM
        return
    if pgm is not None:
        if pgm.group(1).upper() == "BEGIN":
            raise program.fail("a second BEGIN PGM")
        if pgm.group(2) != state["name"] or pgm.group(3).upper() != "MM":
            raise program.fail(f"END PGM {pgm.group(2)} {pgm.group(3)} does not close BEGIN PGM {state['name']} MM")
        program.ended = True
        return
    if _HH_DWELL_DEF.fullmatch(body):
        state["dwell"] = True
        return
    dwell = _HH_DWELL.fullmatch(body)
    if dwell is not None:
        if not state.pop("dwell", False):
            raise program.fail("CYCL DEF 9.1 without CYCL DEF 9.0 DWELL TIME before it")
        program.dwell(float(dwell.group(1)))
        return
    if state.get("dwell"):
        raise program.fail("CYCL DEF 9.0 DWELL TIME is not followed by CYCL DEF 9.1 DWELL")
    tokens = body.split()
    if not tokens or tokens[0].upper() != "L":
        raise program.fail(f"cannot follow {body[:30]!r}: this reader follows L, CYCL DEF 9 and BEGIN/END PGM blocks")
    targets: dict[str, tuple[str, bool]] = {}
    rapid = False
    for token in tokens[1:]:
        upper = token.upper()
        axis = _HH_AXIS.fullmatch(upper)
        if axis is not None and axis.group(2) in program.spec.axes:
            if axis.group(2) in targets:
                raise program.fail(f"{axis.group(2)} twice in one block")
            targets[axis.group(2)] = (axis.group(3), bool(axis.group(1)))
        elif upper == "R0":
            continue
        elif upper in ("RL", "RR", "R+", "R-"):
            raise program.fail(f"radius compensation {upper} is not followed")
        elif upper == "FMAX":
            rapid = True
        elif re.fullmatch(rf"F{_NUMBER}", upper):
            program.set_feed(upper[1:])
        elif re.fullmatch(r"M\d+", upper):
            m = _code("M", upper[1:])
            if m not in _NEUTRAL_M["rs274"]:
                raise program.fail(f"{m} is not an M function this reader follows")
        else:
            raise program.fail(f"cannot follow {token!r} in an L block")
    if targets:
        program.move("rapid" if rapid else "feed", targets, implicit=False)


def program_motions(text: str, *, dialect: str, source: str | None = None) -> tuple[Motion, ...]:
    """The moves and dwells of a G-code program, in order, as ``dialect``'s control runs them.

    Parameters
    ----------
    text : str
        The program.
    dialect : str
        One of :data:`axiscal.io.gcode.DIALECT_NAMES` ("linuxcnc", "fanuc", "sinumerik",
        "heidenhain", "grbl", "marlin", "klipper").
    source : str, optional
        The file the text came from, named in every error.

    Returns
    -------
    tuple of Motion
        One per move (an axis word programmed) and per dwell. Positions in metres (radians for
        A, B, C), feeds in metres per second, dwells in seconds.

    Raises
    ------
    AxiscalError
        Naming ``source`` and the line, for a block the reader cannot follow: a word the dialect
        does not have or the reader does not follow, a macro, a subprogram call, a canned cycle,
        a move before the units or distance mode are set where the control's are a setting, a
        dwell word in the wrong unit (SINUMERIK ``G4 S``), a program without its end where the
        dialect needs one.

    Examples
    --------
    >>> motions = program_motions("G21 G90 G94\\nG1 X10 F600\\nG4 P2\\nM2\\n", dialect="linuxcnc")
    >>> [(m.kind, round(m.end_m["X"], 6), m.dwell_s) for m in motions]
    [('feed', 0.01, 0.0), ('dwell', 0.01, 2.0)]
    >>> program_motions("G4 P2000\\n", dialect="marlin")[0].dwell_s
    2.0
    """
    check_instance("text", text, str)
    spec = find_dialect(dialect)
    if source is not None:
        check_instance("source", source, str)
    program = _Program(spec, source)
    state: dict = {}
    lines = split_lines(text)
    for number, line in enumerate(lines, start=1):
        program.line = number
        if spec.syntax == "conversational":
            _heidenhain_block(line, program, state)
        else:
            _rs274_block(line, program)
    program.line = max(len(lines), 1)
    if spec.end_required and not program.ended:
        ends = ", ".join(spec.end_words) + (" or a closing %" if spec.percent and spec.name == "linuxcnc" else "")
        raise program.fail(f"the program has no end ({ends})")
    return tuple(program.motions)
