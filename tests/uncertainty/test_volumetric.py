"""The volumetric map with uncertainty: Monte Carlo through the HTM model, files with _u columns, Dask."""

from __future__ import annotations

import shutil

import numpy as np
import pytest

from axiscal.errors import AxiscalError
from axiscal.model import load_machine
from axiscal.uncertainty import (
    MachineUncertainty,
    load_machine_uncertainty,
    volumetric_monte_carlo,
)


@pytest.fixture(scope="module")
def machine(tmp_path_factory):
    from pathlib import Path

    return load_machine(Path(__file__).resolve().parents[2] / "examples" / "xfyz_machine" / "machine.toml")


def zero_u(machine):
    return {k: np.zeros_like(machine.table(k).values) for k in machine.letters}


def points(machine, n=40, seed=0):
    rng = np.random.default_rng(seed)
    return {k: rng.uniform(*machine.travel_m(k), n) for k in machine.letters}


def test_one_positioning_error_reaches_the_point_through_the_interpolation(machine):
    """u(EXX) = 1 um on every row alone: the point between rows i, i+1 at fraction f has u sqrt((1-f)^2 + f^2)."""
    tables = zero_u(machine)
    tables["X"] = tables["X"].copy()
    tables["X"][0] = 1e-6
    q = points(machine)
    result = volumetric_monte_carlo(machine, MachineUncertainty(tables, {}), q, 20_000, seed=3)
    pos = machine.table("X").position_m
    i = np.clip(np.searchsorted(pos, q["X"], side="right") - 1, 0, pos.size - 2)
    f = (q["X"] - pos[i]) / (pos[i + 1] - pos[i])
    expected = 1e-6 * np.sqrt((1 - f) ** 2 + f**2)
    np.testing.assert_allclose(result.std[:, 0], expected, rtol=0.03)
    np.testing.assert_allclose(result.std[:, 1:], 0.0, atol=1e-10)  # only through the small angles (~30 urad)
    # a normal output: the 95 % interval is error +- 1.96 u
    np.testing.assert_allclose(result.high[:, 0] - result.error[:, 0], 1.96 * expected, rtol=0.05)
    np.testing.assert_allclose(result.mean, result.error, atol=0.05e-6)


def test_squareness_uncertainty_grows_with_the_arm(machine):
    """u(EC0Y) alone turns the Y guideway: u(ex) = u |y| (Y carries the tool at x offset 0)."""
    u = 2e-6  # rad
    q = points(machine)
    result = volumetric_monte_carlo(machine, MachineUncertainty(zero_u(machine), {"EC0Y": u}), q, 20_000, seed=4)
    np.testing.assert_allclose(result.std[:, 0], u * np.abs(q["Y"]), rtol=0.03, atol=1e-12)
    np.testing.assert_allclose(result.std[:, 2], 0.0, atol=1e-10)


def test_no_uncertainty_gives_the_model(machine):
    q = points(machine, 10)
    result = volumetric_monte_carlo(machine, MachineUncertainty(zero_u(machine), {}), q, 100)
    np.testing.assert_allclose(result.low, result.error, atol=1e-11)
    np.testing.assert_allclose(result.error, machine.volumetric_error(q))


def test_same_seed_same_result_whatever_the_chunks_sizes_stay(machine):
    q = points(machine, 20)
    u = MachineUncertainty({k: np.full_like(v, 1e-6) for k, v in zero_u(machine).items()}, {"EB0Z": 1e-6})
    a = volumetric_monte_carlo(machine, u, q, 500, seed=9, chunk_draws=100)
    b = volumetric_monte_carlo(machine, u, q, 500, seed=9, chunk_draws=100)
    np.testing.assert_array_equal(a.low, b.low)


def write_machine_with_u(examples, folder):
    for name in ("machine.toml", "y_errors.csv", "z_errors.csv"):
        shutil.copy(examples / "xfyz_machine" / name, folder / name)
    lines = (examples / "xfyz_machine" / "x_errors.csv").read_text().splitlines()
    out = [lines[0] + ",EXX_um_u,EAX_urad_u"] + [line + ",0.5,2.0" for line in lines[1:]]
    (folder / "x_errors.csv").write_text("\n".join(out) + "\n")
    toml = (folder / "machine.toml").read_text().replace("EC0Y_arcsec = 4.0", "EC0Y_arcsec = 4.0\nEC0Y_arcsec_u = 1.0")
    (folder / "machine.toml").write_text(toml)
    return folder / "machine.toml"


def test_files_with_u_columns(examples, tmp_path):
    path = write_machine_with_u(examples, tmp_path)
    machine, u = load_machine_uncertainty(path)
    reference = load_machine(examples / "xfyz_machine" / "machine.toml")
    np.testing.assert_array_equal(machine.table("X").values, reference.table("X").values)
    assert machine.squareness_rad == reference.squareness_rad
    np.testing.assert_allclose(u.tables["X"][0], 0.5e-6)
    np.testing.assert_allclose(u.tables["X"][3], 2.0e-6)
    np.testing.assert_array_equal(u.tables["X"][[1, 2, 4, 5]], 0.0)
    assert not np.any(u.tables["Y"])
    assert u.squareness_rad["EC0Y"] == pytest.approx(np.deg2rad(1 / 3600))


def test_bad_u_columns_name_the_file(examples, tmp_path):
    path = write_machine_with_u(examples, tmp_path)
    csv = tmp_path / "x_errors.csv"
    csv.write_text(csv.read_text().replace(",0.5,2.0\n", ",-0.5,2.0\n", 1))
    with pytest.raises(AxiscalError) as info:
        load_machine_uncertainty(path)
    assert info.value.path == str(csv) and info.value.line == 2 and "negative" in info.value.message
    csv.write_text(csv.read_text().replace("EXX_um_u", "EQQ_um_u"))
    with pytest.raises(AxiscalError, match="no error column") as info:
        load_machine_uncertainty(path)
    assert info.value.path == str(csv)


def test_a_bad_table_value_names_the_original_file(examples, tmp_path):
    path = write_machine_with_u(examples, tmp_path)
    csv = tmp_path / "x_errors.csv"
    lines = csv.read_text().splitlines()
    lines[3] = "abc" + lines[3][lines[3].index(","):]
    csv.write_text("\n".join(lines) + "\n")
    with pytest.raises(AxiscalError) as info:
        load_machine_uncertainty(path)
    assert info.value.path == str(csv)


def test_bad_arguments(machine):
    q = points(machine, 5)
    with pytest.raises(AxiscalError, match="draws"):
        volumetric_monte_carlo(machine, MachineUncertainty(zero_u(machine), {}), q, 0)
    with pytest.raises(AxiscalError, match="shape"):
        volumetric_monte_carlo(machine, MachineUncertainty({"X": np.zeros(3)}, {}), q, 100)
    with pytest.raises(AxiscalError, match="squareness"):
        volumetric_monte_carlo(machine, MachineUncertainty(zero_u(machine), {"EXY": 1e-6}), q, 100)
    far = dict(q, X=q["X"] + 10.0)
    with pytest.raises(AxiscalError, match="outside"):
        volumetric_monte_carlo(machine, MachineUncertainty({k: np.full_like(v, 1e-6) for k, v in zero_u(machine).items()}, {}), far, 100)


def test_dask_local_cluster_gives_the_same_interval(machine):
    pytest.importorskip("dask.distributed")
    from dask.distributed import Client, LocalCluster

    q = points(machine, 30)
    u = MachineUncertainty({k: np.full_like(v, 1e-6) for k, v in zero_u(machine).items()}, {"EA0Z": 1e-6})
    here = volumetric_monte_carlo(machine, u, q, 400, seed=11, chunk_draws=100)
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, Client(cluster) as client:
        assert len(client.scheduler_info()["workers"]) == 2
        there = volumetric_monte_carlo(machine, u, q, 400, seed=11, chunk_draws=100, scheduler=client)
    np.testing.assert_array_equal(here.low, there.low)
    np.testing.assert_array_equal(here.high, there.high)


def test_written_map_reads_with_plain_pandas(machine, tmp_path):
    import json

    import pandas as pd

    from axiscal.uncertainty import write_volumetric_uncertainty

    q = points(machine, 7)
    u = MachineUncertainty({k: np.full_like(v, 1e-6) for k, v in zero_u(machine).items()}, {})
    result = volumetric_monte_carlo(machine, u, q, 200, seed=1)
    path = write_volumetric_uncertainty(tmp_path / "map.csv", q, result)
    frame = pd.read_csv(path)
    expected = ["x_mm", "y_mm", "z_mm"] + [f"{e}_{s}um" for e in ("ex", "ey", "ez", "e") for s in ("", "u_", "low_", "high_")]
    assert list(frame.columns) == expected and len(frame) == 7
    np.testing.assert_allclose(frame["ex_high_um"], result.high[:, 0] * 1e6, atol=1e-6)
    np.testing.assert_allclose(frame["x_mm"], q["X"] * 1e3, atol=1e-6)
    np.testing.assert_allclose(frame["e_um"], np.linalg.norm(result.error, axis=1) * 1e6, atol=1e-6)
    assert np.all(frame["e_low_um"] <= frame["e_high_um"])
    side = json.loads((tmp_path / "map.json").read_text())
    assert side["draws"] == 200 and side["probability"] == 0.95
    with pytest.raises(AxiscalError, match="points"):
        write_volumetric_uncertainty(tmp_path / "bad.csv", points(machine, 3), result)


def test_bad_squareness_u_key_names_its_line(examples, tmp_path):
    path = write_machine_with_u(examples, tmp_path)
    path.write_text(path.read_text().replace("EC0Y_arcsec_u = 1.0", "EC0Y_arcsec_u = -1.0"))
    with pytest.raises(AxiscalError, match="non-negative") as info:
        load_machine_uncertainty(path)
    line = path.read_text().splitlines().index("EC0Y_arcsec_u = -1.0") + 1
    assert info.value.path == str(path) and info.value.line == line
    path.write_text(path.read_text().replace("EC0Y_arcsec_u = -1.0", "EQ0Y_arcsec_u = 1.0"))
    with pytest.raises(AxiscalError, match="no squareness term"):
        load_machine_uncertainty(path)


def test_interval_of_the_length_follows_a_single_uncertain_component(machine):
    """u on EXX alone: |e| = sqrt(ex^2 + ey^2 + ez^2) is monotone in ex where ex stays on one side
    of zero, so the interval of |e| is the interval of ex carried through that function."""
    tables = zero_u(machine)
    tables["X"] = tables["X"].copy()
    tables["X"][0] = 0.2e-6
    q = points(machine, 30, seed=5)
    result = volumetric_monte_carlo(machine, MachineUncertainty(tables, {}), q, 4000, seed=2)
    far = np.abs(result.error[:, 0]) > 1.5e-6  # ex keeps its sign in every draw
    assert far.sum() > 5
    rest = np.hypot(result.error[far, 1], result.error[far, 2])
    ends = np.sort(np.stack([np.hypot(result.low[far, 0], rest), np.hypot(result.high[far, 0], rest)]), axis=0)
    np.testing.assert_allclose(result.magnitude_low[far], ends[0], rtol=1e-4)
    np.testing.assert_allclose(result.magnitude_high[far], ends[1], rtol=1e-4)
    np.testing.assert_allclose(result.magnitude, np.linalg.norm(result.error, axis=1))


def test_progress_is_told_every_chunk(machine):
    calls = []
    q = points(machine, 4)
    u = MachineUncertainty({k: np.full_like(v, 1e-6) for k, v in zero_u(machine).items()}, {})
    volumetric_monte_carlo(machine, u, q, 250, chunk_draws=100, progress=lambda done, total: calls.append((done, total)))
    assert calls == [(0, 250), (100, 250), (200, 250), (250, 250)]


@pytest.mark.parametrize("draws,words", [
    (0, "positive whole number"), (-5, "positive whole number"), (2.5, "positive whole number"),
    (True, "positive whole number"), (float("nan"), "positive whole number"), ("100", "positive whole number"),
    (10, "too few"), (1e12, "draw-points"), (10**7, "draw-points"),
])
def test_bad_numbers_of_draws(machine, draws, words):
    q = points(machine, 20)
    with pytest.raises(AxiscalError, match=words):
        volumetric_monte_carlo(machine, MachineUncertainty(zero_u(machine), {}), q, draws)


def test_a_scheduler_that_does_not_answer_is_one_error_within_the_stated_time(machine):
    pytest.importorskip("dask.distributed")
    import time

    q = points(machine, 3)
    u = MachineUncertainty(zero_u(machine), {})
    start = time.monotonic()
    with pytest.raises(AxiscalError, match="no dask scheduler answered at 'tcp://127.0.0.1:9' within 1 s") as info:
        volumetric_monte_carlo(machine, u, q, 100, scheduler="tcp://127.0.0.1:9", timeout_s=1.0)
    assert time.monotonic() - start < 10.0
    assert "\n" not in str(info.value)
    with pytest.raises(AxiscalError, match="cannot use 'nonsense://nowhere' as a dask scheduler"):
        volumetric_monte_carlo(machine, u, q, 100, scheduler="nonsense://nowhere", timeout_s=1.0)
    with pytest.raises(AxiscalError, match="timeout_s"):
        volumetric_monte_carlo(machine, u, q, 100, scheduler="tcp://127.0.0.1:9", timeout_s=0.0)
