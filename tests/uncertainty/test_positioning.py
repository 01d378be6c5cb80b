"""U of the ISO 230-2 figures: the combination rules, a real-format run, and analytic against Monte Carlo."""

from __future__ import annotations

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.errors import AxiscalError
from axiscal.positioning import read_positioning_run
from axiscal.uncertainty import (
    Budget,
    budget_from_dict,
    budget_report,
    length_model,
    positioning_decisions,
    positioning_monte_carlo,
    positioning_uncertainty,
    read_budget,
    uncertainty_payload,
)

FULL = {
    "instrument": {"length_U_ppm": 0.5},
    "air": {"temperature_u_K": 0.1, "pressure_u_Pa": 30.0, "humidity_u_percent": 5.0},
    "machine": {"temperature_C": 23.0, "temperature_u_K": 0.2, "expansion_per_K": 11.5e-6, "expansion_u_per_K": 1.2e-6},
    "setup": {"misalignment_urad": 100.0, "eve_um": 1.0},
}


def test_combined_U_of_E_on_the_example_run(examples):
    """The 800 mm run of examples/ with the example budget, by hand from the component formulas."""
    data = read_positioning_run(examples / "positioning_run.csv")
    result = positioning_uncertainty(examples / "uncertainty_budget.toml", data.run)
    assert result.length_m == pytest.approx(0.8)
    L = 0.8
    b = read_budget(examples / "uncertainty_budget.toml")
    from axiscal.uncertainty import air_sensitivities

    c = air_sensitivities(b)
    by_hand = {
        "device": L * 0.5e-6 / 2,
        "air": L * math.sqrt((c["temperature"] * 0.1) ** 2 + (c["pressure"] * 30) ** 2 + (c["humidity"] * 5) ** 2),
        "machine_expansion": L * 3.0 * 1.2e-6,
        "machine_temperature": L * 11.5e-6 * 0.2,
        "misalignment": L * (1 - math.cos(100e-6)) / (2 * math.sqrt(3)),
        "eve": 1e-6 / (2 * math.sqrt(3)),
    }
    U_E = 2 * math.sqrt(sum(u**2 for u in by_hand.values()))
    assert result.U["E"] == pytest.approx(U_E, rel=1e-9)
    assert U_E == pytest.approx(6.874e-6, abs=0.001e-6)  # the figure docs/uncertainty.md quotes
    assert result.U["M"] == result.U["A"] == result.U["E"]
    assert result.U["B"] == result.U["R"] == pytest.approx(2 * by_hand["eve"], rel=1e-12)
    for name, u in by_hand.items():
        assert result.components[name] == pytest.approx(u, rel=1e-9)
    assert result.degrees_of_freedom == math.inf
    assert sum(result.shares().values()) == pytest.approx(1.0)


def test_payload_has_the_specified_keys():
    body = uncertainty_payload(positioning_uncertainty(budget_from_dict(FULL), 0.8))
    assert body["k"] == 2
    for figure in ("E", "R", "B", "A", "M"):
        assert set(body[figure]) == {"U"}
    assert list(body["components_um"]) == ["device", "air", "machine_expansion", "machine_temperature", "misalignment", "eve"]
    assert body["components_um"]["machine_expansion"] == pytest.approx(2.88)
    assert body["E"]["U"] == pytest.approx(6.874, abs=1e-3)


def test_report_is_a_table_with_shares():
    text = budget_report(positioning_uncertainty(budget_from_dict(FULL), 0.8))
    assert "machine_expansion" in text and "70.2%" in text and "U(E)" in text and "6.874" in text


def test_gtc_budget_names_every_influence():
    from GTC import reporting

    labels = {i.label for i in reporting.budget(length_model(budget_from_dict(FULL), 0.8), trim=0)}
    assert labels == {"device", "air temperature", "air pressure", "air humidity", "machine_expansion",
                      "machine_temperature", "misalignment", "eve"}


LINEAR = {  # no cosine, no product of two uncertain inputs: the model is linear up to the air's tiny curvature
    "instrument": {"length_U_ppm": 1.0},
    "air": {"temperature_u_K": 0.3, "pressure_u_Pa": 50.0, "humidity_u_percent": 10.0},
    "machine": {"temperature_C": 25.0, "expansion_per_K": 11.5e-6, "expansion_u_per_K": 1.0e-6},
    "setup": {"eve_um": 2.0},
}


def test_analytic_and_monte_carlo_agree_for_the_linear_model():
    budget = budget_from_dict(LINEAR)
    analytic = positioning_uncertainty(budget, 1.0)
    mc = positioning_monte_carlo(budget, 1.0, 200_000, seed=1)
    for figure in ("E", "B"):
        u = analytic.U[figure] / 2
        assert mc[figure].std == pytest.approx(u, rel=0.05)
        assert abs(mc[figure].mean) < 0.02 * u
    # E sums mostly normal contributions: its 95 % interval is U = 2 u
    assert mc["E"].half_width == pytest.approx(analytic.U["E"], rel=0.05)
    # B holds the rectangular EVE alone: its 95 % interval is 0.95 sqrt(3) u = 1.65 u, narrower than k = 2 says
    assert mc["B"].half_width == pytest.approx(0.95 * math.sqrt(3) * analytic.U["B"] / 2, rel=0.01)


def test_where_they_part_the_cosine_error():
    """The cosine error is not linear: linearised at zero angle it vanishes; drawn, it is one-sided."""
    from GTC import cos, ureal

    bound = 200e-6
    L = 1.0
    budget = budget_from_dict({"setup": {"misalignment_urad": bound * 1e6}})
    e = L * (1 - math.cos(bound))
    theta = ureal(0.0, bound / math.sqrt(3))
    assert (L * (1 - cos(theta))).u == 0.0  # the first-order law of propagation sees nothing
    analytic = positioning_uncertainty(budget, L)
    assert analytic.components["misalignment"] == pytest.approx(e / (2 * math.sqrt(3)))
    mc = positioning_monte_carlo(budget, L, 200_000, seed=2)["E"]
    # theta uniform on +-bound: the error is e v^2 with v uniform on +-1: mean e/3, sd e sqrt(4/45), all >= 0
    assert mc.mean == pytest.approx(e / 3, rel=0.01)
    assert mc.std == pytest.approx(e * math.sqrt(4 / 45), rel=0.01)
    assert mc.low >= 0.0
    assert mc.std / (analytic.U["E"] / 2) == pytest.approx(math.sqrt(4 / 45) * 2 * math.sqrt(3), rel=0.01)  # 3 % more


def test_monte_carlo_is_reproducible_by_seed():
    budget = budget_from_dict(FULL)
    a = positioning_monte_carlo(budget, 0.8, 1000, seed=5)["E"]
    b = positioning_monte_carlo(budget, 0.8, 1000, seed=5)["E"]
    assert a == b


@settings(max_examples=25, deadline=None)
@given(length=st.floats(0.0, 5.0), ppm=st.floats(0.0, 5.0), eve=st.floats(0.0, 10.0))
def test_U_of_E_grows_with_length_and_never_falls_below_eve(length, ppm, eve):
    budget = budget_from_dict({"instrument": {"length_U_ppm": ppm}, "setup": {"eve_um": eve}})
    result = positioning_uncertainty(budget, length)
    assert result.U["E"] >= result.U["B"] - 1e-18
    assert result.U["E"] == pytest.approx(2 * math.hypot(length * ppm * 1e-6 / 2, eve * 1e-6 / (2 * math.sqrt(3))), rel=1e-9, abs=1e-18)


def test_bad_arguments():
    with pytest.raises(AxiscalError, match="length"):
        positioning_uncertainty(Budget(), -1.0)
    with pytest.raises(AxiscalError, match="draws"):
        positioning_uncertainty(Budget(), 1.0, monte_carlo=-3)
    with pytest.raises(AxiscalError, match="too few"):
        positioning_monte_carlo(Budget(), 1.0, 10)
    with pytest.raises(AxiscalError):
        positioning_uncertainty("/nonexistent/budget.toml", 1.0)


@pytest.mark.parametrize("draws,words", [
    (1e12, "at most 1e\\+07"), (10**8, "at most"), (2.5, "whole number"), (True, "whole number"),
    (float("nan"), "whole number"), (None, "whole number"), ("100", "whole number"),
])
def test_bad_numbers_of_draws_are_one_error_not_an_allocation(draws, words):
    with pytest.raises(AxiscalError, match=words):
        positioning_uncertainty(Budget(), 1.0, monte_carlo=draws)
    with pytest.raises(AxiscalError, match=words):
        positioning_monte_carlo(Budget(), 1.0, draws)


def test_decisions_for_a_campaign(examples):
    from axiscal.positioning import iso230_2

    run = read_positioning_run(examples / "positioning_run.csv").run
    result = iso230_2(run)
    unc = positioning_uncertainty(examples / "uncertainty_budget.toml", run)
    limit = result.E + 0.5 * unc.U["E"]  # inside the limit, but not by U
    simple = positioning_decisions(result, unc, {"E": limit})
    guarded = positioning_decisions(result, unc, {"E": limit, "B": result.B + 2 * unc.U["B"]}, rule="guard-band")
    assert simple["E"].verdict == "pass" and guarded["E"].verdict == "inconclusive"
    assert guarded["B"].verdict == "pass" and "ISO 14253-1" in guarded["B"].statement
    with pytest.raises(AxiscalError, match="S_up"):
        positioning_decisions(result, unc, {"S_up": 1e-6})
