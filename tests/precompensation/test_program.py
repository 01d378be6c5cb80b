"""Part programs pre-compensated through the machine model, checked by running them forward through it."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from axiscal.errors import AxiscalError
from axiscal.precompensation import precompensate_program, rewrite_program
from axiscal.units import UM

from .forward import largest_departure
from .machines import ideal, machines

MACHINES = machines()
TOLERANCE = 0.5 * UM

# one part, in the words of each control: a plunge, a straight cut, two arcs (by centre and by
# radius), an incremental move, a retract
PARTS = {
    "linuxcnc": """%
(part)
G21 G90 G94 G17
N10 G0 X100 Y100 Z150
N20 G1 Z120 F800 (plunge)
N30 G1 X300 Y150
N40 G2 X340 Y190 I0 J40
N50 G3 X300 Y230 R40
G91
G1 X-20 Y-10
G90
G0 Z200
M2
%
""",
    "grbl": """(part)
G21 G90 G94 G17
G0 X100 Y100 Z150
G1 Z120 F800 ; plunge
G1 X300 Y150
G2 X340 Y190 I0 J40
G3 X300 Y230 R40
G91
G1 X-20 Y-10
G90
G0 Z200
M2
""",
    "fanuc": """%
O0100 (PART)
G21
G90 G94 G17
N10 G00 X100. Y100. Z150.
N20 G01 Z120. F800. (PLUNGE)
N30 G01 X300. Y150.
N40 G02 X340. Y190. I0. J40.
N50 G03 X300. Y230. R40.
G91
G01 X-20. Y-10.
G90
G00 Z200.
M30
%
""",
    "sinumerik": """; part
G71 G90 G94 G17
N10 G0 X100 Y100 Z150
N20 G1 Z120 F800 ; plunge
N30 G1 X300 Y150
N40 G2 X340 Y190 I0 J40
N50 G3 X300 Y230 CR=40
G91
G1 X-20 Y-10
G90
G0 Z200
M30
""",
    "marlin": """; part
G21
G90
G0 X100 Y100 Z150 F3000
G1 Z120 F800 ; plunge
G1 X300 Y150
G2 X340 Y190 I0 J40
G3 X300 Y230 R40
G91
G1 X-20 Y-10
G90
G0 Z200
""",
    "klipper": """; part
G90
G0 X100 Y100 Z150 F3000
G1 Z120 F800 ; plunge
G1 X300 Y150
G2 X340 Y190 I0 J40
G3 X300 Y230 I-40 J0
G91
G1 X-20 Y-10
G90
G0 Z200
""",
}


@pytest.mark.parametrize("dialect", list(PARTS))
def test_each_dialects_program_lands_on_the_nominal_path(dialect):
    machine = MACHINES["xfyz"]
    result = rewrite_program(PARTS[dialect], machine, dialect=dialect, source=f"part.{dialect}")
    assert result.rewritten == result.moves and result.lines_out > result.lines_in
    assert result.largest_residual_m <= TOLERANCE and result.largest_correction_m > 10 * UM
    assert largest_departure(machine, PARTS[dialect], result.text, dialect) <= TOLERANCE + 1e-9
    # without pre-compensation the same program misses the path by the machine's error
    assert largest_departure(machine, PARTS[dialect], PARTS[dialect], dialect) > 10 * UM


@pytest.mark.parametrize("name", ["cmm", "router", "module"])
def test_other_chains_land_on_the_nominal_path(name):
    machine = MACHINES[name]
    text = PARTS["linuxcnc"].replace("Z150", "Z-150").replace("Z120", "Z-180").replace("Z200", "Z-100")
    if name == "module":
        text = "%\nG21 G90 G94 G18\nG0 X100 Z100\nG1 X120 Z110 F500\nG2 X150 Z140 I0 K30\nG1 X20 Z20\nM2\n%\n"
    result = rewrite_program(text, machine, dialect="linuxcnc")
    reach = (0, 2) if name == "module" else (0, 1, 2)
    assert largest_departure(machine, text, result.text, "linuxcnc", reach=reach) <= TOLERANCE + 1e-9
    assert largest_departure(machine, text, text, "linuxcnc", reach=reach) > 4 * TOLERANCE


def test_the_trunnion_with_its_rotary_axes_standing_still():
    machine = MACHINES["trunnion"]
    text = ("G21 G90 G94 G17\nG0 A-20 C30 X-100 Y-100 Z-300\nG1 X100 Y-80 F600\nG2 X120 Y-60 I0 J20\n"
            "G0 Z-200\nG0 A10 C120\nG1 X-100 Y50 Z-250\nM2\n")
    result = rewrite_program(text, machine, dialect="linuxcnc")
    assert largest_departure(machine, text, result.text, "linuxcnc") <= TOLERANCE + 1e-9
    assert largest_departure(machine, text, text, "linuxcnc") > 4 * TOLERANCE
    with pytest.raises(AxiscalError, match="^line 3: a move that turns C while it cuts"):
        rewrite_program("G21 G90\nG0 A0 C0 X0 Y0 Z-300\nG1 X10 C5 F100\nM2\n", machine, dialect="linuxcnc")


@pytest.mark.parametrize("dialect", list(PARTS))
def test_without_errors_the_program_comes_out_as_it_went_in_but_for_the_header(dialect):
    out = precompensate_program(PARTS[dialect], ideal(), dialect=dialect).splitlines(keepends=True)
    header = [i for i, line in enumerate(out) if "axiscal" in line and "precompensate" in line]
    assert len(header) == 1 and "machine ideal" in out[header[0]] and "tolerance 0.5 um" in out[header[0]]
    del out[header[0]]
    assert "".join(out) == PARTS[dialect]


def test_inch_programs_g92_and_the_work_offset():
    machine = MACHINES["xfyz"]
    text = ("G20 G90 G94\nG0 X4 Y4 Z6\nG1 X10 Y5 F20\nG92 X0 Y0\nG1 X2 Y2\nG2 X3 Y3 I0 J1\nG92.1\nG21\nG1 X200 Y150\nM2\n")
    offset = {"X": 0.02, "Y": 0.01, "Z": 0.0}
    result = rewrite_program(text, machine, dialect="linuxcnc", work_offset_m=offset)
    assert largest_departure(machine, text, result.text, "linuxcnc", work_offset_m=offset) <= TOLERANCE + 1e-9
    lines = result.text.splitlines()
    # the control stands at the pre-compensated point when G92 names it: its coordinates move by the correction
    (g92,) = [line.split() for line in lines if line.startswith("G92 ")]
    assert g92[1] != "X0" and abs(float(g92[1][1:])) < 1e-4 and abs(float(g92[2][1:])) < 1e-4
    assert any(line.startswith("G1 X9.99") and len(line.split()[1]) == 9 for line in lines)      # inch: 6 decimals


def test_printer_extrusion_is_shared_out_over_the_pieces():
    machine = MACHINES["router"]
    text = "G21\nG90\nM83\nG0 X100 Y100 Z-150 F6000\nG1 X400 Y110 E12.5 F1200\nG1 E-1\nG1 X100 Y300 E8\n"
    result = rewrite_program(text, machine, dialect="marlin")
    pieces = [line for line in result.text.splitlines() if line.startswith("G1") and " E" in line]
    total = sum(float(line.split(" E")[1].split()[0]) for line in pieces)
    assert total == pytest.approx(12.5 - 1 + 8, abs=1e-4) and len(pieces) > 3
    assert largest_departure(machine, text, result.text, "marlin") <= TOLERANCE + 1e-9


BAD = [
    ("G21 G90\nG0 X100 Y100 Z150\nG1 X200 Q5 F100\nM2\n", 3, "Q is not a word of LinuxCNC"),
    ("G21 G90\nG0 X100 Y100 Z150\nG2 X120 Y100 I5 J0 F100\nM2\n", 3, "end point is not on its circle"),
    ("G21 G90\nG0 X100 Y100 Z150\n#1 = 5\nM2\n", 3, "cannot read '#1 = 5'"),
    ("G21 G90\nG0 X100 Y100 Z150\nG81 X1 Y1 Z-1 R2\nM2\n", 3, "canned cycle"),
    ("G21 G90\nG0 X100 Y100 Z150\nO100 call\nM2\n", 3, "cannot read"),
    ("G21 G90\nG0 X100 Y100\nM2\n", 2, "before the program has set Z"),
    ("G21 G90\nG0 X0 Y0 Z150\nM2\n", 2, "outside the error table"),
    ("G21 G90\nG0 X100 Y100 Z150 A5\nM2\n", 2, "A is not an axis of the machine model"),
]


@pytest.mark.parametrize(("text", "line", "message"), BAD)
def test_bad_programs_are_refused_naming_the_line(text, line, message):
    with pytest.raises(AxiscalError) as caught:
        precompensate_program(text, MACHINES["xfyz"], dialect="linuxcnc", source="bad.ngc")
    assert str(caught.value).startswith(f"bad.ngc:{line}: ") and message in str(caught.value)


def test_bad_settings():
    with pytest.raises(AxiscalError, match="tolerance_m must be at least 0.2 um"):
        precompensate_program(PARTS["grbl"], ideal(), dialect="grbl", tolerance_m=0.1e-6)
    with pytest.raises(AxiscalError, match="max_segment_m"):
        precompensate_program(PARTS["grbl"], ideal(), dialect="grbl", max_segment_m=0.0)
    with pytest.raises(AxiscalError, match="not pre-compensated"):
        precompensate_program("0 BEGIN PGM P MM\n1 END PGM P MM\n", ideal(), dialect="heidenhain")


@settings(max_examples=15)
@given(st.lists(st.tuples(st.floats(0.05, 0.75), st.floats(0.05, 0.45), st.floats(0.05, 0.35)), min_size=2, max_size=6),
       st.sampled_from(["linuxcnc", "grbl", "marlin"]))
def test_random_straight_paths_land_on_their_nominal_path(points, dialect):
    machine = MACHINES["xfyz"]
    words = "\n".join(f"G1 X{x * 1e3:.3f} Y{y * 1e3:.3f} Z{z * 1e3:.3f}" for x, y, z in points[1:])
    x, y, z = points[0]
    text = f"G21\nG90\nG0 X{x * 1e3:.3f} Y{y * 1e3:.3f} Z{z * 1e3:.3f} F5000\nG1 X{x * 1e3:.3f} F2000\n{words}\n"
    if dialect == "linuxcnc":
        text = "G94\n" + text + "M2\n"
    result = rewrite_program(text, machine, dialect=dialect)
    assert largest_departure(machine, text, result.text, dialect) <= TOLERANCE + 1e-9
    assert np.isfinite(result.largest_residual_m)


@settings(max_examples=40)
@given(st.sampled_from(list(PARTS)), st.data())
def test_a_mutated_program_is_rewritten_or_refused_in_one_line(dialect, data):
    text = PARTS[dialect]
    position = data.draw(st.integers(0, len(text)))
    cut = data.draw(st.integers(0, 4))
    insert = data.draw(st.text(alphabet="GMXYZIJKRFPN0123456789.-+;()% #=E\n", max_size=5))
    mutated = text[:position] + insert + text[position + cut:]
    try:
        result = rewrite_program(mutated, MACHINES["xfyz"], dialect=dialect, source="m.nc")
    except AxiscalError as error:
        assert str(error).startswith("m.nc:") and "\n" not in str(error)
    else:
        assert result.largest_residual_m <= TOLERANCE and result.text.count("\n") >= mutated.count("\n")


# numbers no float holds (issue 28, item 8): a word such as X1 followed by 400 zeros, a 200 000-digit number
HUGE = ("1" + "0" * 400, "9" * 200_000)


@pytest.mark.parametrize("number", HUGE, ids=["1e400", "200000 digits"])
@pytest.mark.parametrize(("template", "message"), [
    ("G1 X{} F100", "X is not a finite number"),
    ("G1 Z-{} F100", "Z is not a finite number"),
    ("G2 X402 Y250 R{} F100", "the arc's centre or radius is not a finite number"),
    ("G2 X402 Y250 I{} J0 F100", "the arc's centre or radius is not a finite number"),
    ("G1 X410 F100 M{}", "characters) is not a LinuxCNC M code"),
    ("G{} X410 F100", "characters) is not a LinuxCNC G code"),
])
def test_numbers_too_large_for_a_float_are_refused_naming_the_line(number, template, message):
    text = f"G21 G90\nG0 X400 Y250 Z200\n{template.format(number)}\nM2\n"
    with pytest.raises(AxiscalError) as caught:
        rewrite_program(text, MACHINES["xfyz"], dialect="linuxcnc", source="big.ngc")
    said = str(caught.value)
    assert said.startswith("big.ngc:3: ") and message in said and "\n" not in said and len(said) < 200


def test_an_arc_of_a_huge_radius_is_one_chord_or_refused_in_one_line_not_a_division_by_zero():
    # R 1 km: the sagitta of the whole 2 mm arc is far below the tolerance, one chord (the angle of a
    # chord once rounded to nothing for such a radius)
    text = "G21 G90\nG0 X400 Y250 Z200\nG2 X402 Y250 R{} F100\nM2\n"
    result = rewrite_program(text.format("1000000"), MACHINES["xfyz"], dialect="linuxcnc")
    assert result.lines_out == 5 and result.largest_residual_m <= TOLERANCE
    # R 1e30 mm: the reader's circle through both ends is a full turn; refused, the work bounded
    with pytest.raises(AxiscalError, match=r"^r\.ngc:3: the arc \(radius 1e\+30 mm, 360 degrees\) would be cut into 3\.14e\+30 chords"):
        rewrite_program(text.format("1" + "0" * 30), MACHINES["xfyz"], dialect="linuxcnc", source="r.ngc")


def test_a_max_segment_that_would_take_unbounded_work_is_refused_up_front():
    text = "G21 G90\nG0 X400 Y250 Z200\nG1 X410 F100\nM2\n"
    with pytest.raises(AxiscalError, match=r"^max_segment_m must be at least 0\.001 mm .*not 1e-09 mm$"):
        rewrite_program(text, MACHINES["xfyz"], dialect="linuxcnc", max_segment_m=1e-12)
    # 40 moves of 600 mm checked every 0.5 um: 4.8e7 points, past the bound; refused before any is made
    moves = "\n".join(f"G1 X{700 if i % 2 == 0 else 100}" for i in range(40))
    long_moves = f"G21 G90\nG0 X100 Y100 Z200\nG1 X100 F100\n{moves}\nM2\n"
    with pytest.raises(AxiscalError) as caught:
        rewrite_program(long_moves, MACHINES["xfyz"], dialect="linuxcnc", max_segment_m=1e-6, source="long.ngc")
    assert str(caught.value).startswith("long.ngc:4: the path would be checked at 4.8e+07 points (at most 2e+07)")
    assert "take a longer max segment (at least 0.0024 mm for this program)" in str(caught.value)


def test_a_fanuc_program_without_m30_is_refused_even_with_a_closing_percent():
    body = "%\nO1000\nG21 G90\nG0 X400. Y250. Z200.\nG1 X401. F100.\n"
    with pytest.raises(AxiscalError, match=r"^o\.nc:6: the program has no end \(M2, M30\)$"):
        rewrite_program(body + "%\n", MACHINES["xfyz"], dialect="fanuc", source="o.nc")
    assert rewrite_program(body + "M30\n%\n", MACHINES["xfyz"], dialect="fanuc").moves == 2
    # LinuxCNC's closing % ends its program
    assert rewrite_program("%\nG21 G90\nG0 X400 Y250 Z200\nG1 X401 F100\n%\n", MACHINES["xfyz"], dialect="linuxcnc").moves == 2
