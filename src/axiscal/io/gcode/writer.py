"""The G-code writer: moves, dwells and comments in a dialect's own words, start and end.

Each dialect's words come from its description (:mod:`axiscal.io.gcode.dialects`): ``G4 P<s>`` on
LinuxCNC and Grbl, ``G04 X<s>`` on FANUC, ``G4 F<s>`` in a block of its own on SINUMERIK,
``G4 P<ms>`` on Marlin and Klipper, and HEIDENHAIN's ``CYCL DEF 9.0 DWELL TIME`` / ``CYCL DEF 9.1
DWELL <s>`` in a numbered conversational program. Positions are written in millimetres with three
decimals (1 um), feeds in mm/min; what the writer writes, :func:`axiscal.io.gcode.program_motions`
reads back.

Every number a program carries is bounded before it is written, so that every control reads it: a
position within +/-99999.999 mm (degrees), five whole digits and three decimals, the range of an
address word common to LinuxCNC, FANUC, SINUMERIK and HEIDENHAIN; a feed above 0 and at most
100 000 mm/min (100 m/min); a dwell of at most an hour. No word is ever written with an exponent.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_instance, check_mapping, check_number
from axiscal.io.gcode.dialects import Dialect, dialect as find_dialect

__all__ = ["ProgramWriter", "decimal", "MAX_POSITION_MM", "MAX_FEED_MM_MIN", "MAX_DWELL_S", "position_word", "feed_word"]

_MM = 1e-3
_DEG = math.pi / 180.0

#: the largest position (mm, or degrees for A, B, C) a program carries: five whole digits, three decimals
MAX_POSITION_MM = 99_999.999
#: the largest feed a program carries, mm/min (100 m/min, beyond any calibration move)
MAX_FEED_MM_MIN = 100_000.0
#: the longest dwell a program carries, seconds
MAX_DWELL_S = 3600.0


def position_word(name: str, value_mm: float, places: int = 3, *, sign: bool = False) -> str:
    """A position (mm or degrees) as a control reads it: fixed decimals, bounded, never an exponent.

    Parameters
    ----------
    name : str
        What the value is, for the message (``position_m['X']``).
    value_mm : float
        The position, millimetres (degrees for a rotary axis).
    places : int
        Decimals written.
    sign : bool, keyword-only
        Always write the sign (HEIDENHAIN's ``X+10.000``).

    Returns
    -------
    str

    Raises
    ------
    AxiscalError
        For a value that is not finite or beyond :data:`MAX_POSITION_MM`.

    Examples
    --------
    >>> position_word("X", 12.34567), position_word("X", -0.0001), position_word("X", 5.0, sign=True)
    ('12.346', '0.000', '+5.000')
    """
    value = check_number(name, value_mm, unit="mm")
    if abs(value) > MAX_POSITION_MM:
        raise AxiscalError(f"{name} must be within +/-{MAX_POSITION_MM:.3f} (five whole digits, as every control reads"
                           f" a word), not {value:.10g}")
    value = round(value, places) + 0.0
    return f"{value:+.{places}f}" if sign else f"{value:.{places}f}"


def feed_word(feed_mm_min: float, places: int = 3, *, point: bool = False) -> str:
    """A feed (mm/min) as a control reads it: above 0, at most :data:`MAX_FEED_MM_MIN`, never an exponent.

    Parameters
    ----------
    feed_mm_min : float
    places : int
        Decimals kept (trailing zeros dropped).
    point : bool, keyword-only
        Always write a decimal point (FANUC).

    Returns
    -------
    str

    Raises
    ------
    AxiscalError
        For a feed that is not finite, rounds to 0, or is beyond :data:`MAX_FEED_MM_MIN`.

    Examples
    --------
    >>> feed_word(1000.0), feed_word(1234.5678, 1), feed_word(600.0, point=True)
    ('1000', '1234.6', '600.')
    """
    value = check_number("feed_mm_min", feed_mm_min, positive=True, unit="mm/min")
    if round(value, places) <= 0:
        raise AxiscalError(f"feed_mm_min must be at least {10.0 ** -places:g} mm/min (it is written to {places} decimals),"
                           f" not {value:.10g}")
    if value > MAX_FEED_MM_MIN:
        raise AxiscalError(f"feed_mm_min must be at most {MAX_FEED_MM_MIN:.0f} mm/min (100 m/min), not {value:.10g}")
    return decimal(value, places, point=point)


def decimal(value: float, places: int, *, point: bool = False) -> str:
    """``value`` with at most ``places`` decimals, trailing zeros dropped, never an exponent.

    Parameters
    ----------
    value : float
    places : int
        Decimals kept (the value is rounded to them).
    point : bool, keyword-only
        Always write a decimal point (FANUC reads ``2`` as 2 least increments, ``2.`` as 2).

    Returns
    -------
    str

    Examples
    --------
    >>> decimal(2.0, 3), decimal(1.5, 3), decimal(2.0, 3, point=True), decimal(-0.0001, 3)
    ('2', '1.5', '2.', '0')
    """
    text = f"{round(value, places) + 0.0:.{places}f}"
    if "." in text:
        text = text.rstrip("0").rstrip(".")
    if text == "-0":
        text = "0"
    return text + "." if point and "." not in text else text


class ProgramWriter:
    """A G-code program built block by block in one dialect.

    Parameters
    ----------
    dialect : str or Dialect
        One of :data:`axiscal.io.gcode.DIALECT_NAMES`.
    name : str, keyword-only
        The program's name where the dialect writes one (HEIDENHAIN's ``BEGIN PGM name MM``);
        characters other than letters, digits, ``_`` and ``-`` become ``_``.
    comments : sequence of str, keyword-only
        Comment lines written after the program start.

    Examples
    --------
    >>> writer = ProgramWriter("fanuc", comments=["calibration"])
    >>> writer.move({"X": 0.01}, feed_m_per_s=0.01)
    >>> writer.dwell(2.0)
    >>> writer.text().splitlines()
    ['%', 'O0001', '(calibration)', 'G21', 'G90 G94', 'G01 X10.000 F600.', 'G04 X2.', 'M30', '%']
    """

    def __init__(self, dialect: str | Dialect, *, name: str = "AXISCAL", comments: tuple[str, ...] | list[str] = ()):
        self.spec = find_dialect(dialect)
        check_instance("name", name, str)
        self.name = re.sub(r"[^A-Za-z0-9_-]", "_", name) or "AXISCAL"
        self._blocks: list[str] = []
        self._feed: str | None = None
        for text in comments:
            self.comment(text)
        self._blocks.extend(self.spec.setup)

    def comment(self, text: str) -> None:
        """A comment line (characters the dialect's comment syntax cannot hold are replaced)."""
        check_instance("text", text, str)
        text = " ".join(text.split())
        if self.spec.comment_style == "paren":
            self._blocks.append("(" + text.replace("(", "[").replace(")", "]") + ")")
        else:
            self._blocks.append("; " + text)

    def move(self, position_m: Mapping[str, float], *, feed_m_per_s: float | None) -> None:
        """A straight move to ``position_m``: a feed move, or a rapid one when ``feed_m_per_s`` is None.

        Parameters
        ----------
        position_m : Mapping[str, float]
            Axis letter -> absolute position, metres (radians for A, B, C).
        feed_m_per_s : float or None, keyword-only
            The feed along the path (m/s, > 0); written only where it changes.
        """
        spec = self.spec
        check_mapping("position_m", position_m)
        words = []
        for letter, value in position_m.items():
            if letter not in spec.axes:
                raise AxiscalError(f"{letter!r} is not an axis of {spec.controller} ({', '.join(spec.axes)})")
            value = check_number(f"position_m[{letter!r}]", value)
            amount = value / _DEG if letter in "ABC" else value / _MM
            name = f"the {letter} position in {'degrees' if letter in 'ABC' else 'mm'}"
            words.append(f"{letter}{position_word(name, amount, sign=spec.syntax == 'conversational')}")
        if feed_m_per_s is None:
            feed = None
        else:
            per_minute = check_number("feed_m_per_s", feed_m_per_s, positive=True) * 60.0 / _MM
            feed = "F" + feed_word(per_minute, point=spec.decimal_point_needed)
        if spec.syntax == "conversational":
            tail = ["R0", "FMAX"] if feed is None else ["R0"] + ([feed] if feed != self._feed else [])
        else:
            tail = [feed] if feed is not None and feed != self._feed else []
        if feed is not None:
            self._feed = feed
        if feed is None and spec.rapid_at_feed:
            raise AxiscalError(f"{spec.controller} has no rapid move: G0 moves at the programmed feed")
        word = spec.rapid_word if feed is None else spec.feed_word
        self._blocks.append(" ".join([word, *words, *tail]))

    def dwell(self, seconds: float) -> None:
        """A dwell of ``seconds`` (0 to :data:`MAX_DWELL_S`) in the dialect's own words and unit."""
        spec = self.spec
        seconds = check_number("seconds", seconds, nonnegative=True)
        seconds = check_number("seconds", seconds, high=MAX_DWELL_S)
        if spec.syntax == "conversational":
            self._blocks += ["CYCL DEF 9.0 DWELL TIME", f"CYCL DEF 9.1 DWELL {decimal(seconds, spec.dwell_places)}"]
            return
        letter, unit = next(iter(spec.dwell_words.items()))
        value = decimal(seconds / unit, spec.dwell_places, point=spec.decimal_point_needed and unit == 1.0)
        self._blocks.append(f"{spec.dwell_word} {letter}{value}")

    def text(self) -> str:
        """The whole program: start, comments, setup, the blocks, end; one block a line."""
        spec = self.spec
        if spec.syntax == "conversational":
            body = [f"BEGIN PGM {self.name} MM", *self._blocks, f"END PGM {self.name} MM"]
            return "".join(f"{number} {block}\n" for number, block in enumerate(body))
        return "\n".join([*spec.program_start, *self._blocks, *spec.program_end]) + "\n"
