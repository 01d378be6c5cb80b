"""The G-code writer: moves, dwells and comments in a dialect's own words, start and end.

Each dialect's words come from its description (:mod:`axiscal.io.gcode.dialects`): ``G4 P<s>`` on
LinuxCNC and Grbl, ``G04 X<s>`` on FANUC, ``G4 F<s>`` in a block of its own on SINUMERIK,
``G4 P<ms>`` on Marlin and Klipper, and HEIDENHAIN's ``CYCL DEF 9.0 DWELL TIME`` / ``CYCL DEF 9.1
DWELL <s>`` in a numbered conversational program. Positions are written in millimetres with three
decimals (1 um), feeds in mm/min; what the writer writes, :func:`axiscal.io.gcode.program_motions`
reads back.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_instance, check_mapping, check_number
from axiscal.io.gcode.dialects import Dialect, dialect as find_dialect

__all__ = ["ProgramWriter", "decimal"]

_MM = 1e-3
_DEG = math.pi / 180.0


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
            if spec.syntax == "conversational":
                text = f"{round(amount, 3) + 0.0:+.3f}"
            else:
                text = f"{round(amount, 3) + 0.0:.3f}"
            words.append(f"{letter}{text}")
        if feed_m_per_s is None:
            feed = None
        else:
            per_minute = check_number("feed_m_per_s", feed_m_per_s, positive=True) * 60.0 / _MM
            feed = "F" + decimal(per_minute, 3, point=spec.decimal_point_needed)
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
        """A dwell of ``seconds`` (>= 0) in the dialect's own words and unit."""
        spec = self.spec
        seconds = check_number("seconds", seconds, nonnegative=True)
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
