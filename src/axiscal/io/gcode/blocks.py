"""What a G-code reader hands on: the motions of a program and its blocks, with the control's state.

:class:`Motion` is one move or dwell in SI as the control runs it; :class:`Block` is one line of
the program with the words written on it and the modes in force, so that a program can be
rewritten block by block (pre-compensation) with its comments and block numbers kept.
:class:`ControlState` is the control's state while a reader walks the program: units, distance
mode, feed, plane, position and offsets; every dialect's reader moves it the same way.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType

from axiscal.errors import AxiscalError
from axiscal.io.gcode.dialects import Dialect

__all__ = ["Motion", "Block", "ControlState", "MM_PER_INCH", "PLANE_AXES"]

MM_PER_INCH = 25.4
_MM = 1e-3
_DEG = math.pi / 180.0
ROTARY = frozenset("ABC")
#: the two in-plane axes (first, second; the normal is first x second) and the normal of each plane
PLANE_AXES: Mapping[str, tuple[str, str, str]] = MappingProxyType({"XY": ("X", "Y", "Z"), "ZX": ("Z", "X", "Y"), "YZ": ("Y", "Z", "X")})
_EMPTY: Mapping[str, float] = MappingProxyType({})


@dataclass(frozen=True)
class Motion:
    """One move or dwell of a program, as the control runs it.

    Attributes
    ----------
    line : int
        1-based line of the program text the block is on.
    kind : {"rapid", "feed", "arc", "dwell"}
        A rapid move, a straight move at the programmed feed, a circular or helical move at the
        programmed feed, or a dwell.
    end_m : Mapping[str, float]
        Position of every axis programmed so far after the block, as the axis stands: the
        program's coordinate plus the work offset and any ``G92`` offset. Metres for linear axes
        and a printer's extruder E, radians for rotary axes (A, B, C).
    feed_m_per_s : float or None
        The programmed feed (metres per second along the path) of a "feed" or "arc" move; None for
        a rapid move and a dwell.
    dwell_s : float
        Seconds of a "dwell"; 0.0 for a move.
    start_m : Mapping[str, float]
        Position of every axis known before the block (as ``end_m``); empty before the first move.
    centre_m : Mapping[str, float]
        For an "arc": the centre's two in-plane coordinates (as ``end_m``); empty otherwise.
    plane : str or None
        For an "arc": "XY", "ZX" or "YZ" (G17, G18, G19); None otherwise.
    clockwise : bool
        For an "arc": True for G2 (clockwise seen from the plane's positive normal), False for G3.

    Notes
    -----
    A printer's extruder starts at 0, as the firmware's does at power-on, so that relative E words
    (``M83``) can be followed from the first one.
    """

    line: int
    kind: str
    end_m: Mapping[str, float]
    feed_m_per_s: float | None
    dwell_s: float
    start_m: Mapping[str, float] = field(default_factory=lambda: _EMPTY)
    centre_m: Mapping[str, float] = field(default_factory=lambda: _EMPTY)
    plane: str | None = None
    clockwise: bool = False

    @property
    def sweep_rad(self) -> float:
        """For an "arc": the signed angle swept (positive counter-clockwise), radians; 0 otherwise."""
        if self.kind != "arc":
            return 0.0
        a, b, _ = PLANE_AXES[self.plane]
        ca, cb = self.centre_m[a], self.centre_m[b]
        start = math.atan2(self.start_m[b] - cb, self.start_m[a] - ca)
        end = math.atan2(self.end_m[b] - cb, self.end_m[a] - ca)
        if self.clockwise:
            sweep = -((start - end) % (2 * math.pi))
        else:
            sweep = (end - start) % (2 * math.pi)
        return sweep if sweep != 0.0 else (-2 * math.pi if self.clockwise else 2 * math.pi)


@dataclass(frozen=True)
class Block:
    """One line of a program as the reader followed it.

    Attributes
    ----------
    line : int
        1-based line number.
    text : str
        The line as written.
    motion : Motion or None
        The move or dwell the block makes, None for a block that moves nothing.
    words : tuple of (str, str)
        The words written on the line in order (letter upper-cased, number as written), block
        number and comments excluded.
    number : str
        The block number as written (``N120``), or "".
    comment : str
        The line's comments as written, with their delimiters (``(rough cut)``, ``; layer 2``).
    motion_word : str or None
        The motion G code written in the block (``G1``), None when the block relies on the modal one.
    absolute : bool
        Whether the block's axis words are absolute (G90) or incremental (G91).
    metres_per_unit : float
        Metres one program unit of length stands for in the block (0.001 or 0.0254).
    offset_m : Mapping[str, float]
        Axis position minus program coordinate of each axis in the block (work offset plus G92).
    extruder_relative : bool
        Whether E words are increments (printers: M83, or G91).
    """

    line: int
    text: str
    motion: Motion | None
    words: tuple[tuple[str, str], ...]
    number: str
    comment: str
    motion_word: str | None
    absolute: bool
    metres_per_unit: float
    offset_m: Mapping[str, float]
    extruder_relative: bool


class ControlState:
    """The state of the control while a reader walks a program (SI inside).

    Parameters
    ----------
    spec : Dialect
        The control's dialect.
    source : str or None
        The file named in errors.
    work_offset_m : Mapping[str, float]
        Axis position minus program coordinate of the work offset the control starts in.
    """

    def __init__(self, spec: Dialect, source: str | None, work_offset_m: Mapping[str, float]):
        self.spec = spec
        self.source = source
        self.line = 0
        self.metres_per_unit: float | None = {"mm": _MM, None: None}[spec.default_units]
        self.absolute: bool | None = {"absolute": True, None: None}[spec.default_distance]
        self.extruder_absolute = True
        self.feed: float | None = None
        self.motion: str | None = None
        self.plane = "XY"
        self.position: dict[str, float] = {}
        self.work_offset = dict(work_offset_m)
        self.shift: dict[str, float] = {}
        self.ended = False
        #: whether lines read in bulk (:mod:`axiscal.io.gcode.fast`) have moved the machine
        self.moved = False
        self.motions: list[Motion] = []
        self.blocks: list[Block] = []
        #: what a conversational program's blocks keep for the ones after them (its name, a dwell's cycle)
        self.frame: dict = {}
        self._view: Mapping[str, float] = _EMPTY
        self._offsets: tuple[tuple, Mapping[str, float]] = ((), _EMPTY)
        self._shift_version = 0

    def fail(self, message: str) -> AxiscalError:
        """An error naming the source and the current line."""
        return AxiscalError(message, path=self.source, line=self.line)

    def offset(self, letter: str) -> float:
        """Axis position minus program coordinate of ``letter``, metres (radians)."""
        return self.work_offset.get(letter, 0.0) + self.shift.get(letter, 0.0)

    def units_words(self) -> str:
        return " or ".join(self.spec.metric_words + self.spec.inch_words)

    def inch(self) -> bool:
        return self.metres_per_unit is not None and self.metres_per_unit != _MM

    def extruder_relative(self) -> bool:
        if self.spec.g90_sets_extruder:
            return not self.extruder_absolute
        return not self.extruder_absolute or self.absolute is False

    def length(self, letter: str, raw: str, *, implicit: bool = True) -> float:
        """The SI value of a length or angle word: metres (linear, E, I, J, K, R) or radians (A, B, C)."""
        value = float(raw)
        if implicit and self.spec.decimal_point_needed and "." not in raw:
            value *= self.spec.implicit_increment * (0.1 if self.inch() and letter not in ROTARY else 1.0)
        if letter in ROTARY:
            return value * _DEG
        if self.metres_per_unit is None:
            raise self.fail(f"a move before the units are set ({self.units_words()}):"
                            f" {self.spec.controller}'s units at power-on are a setting of the machine")
        return value * self.metres_per_unit

    def target(self, targets: Mapping[str, tuple[str, bool]], *, implicit: bool = True) -> dict[str, float]:
        """Axis positions after a move to ``targets`` (letter -> (number text, incremental))."""
        end = dict(self.position)
        plain = self.metres_per_unit if not self.spec.decimal_point_needed else None
        for letter, (raw, incremental) in targets.items():
            value = float(raw) * plain if plain is not None and letter not in ROTARY else self.length(letter, raw, implicit=implicit)
            if incremental:
                if letter not in self.position and letter != "E":
                    raise self.fail(f"an incremental move of {letter} before its position is known")
                value += self.position.get(letter, 0.0)
            else:
                value += self.offset(letter)
            end[letter] = value
        return end

    def move(self, kind: str, end: dict[str, float], *, centre: Mapping[str, float] = _EMPTY,
             clockwise: bool = False) -> Motion:
        """Record a move to ``end`` (axis positions, SI)."""
        if kind in ("feed", "arc") and self.feed is None:
            raise self.fail("a feed move before any feed (F) is programmed")
        feed = self.feed if kind in ("feed", "arc") else None
        view = MappingProxyType(end)
        motion = Motion(self.line, kind, view, feed, 0.0, self._view,
                        MappingProxyType(dict(centre)) if centre else _EMPTY, self.plane if kind == "arc" else None, clockwise)
        self.position = end
        self._view = view
        self.motions.append(motion)
        return motion

    def dwell(self, seconds: float) -> Motion:
        """Record a dwell of ``seconds``."""
        if not seconds >= 0.0:
            raise self.fail(f"a negative dwell ({seconds:g} s)")
        motion = Motion(self.line, "dwell", self._view, None, seconds, self._view)
        self.motions.append(motion)
        return motion

    def set_feed(self, raw: str) -> None:
        """Set the feed from an F word (program units per minute)."""
        per_minute = float(raw)
        if not per_minute > 0.0:
            raise self.fail(f"the feed must be positive, got F{raw}")
        if self.metres_per_unit is None:
            raise self.fail(f"a feed before the units are set ({self.units_words()})")
        self.feed = per_minute * self.metres_per_unit / 60.0

    def set_coordinates(self, values: Mapping[str, str]) -> None:
        """``G92``: the current point gets the given program coordinates."""
        for letter, raw in values.items():
            if letter not in self.position:
                raise self.fail(f"G92 sets {letter} before its position is known")
            value = self.length(letter, raw)
            self.shift[letter] = self.position[letter] - self.work_offset.get(letter, 0.0) - value
        self._shift_version += 1

    def record(self, text: str, motion: Motion | None, words: tuple[tuple[str, str], ...], number: str,
               comment: str, motion_word: str | None) -> None:
        """Keep the block as read, with the modes in force."""
        key = (len(self.position), self._shift_version, len(self.shift))
        if self._offsets[0] != key:
            self._offsets = (key, MappingProxyType({k: self.offset(k) for k in self.position}))
        self.blocks.append(Block(
            self.line, text, motion, words, number, comment, motion_word, self.absolute is not False,
            self.metres_per_unit or _MM, self._offsets[1], self.extruder_relative(),
        ))
