"""`volumetric --plot` draws the error against the axis positions: a map on a 2-D grid, slices of a 3-D grid."""

from __future__ import annotations

import numpy as np
import pytest

import axiscal.model.plot as plot_module
from axiscal.model.volumetric import volumetric_map


@pytest.fixture
def drawn(monkeypatch):
    figures = []

    def keep(fig, path, **_):
        figures.append(fig)
        return path

    monkeypatch.setattr(plot_module, "save_figure", keep)
    return figures


def test_a_3d_grid_is_drawn_as_slices_against_positions(examples, tmp_path, drawn):
    result = volumetric_map(examples / "xfyz_machine" / "machine.toml", grid="X=0:600:100,Y=0:400:100,Z=0:300:100")
    result.plot(tmp_path / "map.png")
    (fig,) = drawn
    maps = [ax for ax in fig.axes if ax.get_xlabel()]
    assert [ax.get_title() for ax in maps] == ["Z = 0 mm", "Z = 100 mm", "Z = 200 mm", "Z = 300 mm"]
    assert {ax.get_xlabel() for ax in maps} == {"X / mm"} and maps[0].get_ylabel() == "Y / mm"
    # every slice is one colour map over the X-Y grid, on one scale: the largest |e| of the grid
    meshes = [ax.collections[0] for ax in maps]
    assert all(m.get_array().size == 7 * 5 for m in meshes)
    assert max(float(np.max(m.get_array())) for m in meshes) == pytest.approx(result.max_m * 1e6)
    assert {m.get_clim() for m in meshes} == {meshes[0].get_clim()}


def test_one_axis_is_drawn_against_its_position(examples, tmp_path, drawn):
    result = volumetric_map(examples / "xfyz_machine" / "machine.toml", grid="X=0:600:50,Y=200,Z=100")
    result.plot(tmp_path / "line.png")
    (fig,) = drawn
    (ax,) = [ax for ax in fig.axes if ax.get_xlabel()]
    assert ax.get_xlabel() == "X / mm"
    assert ax.lines[0].get_xdata().tolist() == pytest.approx(list(np.arange(0.0, 601.0, 50.0)))


def test_volumetric_and_its_uncertainty_spell_the_positions_alike(run_cli, examples, tmp_path):
    status, plain, _ = run_cli("volumetric", "--machine", examples / "xfyz_machine" / "machine.toml",
                               "--grid", "X=0:600:300,Y=0,Z=0")
    assert status == 0
    status, with_u, _ = run_cli("uncertainty", "volumetric", "--machine", examples / "xfyz_machine_u" / "machine.toml",
                                "--grid", "X=0:600:300,Y=0,Z=0",
                                "--draws", "50")
    assert status == 0
    assert plain.splitlines()[0].split(",")[:3] == with_u.splitlines()[0].split(",")[:3] == ["x_mm", "y_mm", "z_mm"]
