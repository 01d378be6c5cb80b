"""``axiscal air`` and ``axiscal fringes`` end to end: NIST values, JSON shape, one-line errors."""

from __future__ import annotations

import json

import pytest

from axiscal.instruments.air import refractive_index
from axiscal.instruments.interferometer import compensated_length

AIR = ("air", "--temperature-c", "20", "--pressure-pa", "101325", "--humidity-pct", "0", "--wavelength-nm", "633")


def test_air_text_reproduces_nist_check_value(run_cli):
    # NIST EMT check table: 20 degC, 101.325 kPa, 0 %, 633 nm -> Ciddor 1.000271800
    status, out, err = run_cli(*AIR)
    assert status == 0, err
    assert "1.000271800" in out
    assert "271.800 ppm" in out
    assert "632.827997 nm" in out  # 633 / 1.000271800


def test_air_json_has_the_documented_keys(run_cli):
    # NIST EMT check table: 40 degC, 120 kPa, 75 %, 633 nm -> modified Edlen 1.000299406
    status, out, err = run_cli(
        "air", "--temperature-c", "40", "--pressure-pa", "120000", "--humidity-pct", "75", "--wavelength-nm", "633",
        "--method", "edlen", "--json",
    )
    assert status == 0, err
    body = json.loads(out)
    assert set(body) == {
        "refractive_index", "n_minus_1_ppm", "wavelength_in_air_nm", "method",
        "temperature_c", "pressure_pa", "humidity_pct", "wavelength_nm", "co2_ppm",
    }
    assert f"{body['refractive_index']:.9f}" == "1.000299406"
    assert body["n_minus_1_ppm"] == pytest.approx((body["refractive_index"] - 1) * 1e6)
    assert body["wavelength_in_air_nm"] == pytest.approx(633 / body["refractive_index"])
    assert body["method"] == "edlen" and body["co2_ppm"] == 450.0


def test_air_defaults_to_hene_and_ciddor(run_cli):
    status, out, _ = run_cli("air", "--temperature-c", "20", "--pressure-pa", "101325", "--humidity-pct", "50", "--json")
    body = json.loads(out)
    assert status == 0
    assert body["wavelength_nm"] == 632.991 and body["method"] == "ciddor"
    assert body["refractive_index"] == refractive_index(20, 101325, 50, 632.991)


def test_fringes_converts_counts_and_compensates(run_cli):
    counts = 1_579_800  # about 500 mm of He-Ne half-wavelengths
    status, out, err = run_cli(
        "fringes", "--counts", str(counts), "--temperature-c", "20", "--pressure-pa", "101325", "--humidity-pct", "50",
        "--material-temperature-c", "21", "--material-temperature-c", "21.5", "--json",
    )
    assert status == 0, err
    body = json.loads(out)
    vacuum = counts * 632.991e-9 / 2
    assert body["vacuum_length_mm"] == pytest.approx(vacuum * 1e3, rel=1e-15)
    environment = dict(air_temperature_c=20.0, pressure_pa=101325.0, humidity_pct=50.0)
    assert body["length_in_air_mm"] == pytest.approx(float(compensated_length(vacuum, **environment)) * 1e3, rel=1e-15)
    expected = compensated_length([vacuum], material_temperature_c=[[21.0, 21.5]], **environment)[0]
    assert body["length_at_20c_mm"] == pytest.approx(float(expected) * 1e3, rel=1e-15)


def test_fringes_text_without_material_temperature(run_cli):
    status, out, _ = run_cli(
        "fringes", "--counts", "1024", "--optical-fold", "2", "--interpolation", "1024",
        "--temperature-c", "20", "--pressure-pa", "101325", "--humidity-pct", "50",
    )
    assert status == 0
    assert "0.000158 mm" in out  # 632.991 nm / 4
    assert "20 degC" not in out


@pytest.mark.parametrize(
    "changes, message",
    [
        ({"--pressure-pa": "1013.25"}, "air pressure"),
        ({"--pressure-pa": "-1"}, "positive"),
        ({"--humidity-pct": "120"}, "relative humidity"),
        ({"--temperature-c": "293.15"}, "air temperature"),
        ({"--wavelength-nm": "0.633"}, "vacuum wavelength"),
        ({"--co2-ppm": "-3"}, "CO2"),
        ({"--temperature-c": "nan"}, "--temperature-c must be a finite number"),
    ],
)
def test_air_bad_values_exit_2_with_one_line(run_cli, changes, message):
    arguments = dict(zip(AIR[1::2], AIR[2::2]))
    arguments.update(changes)
    status, out, err = run_cli("air", *[item for pair in arguments.items() for item in pair])
    assert status == 2
    assert out == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("axiscal: error: ") and message in lines[0]


@pytest.mark.parametrize(
    "argv",
    [
        ("air", "--temperature-c", "20", "--pressure-pa", "101325", "--humidity-pct", "50", "--method", "lorentz"),
        ("air", "--temperature-c", "20", "--pressure-pa", "101325"),
        ("air", "--temperature-c", "warm", "--pressure-pa", "101325", "--humidity-pct", "50"),
        ("fringes", "--counts", "10", "--optical-fold", "0", "--temperature-c", "20", "--pressure-pa", "101325", "--humidity-pct", "50"),
    ],
)
def test_usage_errors_exit_2(run_cli, argv):
    status, _, err = run_cli(*argv)
    assert status == 2
    assert "Traceback" not in err


def test_fringes_bad_environment_exits_2(run_cli):
    status, _, err = run_cli(
        "fringes", "--counts", "10", "--temperature-c", "20", "--pressure-pa", "101325", "--humidity-pct", "50",
        "--wavelength-nm", "1064", "--method", "shopfloor",
    )
    assert status == 2
    assert err.count("\n") == 1 and "'shopfloor'" in err
