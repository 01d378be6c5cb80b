"""Interferometer lengths: paper 003 eq (1), Tables 1 and 3, ISO 1 normalisation, dead path."""

from __future__ import annotations

import numpy as np
import pytest

from axiscal.air import refractive_index
from axiscal.errors import AxiscalError
from axiscal.interferometer import compensated_length


def test_compensated_length_divides_by_the_air_index_and_normalises_to_20c():
    rng = np.random.default_rng(0)
    reading = rng.uniform(0.0, 1.0, 50)
    air_t = rng.uniform(15.0, 25.0, 50)
    pressure = rng.uniform(95e3, 105e3, 50)
    humidity = rng.uniform(20.0, 80.0, 50)
    material = rng.uniform(18.0, 24.0, (50, 3))
    result = compensated_length(
        reading, air_temperature_c=air_t, pressure_pa=pressure, humidity_pct=humidity, material_temperature_c=material
    )
    for i in range(50):
        n = refractive_index(air_t[i], pressure[i], humidity[i], 632.991)
        t_mean = sum(material[i]) / 3
        expected = reading[i] / n / (1 + 11.5e-6 * (t_mean - 20))
        assert result[i] == pytest.approx(expected, rel=1e-15, abs=1e-18)


def test_compensated_length_rejects_mismatched_shapes():
    with pytest.raises(AxiscalError):
        compensated_length(np.ones(3), air_temperature_c=[20.0, 21.0], pressure_pa=101325.0, humidity_pct=50.0)
