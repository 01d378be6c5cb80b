"""The budget file and its components, each reproduced by hand from the formulas of docs/uncertainty.md."""

from __future__ import annotations

import math

import pytest

from axiscal.errors import AxiscalError
from axiscal.instruments.air import refractive_index
from axiscal.uncertainty import (
    BUDGET_KEYS,
    COMPONENTS,
    Budget,
    air_sensitivities,
    budget_from_dict,
    length_components,
    read_budget,
)

L = 0.8  # m, the travel of examples/positioning_run.csv


def only(name: str, components: dict[str, float]) -> float:
    """The one non-zero component; every other one must be exactly zero."""
    others = {k: v for k, v in components.items() if k != name}
    assert all(v == 0.0 for v in others.values()), others
    return components[name]


def test_device_alone():
    # L * length_U_ppm / 2: 0.8 m * 0.5e-6 / 2 = 0.2 um
    u = only("device", length_components(budget_from_dict({"instrument": {"length_U_ppm": 0.5}}), L))
    assert u == pytest.approx(0.8 * 0.5e-6 / 2, rel=1e-12)


@pytest.mark.parametrize(
    "key, u, sensor, step",
    [("temperature_u_K", 0.1, 0, 0.5), ("pressure_u_Pa", 30.0, 1, 50.0), ("humidity_u_percent", 5.0, 2, 5.0)],
)
def test_air_alone_each_sensor(key, u, sensor, step):
    # L * |dn/dx| * u(x), dn/dx by a wide secant of the Ciddor equation (the code uses narrow central differences)
    base = [20.0, 101325.0, 50.0]
    hi, lo = list(base), list(base)
    hi[sensor] += step
    lo[sensor] -= step
    slope = (refractive_index(*hi, 632.991) - refractive_index(*lo, 632.991)) / (2 * step)
    got = only("air", length_components(budget_from_dict({"air": {key: u}}), L))
    assert got == pytest.approx(L * abs(slope) * u, rel=1e-4)


def test_air_sensors_add_in_quadrature():
    b = budget_from_dict({"air": {"temperature_u_K": 0.1, "pressure_u_Pa": 30.0, "humidity_u_percent": 5.0}})
    c = air_sensitivities(b)
    expected = L * math.sqrt((c["temperature"] * 0.1) ** 2 + (c["pressure"] * 30.0) ** 2 + (c["humidity"] * 5.0) ** 2)
    assert only("air", length_components(b, L)) == pytest.approx(expected, rel=1e-12)


def test_air_sensitivities_have_the_known_size():
    # near standard air a He-Ne wavelength changes by about -0.95 ppm/K, +2.7 ppm/kPa, -0.0085 ppm/% RH
    c = air_sensitivities(Budget())
    assert c["temperature"] == pytest.approx(-0.95e-6, rel=0.03)
    assert c["pressure"] == pytest.approx(2.68e-9, rel=0.03)
    assert c["humidity"] == pytest.approx(-8.5e-9, rel=0.05)


def test_air_sensitivities_follow_the_stated_conditions():
    warm = air_sensitivities(budget_from_dict({"air": {"temperature_C": 30.0}}))
    assert abs(warm["temperature"]) < abs(air_sensitivities(Budget())["temperature"])
    edlen = air_sensitivities(budget_from_dict({"instrument": {"method": "edlen"}}))
    assert edlen["temperature"] == pytest.approx(air_sensitivities(Budget())["temperature"], rel=1e-3)


def test_machine_expansion_alone():
    # L * |T - 20| * u(alpha) = 0.8 * 3 * 1.2e-6 = 2.88 um
    b = budget_from_dict({"machine": {"temperature_C": 23.0, "expansion_per_K": 11.5e-6, "expansion_u_per_K": 1.2e-6}})
    assert only("machine_expansion", length_components(b, L)) == pytest.approx(2.88e-6, rel=1e-12)


def test_machine_temperature_alone():
    # L * alpha * u(T) = 0.8 * 11.5e-6 * 0.2 = 1.84 um
    b = budget_from_dict({"machine": {"temperature_C": 20.0, "expansion_per_K": 11.5e-6, "temperature_u_K": 0.2}})
    assert only("machine_temperature", length_components(b, L)) == pytest.approx(1.84e-6, rel=1e-12)


def test_misalignment_alone():
    # cosine error of the bound, rectangular of that full width: L (1 - cos 100 urad) / (2 sqrt 3)
    b = budget_from_dict({"setup": {"misalignment_urad": 100.0}})
    expected = L * (1 - math.cos(100e-6)) / (2 * math.sqrt(3))
    assert only("misalignment", length_components(b, L)) == pytest.approx(expected, rel=1e-9)
    assert expected == pytest.approx(1.1547e-9, rel=1e-4)


def test_eve_alone():
    # eve_um / (2 sqrt 3): 1 um -> 0.288675 um, whatever the length
    b = budget_from_dict({"setup": {"eve_um": 1.0}})
    assert only("eve", length_components(b, L)) == pytest.approx(0.2886751e-6, rel=1e-6)
    assert length_components(b, 0.1)["eve"] == length_components(b, 2.0)["eve"]


def test_empty_budget_is_all_zero():
    assert length_components(budget_from_dict({}), L) == dict.fromkeys(COMPONENTS, 0.0)


def test_example_file_reads(examples):
    b = read_budget(examples / "uncertainty_budget.toml")
    assert b.length_U_rel == pytest.approx(0.5e-6)
    assert b.eve_m == pytest.approx(1e-6)
    assert b.misalignment_rad == pytest.approx(100e-6)


def test_unknown_key_names_its_line(tmp_path):
    path = tmp_path / "b.toml"
    path.write_text("[instrument]\nlength_U_ppm = 0.5\n\n[air]\ntemperature_u_k = 0.1\n")
    with pytest.raises(AxiscalError) as info:
        read_budget(path)
    assert info.value.line == 5 and "temperature_u_K" in info.value.message


def test_unknown_section_and_negative_value(tmp_path):
    path = tmp_path / "b.toml"
    path.write_text("[laser]\nx = 1\n")
    with pytest.raises(AxiscalError) as info:
        read_budget(path)
    assert info.value.line == 1
    path.write_text("[setup]\nmisalignment_urad = 10\neve_um = -1.0\n")
    with pytest.raises(AxiscalError) as info:
        read_budget(path)
    assert info.value.line == 3 and "negative" in info.value.message
    path.write_text("[setup]\neve_um = 'one'\n")
    with pytest.raises(AxiscalError, match="must be a finite number"):
        read_budget(path)


@pytest.mark.parametrize("text,line,words", [
    ("[setup]\neve_um = 'one'\n", 2, "finite number"),
    ("[setup]\neve_um = true\n", 2, "finite number"),
    ("[setup]\neve_um = [1.0]\n", 2, "finite number"),
    ("[setup]\nmisalignment_urad = 5\neve_um = nan\n", 3, "finite number"),
    ("[air]\ntemperature_u_K = inf\n", 2, "finite number"),
    ("[air]\ntemperature_u_K = -inf\n", 2, "finite number"),
    ("[machine]\nexpansion_u_per_K = -1e-6\n", 2, "negative"),
    ("[instrument]\nlength_U_ppm = 0.5\nmethod = 3\n", 3, "method"),
    ("[instrument]\nlength_u_ppm = 0.5\n", 2, "unknown key"),
    ("setup = 1\n", 1, "table"),
    ("[[setup]]\neve_um = 1\n", 1, "table"),
])
def test_every_bad_value_is_one_error_naming_file_and_line(tmp_path, text, line, words):
    path = tmp_path / "b.toml"
    path.write_text(text)
    with pytest.raises(AxiscalError, match=words) as info:
        read_budget(path)
    assert info.value.path == str(path) and info.value.line == line
    assert "\n" not in str(info.value)


def test_malformed_toml_is_one_error(tmp_path):
    path = tmp_path / "b.toml"
    path.write_text("[setup\n")
    with pytest.raises(AxiscalError):
        read_budget(path)


def test_unknown_method_names_its_line(tmp_path):
    path = tmp_path / "b.toml"
    path.write_text("[instrument]\nlength_U_ppm = 0.5\nmethod = 'magic'\n")
    with pytest.raises(AxiscalError, match="method") as info:
        read_budget(path)
    assert info.value.line == 3


def test_python_budget_refuses_negative_values():
    with pytest.raises(AxiscalError, match="negative"):
        Budget(eve_m=-1e-6)


def test_air_conditions_in_the_wrong_unit_name_the_section(tmp_path):
    path = tmp_path / "b.toml"
    path.write_text("[setup]\neve_um = 1.0\n\n[air]\npressure_Pa = 1013.25\n")
    with pytest.raises(AxiscalError, match="pressure") as info:
        read_budget(path)
    assert info.value.line == 4


def test_every_bounded_key_is_a_key_of_the_file():
    from axiscal.uncertainty.budget import BUDGET_RANGES

    assert all(key in BUDGET_KEYS[section] for section, key in BUDGET_RANGES)
    numbers = {(s, k) for s, keys in BUDGET_KEYS.items() for k in keys} - {("instrument", "method"), ("instrument", "wavelength_nm")}
    air_conditions = {("air", "temperature_C"), ("air", "pressure_Pa"), ("air", "humidity_percent")}
    assert set(BUDGET_RANGES) == numbers - air_conditions  # those three and the wavelength: the air equation's range


@pytest.mark.parametrize("section, key", [
    ("instrument", "length_U_ppm"), ("instrument", "straightness_U_um"), ("air", "temperature_u_K"),
    ("air", "pressure_u_Pa"), ("air", "humidity_u_percent"), ("machine", "temperature_C"), ("machine", "temperature_u_K"),
    ("machine", "expansion_per_K"), ("machine", "expansion_u_per_K"), ("setup", "misalignment_urad"), ("setup", "eve_um"),
    ("setup", "prism_deviation_u_arcsec"),
])
@pytest.mark.parametrize("value", ["1e300", "1.7e308", "-1e300"])
def test_an_absurd_value_names_its_key_and_line(tmp_path, section, key, value):
    """eve_um = 1e300 ended positioning --uncertainty in an OverflowError; now it is refused where it is read."""
    path = tmp_path / "b.toml"
    path.write_text(f"# a budget\n[{section}]\n{key} = {value}\n")
    with pytest.raises(AxiscalError) as info:
        read_budget(path)
    assert info.value.path == str(path) and info.value.line == 3 and f"[{section}] {key} must" in info.value.message


def test_the_largest_budget_keeps_every_figure_finite():
    from axiscal.uncertainty import positioning_uncertainty
    from axiscal.uncertainty.budget import BUDGET_RANGES

    tables: dict[str, dict[str, float]] = {}
    for (section, key), (_, high) in BUDGET_RANGES.items():
        tables.setdefault(section, {})[key] = high
    budget = budget_from_dict(tables)
    result = positioning_uncertainty(budget, 1e6)  # a million metres of travel, the most the reader takes
    assert all(math.isfinite(u) for u in result.U.values()) and all(math.isfinite(u) for u in result.components.values())


def test_python_budget_refuses_values_beyond_their_range():
    with pytest.raises(AxiscalError, match="budget value eve_m must be 0 to 0.01, got 1e"):
        Budget(eve_m=1e300)


def test_cli_names_the_budget_line(run_cli, examples, tmp_path):
    text = (examples / "uncertainty_budget.toml").read_text().replace("eve_um = 1.0 ", "eve_um = 1e300")
    (tmp_path / "b.toml").write_text(text)
    line = next(n for n, row in enumerate(text.splitlines(), start=1) if row.startswith("eve_um"))
    status, out, err = run_cli("positioning", examples / "positioning_run.csv", "--uncertainty", tmp_path / "b.toml")
    assert status == 2 and out == "" and err == f"axiscal: error: {tmp_path / 'b.toml'}:{line}: [setup] eve_um must be 0 to 10000, not 1e+300\n"
