"""HEIDENHAIN's conversational programs (``.h``): numbered plain-language blocks.

The TNC User's Manual (conversational programming) gives the frame: ``0 BEGIN PGM name MM`` ...
``n END PGM name MM``, every block numbered, comments after ``;`` and structure lines ``*``; the
path function ``L`` with absolute or incremental (``IX``) coordinates, ``R0`` (no radius
compensation), ``F`` in mm/min kept until changed and ``FMAX`` for one rapid block. The cycle
programming manual gives Cycle 9: ``CYCL DEF 9.0 DWELL TIME`` then ``CYCL DEF 9.1 DWELL <s>``, the
dwell in seconds, active as soon as it is defined (the word after 9.1 is in the control's dialogue
language, so any word is read there).
"""

from __future__ import annotations

import re

from axiscal.io.gcode.blocks import ControlState

__all__ = ["run_conversational_block"]

_MM = 1e-3
_NUMBER = r"[+-]?(?:\d+\.?\d*|\.\d+)"
_BLOCK = re.compile(r"\s*(\d+)\s*(.*?)\s*")
_PGM = re.compile(r"(BEGIN|END)\s+PGM\s+(\S+)\s+(MM|INCH)", re.IGNORECASE)
_DWELL_DEF = re.compile(r"CYCL\s+DEF\s+9\.0(\s.*)?", re.IGNORECASE)
_DWELL = re.compile(rf"CYCL\s+DEF\s+9\.1\s+\S+\s+({_NUMBER})", re.IGNORECASE)
_AXIS = re.compile(rf"(I?)([A-Z])({_NUMBER})")
_NEUTRAL_M = frozenset({"M3", "M4", "M5", "M7", "M8", "M9"})


def run_conversational_block(text: str, state: ControlState, frame: dict) -> None:
    """Run one numbered block of a conversational program on ``state``; ``frame`` keeps the program's name."""
    if not text.strip():
        state.record(text, None, (), "", "", None)
        return
    match = _BLOCK.fullmatch(text)
    if match is None:
        raise state.fail("a conversational block starts with its block number")
    body = match.group(2)
    number = match.group(1)
    if body.startswith(";") or body.startswith("*"):
        state.record(text, None, (), number, body, None)
        return
    body = body.split(";", 1)[0].strip()
    if state.ended:
        raise state.fail("a block after END PGM")
    pgm = _PGM.fullmatch(body)
    if frame.get("name") is None:
        if pgm is None or pgm.group(1).upper() != "BEGIN":
            raise state.fail("a conversational program starts with BEGIN PGM name MM")
        if pgm.group(3).upper() == "INCH":
            raise state.fail("inch programs (BEGIN PGM ... INCH) are not read")
        frame["name"] = pgm.group(2)
        state.metres_per_unit = _MM
        state.record(text, None, (), number, "", None)
        return
    if pgm is not None:
        if pgm.group(1).upper() == "BEGIN":
            raise state.fail("a second BEGIN PGM")
        if pgm.group(2) != frame["name"] or pgm.group(3).upper() != "MM":
            raise state.fail(f"END PGM {pgm.group(2)} {pgm.group(3)} does not close BEGIN PGM {frame['name']} MM")
        state.ended = True
        state.record(text, None, (), number, "", None)
        return
    if _DWELL_DEF.fullmatch(body):
        frame["dwell"] = True
        state.record(text, None, (), number, "", None)
        return
    dwell = _DWELL.fullmatch(body)
    if dwell is not None:
        if not frame.pop("dwell", False):
            raise state.fail("CYCL DEF 9.1 without CYCL DEF 9.0 DWELL TIME before it")
        state.record(text, state.dwell(float(dwell.group(1))), (), number, "", None)
        return
    if frame.get("dwell"):
        raise state.fail("CYCL DEF 9.0 DWELL TIME is not followed by CYCL DEF 9.1 DWELL")
    tokens = body.split()
    if not tokens or tokens[0].upper() != "L":
        raise state.fail(f"cannot follow {body[:30]!r}: this reader follows L, CYCL DEF 9 and BEGIN/END PGM blocks")
    targets: dict[str, tuple[str, bool]] = {}
    rapid = False
    for token in tokens[1:]:
        upper = token.upper()
        axis = _AXIS.fullmatch(upper)
        if axis is not None and axis.group(2) in state.spec.axes:
            if axis.group(2) in targets:
                raise state.fail(f"{axis.group(2)} twice in one block")
            targets[axis.group(2)] = (axis.group(3), bool(axis.group(1)))
        elif upper == "R0":
            continue
        elif upper in ("RL", "RR", "R+", "R-"):
            raise state.fail(f"radius compensation {upper} is not followed")
        elif upper == "FMAX":
            rapid = True
        elif re.fullmatch(rf"F{_NUMBER}", upper):
            state.set_feed(upper[1:])
        elif re.fullmatch(r"M\d+", upper):
            m = f"M{int(upper[1:])}"
            if m not in _NEUTRAL_M:
                raise state.fail(f"{m} is not an M function this reader follows")
        else:
            raise state.fail(f"cannot follow {token!r} in an L block")
    motion = state.move("rapid" if rapid else "feed", state.target(targets, implicit=False)) if targets else None
    state.record(text, motion, (), number, "", "L")
