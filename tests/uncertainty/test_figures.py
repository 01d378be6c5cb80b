"""The U and the verdict of a campaign test's figures: positioning, straightness and squareness, bad input."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.errors import AxiscalError
from axiscal.positioning import evaluate_positioning_file
from axiscal.squareness.evaluation import squareness_from_files
from axiscal.straightness.files import evaluate_straightness_file
from axiscal.uncertainty import (
    Budget,
    figure_uncertainties,
    figure_verdicts,
    positioning_uncertainty,
    read_budget,
    squareness_uncertainty,
    straightness_uncertainty,
)

ARCSEC = math.pi / 648000


@pytest.fixture(scope="module")
def paths():
    from pathlib import Path

    root = Path(__file__).resolve().parents[2] / "examples"
    return {"budget": root / "uncertainty_budget.toml", "run": root / "positioning_run.csv",
            "profile": root / "straightness_profile.csv", "x": root / "squareness_x.csv", "y": root / "squareness_y.csv"}


@pytest.fixture(scope="module")
def positioning(paths):
    return evaluate_positioning_file(paths["run"])


def test_positioning_figures_get_the_U_of_their_kind(paths, positioning):
    U = figure_uncertainties("positioning", positioning, paths["budget"])
    reference = positioning_uncertainty(paths["budget"], positioning.run).U
    for symbol in ("E", "E_up", "E_down", "A", "A_up", "A_down", "M"):
        assert U[symbol] == pytest.approx(reference["E"] * 1e6, rel=1e-12)
    for symbol in ("R", "R_up", "R_down", "B", "B_mean"):
        assert U[symbol] == pytest.approx(reference["R"] * 1e6, rel=1e-12)
    assert "S_up" not in U and "S_down" not in U
    # the numbers docs/uncertainty.md prints for this run and budget (k = 2, um)
    assert (round(U["E"], 3), round(U["R"], 3)) == (6.874, 0.577)


def test_positioning_figures_as_a_mapping_with_the_run(paths, positioning):
    figures = positioning.to_dict()
    by_mapping = figure_uncertainties("positioning", figures, read_budget(paths["budget"]), run=positioning.run)
    assert by_mapping == figure_uncertainties("positioning", positioning, paths["budget"])
    by_length = figure_uncertainties("positioning", {"E": 1.0}, Budget(length_U_rel=0.5e-6), run=1.0)
    assert by_length == {"E": pytest.approx(0.5)}
    with pytest.raises(AxiscalError, match="run="):
        figure_uncertainties("positioning", figures, paths["budget"])


def test_vdi_figures_have_no_budget(paths):
    evaluation = evaluate_positioning_file(paths["run"], standard="vdi3441")
    with pytest.raises(AxiscalError, match="ISO 230-2"):
        figure_uncertainties("positioning", evaluation, paths["budget"])


def test_straightness_and_squareness(paths):
    budget = read_budget(paths["budget"])
    evaluation = evaluate_straightness_file(paths["profile"], reference="minimum-zone")
    p = evaluation.profile
    expected = straightness_uncertainty(budget, p.position_m, p.deviation_m, reference="minimum-zone").U
    assert figure_uncertainties("straightness", evaluation, budget) == {"straightness_um": pytest.approx(expected * 1e6)}
    evaluation = squareness_from_files(paths["x"], paths["y"], plane="XY", convention="iso")
    U = figure_uncertainties("squareness", evaluation, budget)
    a, b = evaluation.first, evaluation.second
    expected = squareness_uncertainty(budget, a.position_m, a.deviation_m, b.position_m, b.deviation_m).U / ARCSEC
    assert U == {"squareness_arcsec": pytest.approx(expected), "iso_value_arcsec": pytest.approx(expected)}
    assert round(U["squareness_arcsec"], 2) == 1.37  # docs/uncertainty.md


def test_verdicts_under_both_rules(paths, positioning):
    E, R = positioning.result.E * 1e6, positioning.result.R * 1e6  # 13.427, 7.671 um
    tolerances = {"E_um": 15.0, "R_um": 10.0, "B_mean_um": 5.0}
    simple = figure_verdicts("positioning", positioning, paths["budget"], tolerances)
    guarded = figure_verdicts("positioning", positioning, paths["budget"], tolerances, rule="guard-band")
    assert {k: d.verdict for k, d in simple.items()} == {"E_um": "pass", "R_um": "pass", "B_mean_um": "pass"}
    assert {k: d.verdict for k, d in guarded.items()} == {"E_um": "inconclusive", "R_um": "pass", "B_mean_um": "pass"}
    assert guarded["E_um"].value == pytest.approx(E) and guarded["R_um"].value == pytest.approx(R)
    assert guarded["E_um"].U == pytest.approx(6.874, abs=1e-3)
    assert guarded["E_um"].acceptance_limit == pytest.approx(15.0 - guarded["E_um"].U)
    assert "ISO 14253-1" in guarded["E_um"].statement
    # a negative figure is judged by its magnitude, as the campaign does
    square = squareness_from_files(paths["x"], paths["y"], convention="iso")
    verdict = figure_verdicts("squareness", square, paths["budget"], {"squareness_arcsec": 30.0})["squareness_arcsec"]
    assert verdict.value == pytest.approx(abs(square.result.squareness_rad) / ARCSEC)


def test_a_figure_that_could_not_be_computed_fails(paths):
    figures = {"E": 3.0, "R": float("nan")}
    verdicts = figure_verdicts("positioning", figures, Budget(), {"E_um": 5.0, "R_um": 5.0}, run=0.5, rule="guard-band")
    assert verdicts["E_um"].verdict == "pass" and verdicts["R_um"].verdict == "fail"
    assert math.isnan(verdicts["R_um"].value)


@pytest.mark.parametrize("kind,tolerances,words", [
    ("ballbar", {"circular_deviation_um": 5.0}, "kind 'ballbar'"),
    ("positioning", {"S_up_um": 5.0}, "no figure with an uncertainty"),
    ("positioning", {"E_um": -1.0}, "non-negative"),
    ("positioning", {"E_um": float("nan")}, "non-negative"),
    ("positioning", {"E_um": "5"}, "non-negative"),
])
def test_bad_input(paths, positioning, kind, tolerances, words):
    with pytest.raises(AxiscalError, match=words):
        figure_verdicts(kind, positioning, paths["budget"], tolerances)


def test_bad_rule_and_wrong_evaluation(paths, positioning):
    with pytest.raises(AxiscalError, match="decision rule"):
        figure_verdicts("positioning", positioning, paths["budget"], {"E_um": 5.0}, rule="strict")
    with pytest.raises(AxiscalError, match="StraightnessEvaluation"):
        figure_uncertainties("straightness", positioning, paths["budget"])
    with pytest.raises(AxiscalError, match="SquarenessEvaluation"):
        figure_uncertainties("squareness", positioning, paths["budget"])


def test_a_bad_budget_file_names_its_line(tmp_path, positioning):
    bad = tmp_path / "b.toml"
    bad.write_text("[setup]\neve_um = nan\n")
    with pytest.raises(AxiscalError) as info:
        figure_uncertainties("positioning", positioning, bad)
    assert info.value.path == str(bad) and info.value.line == 2


@settings(max_examples=60, deadline=None)
@given(value=st.floats(0.0, 50.0), limit=st.floats(0.0, 50.0), length=st.floats(0.01, 2.0), ppm=st.floats(0.0, 5.0))
def test_a_guarded_pass_is_a_simple_pass_and_a_guarded_fail_a_simple_fail(value, limit, length, ppm):
    budget = Budget(length_U_rel=ppm * 1e-6)
    guarded = figure_verdicts("positioning", {"E": value}, budget, {"E_um": limit}, run=length, rule="guard-band")["E_um"]
    simple = figure_verdicts("positioning", {"E": value}, budget, {"E_um": limit}, run=length)["E_um"]
    assert guarded.U == pytest.approx(length * ppm, rel=1e-9, abs=1e-12)
    if guarded.verdict == "pass":
        assert simple.verdict == "pass"
    if guarded.verdict == "fail":
        assert simple.verdict == "fail"
    assert np.isfinite(guarded.acceptance_limit)
