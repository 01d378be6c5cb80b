"""Backlash parameters: the reversal of ISO 230-2 turned into each controller's parameter, and read back.

The readers below follow each controller's documentation: LinuxCNC INI ``[JOINT_n] BACKLASH``
(machine units), FANUC parameter 1851 (word axis, detection units, -9999..9999), SINUMERIK
``$MA_BACKLASH[0,AXn]`` (MD32450, mm), HEIDENHAIN ``MP_backLash`` (mm), TwinCAT CNC
``getriebe[0].lose`` (P-AXIS-00103, SGN16, 0.1 um), grblHAL ``$160+axis`` (mm), Marlin and
RepRapFirmware ``M425`` (mm).
"""

from __future__ import annotations

import re

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.compensation.backlash import (
    BACKLASH_CONTROLLERS,
    backlash_from_run,
    backlash_setting,
    reversal_backlash,
)
from axiscal.errors import AxiscalError
from axiscal.positioning import PositioningRun, iso230_2
from axiscal.units import MM, UM


def read_back(controller, lines, axis):
    """The backlash in metres, read from the controller's own syntax."""
    text = "\n".join(lines)
    if controller == "linuxcnc":
        assert re.fullmatch(r"\[JOINT_\d+\]", lines[0])
        return float(re.search(r"^BACKLASH = (\S+)$", text, re.M).group(1)) * MM
    if controller == "fanuc":
        number, letter, value = lines[0].split()
        assert number == "1851" and letter == axis and -9999 <= int(value) <= 9999
        return int(value) * UM
    if controller == "siemens":
        m = re.fullmatch(r"\$MA_BACKLASH\[0,AX(\d+)\]=(\S+)", lines[0])
        return float(m.group(2)) * MM
    if controller == "heidenhain":
        name, letter, value = lines[0].split()
        assert name == "MP_backLash" and letter == axis
        return float(value) * MM
    if controller == "twincat":
        name, value = lines[0].split()
        assert name == "getriebe[0].lose" and -32767 <= int(value) <= 32767
        return int(value) * 0.1 * UM
    if controller == "grblhal":
        m = re.fullmatch(r"\$(\d+)=(\S+)", lines[0])
        assert int(m.group(1)) == 160 + "XYZABC".index(axis)
        return float(m.group(2)) * MM
    m = re.fullmatch(r"M425 ([XYZABC])(\S+)", lines[0])
    assert m.group(1) == axis
    return float(m.group(2)) * MM


#: the resolution each controller's value is written with, metres
RESOLUTION = {"linuxcnc": 1e-6 * MM, "fanuc": UM, "siemens": 1e-6 * MM, "heidenhain": 1e-4 * MM,
              "twincat": 0.1 * UM, "grblhal": 1e-3 * MM, "marlin": 1e-4 * MM, "rrf": 1e-4 * MM}


@pytest.mark.parametrize("controller", sorted(BACKLASH_CONTROLLERS))
@pytest.mark.parametrize("axis", ["X", "Z"])
def test_round_trip(controller, axis):
    value = 23.456 * UM
    setting = backlash_setting(controller, value, axis=axis)
    back = read_back(controller, setting.lines, axis)
    assert back == pytest.approx(setting.written_m, abs=1e-12)
    assert abs(back - value) <= RESOLUTION[controller] / 2 + 1e-15
    assert setting.parameter == BACKLASH_CONTROLLERS[controller][0]


def play_run(play_m, *, targets=5, runs=5, seed=0):
    """A slide with play between encoder and slide: b/2 behind moving up, b/2 ahead moving down."""
    rng = np.random.default_rng(seed)
    t = np.linspace(0.0, 0.4, targets)
    pitch = 3 * UM * np.sin(t / 0.4 * np.pi)[:, None]
    up = pitch - play_m / 2 + rng.normal(0, 0.1 * UM, (targets, runs))
    down = pitch + play_m / 2 + rng.normal(0, 0.1 * UM, (targets, runs))
    return PositioningRun(t, up, down)


def test_play_is_recovered_with_the_iso_sign():
    run = play_run(12 * UM)
    result = iso230_2(run)
    # ISO 230-2: B_i = mean_up - mean_down, negative for the usual play
    assert result.B_mean == pytest.approx(-12 * UM, abs=0.2 * UM)
    assert reversal_backlash(run) == pytest.approx(-result.B_mean)
    assert abs(reversal_backlash(run, method="max")) == pytest.approx(result.B)
    assert reversal_backlash(run, method="target", target_m=0.1) == pytest.approx(
        -(run.deviations_up[1].mean() - run.deviations_down[1].mean()))
    setting = backlash_from_run("siemens", run)
    assert setting.lines[0].startswith("$MA_BACKLASH[0,AX1]=0.01")


@settings(max_examples=40, deadline=None)
@given(st.floats(0.0, 500.0))
def test_backlash_property(play_um):
    run = play_run(play_um * UM, runs=1, seed=1)
    # one run per direction: the noise is 0.1 um per reading
    assert reversal_backlash(run) == pytest.approx(play_um * UM, abs=0.3 * UM)


def test_refusals():
    with pytest.raises(AxiscalError, match="only a positive distance"):
        backlash_setting("marlin", -5 * UM)
    assert backlash_setting("siemens", -5 * UM).lines == ("$MA_BACKLASH[0,AX1]=-0.005",)
    with pytest.raises(AxiscalError, match="beyond parameter 1851"):
        backlash_setting("fanuc", 10.5 * MM)
    with pytest.raises(AxiscalError, match="beyond P-AXIS-00103"):
        backlash_setting("twincat", 3.3 * MM)
    with pytest.raises(AxiscalError, match="unknown controller"):
        backlash_setting("mach3", 5 * UM)
    with pytest.raises(AxiscalError, match="unknown axis"):
        backlash_setting("rrf", 5 * UM, axis="Q")
    with pytest.raises(AxiscalError, match="not a target"):
        reversal_backlash(play_run(1 * UM), method="target", target_m=0.05)
