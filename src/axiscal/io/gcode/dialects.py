"""The G-code dialects axiscal reads and writes, each described once, as data, with its source.

The same text means different things on different controls: ``G4 P2`` waits 2 s on LinuxCNC and
Grbl, 2 ms on FANUC and Marlin, and is no dwell at all on SINUMERIK. Each :class:`Dialect` below
holds what the reader (:mod:`axiscal.io.gcode.reader`) and the writer
(:mod:`axiscal.io.gcode.writer`) need to know about one control: the dwell word and its unit, the
units words, the comment syntax, how a program starts and ends, block numbers, the file extension,
and the manual or source file each fact was taken from.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType

from axiscal.io.arguments import check_choice, check_instance

__all__ = ["Dialect", "DIALECTS", "DIALECT_NAMES", "dialect"]


@dataclass(frozen=True)
class Dialect:
    """One control's G-code: what its reader accepts and how its writer writes.

    Attributes
    ----------
    name : str
        Short name used by the Python API and the command line (``"linuxcnc"``).
    controller : str
        The control as its maker names it (``"LinuxCNC"``).
    syntax : {"rs274", "printer", "conversational"}
        "rs274": words in any order, several G codes in a block (ISO 6983 / RS-274);
        "printer": one G or M command a line followed by its parameters (Marlin, Klipper);
        "conversational": HEIDENHAIN's numbered plain-language blocks.
    extension : str
        The file extension programs of this control use.
    comments : tuple of str
        Comment syntaxes the reader accepts: "paren" (``(text)``) and/or "semicolon" (``; text``
        to the end of the line). The writer uses the first.
    program_start, program_end : tuple of str
        Lines the writer puts before the comments and after the last block (``%``, ``O0001``, ``M2``).
    setup : tuple of str
        Blocks the writer puts after the comments: units, distance mode, feed mode.
    end_words : tuple of str
        Words that end the program (``M2``, ``M30``); nothing but comments may follow them.
    end_required : bool
        Whether the reader refuses a program without an end (a streamed printer file has none).
    percent : bool
        Whether a line holding only ``%`` (tape start or end) belongs to the dialect.
    metric_words, inch_words : tuple of str
        G codes that select millimetres and inches (the writer uses the first metric word).
    default_units, default_distance : str or None
        The units ("mm") and distance mode ("absolute") the control starts in when its
        documentation fixes them; None where they are a setting of the machine, so the reader
        refuses a move before the program has set them.
    feed_word, rapid_word, dwell_word : str
        The motion and dwell G codes the writer writes (``G1`` or ``G01``, ``G0``, ``G4`` or ``G04``).
    rapid_at_feed : bool
        True where ``G0`` moves at the programmed feed like ``G1`` (Marlin, Klipper).
    dwell_words : Mapping[str, float]
        Letters that give a dwell's time, and the seconds one unit of each stands for. The writer
        uses the first.
    dwell_places : int
        Decimal places the writer gives the dwell (its resolution in the dwell word's unit).
    refused_dwell_words : Mapping[str, str]
        Dwell letters the reader refuses, with the reason (SINUMERIK ``G4 S``: spindle revolutions).
    dwell_alone : bool
        Whether the dwell must stand in a block of its own (it always does in what the writer writes).
    dwell_keeps_feed : bool
        True where the dwell's letter is ``F`` and does not change the programmed feed (SINUMERIK).
    decimal_point_needed : bool
        True where a number without a decimal point counts least input increments (FANUC: ``X10``
        is 0.010 mm and ``G04 X2000`` 2 s in the increment system IS-B); the writer then always
        writes a decimal point.
    implicit_increment : float
        The least input increment, in millimetres, seconds or degrees, a number without a decimal
        point counts where ``decimal_point_needed`` (a tenth of it in inch mode).
    block_numbers : {"optional", "required"}
        Whether every block carries a number (HEIDENHAIN conversational) or may (``N10``).
    axes : tuple of str
        Axis letters the dialect moves; A, B and C are rotary (degrees in the program); E is a
        printer's extruder (millimetres of filament).
    arc_words : tuple of str
        Words of a circular move (``G2``, ``G3``) the dialect has: the centre's offsets from the
        start (I, J, K) and the radius ("R"; "CR" for SINUMERIK's ``CR=``); empty where arcs are
        not read.
    planes : tuple of str
        The plane selection words (``G17``, ``G18``, ``G19``); empty where arcs lie in XY only.
    set_position, clear_position : tuple of str
        The words that set the current point's coordinates (``G92``) and cancel that again
        (``G92.1``); empty where the dialect has none.
    work_offset_words : tuple of str
        The work offset selection the reader follows (``G54``, the one the control starts in); its
        offset is the one given to the reader.
    g90_sets_extruder : bool
        Whether G90 and G91 also switch the extruder between absolute and relative (Marlin), or
        only ``M82``/``M83`` do besides a G91 (Klipper).
    sources : tuple of str
        The manuals and source files the description was taken from.
    """

    name: str
    controller: str
    syntax: str
    extension: str
    comments: tuple[str, ...]
    program_start: tuple[str, ...]
    setup: tuple[str, ...]
    program_end: tuple[str, ...]
    end_words: tuple[str, ...]
    end_required: bool
    percent: bool
    metric_words: tuple[str, ...]
    inch_words: tuple[str, ...]
    default_units: str | None
    default_distance: str | None
    feed_word: str
    rapid_word: str
    dwell_word: str
    rapid_at_feed: bool
    dwell_words: Mapping[str, float]
    dwell_places: int
    refused_dwell_words: Mapping[str, str]
    dwell_alone: bool
    dwell_keeps_feed: bool
    decimal_point_needed: bool
    implicit_increment: float
    block_numbers: str
    axes: tuple[str, ...]
    sources: tuple[str, ...]
    arc_words: tuple[str, ...] = ("I", "J", "K", "R")
    planes: tuple[str, ...] = ("G17", "G18", "G19")
    set_position: tuple[str, ...] = ("G92",)
    clear_position: tuple[str, ...] = ()
    work_offset_words: tuple[str, ...] = ("G54",)
    g90_sets_extruder: bool = False

    @property
    def set_position_codes(self) -> frozenset[str]:
        """:attr:`set_position` as a set."""
        return frozenset(self.set_position)

    @property
    def comment_style(self) -> str:
        """The comment syntax the writer uses: "paren" or "semicolon"."""
        return self.comments[0]


def _frozen(mapping: dict[str, float | str]) -> Mapping:
    return MappingProxyType(dict(mapping))


_RS274 = dict(syntax="rs274", rapid_word="G0", feed_word="G1", dwell_word="G4", rapid_at_feed=False,
              refused_dwell_words=_frozen({}), dwell_alone=True, dwell_keeps_feed=False,
              decimal_point_needed=False, implicit_increment=0.0, block_numbers="optional",
              inch_words=("G20",), metric_words=("G21",))

DIALECTS: Mapping[str, Dialect] = MappingProxyType({
    "linuxcnc": Dialect(
        name="linuxcnc", controller="LinuxCNC", extension=".ngc", comments=("paren", "semicolon"),
        program_start=("%",), setup=("G21 G90 G94",), program_end=("M2", "%"), end_words=("M2", "M30"),
        end_required=True, percent=True, default_units=None, default_distance=None,
        dwell_words=_frozen({"P": 1.0}), dwell_places=3,
        axes=("X", "Y", "Z", "A", "B", "C", "U", "V", "W"), clear_position=("G92.1", "G92.2"),
        sources=("LinuxCNC G-code reference, G4 Dwell ('P seconds to dwell'), G20/G21, G90/G91, G94; "
                 "G2/G3 (centre and radius formats; end off the circle by more than 0.002 mm refused), G17-G19, "
                 "G92/G92.1, G54; Overview: comments in parentheses or after ';', '%' program demarcation, M2/M30 "
                 "program end (linuxcnc.org/docs/html/gcode/g-code.html, overview.html)",),
        **_RS274),
    "grbl": Dialect(
        name="grbl", controller="Grbl", extension=".nc", comments=("paren", "semicolon"),
        program_start=(), setup=("G21 G90 G94",), program_end=("M2",), end_words=("M2", "M30"),
        end_required=False, percent=False, default_units="mm", default_distance="absolute",
        dwell_words=_frozen({"P": 1.0}), dwell_places=3, axes=("X", "Y", "Z"), clear_position=("G92.1",),
        sources=("Grbl v1.1 wiki, Commands and G-code support: 'G4 Dwell', P in seconds; G2/G3 (I J K and R), "
                 "G17-G19, G92/G92.1, G54; power-up modes G21 G90 G94 (github.com/gnea/grbl/wiki, grbl/gcode.c)",),
        **_RS274),
    "fanuc": Dialect(
        name="fanuc", controller="FANUC Series 0i (M, G code system A)", extension=".nc",
        comments=("paren",), program_start=("%", "O0001"), setup=("G21", "G90 G94"),
        program_end=("M30", "%"), end_words=("M2", "M30"), end_required=True, percent=True,
        default_units=None, default_distance=None,
        dwell_words=_frozen({"X": 1.0, "P": 0.001}), dwell_places=3,
        axes=("X", "Y", "Z", "A", "B", "C"),
        sources=("FANUC Series 0i-MODEL F Operator's Manual (B-64604EN), II.4 'Dwell (G04)': G04 X in seconds, "
                 "G04 P in milliseconds without a decimal point; II.8 'Inch/metric conversion (G20, G21)' in a "
                 "block of its own at the head of the program; II.9 'Decimal point programming': a number "
                 "without a decimal point counts least input increments (IS-B: 0.001 mm, 0.0001 in, 0.001 s); "
                 "circular interpolation G02/G03 (I J K or R) in the plane of G17/G18/G19; G92 coordinate system "
                 "setting; program number O, '%' at tape start and end, M30 end of program",),
        **{**_RS274, "feed_word": "G01", "rapid_word": "G00", "dwell_word": "G04",
           "decimal_point_needed": True, "implicit_increment": 0.001}),
    "sinumerik": Dialect(
        name="sinumerik", controller="Siemens SINUMERIK 840D sl / 828D", extension=".mpf",
        comments=("semicolon",), program_start=(), setup=("G71 G90 G94",), program_end=("M30",),
        end_words=("M2", "M30"), end_required=True, percent=False, default_units=None, default_distance=None,
        dwell_words=_frozen({"F": 1.0}), dwell_places=3, axes=("X", "Y", "Z", "A", "B", "C"),
        arc_words=("I", "J", "K", "CR"), set_position=(),
        sources=("SINUMERIK 840D sl Programming Manual Fundamentals, 'Dwell time (G4)': G4 F in seconds, "
                 "G4 S in spindle revolutions, in a block of its own, the programmed F and S kept; "
                 "'Inch or metric dimensions (G70/G700, G71/G710)'; circular interpolation G2/G3 with I J K "
                 "(incremental centre) or CR= (radius); G17-G19; comments after ';'; M30 end of program",),
        **{**_RS274, "metric_words": ("G71", "G710"), "inch_words": ("G70", "G700"),
           "refused_dwell_words": _frozen({"S": "G4 S counts spindle revolutions, not seconds"}),
           "dwell_keeps_feed": True}),
    "heidenhain": Dialect(
        name="heidenhain", controller="HEIDENHAIN TNC (conversational)", syntax="conversational", extension=".h",
        comments=("semicolon",), program_start=(), setup=(), program_end=(), end_words=("END PGM",),
        end_required=True, percent=False, metric_words=("MM",), inch_words=("INCH",),
        default_units=None, default_distance="absolute", feed_word="L", rapid_word="L", dwell_word="CYCL DEF 9",
        rapid_at_feed=False, dwell_words=_frozen({"DWELL": 1.0}), dwell_places=3,
        refused_dwell_words=_frozen({}), dwell_alone=True, dwell_keeps_feed=False,
        decimal_point_needed=False, implicit_increment=0.0, block_numbers="required",
        axes=("X", "Y", "Z", "A", "B", "C", "U", "V", "W"), arc_words=(), planes=(), set_position=(),
        work_offset_words=(),
        sources=("HEIDENHAIN TNC 640 User's Manual, Conversational Programming: 'BEGIN PGM name MM' ... "
                 "'END PGM name MM', numbered blocks, comments after ';', path function L with absolute or "
                 "incremental (I) coordinates, F in mm/min kept until changed, FMAX for one block only",
                 "HEIDENHAIN TNC 640 User's Manual, Cycle Programming, Cycle 9 DWELL TIME: "
                 "'CYCL DEF 9.0 DWELL TIME' / 'CYCL DEF 9.1 DWELL 1.5', the dwell in seconds, active when defined"),
    ),
    "marlin": Dialect(
        name="marlin", controller="Marlin", extension=".gcode", comments=("semicolon",), program_start=(),
        setup=("G21", "G90"), program_end=(), end_words=(), end_required=False, percent=False,
        default_units="mm", default_distance="absolute",
        dwell_words=_frozen({"P": 0.001, "S": 1.0}), dwell_places=0,
        axes=("X", "Y", "Z", "E"), arc_words=("I", "J", "R"), planes=(), work_offset_words=(),
        g90_sets_extruder=True,
        sources=("Marlin G-code reference 'G4 - Dwell': P milliseconds, S seconds; 'G0-G1 - Linear Move' "
                 "(G0 moves at the feed like G1); 'G2-G3 - Arc or Circle Move' (I J or R, in XY unless built with "
                 "CNC_WORKSPACE_PLANES); G20/G21, G90/G91, G92, M82/M83 (marlinfw.org/docs/gcode; "
                 "Marlin/src/gcode/gcode_d.cpp and G4.cpp); one command a line, comments after ';'",),
        **{**_RS274, "syntax": "printer", "rapid_at_feed": True}),
    "klipper": Dialect(
        name="klipper", controller="Klipper", extension=".gcode", comments=("semicolon",), program_start=(),
        setup=("G90",), program_end=(), end_words=(), end_required=False, percent=False,
        default_units="mm", default_distance="absolute",
        dwell_words=_frozen({"P": 0.001}), dwell_places=0,
        axes=("X", "Y", "Z", "E"), arc_words=("I", "J", "K"), work_offset_words=(),
        sources=("Klipper docs/G-Codes.md: 'Move (G0 or G1): G1 [X<pos>] [Y<pos>] [Z<pos>] [E<pos>] [F<speed>]', "
                 "'Dwell: G4 P<milliseconds>', G90/G91, G92, M82/M83; millimetres only (no G20); "
                 "docs/Config_Reference.md [gcode_arcs]: G2/G3 by the centre (I J, with G17-G19 I K or J K), "
                 "no R; one command a line, comments after ';'",),
        **{**_RS274, "syntax": "printer", "rapid_at_feed": True, "inch_words": ()}),
})

#: the dialect names, in the order the documentation lists them
DIALECT_NAMES: tuple[str, ...] = tuple(DIALECTS)


def dialect(name: str | Dialect) -> Dialect:
    """The :class:`Dialect` called ``name`` (a Dialect is returned as it is).

    Parameters
    ----------
    name : str or Dialect
        One of :data:`DIALECT_NAMES`.

    Returns
    -------
    Dialect

    Raises
    ------
    AxiscalError
        For a name that is not a dialect.

    Examples
    --------
    >>> dialect("fanuc").dwell_words["P"]
    0.001
    """
    if isinstance(name, Dialect):
        return name
    check_instance("dialect", name, str)
    return DIALECTS[check_choice("dialect", name, DIALECT_NAMES)]
