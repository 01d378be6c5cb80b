"""Every command of ``axiscal`` at once: number options refuse nan and infinities where they are parsed."""

from __future__ import annotations

import click
import pytest

from axiscal.cli.common import FiniteFloat, FiniteRange
from cli_commands import leaf_commands


def long_name(option: click.Option) -> str:
    return max(option.opts, key=len)


NUMBER_OPTIONS = [
    pytest.param(path, long_name(option), option.nargs, id=" ".join(path) + " " + long_name(option))
    for path, command in leaf_commands()
    for option in command.params
    if isinstance(option, click.Option) and isinstance(option.type, click.types.FloatParamType)
]


def test_there_are_number_options_to_check():
    assert len(NUMBER_OPTIONS) > 40


@pytest.mark.parametrize("path, flag, nargs", NUMBER_OPTIONS)
def test_every_number_option_is_finite(path, flag, nargs):
    command = dict(leaf_commands())[path]
    option = next(o for o in command.params if isinstance(o, click.Option) and long_name(o) == flag)
    assert isinstance(option.type, (FiniteFloat, FiniteRange)), f"axiscal {' '.join(path)} {flag} takes nan"


@pytest.mark.parametrize("value", ["nan", "inf", "-inf"])
@pytest.mark.parametrize("path, flag, nargs", NUMBER_OPTIONS)
def test_a_non_finite_number_is_refused_used_or_not(run_cli, path, flag, nargs, value):
    status, out, err = run_cli(*path, flag, *[value] * nargs)
    assert status == 2 and out == ""
    assert err == f"axiscal: error: {flag} must be a finite number, got {value}\n"


@pytest.mark.parametrize(
    "argv",
    [
        ("plan", "--start-mm", "0", "--end-mm", "100", "--dwell-s", "nan"),
        ("plan", "--start-mm", "0", "--end-mm", "100", "--feed-mm-min", "inf"),
        ("fringes", "--counts", "1000", "--temperature-c", "20", "--pressure-pa", "101325", "--humidity-pct", "50",
         "--expansion-per-k", "inf"),
    ],
)
def test_options_the_command_does_not_use(run_cli, argv):
    """Without --gcode plan does not use --dwell-s or --feed-mm-min, nor fringes --expansion-per-k without a
    material temperature: their values are checked all the same."""
    status, _, err = run_cli(*argv)
    assert status == 2 and f"{argv[-2]} must be a finite number, got {argv[-1]}" in err


def test_simulate_probes_is_one_name_and_the_old_one_says_so(run_cli, examples, tmp_path):
    args = ["--profile", examples / "separation_profile.csv", "--motion", examples / "separation_motion.csv",
            "--spacing-mm", "15", "--step-mm", "1"]
    status, new, err = run_cli("simulate", "probes", *args)
    assert status == 0 and err == "" and new.startswith("position_mm,a_um,b_um,c_um\n")
    status, old, err = run_cli("simulate-probes", *args)
    assert status == 0 and old == new and err == "axiscal: 'simulate-probes' is now 'simulate probes'; the old name will go\n"
    status, listing, _ = run_cli("--help")
    assert status == 0 and "simulate-probes" not in listing and "\n  simulate " in listing
    status, listing, _ = run_cli("simulate", "--help")
    assert all(f"\n  {name} " in listing for name in ("ballbar", "frames", "laser", "probes"))


def test_simulate_ballbar_is_registered(run_cli, tmp_path):
    status, _, err = run_cli("simulate", "ballbar", "--step-deg", "1", "--direction", "ccw", "-o", tmp_path / "t.csv")
    assert status == 0 and (tmp_path / "t.csv").read_text().startswith("angle_deg,direction,radius_deviation_um\n")
