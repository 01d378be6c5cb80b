"""G-code, the one room for it: each control's dialect described once, a reader and a writer.

The dialects (:mod:`axiscal.io.gcode.dialects`) hold each control's words with their documented
source; :func:`program_motions` reads a program's moves and dwells in SI as that control runs them;
:class:`ProgramWriter` writes moves, dwells and comments in the control's own words. Test planning
writes its programs through the writer; the same reader follows them.
"""

from __future__ import annotations

from axiscal.io.gcode.dialects import DIALECT_NAMES, DIALECTS, Dialect, dialect
from axiscal.io.gcode.blocks import MM_PER_INCH, PLANE_AXES, Block, Motion
from axiscal.io.gcode.reader import Program, program_motions, read_program, split_lines
from axiscal.io.gcode.writer import ProgramWriter, decimal

__all__ = [
    "DIALECT_NAMES",
    "DIALECTS",
    "Dialect",
    "dialect",
    "MM_PER_INCH",
    "PLANE_AXES",
    "Block",
    "Motion",
    "Program",
    "program_motions",
    "read_program",
    "split_lines",
    "ProgramWriter",
    "decimal",
]
