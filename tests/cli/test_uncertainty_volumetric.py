"""`axiscal uncertainty volumetric`: the map with its interval on the example machine with _u columns, files, Dask, bad input."""

from __future__ import annotations

import io
import json
import shutil
import sys

import pandas as pd
import pytest

GRID = "X=0:800:400,Y=0:500:250,Z=0:400:400"


@pytest.fixture
def machine(examples):
    return examples / "xfyz_machine_u" / "machine.toml"


def test_csv_on_standard_output_reads_with_plain_pandas(run_cli, machine):
    status, out, err = run_cli("uncertainty", "volumetric", "--machine", machine, "--grid", GRID, "--draws", "200")
    assert status == 0 and err == ""
    frame = pd.read_csv(io.StringIO(out))
    assert len(frame) == 18
    assert list(frame.columns) == ["x_mm", "y_mm", "z_mm"] + [
        f"{e}_{s}um" for e in ("ex", "ey", "ez", "e") for s in ("", "u_", "low_", "high_")]
    assert (frame["e_low_um"] <= frame["e_high_um"]).all()


def test_same_seed_same_map_other_seed_other_map(run_cli, machine):
    runs = [run_cli("uncertainty", "volumetric", "--machine", machine, "--grid", GRID, "--draws", "200", "--seed", s)[1]
            for s in ("3", "3", "4")]
    assert runs[0] == runs[1] != runs[2]


def test_output_file_sidecar_plot_and_json(run_cli, machine, tmp_path):
    out, figure = tmp_path / "map.csv", tmp_path / "map.png"
    status, stdout, err = run_cli("uncertainty", "volumetric", "--machine", machine, "--grid", GRID, "--draws", "200",
                                  "-o", out, "--plot", figure, "--json")
    assert status == 0 and err == ""
    summary = json.loads(stdout)
    frame = pd.read_csv(out)
    assert summary["max_e_um"] == pytest.approx(frame["e_um"].max(), abs=1e-6)
    assert summary["draws"] == 200 and summary["unit"] == "um"
    side = json.loads(out.with_suffix(".json").read_text())
    assert side["kind"] == "volumetric uncertainty" and side["sources"] == [str(machine)]
    assert figure.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    status, stdout, _ = run_cli("uncertainty", "volumetric", "--machine", machine, "--grid", GRID, "--draws", "200",
                                "-o", tmp_path / "quiet.csv")
    assert status == 0 and stdout == ""


def test_points_file(run_cli, machine, tmp_path):
    points = tmp_path / "p.csv"
    points.write_text("X_mm,Y_mm,Z_mm\n100,50,20\n700,450,380\n")
    status, out, _ = run_cli("uncertainty", "volumetric", "--machine", machine, "--points", points, "--draws", "100")
    assert status == 0 and len(pd.read_csv(io.StringIO(out))) == 2


def test_progress_bar_only_on_a_terminal_and_never_on_standard_output(run_cli, machine, monkeypatch):
    monkeypatch.setattr(sys.stderr, "isatty", lambda: True, raising=False)
    status, out, _ = run_cli("uncertainty", "volumetric", "--machine", machine, "--grid", GRID, "--draws", "600")
    assert status == 0
    assert len(pd.read_csv(io.StringIO(out))) == 18  # standard output stays plain CSV


def test_dask_local_cluster_gives_the_same_map(run_cli, machine):
    pytest.importorskip("dask.distributed")
    args = ("uncertainty", "volumetric", "--machine", machine, "--grid", GRID, "--draws", "500", "--seed", "7")
    status, here, _ = run_cli(*args)
    status_dask, there, _ = run_cli(*args, "--scheduler", "local")
    assert status == status_dask == 0
    assert here == there


@pytest.mark.parametrize("extra,words", [
    ((), "exactly one of --points FILE or --grid SPEC"),
    (("--grid", GRID, "--draws", "0"), "positive whole number"),
    (("--grid", GRID, "--draws", "10"), "too few"),
    (("--grid", GRID, "--draws", "1000000000000"), "draw-points"),
    (("--grid", GRID, "--draws", "1e12"), "--draws"),
    (("--grid", GRID, "--plot", "map.txt"), "figure format"),
    (("--grid", "X=0:900:100,Y=0,Z=0"), "outside"),
    (("--grid", GRID, "--draws", "100", "--scheduler", "tcp://127.0.0.1:9", "--scheduler-timeout-s", "1"),
     "no dask scheduler answered at 'tcp://127.0.0.1:9' within 1 s"),
])
def test_bad_input_is_one_line(run_cli, machine, extra, words):
    status, out, err = run_cli("uncertainty", "volumetric", "--machine", machine, *extra)
    assert status == 2 and out == ""
    assert err.startswith("axiscal: error:") and words in err and len(err.strip().splitlines()) == 1


def test_a_bad_u_value_names_file_and_line(run_cli, examples, tmp_path):
    for path in (examples / "xfyz_machine_u").iterdir():
        shutil.copy(path, tmp_path / path.name)
    table = tmp_path / "y_errors.csv"
    lines = table.read_text().splitlines()
    lines[4] = lines[4][: lines[4].rindex(",")] + ",nan"
    table.write_text("\n".join(lines) + "\n")
    status, _, err = run_cli("uncertainty", "volumetric", "--machine", tmp_path / "machine.toml", "--grid", GRID)
    assert status == 2 and err.startswith(f"axiscal: error: {table}:5:") and len(err.strip().splitlines()) == 1
    toml = tmp_path / "machine.toml"
    toml.write_text(toml.read_text().replace("EB0Z_arcsec_u = 1.0", "EB0Z_arcsec_u = 'one'"))
    table.write_text(table.read_text().replace(",nan\n", ",1.5\n"))
    status, _, err = run_cli("uncertainty", "volumetric", "--machine", toml, "--grid", GRID)
    line = toml.read_text().splitlines().index("EB0Z_arcsec_u = 'one'") + 1
    assert status == 2 and err.startswith(f"axiscal: error: {toml}:{line}:")
