"""Reading ballbar trace files: units, every refusal naming file and line, and mutated files."""

from __future__ import annotations

import csv
import io
import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from axiscal.circular.reader import read_ballbar
from axiscal.errors import AxiscalError
from axiscal.units import MM, UM

R = 100.0 * MM


def _lines(n: int = 40, unit: str = "um") -> list[str]:
    out = [f"angle_deg,direction,radius_deviation_{unit}"]
    for d in ("ccw", "cw"):
        for k in range(n):
            out.append(f"{k * 360.0 / n:.3f},{d},{math.sin(k) * 2:.4f}")
    return out


def _write(tmp_path, lines, name="run.csv"):
    path = tmp_path / name
    path.write_text("\n".join(lines) + "\n")
    return path


def test_the_shipped_example_reads(examples):
    trace = read_ballbar(examples / "ballbar" / "ballbar_run.csv", radius=R, plane="XY")
    assert trace.present == ("ccw", "cw") and trace.angles.size == 7200


@pytest.mark.parametrize("unit, factor", [("nm", 1e-9), ("um", UM), ("mm", MM)])
def test_units_of_the_deviation(tmp_path, unit, factor):
    trace = read_ballbar(_write(tmp_path, _lines(unit=unit)), radius=R)
    assert trace.deviations[1] == pytest.approx(round(math.sin(1) * 2, 4) * factor)


def test_other_columns_are_ignored_and_directions_any_case(tmp_path):
    lines = _lines()
    lines = [lines[0] + ",note"] + [line.replace("ccw", "CCW") + ",x" for line in lines[1:]]
    trace = read_ballbar(_write(tmp_path, lines), radius=R, plane="yz")
    assert trace.plane == "YZ" and trace.present == ("ccw", "cw")


@pytest.mark.parametrize(
    "edit, line, message",
    [
        (lambda ls: ls.__setitem__(5, "48.000,up,0.1"), 6, "not a direction"),
        (lambda ls: ls.__setitem__(7, "abc,ccw,0.1"), 8, "not a number"),
        (lambda ls: ls.__setitem__(9, "54.0,ccw,inf"), 10, "finite"),
        (lambda ls: ls.__setitem__(3, "18.0,ccw"), 4, "cells"),
        (lambda ls: ls.__setitem__(0, "angle_deg,direction,deviation_um"), 1, "no radius_deviation"),
        (lambda ls: ls.__setitem__(slice(None), [ls[0] + ",radius_deviation_nm"] + [x + ",0" for x in ls[1:]]), 1, "2 \\("),
        (lambda ls: ls.__setitem__(0, "angle_deg,direction,radius_deviation_in"), 1, "unknown length unit"),
        (lambda ls: ls.__setitem__(0, "angle,direction,radius_deviation_um"), 1, "missing column 'angle_deg'"),
    ],
)
def test_refusals_name_file_and_line(tmp_path, edit, line, message):
    lines = _lines()
    edit(lines)
    path = _write(tmp_path, lines)
    with pytest.raises(AxiscalError, match=message) as caught:
        read_ballbar(path, radius=R)
    assert caught.value.path == str(path) and caught.value.line == line


def test_a_gap_names_the_point_before_it(tmp_path):
    lines = [ln for ln in _lines(72) if not (ln.split(",")[1] == "cw" and 100.0 < float(ln.split(",")[0]) < 150.0)]
    path = _write(tmp_path, lines)
    with pytest.raises(AxiscalError, match="50.0 deg unmeasured after 100.00 deg") as caught:
        read_ballbar(path, radius=R)
    assert caught.value.line == next(k for k, ln in enumerate(lines, 1) if ln.startswith("100.000,cw,"))


def test_too_few_points_and_bad_settings(tmp_path):
    with pytest.raises(AxiscalError, match="at least 36") as caught:
        read_ballbar(_write(tmp_path, _lines(n=20)), radius=R)
    assert caught.value.line is not None
    path = _write(tmp_path, _lines())
    with pytest.raises(AxiscalError, match="radius") as caught:
        read_ballbar(path, radius=0.0)
    assert caught.value.path == str(path)
    with pytest.raises(AxiscalError, match="plane"):
        read_ballbar(path, radius=R, plane="XX")
    with pytest.raises(AxiscalError, match="not found"):
        read_ballbar(tmp_path / "missing.csv", radius=R)


def _reference_parse(text: str):
    """Plain reference: what a correct reader returns for a file it accepts (blank and # lines skipped)."""
    rows = [r for r in csv.reader(io.StringIO(text)) if r and "".join(r).strip() and not r[0].strip().startswith("#")]
    header = [c.strip() for c in rows[0]]
    i_a, i_d = header.index("angle_deg"), header.index("direction")
    i_v = header.index("radius_deviation_um")
    return (
        np.radians([float(r[i_a]) for r in rows[1:]]),
        tuple(r[i_d].strip().lower() for r in rows[1:]),
        np.array([float(r[i_v]) for r in rows[1:]]) * UM,
    )


_cells = st.one_of(
    st.sampled_from(["", "nan", "inf", "-1e400", "ccw", "CW", "cw ", "1e3", "-0", "x", '"', "1,2", "up"]),
    st.floats(allow_nan=False, allow_infinity=False, width=32).map(repr),
    st.text(alphabet=st.characters(blacklist_categories=("Cs",), blacklist_characters="\r\n\x0b\x0c\x1c\x1d\x1e\x85\u2028\u2029"), max_size=6),
)


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(
    mutation=st.sampled_from(["cell", "drop_cell", "add_cell", "drop_line", "duplicate_line", "insert_line", "header"]),
    row=st.integers(0, 80),
    col=st.integers(0, 2),
    value=_cells,
)
def test_mutated_files_parse_correctly_or_fail_with_file_and_line(tmp_path, mutation, row, col, value):
    lines = _lines()
    k = row % len(lines)
    cells = lines[k].split(",")
    if mutation == "cell":
        cells[col] = value
        lines[k] = ",".join(cells)
    elif mutation == "drop_cell":
        del cells[col]
        lines[k] = ",".join(cells)
    elif mutation == "add_cell":
        cells.insert(col, value)
        lines[k] = ",".join(cells)
    elif mutation == "drop_line":
        del lines[k]
    elif mutation == "duplicate_line":
        lines.insert(k, lines[k])
    elif mutation == "insert_line":
        lines.insert(k, value)
    else:
        header = lines[0].split(",")
        header[col] = value
        lines[0] = ",".join(header)
    text = "\n".join(lines) + "\n"
    path = tmp_path / "mutated.csv"
    path.write_text(text, encoding="utf-8")
    try:
        trace = read_ballbar(path, radius=R)
    except AxiscalError as exc:
        assert exc.path == str(path)
        assert exc.line is not None and 1 <= exc.line <= len(lines)
        return
    angles, directions, deviations = _reference_parse(text)
    np.testing.assert_array_equal(trace.angles, angles)
    assert trace.directions == directions
    np.testing.assert_array_equal(trace.deviations, deviations)
