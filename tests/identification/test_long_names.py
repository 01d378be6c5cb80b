"""An artefact's name titles its figure and names its file: a name of megabytes is refused by the reader, cut in a title."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from axiscal.errors import AxiscalError
from axiscal.identification import read_artefact, write_artefact
from axiscal.identification import plot as plot_module
from axiscal.identification.simulate import plate_grid, simulate_ball_plate
from axiscal.model.machine import Axis, Machine


def test_a_name_of_ten_megabytes_is_refused_in_one_line(tmp_path):
    plate = simulate_ball_plate(Machine("FYXZ", {k: Axis(k) for k in "XYZ"}), plate_grid(3, 0.1), np.eye(3),
                                np.full(3, 0.05), np.zeros(3), noise_m=1e-7, rng=np.random.default_rng(0))
    path = write_artefact(plate, tmp_path / "plate.toml")
    text = path.read_text()
    path.write_text(f'name = "{"n" * 10_000_000}"\n' + "\n".join(line for line in text.splitlines() if not line.startswith("name")))
    with pytest.raises(AxiscalError) as caught:
        read_artefact(path)
    message = str(caught.value)
    assert message.startswith(f"{path}:1: name must be a text of at most 100 characters, not 'nnn") and len(message) < 300
    path.write_text(f'name = "{"n" * 100}"\n' + "\n".join(line for line in text.splitlines() if not line.startswith("name")))
    assert read_artefact(path).name == "n" * 100


def test_a_long_name_is_cut_in_the_residuals_title(tmp_path, monkeypatch):
    titles = []

    def keep(fig, path):
        titles.append(fig.axes[0].get_title())
        return path

    monkeypatch.setattr(plot_module, "save_figure", keep)
    name = "plate " + "n" * 1_000_000
    result = SimpleNamespace(residuals={name: np.zeros(4), "short": np.zeros(4)}, kinds={name: "ball_plate", "short": "ball_plate"})
    plot_module.plot_residuals(result, name, tmp_path / "r.png")
    plot_module.plot_residuals(result, "short", tmp_path / "s.png")
    assert titles[0] == "plate " + "n" * 51 + "... (ball_plate)" and titles[1] == "short (ball_plate)"
