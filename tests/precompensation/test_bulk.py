"""A program read in bulk is rewritten to the same text, to the byte, as one read block by block.

Long programs' plain lines are read in bulk (:mod:`axiscal.io.gcode.fast`) and rewritten from
columns; every other line keeps its Block. Over seeded programs of each word dialect that mix plain
moves (with and without their G word, with a feed, with rotary words) with arcs, comments, block
numbers, incremental moves, G92, inch blocks and dwells, both ways give the same text and summary.
"""

from __future__ import annotations

import numpy as np
import pytest

from axiscal.errors import AxiscalError
from axiscal.io.gcode import reader
from axiscal.precompensation import rewrite_program

from .machines import machines

MACHINES = machines()


def _rewrite(text, machine, dialect, bulk):
    old = reader._BULK, reader._BULK_FROM
    reader._BULK, reader._BULK_FROM = bulk, 0
    try:
        return rewrite_program(text, machine, dialect=dialect, source="p")
    except AxiscalError as error:
        return str(error)
    finally:
        reader._BULK, reader._BULK_FROM = old


def _program(rng, dialect: str, rotary: bool) -> str:
    printer = dialect in ("marlin", "klipper")
    head = {"linuxcnc": ["%", "(part)", "G21 G90 G94 G17"], "grbl": ["G21 G90 G94 G17"], "sinumerik": ["G71 G90 G94 G17"],
            "marlin": ["G21", "G90", "M82"], "klipper": ["G90", "M82"]}[dialect]
    start = "G0 X400 Y250 Z200" + (" A0 C0" if rotary else "") + (" F3000" if printer else "")
    lines = head + [start, ("G1 F1500" if not printer else "G1 X400 Y250 Z200 F1500")]
    x, y, z, e = 400.0, 250.0, 200.0, 0.0
    for k in range(400):
        x = min(650.0, max(150.0, x + rng.uniform(-3, 3)))
        y = min(380.0, max(120.0, y + rng.uniform(-3, 3)))
        z = min(280.0, max(120.0, z + rng.normal(0, 0.2)))
        e += rng.uniform(0.0, 0.5)
        r = rng.random()
        arc_mode = next((line.startswith("G2") for line in reversed(lines) if line[:2] in ("G0", "G1", "G2", "N1", "N2",
                                                                                        "N3", "N4", "N5", "N6", "N7", "N8", "N9")), False)
        g = "G1 " if printer or rng.random() < 0.3 or arc_mode else ""
        words = f"X{x:.4f} Y{y:.3f} Z{z:.2f}"
        if printer and rng.random() < 0.7:
            words += f" E{e:.4f}"
        if r < 0.04:
            radius = "CR=" if dialect == "sinumerik" else "R"
            lines.append(f"G2 X{x:.4f} Y{y:.4f} {radius}{rng.uniform(5, 9):.3f}" if dialect != "klipper" else f"G1 {words}")
            if dialect != "klipper" and rng.random() < 0.5:
                lines.append("G1")  # the mode alone: the moves after it rely on it
        elif r < 0.07 and not printer:
            lines.append(f"N{k * 10} G1 {words} " + (f"(row {k})" if dialect != "sinumerik" else f"; row {k}"))
        elif r < 0.10:
            lines.append(f"{g or 'G1 '}{words} F{rng.choice([900, 1200, 1500])}")
        elif r < 0.12:
            lines.append("G4 P1" if dialect != "sinumerik" else "G4 F1")
        elif r < 0.14 and not printer:
            lines.extend(["G91", f"G1 X{rng.uniform(-1, 1):.3f} Y{rng.uniform(-1, 1):.3f}", "G90"])
            continue
        elif r < 0.15 and dialect in ("linuxcnc", "grbl"):
            lines.extend([f"G92 X{x:.3f}", f"G1 X{x:.3f}", "G92.1"])
            continue
        elif r < 0.16 and dialect in ("linuxcnc", "grbl"):
            lines.extend(["G20", f"G1 X{x / 25.4:.5f} Y{y / 25.4:.5f}", "G21"])
            continue
        elif r < 0.17:
            lines.append("; a note" if dialect != "linuxcnc" else "(a note)")
        elif rotary and r < 0.2:
            lines.append(f"G0 {words} A{rng.uniform(-10, 10):.3f} C{rng.uniform(0, 90):.3f}")
        else:
            lines.append(f"{g}{words}" if not printer else f"G1 {words}")
    lines += {"linuxcnc": ["M2", "%"], "grbl": ["M2"], "sinumerik": ["M30"]}.get(dialect, [])
    return "\n".join(lines) + "\n"


@pytest.mark.parametrize("dialect", ["linuxcnc", "grbl", "sinumerik", "marlin", "klipper"])
@pytest.mark.parametrize("seed", range(3))
def test_the_same_text_comes_out_either_way(dialect, seed):
    rng = np.random.default_rng(seed)
    text = _program(rng, dialect, rotary=False)
    machine = MACHINES["xfyz"]
    bulk, blocks = _rewrite(text, machine, dialect, True), _rewrite(text, machine, dialect, False)
    assert not isinstance(blocks, str), blocks
    assert bulk == blocks
    assert bulk.rewritten > 300


def test_rotary_words_and_feeds_are_kept_on_the_trunnion():
    rng = np.random.default_rng(7)
    text = _program(rng, "linuxcnc", rotary=True).replace("X400 Y250 Z200", "X-100 Y-100 Z-300")
    text = "\n".join(line for line in text.split("\n") if not line.startswith("G2"))
    # the trunnion's travel: move the program into it
    shifted = []
    for line in text.split("\n"):
        words = []
        for word in line.split():
            if word[:1] in "XYZ" and word[1:2] in "-0123456789" and not line.startswith(("G92", "G20")):
                value = float(word[1:]) - {"X": 500.0, "Y": 350.0, "Z": 500.0}[word[0]]
                words.append(f"{word[0]}{value:.4f}")
            else:
                words.append(word)
        shifted.append(" ".join(words))
    text = "\n".join(line for line in shifted if not line.startswith(("G92", "G20", "G21", "G1 X"))
                     or line.startswith("G21 G90")) + "\n"
    machine = MACHINES["trunnion"]
    bulk, blocks = _rewrite(text, machine, "linuxcnc", True), _rewrite(text, machine, "linuxcnc", False)
    assert bulk == blocks
    if not isinstance(bulk, str):
        assert " A" in bulk.text and " F" in bulk.text
