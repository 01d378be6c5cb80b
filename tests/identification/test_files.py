"""Artefact files: written and read back, refused with one line naming file and line, and the CLI end to end."""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from axiscal.errors import AxiscalError
from axiscal.identification import r_test_positions, read_artefact, write_artefact
from axiscal.identification.simulate import (
    plate_grid,
    simulate_ball_plate,
    simulate_ballbar,
    simulate_multilateration,
    simulate_r_test,
    simulate_step_gauge,
)
from axiscal.model.machine import Axis, Machine, load_machine

CMM = Machine("FYXZ", {k: Axis(k) for k in "XYZ"})


def artefacts(rng):
    trunnion = Machine("CAFXYZ", {"A": Axis("A", origin_m=(0, 0, -0.3)), "C": Axis("C")} | {k: Axis(k) for k in "XYZ"}, tool_m=(0, 0, -0.15))
    angles = {"C": np.deg2rad(np.arange(0, 360, 45.0)), "A": np.deg2rad(np.full(8, -30.0))}
    grid = np.linspace(0.0, 0.3, 3)
    return [
        simulate_ball_plate(CMM, plate_grid(3, 0.1), np.eye(3), np.full(3, 0.05), np.zeros(3), noise_m=1e-7, rng=rng, repeats=2),
        simulate_step_gauge(CMM, np.zeros(3), np.array([1.0, 0, 0]), np.linspace(0, 0.3, 5), np.zeros(3), noise_m=1e-7, rng=rng),
        simulate_ballbar(CMM, np.array([[0.1, 0.1, 0.1]]), np.array([[0.2, 0.1, 0.1], [0.1, 0.2, 0.1], [0.1, 0.1, 0.2]]), np.zeros(3, int),
                         0.1, np.zeros(3), noise_m=1e-7, rng=rng),
        simulate_multilateration(CMM, np.array([[-0.5, 0.0, 0.0], [0.8, 0.1, 0.3]]), np.array([0.1, 0.2]),
                                 np.array(np.meshgrid(grid, grid, grid)).reshape(3, -1).T, np.zeros(3), noise_m=1e-7, rng=rng),
        simulate_r_test(trunnion, r_test_positions(trunnion, angles, np.array([0.1, 0.0, 0.05])), np.eye(3), noise_m=1e-7, rng=rng),
    ]


@pytest.mark.parametrize("index", range(5))
def test_an_artefact_written_reads_back_the_same(tmp_path, index):
    artefact = artefacts(np.random.default_rng(index))[index]
    back = read_artefact(write_artefact(artefact, tmp_path / "a.toml"))
    assert type(back) is type(artefact) and back.name == artefact.name
    assert np.allclose(back.tool_m, artefact.tool_m)
    for name in ("measured_m", "ends_m", "targets_m", "readings_m"):
        if hasattr(artefact, name):
            assert np.allclose(getattr(back, name), getattr(artefact, name), atol=1e-9)
    if hasattr(artefact, "lengths_m"):
        assert np.allclose(back.lengths_m, artefact.lengths_m, atol=1e-11)
    if hasattr(artefact, "ranges_m"):
        assert np.allclose(back.ranges_m, artefact.ranges_m, atol=1e-9)


def _plate(tmp_path: Path) -> Path:
    rng = np.random.default_rng(0)
    plate = simulate_ball_plate(CMM, plate_grid(3, 0.1), np.eye(3), np.full(3, 0.05), np.zeros(3), noise_m=1e-7, rng=rng)
    return write_artefact(plate, tmp_path / "plate.toml")


def test_an_unknown_ball_names_its_line(tmp_path):
    path = _plate(tmp_path)
    measured = tmp_path / "plate_measured.csv"
    lines = measured.read_text().splitlines()
    lines[3] = "99" + lines[3][lines[3].index(","):]
    measured.write_text("\n".join(lines) + "\n")
    with pytest.raises(AxiscalError) as caught:
        read_artefact(path)
    assert "unknown ball '99'" in str(caught.value) and str(caught.value).startswith(f"{measured}:4:")


def test_a_pose_that_is_not_orthonormal_names_its_line(tmp_path):
    path = _plate(tmp_path)
    text = path.read_text().replace('pose = "fit"\n', "")
    path.write_text(text + '\n[pose]\norigin_mm = [50, 50, 50]\nx_direction = [1, 0, 0]\ny_direction = [0.1, 0.995, 0]\n')
    with pytest.raises(AxiscalError) as caught:
        read_artefact(path)
    line = path.read_text().splitlines().index("y_direction = [0.1, 0.995, 0]") + 1
    assert str(caught.value).startswith(f"{path}:{line}: the pose is not orthonormal")


def test_a_direction_that_is_not_a_unit_vector_is_refused(tmp_path):
    path = _plate(tmp_path)
    text = path.read_text().replace('pose = "fit"\n', "")
    path.write_text(text + '\n[pose]\norigin_mm = [50, 50, 50]\nx_direction = [2, 0, 0]\ny_direction = [0, 1, 0]\n')
    with pytest.raises(AxiscalError, match="unit vector"):
        read_artefact(path)


def test_ranges_that_do_not_fit_name_their_line(tmp_path):
    from axiscal.identification import identify

    rng = np.random.default_rng(1)
    grid = np.linspace(0.0, 0.3, 3)
    tracker = simulate_multilateration(CMM, np.array([[-0.5, 0.0, 0.0], [0.8, 0.1, 0.3]]), np.array([0.1, 0.2]),
                                       np.array(np.meshgrid(grid, grid, grid)).reshape(3, -1).T, np.zeros(3), noise_m=1e-7, rng=rng)
    path = write_artefact(tracker, tmp_path / "t.toml")
    measured = tmp_path / "t_measured.csv"
    lines = measured.read_text().splitlines()
    cells = lines[7].split(",")
    cells[-1] = f"{float(cells[-1]) + 2.5:.6f}"
    lines[7] = ",".join(cells)
    measured.write_text("\n".join(lines) + "\n")
    with pytest.raises(AxiscalError) as caught:
        identify(CMM, [path], model="poly:1")
    assert str(caught.value).startswith(f"{measured}:8:") and "range does not fit" in str(caught.value)


def test_an_unknown_key_or_kind_names_its_line(tmp_path):
    path = _plate(tmp_path)
    text = path.read_text()
    path.write_text("colour = 3\n" + text)
    with pytest.raises(AxiscalError, match=r":1: unknown key .colour."):
        read_artefact(path)
    path.write_text('kind = "laser"\n')
    with pytest.raises(AxiscalError, match=r":1: kind must be one of"):
        read_artefact(path)


@settings(max_examples=60, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(kind=st.integers(0, 4), row=st.integers(0, 9), column=st.integers(0, 7),
       text=st.sampled_from(["", "x", "nan", "1e400", "-", "7", "1,2", "inf", "\"q\"", "1e-300", "-0"]))
def test_every_reader_fed_a_mutated_measurement_file_refuses_it_cleanly_or_reads_it(tmp_path_factory, kind, row, column, text):
    folder = tmp_path_factory.mktemp("mutated")
    path = write_artefact(artefacts(np.random.default_rng(kind))[kind], folder / "a.toml")
    measured = folder / "a_measured.csv"
    lines = measured.read_text().splitlines()
    row %= len(lines)
    cells = lines[row].split(",")
    cells[column % len(cells)] = text
    lines[row] = ",".join(cells)
    measured.write_text("\n".join(lines) + "\n")
    try:
        artefact = read_artefact(path)
    except AxiscalError as exc:
        assert str(exc).startswith(str(measured)), str(exc)
    else:
        for name in ("measured_m", "ends_m", "targets_m", "readings_m", "lengths_m", "ranges_m"):
            if hasattr(artefact, name):
                assert np.all(np.isfinite(getattr(artefact, name)))


def test_the_command_line_writes_a_machine_folder_that_volumetric_reads(tmp_path, examples, run_cli):
    folder = examples / "identification"
    plates = sorted(str(p) for p in folder.glob("plate_*.toml"))
    status, out, err = run_cli("identify", str(folder / "start" / "machine.toml"), *plates, "--model", "poly:3", "-o", str(tmp_path / "out"))
    assert status == 0, err
    assert "identified" in out and "plate_xz (ball_plate)" in out
    machine = load_machine(tmp_path / "out" / "machine.toml")
    assert machine.chain == "FYXZ" and machine.travel_m("X") == pytest.approx((0.0, 0.5))
    summary = json.loads((tmp_path / "out" / "identify.json").read_text())
    assert set(summary["residuals"]) == {"plate_xy", "plate_xz", "plate_xz_probe_y", "plate_yz"}
    assert len(summary["covariance_si"]["matrix"]) == len(summary["covariance_si"]["names"])
    assert summary["residual_std_um"] < 0.3  # the plates were measured with 0.2 um of noise
    html = (tmp_path / "out" / "identify.html").read_text()
    assert "Identification from artefacts: moving-bridge CMM" in html
    # self-contained: the plots inline (residuals of 4 plates, motions of 3 axes), nothing linked
    assert html.count("<svg") == 7 and "<img" not in html and 'src="' not in html
    text = re.sub(r"<svg.*?</svg>", "", html, flags=re.S)
    axes = re.findall(r"<figcaption>Axis ([A-Z]):", text)
    assert axes == ["X", "Y", "Z"]
    assert not re.search(r"\de[+-]\d", text)                         # no 4.5e+05
    assert re.search(r"<tr><td>plate_xz:ty</td><td class=\"num\">450\.0\d{3}</td>.*?<td>mm</td>", text)
    assert text.count("k = 2") == 1 and "k = 2 band" not in text     # the coverage factor stated once
    assert re.search(r"<th>Date</th><td>\d{4}-\d\d-\d\d</td>", text)
    status, out, err = run_cli("volumetric", "--machine", str(tmp_path / "out" / "machine.toml"), "--grid", "X=0:500:250,Y=0:500:250,Z=100")
    assert status == 0 and len(out.splitlines()) == 10


def test_the_command_line_refuses_a_bad_artefact_in_one_line(tmp_path, run_cli):
    path = _plate(tmp_path)
    path.write_text(path.read_text().replace('kind = "ball_plate"', 'kind = "plate"'))
    (tmp_path / "m.toml").write_text('chain = "FYXZ"\n[axes.X]\nerrors = "x.csv"\n[axes.Y]\nerrors = "x.csv"\n[axes.Z]\nerrors = "x.csv"\n')
    status, out, err = run_cli("identify", str(tmp_path / "m.toml"), str(path), "-o", str(tmp_path / "o"))
    assert status == 2 and len(err.strip().splitlines()) == 1 and "Traceback" not in err


def test_the_command_line_keeps_fixed_terms_and_prints_json(tmp_path, examples, run_cli):
    folder = examples / "identification"
    status, out, err = run_cli("identify", str(folder / "start" / "machine.toml"), str(folder / "plate_xy.toml"), str(folder / "plate_xz.toml"),
                               "--model", "poly:1", "--fix", "squareness", "--fix", "Z", "--json", "-o", str(tmp_path / "out"))
    assert status == 0, err
    summary = json.loads(out)
    names = {p["name"] for p in summary["parameters"] if p["machine"]}
    assert not names & {"EC0Y", "EB0Z", "EA0Z", "EZZ:1", "ECZ:1"} and "EXX:1" in names
    assert set(summary["fixed"]) >= {"EC0Y", "EZZ:1"}
    status, out, err = run_cli("identify", str(folder / "start" / "machine.toml"), str(folder / "plate_xy.toml"),
                               "--fix", "EQQ", "-o", str(tmp_path / "o2"))
    assert status == 2 and "--fix EQQ" in err and len(err.strip().splitlines()) == 1


def test_a_mutated_certificate_is_refused_cleanly_or_read(tmp_path):
    path = _plate(tmp_path)
    certificate = tmp_path / "plate_certificate.csv"
    original = certificate.read_text()
    for row, column, text in ((1, 4, "-1"), (2, 0, "1"), (3, 1, "abc"), (0, 4, "V_um")):
        lines = original.splitlines()
        cells = lines[row].split(",")
        cells[column] = text
        lines[row] = ",".join(cells)
        certificate.write_text("\n".join(lines) + "\n")
        try:
            read_artefact(path)
        except AxiscalError as exc:
            assert str(exc).startswith(str(certificate)), str(exc)


def test_an_r_test_file_may_give_the_rotary_axes_only_and_the_ball_on_the_table(tmp_path):
    rtest = artefacts(np.random.default_rng(4))[4]
    path = write_artefact(rtest, tmp_path / "r.toml")
    measured = tmp_path / "r_measured.csv"
    table = [line.split(",") for line in measured.read_text().splitlines()]
    keep = [k for k, name in enumerate(table[0]) if not name.endswith("_mm")]
    measured.write_text("\n".join(",".join(row[k] for k in keep) for row in table) + "\n")
    path.write_text(path.read_text().replace("sensors =", "ball_on_table_mm = [100, 0, 50]\nsensors =", 1))
    machine = Machine("CAFXYZ", {"A": Axis("A", origin_m=(0, 0, -0.3)), "C": Axis("C")} | {k: Axis(k) for k in "XYZ"})
    positions = read_artefact(path).positions(machine)
    for letter in "XYZ":
        assert np.allclose(positions[letter], rtest.axis_positions_m[letter], atol=1e-12)


@pytest.mark.parametrize("folder", ["xfyz_machine", "trunnion_machine"])
def test_a_machine_folder_written_reads_back_the_same_machine(tmp_path, examples, folder):
    from axiscal.identification import write_machine_folder

    machine = load_machine(examples / folder / "machine.toml")
    again = load_machine(write_machine_folder(machine, tmp_path / "m"))
    rng = np.random.default_rng(0)
    positions = {k: rng.uniform(*machine.travel_m(k), 200) for k in machine.letters}
    assert np.allclose(again.volumetric_error(positions), machine.volumetric_error(positions), atol=1e-12)


def test_a_stated_pose_is_checked_against_the_readings_and_refined(tmp_path):
    import dataclasses

    from axiscal.identification import identify

    rng = np.random.default_rng(2)
    plate = simulate_ball_plate(CMM, plate_grid(3, 0.1), np.eye(3), np.full(3, 0.05), np.zeros(3), noise_m=1e-7, rng=rng)
    stated = dataclasses.replace(plate, rotation=np.eye(3), origin_m=np.full(3, 0.05))
    back = read_artefact(write_artefact(stated, tmp_path / "posed.toml"))
    assert np.allclose(back.rotation, np.eye(3)) and np.allclose(back.origin_m, 0.05)
    assert identify(CMM, [back], model="poly:1").residual_std < 1e-6
    moved = dataclasses.replace(stated, origin_m=np.array([0.05, 0.05, 0.06]))
    with pytest.raises(AxiscalError, match="where the stated pose does not put it"):
        identify(CMM, [moved], model="poly:1")
