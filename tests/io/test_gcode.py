"""G-code dialects: the plan's program in each control's words, read back by each dialect's reader.

The reader's rules come from each control's documentation (the sources in
axiscal.io.gcode.dialects); the hand-written programs below are the manuals' own examples of a
dwell and a move, with the time and position the manual gives for them.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, strategies as st

from axiscal.errors import AxiscalError
from axiscal.io.gcode import DIALECT_NAMES, DIALECTS, ProgramWriter, decimal, program_motions
from axiscal.positioning.plan import gcode_program, plan_test
from axiscal.units import MM

UM = 1e-6


def _moves_and_dwells(motions):
    moves = [m for m in motions if m.kind != "dwell"]
    return moves, [m for m in motions if m.kind == "dwell"]


@pytest.mark.parametrize("cycle", ["linear", "pilgrim"])
@pytest.mark.parametrize("name", DIALECT_NAMES)
def test_each_dialect_reads_back_the_plans_moves_and_dwells_in_seconds(name, cycle):
    plan = plan_test(0.0, 0.8, 17, runs=2, seed=7, cycle=cycle)
    program = gcode_program(plan, dialect=name, axis="Y", dwell_s=1.5, feed_mm_per_min=1500)
    motions = program_motions(program, dialect=name, source=f"cycle{DIALECTS[name].extension}")
    moves, dwells = _moves_and_dwells(motions)
    assert [m.kind for m in moves] == ["feed"] * plan.moves.size
    assert np.allclose([m.end_m["Y"] for m in moves], plan.moves, rtol=0, atol=0.5 * UM)
    assert all(m.feed_m_per_s == pytest.approx(1500 * MM / 60) for m in moves)
    assert len(dwells) == plan.readings and all(d.dwell_s == pytest.approx(1.5) for d in dwells)
    # a dwell follows exactly the moves that end at a target, and holds the axis there
    after_target = [motions[i + 1].kind == "dwell" for i, m in enumerate(motions) if m.kind == "feed" and i + 1 < len(motions)]
    expected = [not math.isnan(t) for t in plan.move_target][: len(after_target)]
    assert after_target == expected
    assert all(d.end_m["Y"] == pytest.approx(motions[i - 1].end_m["Y"]) for i, d in enumerate(motions) if d.kind == "dwell")


def test_the_linuxcnc_program_is_todays_program():
    plan = plan_test(0.0, 0.4, 5, runs=1, seed=1)
    lines = gcode_program(plan).splitlines()
    assert lines[:5] == ["%", f"(axiscal plan: {plan.description})",
                         "(a dwell follows every move that ends at a target: take the reading there)",
                         "G21 G90 G94", "G1 X-5.000 F2000"]
    assert lines[-2:] == ["M2", "%"] and lines.count("G4 P2") == plan.readings


@pytest.mark.parametrize(("name", "word"), [
    ("linuxcnc", "G4 P2"), ("grbl", "G4 P2"), ("fanuc", "G04 X2."), ("sinumerik", "G4 F2"),
    ("heidenhain", "CYCL DEF 9.1 DWELL 2"), ("marlin", "G4 P2000"), ("klipper", "G4 P2000"),
])
def test_each_dialect_writes_its_own_dwell_for_two_seconds(name, word):
    program = gcode_program(plan_test(0.0, 0.4, 5, runs=1, seed=1), dialect=name)
    assert sum(line.endswith(word) for line in program.splitlines()) == 10


def test_heidenhain_is_a_numbered_conversational_program_named_after_its_file(tmp_path):
    from axiscal.positioning.plan import write_plan

    plan = plan_test(0.0, 0.4, 5, runs=1, seed=1)
    (path,) = write_plan(plan, gcode_path=tmp_path / "x axis.h", dialect="heidenhain")
    lines = path.read_text().splitlines()
    assert lines[0] == "0 BEGIN PGM x_axis MM" and lines[-1] == f"{len(lines) - 1} END PGM x_axis MM"
    assert [int(line.split()[0]) for line in lines] == list(range(len(lines)))
    assert "CYCL DEF 9.0 DWELL TIME" in lines[5]


# the manuals' examples: (dialect, program, dwell in seconds or X position in mm)
DWELLS = [
    ("linuxcnc", "G21 G90\nG4 P0.5\nM2\n", 0.5),            # LinuxCNC G4: P seconds
    ("grbl", "G4 P0.5\n", 0.5),                              # Grbl v1.1: P seconds
    ("fanuc", "%\nO0001\nG04 X2.5\nM30\n%\n", 2.5),          # FANUC G04 X: seconds
    ("fanuc", "%\nO0001\nG04 P2500\nM30\n%\n", 2.5),         # FANUC G04 P: milliseconds
    ("fanuc", "%\nO0001\nG04 X2500\nM30\n%\n", 2.5),         # no decimal point: 0.001 s increments (IS-B)
    ("sinumerik", "N10 G4 F3\nM30\n", 3.0),                  # SINUMERIK G4 F: seconds
    ("heidenhain", "0 BEGIN PGM T MM\n1 CYCL DEF 9.0 DWELL TIME\n2 CYCL DEF 9.1 DWELL 1.5\n3 END PGM T MM\n", 1.5),
    ("marlin", "G4 P500\n", 0.5),                            # Marlin G4: P milliseconds
    ("marlin", "G4 S2\n", 2.0),                              # Marlin G4: S seconds
    ("klipper", "G4 P500\n", 0.5),                           # Klipper G4: P milliseconds
]


@pytest.mark.parametrize(("name", "program", "seconds"), DWELLS)
def test_the_manuals_dwells(name, program, seconds):
    (motion,) = program_motions(program, dialect=name)
    assert motion.kind == "dwell" and motion.dwell_s == pytest.approx(seconds, abs=1e-12)


def test_fanuc_reads_a_number_without_decimal_point_in_least_increments():
    motions = program_motions("%\nO0001\nG21\nG90 G94\nG01 X10 F100\nG01 X10.\nG20\nG01 X10\nM30\n%\n", dialect="fanuc")
    assert [round(m.end_m["X"] / MM, 6) for m in motions] == [0.01, 10.0, 0.0254]
    assert motions[0].feed_m_per_s == pytest.approx(100 * MM / 60)


def test_sinumerik_keeps_the_feed_across_a_dwell_and_refuses_revolutions():
    motions = program_motions("G71 G90 G94\nG1 X1 F600\nG4 F2\nG1 X2\nM30\n", dialect="sinumerik")
    assert [m.kind for m in motions] == ["feed", "dwell", "feed"]
    assert motions[2].feed_m_per_s == pytest.approx(0.01) and motions[1].dwell_s == 2.0
    with pytest.raises(AxiscalError, match=r"^p.mpf:2: G4 S counts spindle revolutions"):
        program_motions("G71 G90\nG4 S30\nM30\n", dialect="sinumerik", source="p.mpf")


def test_heidenhain_fmax_is_for_one_block_and_i_is_incremental():
    program = ("0 BEGIN PGM P MM\n1 L X+10 R0 F300\n2 L IX-2.5 Y+1 R0 FMAX\n3 L X+0 ; back\n"
               "4 * - a section\n5 END PGM P MM\n")
    motions = program_motions(program, dialect="heidenhain")
    assert [m.kind for m in motions] == ["feed", "rapid", "feed"]
    assert [round(m.end_m["X"] / MM, 9) for m in motions] == [10.0, 7.5, 0.0]
    assert motions[2].end_m["Y"] == pytest.approx(1 * MM) and motions[2].feed_m_per_s == pytest.approx(0.005)


def test_printers_move_g0_at_the_feed_and_units_follow_g20():
    motions = program_motions("G1 X1 F600\nG0 X2\nG20\nG91\nG1 X1\n", dialect="marlin")
    assert [m.kind for m in motions] == ["feed", "feed", "feed"]
    assert motions[2].end_m["X"] == pytest.approx(2 * MM + 25.4 * MM)
    motions = program_motions("G0 X1 F600\nG0 X2\n", dialect="grbl")
    assert [m.kind for m in motions] == ["rapid", "rapid"] and motions[0].feed_m_per_s is None


BAD = [
    ("linuxcnc", "G21 G90\n#1 = 2\nM2\n", 2, "cannot read '#1 = 2'"),
    ("linuxcnc", "G21 G90\nO100 sub\nM2\n", 2, "cannot read"),
    ("linuxcnc", "G21 G90\nG1 X1 F100 (open\nM2\n", 2, "not closed"),
    ("linuxcnc", "G1 X1 F100\nM2\n", 1, "before the units are set"),
    ("linuxcnc", "G21\nG1 X1 F100\nM2\n", 2, "before the distance mode is set"),
    ("linuxcnc", "G21 G90\nG1 X1\nM2\n", 2, "before any feed"),
    ("linuxcnc", "G21 G90\nG1 X1 F100\n", 2, "no end (M2, M30 or a closing %)"),
    ("linuxcnc", "G21 G90\nG81 X1 Z-1 R1\nM2\n", 2, "a canned cycle (G81) is not followed"),
    ("linuxcnc", "G21 G90\nG4 P1 X3\nM2\n", 2, "X is not a dwell word"),
    ("linuxcnc", "G21 G90\nM2\nG1 X1 F10\n", 3, "after the program end"),
    ("linuxcnc", "G21 G91\nG1 X1 F100\nM2\n", 2, "incremental move of X before its position is known"),
    ("fanuc", "%\nO0001\nG21\nG65 P9000\nM30\n%\n", 4, "macro call"),
    ("fanuc", "%\nO0001\nM98 P100\nM30\n%\n", 3, "subprogram call"),
    ("fanuc", "%\nO0001\nG04 P2.5\nM30\n%\n", 3, "milliseconds and takes no decimal point"),
    ("sinumerik", "G71 G90\nR1=5\nM30\n", 2, "cannot read"),
    ("sinumerik", "G71 G90\nG1 X1 G4 F2\nM30\n", 2, "block of its own"),
    ("grbl", "%\nG4 P1\n", 1, "'%' is not a Grbl block"),
    ("marlin", "G1 X1 Y2 F100 G4 P1\n", 1, "one G or M command a line"),
    ("marlin", "G1 X1 E2 F100 G4\n", 1, "one G or M command a line"),
    ("klipper", "G20\n", 1, "G20 is not a Klipper G code"),
    ("klipper", "G4 S2\n", 1, "S is not a dwell word of Klipper"),
    ("klipper", "PRINT_START\n", 1, "cannot read"),
    ("heidenhain", "L X+1 F100\n", 1, "starts with its block number"),
    ("heidenhain", "0 BEGIN PGM P INCH\n1 END PGM P INCH\n", 1, "inch programs"),
    ("heidenhain", "0 BEGIN PGM P MM\n1 CALL LBL 1\n2 END PGM P MM\n", 2, "cannot follow 'CALL LBL 1'"),
    ("heidenhain", "0 BEGIN PGM P MM\n1 CYCL DEF 200 DRILLING\n2 END PGM P MM\n", 2, "cannot follow"),
    ("heidenhain", "0 BEGIN PGM P MM\n1 L X+1 RL F100\n2 END PGM P MM\n", 2, "radius compensation RL"),
    ("heidenhain", "0 BEGIN PGM P MM\n1 L X+1 F100\n", 2, "no end (END PGM)"),
    ("heidenhain", "0 BEGIN PGM P MM\n1 END PGM Q MM\n", 2, "does not close"),
]


@pytest.mark.parametrize(("name", "program", "line", "message"), BAD)
def test_what_the_reader_cannot_follow_is_refused_naming_source_and_line(name, program, line, message):
    with pytest.raises(AxiscalError) as caught:
        program_motions(program, dialect=name, source="prog.txt")
    assert str(caught.value).startswith(f"prog.txt:{line}: ") and message in str(caught.value)


def test_bad_arguments():
    with pytest.raises(AxiscalError, match="unknown dialect 'haas'"):
        program_motions("G4 P1\n", dialect="haas")
    with pytest.raises(AxiscalError, match="text must be a str"):
        program_motions(b"G4 P1\n", dialect="grbl")
    with pytest.raises(AxiscalError, match="axis must be one letter of Klipper's axes"):
        gcode_program(plan_test(0.0, 0.4, 5, seed=1), dialect="klipper", axis="A")
    with pytest.raises(AxiscalError, match="no rapid move"):
        ProgramWriter("marlin").move({"X": 0.0}, feed_m_per_s=None)


def test_decimal_never_writes_an_exponent():
    assert decimal(1e-7, 3) == "0" and decimal(1.23456789e6, 3) == "1234567.89" and "e" not in decimal(1e20, 3)


STEPS = st.lists(
    st.one_of(
        st.tuples(st.just("move"), st.floats(-2.0, 2.0), st.sampled_from([None, 1e-4, 0.02, 1.5])),
        st.tuples(st.just("dwell"), st.floats(0.0, 100.0), st.none()),
    ),
    min_size=1, max_size=20,
)


@given(name=st.sampled_from(DIALECT_NAMES), steps=STEPS)
def test_what_the_writer_writes_the_reader_reads_back(name, steps):
    spec = DIALECTS[name]
    writer = ProgramWriter(name, comments=["round trip (with parentheses) ; and a semicolon"])
    expected = []
    feed = 0.01
    for kind, value, step_feed in steps:
        if kind == "dwell":
            writer.dwell(value)
            expected.append(("dwell", value))
            continue
        if step_feed is None and spec.rapid_at_feed:
            step_feed = feed
        writer.move({"X": value}, feed_m_per_s=step_feed)
        if step_feed is not None:
            feed = step_feed
        expected.append(("rapid" if step_feed is None else "feed", value, step_feed))
    motions = program_motions(writer.text(), dialect=name)
    assert len(motions) == len(expected)
    resolution = max(spec.dwell_words.values()) / 10**spec.dwell_places
    for motion, want in zip(motions, expected):
        assert motion.kind == want[0]
        if want[0] == "dwell":
            assert abs(motion.dwell_s - want[1]) <= resolution / 2 + 1e-9
        else:
            assert abs(motion.end_m["X"] - want[1]) <= 0.5 * UM + 1e-12
            if want[2] is not None:
                assert motion.feed_m_per_s == pytest.approx(want[2], rel=1e-6, abs=1e-3 * MM / 60)


@given(name=st.sampled_from(DIALECT_NAMES), data=st.data())
def test_a_mutated_program_is_read_or_refused_cleanly(name, data):
    text = gcode_program(plan_test(0.0, 0.4, 5, runs=1, seed=3), dialect=name)
    position = data.draw(st.integers(0, len(text)))
    cut = data.draw(st.integers(0, 3))
    insert = data.draw(st.text(alphabet="GMXPFSN0123456789.-+;()% #=\n\rLIR", max_size=4))
    mutated = text[:position] + insert + text[position + cut:]
    try:
        motions = program_motions(mutated, dialect=name, source="m")
    except AxiscalError as error:
        assert str(error).startswith("m:") and "\n" not in str(error)
    else:
        assert all(m.kind in ("rapid", "feed", "dwell") and m.dwell_s >= 0 for m in motions)


def _mm(motion, letter):
    return round(motion.end_m[letter] / MM, 9)


def test_arcs_by_centre_and_by_radius_in_each_plane():
    motions = program_motions("G21 G90 G17\nG0 X0 Y0 Z0\nG2 X10 Y0 I5 J0 F100\nG3 X0 Y0 R5 Z-1\nM2\n", dialect="linuxcnc")
    first, second = motions[1], motions[2]
    assert first.kind == "arc" and first.clockwise and first.plane == "XY"
    assert (round(first.centre_m["X"] / MM, 9), round(first.centre_m["Y"] / MM, 9)) == (5.0, 0.0)
    assert first.sweep_rad == pytest.approx(-math.pi) and second.sweep_rad == pytest.approx(math.pi)
    assert _mm(second, "Z") == -1.0 and second.feed_m_per_s == pytest.approx(100 * MM / 60)
    # a quarter circle clockwise by its radius: the centre on the right of the chord
    (quarter,) = program_motions("G0 X0 Y0\nG2 X10 Y10 R10 F60\n", dialect="grbl")[1:]
    assert round(quarter.centre_m["X"] / MM, 9) == 10.0 and abs(quarter.centre_m["Y"]) < 1e-15
    assert quarter.sweep_rad == pytest.approx(-math.pi / 2)
    # G18 is the ZX plane: centre offsets K (Z) and I (X); a full circle when the end is the start
    (full,) = program_motions("%\nO1\nG21\nG90 G94 G18\nG00 X0 Y0 Z0\nG02 I5. F100.\nM30\n%\n", dialect="fanuc")[1:]
    assert full.plane == "ZX" and full.sweep_rad == pytest.approx(-2 * math.pi)
    (yz,) = program_motions("G71 G90 G19\nG0 Y0 Z0\nG3 Y10 Z0 CR=5 F100\nM30\n", dialect="sinumerik")[1:]
    assert yz.plane == "YZ" and round(yz.centre_m["Y"] / MM, 9) == 5.0 and not yz.clockwise


def test_g92_and_the_work_offset_shift_program_coordinates_to_axis_positions():
    motions = program_motions("G21 G90\nG54 G0 X10\nG92 X0\nG0 X5\nG92.1\nG0 X5\nM2\n", dialect="linuxcnc",
                              work_offset_m={"X": 0.1})
    assert [_mm(m, "X") for m in motions] == [110.0, 115.0, 105.0]
    with pytest.raises(AxiscalError, match="prog:2: work offset G55 is not followed"):
        program_motions("G21 G90\nG55\nM2\n", dialect="linuxcnc", source="prog")


def test_the_extruder_follows_m83_and_g90_as_each_firmware_documents():
    program = "M83\nG1 X1 E0.5 F100\nG1 X2 E0.5\nG90\nG1 X3 E2\n"
    marlin = program_motions(program, dialect="marlin")
    klipper = program_motions(program, dialect="klipper")
    assert [_mm(m, "E") for m in marlin] == [0.5, 1.0, 2.0]      # Marlin: G90 makes E absolute again
    assert [_mm(m, "E") for m in klipper] == [0.5, 1.0, 3.0]     # Klipper: M83 holds until M82


@pytest.mark.parametrize(("program", "message"), [
    ("G21 G90\nG0 X0 Y0\nG2 X10 Y1 I5 J0 F100\nM2\n", "end point is not on its circle"),
    ("G21 G90\nG0 X0 Y0\nG2 X30 Y0 R5 F100\nM2\n", "shorter than half the distance"),
    ("G21 G90\nG0 X0 Y0\nG2 X10 Y0 I5 R5 F100\nM2\n", "not both"),
    ("G21 G90\nG0 X0 Y0\nG2 X10 Y0 K5 F100\nM2\n", "K is not a centre offset in the XY plane"),
    ("G21 G90\nG0 X0 Y0\nG1 X10 I5 F100\nM2\n", "without a circular move"),
])
def test_bad_arcs_are_refused_with_the_line(program, message):
    with pytest.raises(AxiscalError, match=f"^p:3: .*{message}"):
        program_motions(program, dialect="linuxcnc", source="p")
