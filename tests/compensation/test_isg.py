"""ISG CSV parameter files and TwinCAT CNC compensation lists: the manuals' own examples read, and every file written read back.

Sources: Beckhoff Information System, TF5280 TwinCAT 3 CNC Volumetric Compensation, "ISG CSV format"
(infosys.beckhoff.com/content/1033/tf5280_volumetric_comp/296429067.html), "Units of measure"
(isg-stuttgart.de/fileadmin/kernel/kernel-html/en-GB/296426379.html), "Updating the Volumetric
Compensation" (.../tf5280_volumetric_comp/1218769547.html); TF5200 Axis compensation, "Example -
Non-equidistant bilateral SSFK" (infosys.beckhoff.com/content/1033/tf5200_axis_compensation/308695435.html).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from axiscal.compensation import (
    ErrorCurve,
    IsgTable,
    grid_values,
    parse_isg_csv,
    parse_twincat_table,
    read_isg_csv,
    twincat_table,
    volcomp_list_text,
)
from axiscal.errors import AxiscalError
from axiscal.units import MM, UM

# the manual's "Component errors of the X axis for Z = 0 and Z = 100", then (after a file break)
# its "Updating" example's grid of X Y Z EXX EYY, with its row comments
MANUAL = """// The argument "Z" now crops up in the header.
Z      X      EXX    EYX    EZX    EAX    EBX    ECX
// In the first block Z is always = 0.
0.0    0.0    0.02   0.01   0.07   0.00   0.0042 0.003
0.0    10.0   0.00   -0.1   0.01   0.00   0.0011 0.002
// In the second block Z is always = 100.
100.0  0.0    0.01   0.02   0.03   0.07   0.0040 0.003
100.0  10.0   0.03   -0.09  0.03   0.06   0.0015 0.000
#
X Y Z EXX EYY
0 0 0 0.000 0.000
0 5 0 0.001 0.001
0 10 0 0.002 0.002
"""


def test_the_manuals_examples_are_read_in_si():
    sag, grid = parse_isg_csv(MANUAL)
    assert sag.arguments == ("Z", "X") and sag.parameters == ("EXX", "EYX", "EZX", "EAX", "EBX", "ECX")
    # offsets in millimetres, angles in radians (Units of measure)
    assert sag.argument_si[2].tolist() == [0.1, 0.0]
    assert sag.parameter_si[0, 0] == pytest.approx(0.02 * MM) and sag.parameter_si[1, 1] == pytest.approx(-0.1 * MM)
    assert sag.parameter_si[0, 4] == 0.0042 and sag.parameter_si[3, 3] == 0.06
    assert grid.arguments == ("X", "Y", "Z") and grid.parameters == ("EXX", "EYY")
    assert grid.parameter_si[:, 1] == pytest.approx([0.0, 1 * UM, 2 * UM])
    nodes, values = grid_values(grid)
    assert nodes["Y"].tolist() == [0.0, 0.005, 0.01] and values.shape == (1, 3, 1, 2)


def test_bad_files_name_the_line():
    cases = {
        "X EXX\n0 0.1\n10\n": ":3: 1 values where the header names 2 columns",
        "X EXX\n0 0.1\n10 abc\n": ":3: 'abc' is not a number",
        "// header\nX QXX\n0 1\n": ":2: 'QXX' is not an ISG argument",
        "EXX X\n1 0\n": ":1: the arguments come before the error parameters",
        "X EXX EXX\n0 1 2\n": ":1: a column is named twice",
    }
    for text, message in cases.items():
        with pytest.raises(AxiscalError) as caught:
            parse_isg_csv(text, source="v.csv")
        assert str(caught.value).startswith("v.csv" + message), str(caught.value)


def test_the_volcomp_list_holds_the_manuals_keys():
    text = volcomp_list_text(["volcomp1.csv"], workpiece_axes=0)
    pairs = [line.split() for line in text.splitlines()]
    assert pairs == [["workpiece_axes", "0"], ["X", "1"], ["Y", "2"], ["Z", "3"], ["interpolation", "GRID"],
                     ["file[0]", "volcomp1.csv"], ["file_format[0]", "ISG_CSV"]]


finite = st.floats(-1e3, 1e3, allow_nan=False)


@settings(max_examples=40, deadline=None)
@given(st.integers(1, 12), st.data())
def test_a_written_table_reads_back_to_its_resolution(rows, data):
    arguments = data.draw(st.sampled_from([("X",), ("X", "Y", "Z"), ("Z", "X"), ("C",), ()]))
    parameters = data.draw(st.sampled_from([("EXX", "EYY", "EZZ"), ("EYX", "EAX", "EBX", "ECX"), ("C0Y", "B0Z", "X0Y")]))
    arguments_si = np.array(data.draw(st.lists(st.lists(finite, min_size=len(arguments), max_size=len(arguments)),
                                               min_size=rows, max_size=rows)), dtype=float).reshape(rows, len(arguments))
    arguments_si *= np.array([math.pi / 180 if a in "ABC" else MM for a in arguments])
    values = np.array(data.draw(st.lists(st.lists(st.floats(-1, 1), min_size=len(parameters), max_size=len(parameters)),
                                         min_size=rows, max_size=rows)), dtype=float)
    values *= np.array([1e-3 if p[1 if p.startswith("E") else 0] in "ABC" else 1e-4 for p in parameters])
    table = IsgTable(arguments, parameters, arguments_si, values)
    (back,) = parse_isg_csv(table.text())
    assert back.arguments == arguments and back.parameters == parameters
    # arguments to 1e-6 mm or 1e-6 degree
    step = np.array([math.radians(0.5e-6) if a in "ABC" else 0.5e-6 * MM for a in arguments])
    assert np.all(np.abs(back.argument_si - arguments_si) <= step * (1 + 1e-6) + 1e-15)
    resolution = np.array([0.5e-10 if p[1 if p.startswith("E") else 0] in "ABC" else 0.5e-7 * MM for p in parameters])
    assert np.all(np.abs(back.parameter_si - values) <= resolution * (1 + 1e-6) + 1e-18)


def test_read_isg_csv_names_the_file(tmp_path):
    path = tmp_path / "volcomp.csv"
    path.write_text(MANUAL)
    assert len(read_isg_csv(path)) == 2
    path.write_text("X EXX\n0 nan\n")
    with pytest.raises(AxiscalError, match=rf"^{path}:2: a value is not a finite number$"):
        read_isg_csv(path)


def test_the_ssfk_list_of_the_manual_reads_back():
    # the manual's third gauged point: programmed 19866.7 um, reached 19856.5 (+) and 19874.7 um (-),
    # entered as -102 and 80 (0.1 um); the list read back gives the same numbers
    text = """kopf.achs_nr                        2
kopf.log_achs_name                    Y_AXIS
kw.ssfk.interval                    0
kw.ssfk.kw_startpos                 -200000
kw.ssfk.kw_nr_max                   3
kw.ssfk.unit                        1
kw.ssfk.bilateral                   1
kw.ssfk.table[0].setpoint           -200000
kw.ssfk.table[1].setpoint           -199306
kw.ssfk.table[2].setpoint           -198667
kw.ssfk.table[0].pos                0
kw.ssfk.table[1].pos                24
kw.ssfk.table[2].pos                -102
kw.ssfk.table[0].neg                0
kw.ssfk.table[1].neg                67
kw.ssfk.table[2].neg                80
"""
    table = parse_twincat_table(text)
    assert table.axis == "Y_AXIS" and table.axis_number == 2 and table.bilateral
    assert table.setpoints.tolist() == [-200000, -199306, -198667]
    assert table.pos.tolist() == [0, 24, -102] and table.neg.tolist() == [0, 67, 80]
    again = parse_twincat_table(table.text())
    assert again.setpoints.tolist() == table.setpoints.tolist() and again.neg.tolist() == table.neg.tolist()


@pytest.mark.parametrize("interval_m", [None, 0.01])
@pytest.mark.parametrize("bilateral", [True, False])
def test_a_written_ssfk_list_reads_back_whole(interval_m, bilateral):
    rng = np.random.default_rng(4)
    positions = np.linspace(0.0, 0.5, 11)
    curve = ErrorCurve(positions, rng.normal(size=11) * 5 * UM, rng.normal(size=11) * 5 * UM)
    table = twincat_table(curve, axis="X", axis_number=1, interval_m=interval_m, bilateral=bilateral)
    back = parse_twincat_table(table.text(), source="x.lis")
    for field in ("setpoints", "pos", "neg"):
        assert getattr(back, field).tolist() == getattr(table, field).tolist()
    assert (back.interval, back.bilateral, back.axis, back.axis_number) == (table.interval, bilateral, "X", 1)
    with pytest.raises(AxiscalError, match=r"^x\.lis: the list has no kw\.ssfk\.table\[10\]\.pos$"):
        parse_twincat_table(table.text().replace("kw.ssfk.table[10].pos", "# gone"), source="x.lis")


def test_the_volcomp_list_declares_the_chain_and_refuses_one_number_twice():
    text = volcomp_list_text(["v.csv"], workpiece_axes=1, chain="XYZ")
    assert [line.split() for line in text.splitlines()][:3] == [["chain", "XYZ"], ["workpiece_axes", "1"], ["X", "1"]]
    with pytest.raises(AxiscalError, match=r"^axes X and Z are both given logical axis number 1$"):
        volcomp_list_text(["v.csv"], axis_numbers={"X": 1, "Y": 2, "Z": 1})
    with pytest.raises(AxiscalError, match=r"^chain must name each numbered axis \(X, Y, Z\) once, not 'XXZ'$"):
        volcomp_list_text(["v.csv"], chain="XXZ")
