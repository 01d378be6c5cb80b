"""A library message about an argument in SI, shown under a flag with another unit, speaks the flag's unit."""

from __future__ import annotations

import math

import pytest

from axiscal.cli.common import flags_named
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_number


@pytest.mark.parametrize(("key", "flag", "bounds", "value", "said"), [
    ("stability_m", "--stability-um", {"positive": True}, -1e-6, "--stability-um must be a positive finite number of um, not -1"),
    ("stability_m", "--stability-um", {"positive": True, "high": 1e-3}, 1.0, "--stability-um must be at most 1000 um, not 1e+06"),
    ("moving_m_s", "--moving-mm-s", {"positive": True}, -1e-3, "--moving-mm-s must be a positive finite number of mm/s, not -1"),
    ("window_s", "--window-ms", {"positive": True}, -0.02, "--window-ms must be a positive finite number of ms, not -20"),
    ("wavelength_m", "--wavelength-nm", {"low": 100e-9, "high": 20e-6}, 0.0, "--wavelength-nm must be between 100 and 20000 nm, not 0"),
    ("spacing_m", "--spacing-mm", {"positive": True}, math.nan, "--spacing-mm must be a positive finite number of mm, not nan"),
    ("window_s", "--window-s", {"positive": True}, -1.0, "--window-s must be a positive finite number of seconds, not -1.0"),
])
def test_the_message_speaks_the_flags_unit(key, flag, bounds, value, said):
    with pytest.raises(AxiscalError) as info, flags_named({key: flag}):
        check_number(key, value, **bounds)
    assert info.value.message == said


def test_the_dynamics_flag_of_a_speed_is_refused_in_mm_per_s(run_cli, examples):
    status, _, err = run_cli("dynamics", examples / "capture" / "recording_x.csv", "--moving-mm-s", "-1")
    assert status == 2 and err == "axiscal: error: --moving-mm-s must be a positive finite number of mm/s, not -1\n"
