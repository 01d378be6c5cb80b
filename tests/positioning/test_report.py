"""evaluate_positioning_file: the one call behind `axiscal positioning`, its JSON object and its text report."""

from __future__ import annotations

import numpy as np
import pytest

from axiscal.errors import AxiscalError
from axiscal.positioning import (
    ISO_SYMBOLS,
    VDI_SYMBOLS,
    PositioningEvaluation,
    evaluate_positioning_file,
    iso230_2,
    read_positioning_run,
    render_template,
    vdi3441,
)
from axiscal.units import MM, UM


def test_the_evaluation_holds_the_run_and_the_result_in_si(examples):
    evaluation = evaluate_positioning_file(examples / "positioning_run.csv")
    direct = iso230_2(read_positioning_run(examples / "positioning_run.csv").run)
    assert isinstance(evaluation, PositioningEvaluation) and evaluation.standard == "iso230-2:2014"
    assert evaluation.result.figures() == direct.figures()
    assert evaluation.run.targets[-1] == pytest.approx(800 * MM)
    assert evaluation.run_labels == ("1", "2", "3", "4", "5") and not evaluation.compensated
    # the published example figures of docs/positioning.md, in metres
    assert evaluation.result.A == pytest.approx(14.936 * UM, abs=0.0005 * UM)
    with pytest.raises(AttributeError):
        evaluation.compensated = True  # frozen


def test_to_dict_gives_micrometres_under_the_symbols(examples):
    evaluation = evaluate_positioning_file(examples / "positioning_run.csv", standard="vdi3441")
    body = evaluation.to_dict()
    assert body["standard"] == "vdi3441" and body["unit"] == "um" and "coverage_factor" not in body
    assert set(VDI_SYMBOLS) <= set(body)
    assert body["P"] == pytest.approx(vdi3441(evaluation.run).P / UM)
    assert np.asarray(body["targets"]["Ps_um"]) == pytest.approx(evaluation.result.scatter / UM)
    iso = evaluate_positioning_file(examples / "positioning_run.csv", standard="jis-b6192").to_dict()
    assert iso["coverage_factor"] == 3 and set(ISO_SYMBOLS) <= set(iso)


def test_report_is_the_table_and_the_figures(examples):
    evaluation = evaluate_positioning_file(examples / "laser_raw_run.csv")
    lines = evaluation.report().splitlines()
    assert lines[0].endswith(": iso230-2:2014, 17 targets, 5 runs each way")
    assert lines[1] == ("raw laser readings compensated for the air index (ciddor) and normalised to 20 degC"
                        " (material temperature, 1 sensor)")
    assert lines[2] == "" and lines[3].split() == list(evaluation.per_target_um())
    assert len(lines) == 4 + 17 + 2 + len(ISO_SYMBOLS)
    figure_lines = lines[-len(ISO_SYMBOLS):]
    for name, line in zip(ISO_SYMBOLS, figure_lines):
        assert line == f"  {name:<8} {getattr(evaluation.result, name) / UM:>9.3f}"
    assert not evaluation.report().endswith("\n")


def test_one_run_reports_n_a_and_a_warning(tmp_path):
    lines = ["target_mm,run,direction,deviation_um"]
    lines += [f"{t},1,{d},{v}" for d, v in (("+", 1.0), ("-", -1.0)) for t in (0, 100, 200)]
    path = tmp_path / "one.csv"
    path.write_text("\n".join(lines) + "\n")
    evaluation = evaluate_positioning_file(path)
    assert evaluation.warnings and "cannot be estimated" in evaluation.warnings[0]
    text = evaluation.report()
    assert "1 run each way" in text and "      n/a" in text


def test_raw_reading_options_need_raw_readings(examples):
    for option in ({"wavelength_nm": 632.99}, {"expansion_per_k": 23e-6}):
        with pytest.raises(AxiscalError, match=f"{next(iter(option))} applies to raw laser readings"):
            evaluate_positioning_file(examples / "positioning_run.csv", **option)
        assert evaluate_positioning_file(examples / "laser_raw_run.csv", **option).compensated


def test_unknown_standard_is_refused(examples):
    with pytest.raises(AxiscalError, match="unknown standard"):
        evaluate_positioning_file(examples / "positioning_run.csv", standard="iso9999")


def test_plot_method_writes_the_figure(examples, tmp_path):
    evaluation = evaluate_positioning_file(examples / "positioning_run.csv")
    out = evaluation.plot(tmp_path / "p.svg")
    assert out.read_text().lstrip().startswith("<?xml")
    # with another test drawn behind, the figures table still names the unit as the plot does
    targets = evaluation.to_dict()["targets"]
    with_overlay = evaluation.plot(tmp_path / "o.svg", overlay=targets).read_text()
    assert "µm" in with_overlay
    # a report that shows the figures itself draws the plot alone
    alone = evaluation.plot(tmp_path / "a.svg", figures_table=False).read_text()
    assert ">figure<" not in alone.replace(" ", "") and len(alone) < len(out.read_text())


def test_render_template_shipped_with_the_package():
    text = render_template(
        "positioning_report.txt.j2", source="s.csv", standard="vdi3441", target_count=2, runs=2,
        compensated=False, columns=["target_mm"], rows=[["    0.000"]], figures=[("P", float("nan"))],
    )
    assert text.splitlines() == ["s.csv: vdi3441, 2 targets, 2 runs each way", "", "target_mm", "    0.000", "",
                                 "axis figures (um):", "  P              n/a"]


def test_the_shipped_run_files_are_plain_csv_with_a_sidecar(examples):
    import json

    import pandas as pd

    plain = pd.read_csv(examples / "positioning_run.csv")
    assert list(plain.columns) == ["target_mm", "run", "direction", "deviation_um"] and len(plain) == 170
    raw = pd.read_csv(examples / "laser_raw_run.csv")
    assert list(raw.columns) == ["target_mm", "run", "direction", "actual_mm", "air_temperature_c", "pressure_pa",
                                 "humidity_pct", "material_temperature_c"]
    for name in ("positioning_run", "laser_raw_run"):
        meta = json.loads((examples / f"{name}.json").read_text())
        assert meta["kind"] == "positioning run" and meta["file"] == f"{name}.csv"
