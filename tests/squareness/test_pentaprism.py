"""The pentaprism's sensitivity to its set-up (paper 002 section 3, Fig. 5, eq 12)."""

from __future__ import annotations

import numpy as np
import pytest

from axiscal.errors import AxiscalError
from axiscal.instruments.optics import pentaprism_sensitivity
from axiscal.squareness.pentaprism import (
    PAPER_002_QUADRATIC_ARCSEC,
    PENTAPRISM_SHIFTS_M,
    pentaprism_study,
)
from axiscal.units import ARCMIN, ARCSEC


def test_eq_12_at_printed_precision():
    # paper 002 eq (12): a rotation gamma about Z changes the deviation by 4.84803e-6 gamma^2
    # (arc seconds); 5 arc minutes -> 0.436 arc seconds (the paper prints 0.43)
    study = pentaprism_study(range_rad=5 * ARCMIN, steps=3)
    assert round(study.payload()["deviation_change_arcsec"]["Z"][0], 2) == -0.44
    # the ray trace's coefficient agrees with the printed one to 4 figures (4.8481e-6 against 4.84803e-6)
    assert f"{study.table.quadratic_coefficient * ARCSEC:.3e}" == f"{PAPER_002_QUADRATIC_ARCSEC:.3e}" == "4.848e-06"


def test_study_is_the_ray_trace_and_its_report():
    study = pentaprism_study(range_rad=10 * ARCMIN, steps=5)
    table = pentaprism_sensitivity(np.linspace(-10, 10, 5) * ARCMIN, PENTAPRISM_SHIFTS_M)
    np.testing.assert_allclose(study.table.change_rad, table.change_rad)
    lines = study.report().splitlines()
    assert lines[0] == "pentaprism of paper 002 (index 1.5168): angle between incident and exit beam minus 90 deg"
    assert lines[3] == "          -10.00          0.0000          0.0000         -1.7453"
    assert lines[-1].endswith("(paper 002 eq 12: 4.84803e-6)")
    assert "-0.0000" not in study.report()


@pytest.mark.parametrize(("kwargs", "message"), [({"range_rad": 0.0}, "rotation range"), ({"steps": 1}, "2 to 2001")])
def test_bad_sweeps(kwargs, message):
    with pytest.raises(AxiscalError, match=message):
        pentaprism_study(**kwargs)
