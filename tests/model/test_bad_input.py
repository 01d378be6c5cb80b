"""Every bad input of the model room raises AxiscalError naming the file, key and line: never a traceback."""

from __future__ import annotations

import shutil
import warnings

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from axiscal.errors import AxiscalError
from axiscal.model import (
    MAX_DIAGONAL_STEPS,
    Axis,
    ErrorTable,
    Machine,
    as_machine,
    axis_positions_from_grid,
    diagonal_positions,
    diagonal_test,
    inverse_commands,
    load_machine,
    parse_chain,
    positions_from_points,
    volumetric_map,
)


@pytest.fixture
def machine_dir(tmp_path, examples):
    folder = tmp_path / "xfyz"
    shutil.copytree(examples / "xfyz_machine", folder)
    return folder


def edit(folder, old, new, name="machine.toml"):
    path = folder / name
    text = path.read_text()
    assert old in text
    path.write_text(text.replace(old, new, 1))
    return path


def line_of(path, needle):
    return next(i for i, line in enumerate(path.read_text().splitlines(), start=1) if needle in line)


_FIVE_AXIS = [  # (example folder, text, its replacement, text of the line named, words of the message)
    ("EX0C_um = 8.0", "EX0C_um = true", "EX0C_um", "finite number"),
    ("EX0C_um = 8.0", "EZ0C_um = 8.0", "EZ0C_um", "unknown term"),
    ("EX0C_um = 8.0", "EX0B_um = 8.0", "EX0B_um", "no axis B"),
    ("EX0C_um = 8.0", "EX0C_urad = 8.0", "EX0C_urad", "unit"),
    ("EA0C_urad = 15.0", "EA0C_urad = 1e9", "EA0C_urad", "no physical meaning"),
    ("periodic = false", 'periodic = "no"', "periodic", "true or false"),
    ('errors = "x_errors.csv"', 'errors = "x_errors.csv"\nperiodic = true', "periodic = true", "only a rotary axis"),
    ('chain = "CAFXYZ"', 'chain = "CAFXYZQ"', "chain", "not a linear axis"),
]


@pytest.mark.parametrize(
    ("example", "old", "new", "needle", "words"),
    [("trunnion_machine", *case) for case in _FIVE_AXIS] + [("xfyz_machine", *case) for case in [
        ('errors = "x_errors.csv"', 'errors = "x_errors.csv"\nhold_ends = "false"', "hold_ends", "true or false"),
        ("tool_mm = [0.0, 0.0, -150.0]", "tool_mm = [true, 0, 0]", "tool_mm", "3 finite numbers"),
        ("tool_mm = [0.0, 0.0, -150.0]", 'tool_mm = "150"', "tool_mm", "3 finite numbers"),
        ("tool_mm = [0.0, 0.0, -150.0]", "tool_mm = [0, 0, 1e300]", "tool_mm", "3 finite numbers"),
        ("EC0Y_arcsec = 4.0", 'EC0Y_arcsec = "4"', "EC0Y_arcsec", "finite number"),
        ("EC0Y_arcsec = 4.0", "EC0Y_arcsec = true", "EC0Y_arcsec", "finite number"),
        ("EC0Y_arcsec = 4.0", "EC0Y_arcsec = [4.0]", "EC0Y_arcsec", "finite number"),
        ("EC0Y_arcsec = 4.0", "EC0Y_arcsec = nan", "EC0Y_arcsec", "finite number"),
        ("EC0Y_arcsec = 4.0", "EC0Y_arcsec = 1e300", "EC0Y_arcsec", "not a squareness error"),
        ('chain = "XFYZ"', "chain = 5", "chain", "string"),
        ('chain = "XFYZ"', 'chain = "XFYQ"', "chain", "not a linear axis"),
        ('name = "3-axis machine tool XFYZ"', "name = 3", "name", "string"),
        ('origin_mm = [0.0, 0.0, 0.0]', 'origin_mm = [0.0, "a", 0.0]', "origin_mm", "3 finite numbers"),
        ('errors = "z_errors.csv"', "errors = 7", 'errors = 7', "string"),
        ('errors = "z_errors.csv"', 'errors = "z_errors.csv"\ninterpolation = "quintic"', "interpolation", "interpolation"),
        ('errors = "z_errors.csv"', 'errors = "z_errors.csv"\nspeed = 3', "speed", "unknown key"),
    ]],
)
def test_machine_file_values_of_the_wrong_kind_name_key_and_line(tmp_path, examples, example, old, new, needle, words):
    folder = tmp_path / example
    shutil.copytree(examples / example, folder)
    path = edit(folder, old, new)
    with pytest.raises(AxiscalError) as caught:
        load_machine(path)
    assert caught.value.path == str(path)
    assert caught.value.line == line_of(path, needle)
    assert words in caught.value.message


@pytest.mark.parametrize(
    ("chain", "term"), [("FXZ", "EC0Y"), ("FXZ", "EA0Z"), ("FXY", "EB0Z"), ("XFY", "EA0Z"), ("FYZ", "EC0Y")]
)
def test_a_squareness_term_of_an_axis_not_in_the_chain_is_refused(chain, term):
    axes = {k: Axis(k) for k in chain if k != "F"}
    with pytest.raises(AxiscalError, match=f"{term}.*{chain}"):
        Machine(chain, axes, squareness_rad={term: 1e-5})


def test_a_squareness_term_not_in_the_chain_names_the_line(examples, tmp_path):
    folder = tmp_path / "xz"
    shutil.copytree(examples / "xz_module", folder)
    path = edit(folder, "[squareness]", "[squareness]\nEC0Y_arcsec = 3.0")
    with pytest.raises(AxiscalError, match="EC0Y_arcsec: chain 'FXZ'") as caught:
        load_machine(path)
    assert caught.value.line == line_of(path, "EC0Y_arcsec")


@pytest.mark.parametrize("outside", ["/etc/shadow", "../outside.csv", "../../../../../../etc/passwd"])
def test_error_table_paths_stay_in_the_machine_folder_and_nothing_is_echoed(machine_dir, outside):
    (machine_dir.parent / "outside.csv").write_text("secret line\n")
    path = edit(machine_dir, '"x_errors.csv"', f'"{outside}"')
    with pytest.raises(AxiscalError) as caught:
        load_machine(path)
    assert caught.value.line == line_of(path, outside)
    assert "inside the machine file's folder" in caught.value.message
    assert "secret" not in str(caught.value) and "root:" not in str(caught.value)


def test_a_folder_the_user_names_may_hold_the_tables(machine_dir, tmp_path):
    shared = tmp_path / "tables"
    shared.mkdir()
    shutil.move(machine_dir / "x_errors.csv", shared / "x_errors.csv")
    path = machine_dir / "machine.toml"
    with pytest.raises(AxiscalError):
        load_machine(path)
    assert load_machine(path, tables_dir=shared).table("X").end_m == pytest.approx(0.8)


@pytest.mark.parametrize("value", ["1e308", "-1e308", "20000"])
def test_error_table_values_without_physical_meaning_name_the_line(machine_dir, value):
    edit(machine_dir, "8.081,5.2310", f"8.081,{value}", name="x_errors.csv")
    with pytest.raises(AxiscalError, match="no physical meaning|beyond any physical value") as caught:
        load_machine(machine_dir / "machine.toml")
    assert caught.value.path == str(machine_dir / "x_errors.csv")
    assert caught.value.line == 3


def test_error_table_rejects_values_and_hold_ends_of_the_wrong_kind():
    with pytest.raises(AxiscalError, match="beyond the largest"):
        ErrorTable("X", [0.0, 1.0], np.full((6, 2), 1.0))
    with pytest.raises(AxiscalError, match="hold_ends"):
        ErrorTable("X", [0.0, 1.0], np.zeros((6, 2)), hold_ends="false")


@pytest.mark.parametrize("spec", ["X=nan,Y=0,Z=0", "X=0:inf:1,Y=0,Z=0", "X=0:100:nan,Y=0,Z=0", "X=-inf,Y=0,Z=0"])
def test_grid_with_non_finite_numbers_is_refused(spec):
    with pytest.raises(AxiscalError, match="finite"):
        axis_positions_from_grid(spec)


def test_grid_too_large_is_refused_before_allocating():
    with pytest.raises(AxiscalError, match="more than"):
        axis_positions_from_grid("X=0:800:1e-9,Y=0,Z=0")
    with pytest.raises(AxiscalError, match="more than"):
        axis_positions_from_grid("X=0:800:0.01,Y=0:800:0.01,Z=0:800:0.01")


def test_grid_ends_on_the_table_end_it_names(tmp_path):
    table = tmp_path / "x.csv"
    table.write_text("position_mm,EXX_um\n0,0\n0.1,1\n0.2,2\n0.3,3\n")
    (tmp_path / "m.toml").write_text('chain = "FX"\n[axes.X]\nerrors = "x.csv"\n')
    result = volumetric_map(tmp_path / "m.toml", grid="X=0:0.3:0.1")
    assert result.positions_m["X"].size == 4
    assert result.error_m[-1, 0] == pytest.approx(3e-6)


@pytest.mark.parametrize("steps", [0, -1, MAX_DIAGONAL_STEPS + 1, 10**8, 2.5, True, "10"])
def test_diagonal_steps_out_of_bounds_are_refused(steps):
    with pytest.raises(AxiscalError, match="steps"):
        diagonal_positions({"X": 0.0}, {"X": 0.1}, steps)


def test_diagonal_points_must_be_finite():
    with pytest.raises(AxiscalError, match="finite"):
        diagonal_positions({"X": float("nan")}, {"X": 0.1}, 10)


def test_inverse_names_the_line_of_a_point_outside_the_tables(machine_dir, tmp_path):
    points = tmp_path / "targets.csv"
    points.write_text("x_mm,y_mm,z_mm\n-100,100,-200\n-100,900,-200\n")
    with pytest.raises(AxiscalError, match="outside the error table of axis Y") as caught:
        inverse_commands(machine_dir / "machine.toml", points)
    assert (caught.value.path, caught.value.line) == (str(points), 3)


@pytest.fixture
def xfyz(examples):
    return load_machine(examples / "xfyz_machine" / "machine.toml")


@pytest.mark.parametrize(
    ("call", "words"),
    [
        (lambda m: m.command_for([[0.1, 0.1, -0.2]], max_iterations=0), "max_iterations"),
        (lambda m: m.command_for([[0.1, 0.1, -0.2]], tolerance_m=-1.0), "tolerance"),
        (lambda m: m.command_for([[0.1, 0.1]]), "shape"),
        (lambda m: m.command_for([[0.1, float("nan"), -0.2]]), "point 1"),
        (lambda m: m.command_for("x"), "numbers"),
        (lambda m: m.volumetric_error({"X": [0.1], "Y": [0.1, 0.2], "Z": [0.0]}), "same number"),
        (lambda m: m.volumetric_error({"X": [float("nan")], "Y": [0.1], "Z": [0.0]}), "non-finite"),
        (lambda m: m.volumetric_error({"X": ["a"], "Y": [0.1], "Z": [0.0]}), "numbers"),
        (lambda m: m.volumetric_error([0.1, 0.1, 0.1]), "map"),
        (lambda m: m.volumetric_error({"X": [[0.1]], "Y": [0.1], "Z": [0.0]}), "one-dimensional"),
        (lambda m: m.table("X").evaluate([float("nan")]), "outside"),
        (lambda m: parse_chain(5), "string"),
        (lambda m: Machine(5, {}), "string"),
        (lambda m: axis_positions_from_grid(None), "string"),
        (lambda m: positions_from_points([{"X": "a"}]), "numbers"),
        (lambda m: positions_from_points([{"X": 1.0}, {"Y": 2.0}]), "point 2"),
        (lambda m: as_machine(5), "path"),
        (lambda m: volumetric_map(m, positions=5), "map"),
        (lambda m: volumetric_map(m, positions={"X": [0.1], "Y": [0.1], "Z": ["q"]}), "numbers"),
        (lambda m: diagonal_test(m, {"X": "a", "Y": 0, "Z": 0}, {"X": 0.1, "Y": 0, "Z": 0}), "finite number"),
        (lambda m: diagonal_test(m, 5, {"X": 0.1}), "map"),
        (lambda m: ErrorTable.from_components("X", [0, 1], {"EXX": [1e-6]}), "shape"),
        (lambda m: m.table("X").evaluate("a"), "numbers"),
        (lambda m: m.volumetric_error({"X": [0.1], "Y": [0.1], "Z": [-0.1]}, errors={"X": "a"}), "numbers"),
        (lambda m: Machine("FX", {"X": 5}), "must be an Axis"),
        (lambda m: Machine("FX", {"X": Axis("X", origin_m="abc")}), "numbers"),
        (lambda m: Machine("FX", {"X": Axis("X")}, tool_m=(True, 0, 0)), "numbers"),
        (lambda m: ErrorTable("X", [0, 1], np.zeros((6, 2), dtype=bool)), "numbers"),
    ],
)
def test_public_functions_raise_axiscal_error_for_bad_arguments(xfyz, call, words):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(AxiscalError, match=words):
            call(xfyz)


def test_ideal_axis_evaluated_at_nan_is_refused():
    with pytest.raises(AxiscalError, match="nan mm is outside"):
        ErrorTable.zeros("X").evaluate([float("nan")])


_JUNK = st.sampled_from(
    ['"false"', "true", "[true, 0, 0]", "1e308", "-1e400", "nan", "inf", '"/etc/shadow"', "[]", "{}", "[1, 2]",
     '"../x_errors.csv"', "0", "-5", '"XFYZ"', '"cubic"', '"x_errors.csv"', "1.5", '""', "[1.0, 2.0, 3.0]"]
)


@settings(max_examples=80, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(data=st.data())
def test_mutated_machine_files_parse_or_fail_cleanly(machine_dir, data):
    path = machine_dir / "machine.toml"
    original = (machine_dir.parent / "original.toml")
    if not original.exists():
        original.write_text(path.read_text())
    lines = original.read_text().splitlines()
    k = data.draw(st.sampled_from([i for i, line in enumerate(lines) if "=" in line]))
    key = lines[k].split("=")[0].strip()
    lines[k] = f"{key} = {data.draw(_JUNK)}"
    path.write_text("\n".join(lines) + "\n")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        try:
            machine = load_machine(path)
        except AxiscalError as exc:
            assert exc.path is not None and exc.line is not None, str(exc)
            assert "root:" not in str(exc)
        else:
            assert np.all(np.isfinite(machine.volumetric_error({k: [machine.travel_m(k)[0]] for k in machine.letters})))


_CELL = st.sampled_from(["1e308", "-1e308", "nan", "inf", "abc", "", "1e3", "0.5", "-3", "1e-300", "5"])


@settings(max_examples=80, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(data=st.data())
def test_mutated_error_tables_parse_or_fail_with_file_and_line(machine_dir, data):
    path = machine_dir / "y_errors.csv"
    original = machine_dir.parent / "original.csv"
    if not original.exists():
        original.write_text(path.read_text())
    rows = [line.split(",") for line in original.read_text().splitlines()]
    for _ in range(data.draw(st.integers(1, 3))):
        row = data.draw(st.integers(1, len(rows) - 1))
        column = data.draw(st.integers(0, len(rows[0]) - 1))
        rows[row][column] = data.draw(_CELL)
    path.write_text("\n".join(",".join(r) for r in rows) + "\n")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        try:
            machine = load_machine(machine_dir / "machine.toml")
        except AxiscalError as exc:
            assert exc.path == str(path) and exc.line is not None, str(exc)
        else:
            q = {k: np.linspace(*machine.travel_m(k), 5) for k in machine.letters}
            assert np.all(np.isfinite(machine.volumetric_error(q)))


@pytest.fixture
def trunnion_dir(tmp_path, examples):
    folder = tmp_path / "trunnion"
    shutil.copytree(examples / "trunnion_machine", folder)
    return folder


def test_a_periodic_table_longer_than_a_turn_names_the_file(trunnion_dir):
    edit(trunnion_dir, "position_deg", "position_deg", name="c_errors.csv")
    path = trunnion_dir / "c_errors.csv"
    path.write_text(path.read_text() + "400.000,0,0,0,0,0,0\n")
    with pytest.raises(AxiscalError, match="at most 360 deg") as caught:
        load_machine(trunnion_dir / "machine.toml")
    assert caught.value.path == str(path)
