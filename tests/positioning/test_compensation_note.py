"""A positioning run says what was applied to its raw laser readings: the air always, 20 degC only with a material temperature."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

from matplotlib.axes import Axes  # noqa: E402

import axiscal.positioning.plot as plot_module  # noqa: E402
from axiscal.positioning import evaluate_positioning_file, read_positioning_run  # noqa: E402


def _without_material(examples, tmp_path):
    lines = (examples / "laser_raw_run.csv").read_text().splitlines()
    path = tmp_path / "air_only.csv"
    path.write_text("\n".join(line.rsplit(",", 1)[0] for line in lines) + "\n")
    return path


def test_a_run_without_material_temperature_is_not_said_normalised(examples, tmp_path, monkeypatch):
    path = _without_material(examples, tmp_path)
    assert "material" not in path.read_text().splitlines()[0]
    data = read_positioning_run(path)
    assert data.compensated
    assert data.compensation == ("raw laser readings compensated for the air index (ciddor); no material temperature:"
                                 " not normalised to 20 degC")
    evaluation = evaluate_positioning_file(path)
    assert evaluation.report().splitlines()[1] == data.compensation
    assert "material temperature" not in evaluation.report().replace("no material temperature", "")
    notes = []
    real_text = Axes.text

    def text(self, x, y, s, *args, **kwargs):
        notes.append(s)
        return real_text(self, x, y, s, *args, **kwargs)

    monkeypatch.setattr(Axes, "text", text)
    evaluation.plot(tmp_path / "run.png")
    assert any(data.compensation in note for note in notes)
    assert not any("air index and material temperature" in note for note in notes)


def test_a_run_with_material_temperature_says_it_was_normalised(examples):
    data = read_positioning_run(examples / "laser_raw_run.csv")
    assert data.compensation == ("raw laser readings compensated for the air index (ciddor) and normalised to 20 degC"
                                 " (material temperature, 1 sensor)")
    assert evaluate_positioning_file(examples / "laser_raw_run.csv").to_dict()["compensation"] == data.compensation


def test_a_run_of_deviations_says_nothing_was_compensated(examples):
    assert read_positioning_run(examples / "positioning_run.csv").compensation == ""
    assert plot_module.plot_positioning.__doc__ and "compensation" in plot_module.plot_positioning.__doc__
