"""`axiscal positioning --uncertainty/--monte-carlo` on the shipped examples and bad input."""

from __future__ import annotations

import json

import pytest


def test_text_shows_the_budget_table(run_cli, examples):
    status, out, err = run_cli("positioning", examples / "positioning_run.csv", "--uncertainty",
                               examples / "uncertainty_budget.toml")
    assert status == 0 and err == ""
    assert "axis figures (um)" in out
    for name in ("device", "air", "machine_expansion", "machine_temperature", "misalignment", "eve", "U(E)", "U(M)"):
        assert name in out
    assert "6.874" in out and "Monte Carlo" not in out


def test_json_uncertainty_object(run_cli, examples):
    status, out, _ = run_cli("positioning", examples / "positioning_run.csv", "--json", "--uncertainty",
                             examples / "uncertainty_budget.toml", "--monte-carlo", "20000")
    assert status == 0
    unc = json.loads(out)["uncertainty"]
    assert unc["k"] == 2
    assert unc["E"]["U"] == pytest.approx(6.874, abs=1e-3)
    assert unc["B"]["U"] == unc["R"]["U"] == pytest.approx(0.577, abs=1e-3)
    assert unc["components_um"]["device"] == pytest.approx(0.2)
    assert unc["monte_carlo"]["draws"] == 20000
    assert unc["monte_carlo"]["E"]["U"] == pytest.approx(unc["E"]["U"], rel=0.05)


def test_without_the_option_the_output_is_unchanged(run_cli, examples):
    _, out, _ = run_cli("positioning", examples / "positioning_run.csv", "--json")
    assert "uncertainty" not in json.loads(out)


def test_errors_are_one_line(run_cli, examples, tmp_path):
    status, _, err = run_cli("positioning", examples / "positioning_run.csv", "--monte-carlo", "100")
    assert status == 2 and "--uncertainty" in err
    bad = tmp_path / "b.toml"
    bad.write_text("[setup]\neve_um = -2\n")
    status, _, err = run_cli("positioning", examples / "positioning_run.csv", "--uncertainty", bad)
    assert status == 2 and err.startswith(f"axiscal: error: {bad}:2:") and len(err.strip().splitlines()) == 1
    status, _, err = run_cli("positioning", examples / "positioning_run.csv", "--standard", "vdi3441",
                             "--uncertainty", examples / "uncertainty_budget.toml")
    assert status == 2 and "iso230-2" in err


def test_raw_laser_run_has_the_same_travel_and_U(run_cli, examples):
    status, out, _ = run_cli("positioning", examples / "laser_raw_run.csv", "--json", "--uncertainty",
                             examples / "uncertainty_budget.toml")
    assert status == 0
    body = json.loads(out)
    assert body["compensated"] is True
    assert set(body["uncertainty"]) == {"k", "E", "R", "B", "A", "M", "components_um"}
    assert body["uncertainty"]["E"]["U"] == pytest.approx(6.874, abs=1e-3)


def test_a_huge_monte_carlo_is_one_line_not_an_allocation(run_cli, examples):
    status, _, err = run_cli("positioning", examples / "positioning_run.csv", "--uncertainty",
                             examples / "uncertainty_budget.toml", "--monte-carlo", "1000000000000")
    assert status == 2 and "at most 1e+07" in err and len(err.strip().splitlines()) == 1


def test_a_budget_value_that_is_nan_names_its_line(run_cli, examples, tmp_path):
    bad = tmp_path / "b.toml"
    bad.write_text("[instrument]\nlength_U_ppm = 0.5\n\n[air]\npressure_u_Pa = nan\n")
    status, _, err = run_cli("positioning", examples / "positioning_run.csv", "--uncertainty", bad)
    assert status == 2 and err.startswith(f"axiscal: error: {bad}:5:") and "finite number" in err
