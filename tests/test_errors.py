"""Messages show long numbers in exponent form: an input of 1e300 never prints 300 digits."""

from __future__ import annotations

import re

import pytest
from hypothesis import given
from hypothesis import strategies as st

from axiscal.errors import MAX_PLAIN_DIGITS, AxiscalError, exponent_form
from axiscal.io.arguments import check_count, check_integer

#: a whole part of more than MAX_PLAIN_DIGITS digits (the decimals of a float's repr may be longer)
LONG = re.compile(r"(?<![\d.])\d{%d,}" % (MAX_PLAIN_DIGITS + 1))


def test_a_long_number_is_shown_in_exponent_form():
    assert exponent_form("1" + "0" * 300 + ".000 mm") == "1e+300 mm"
    assert exponent_form("needs at least " + str(5 * 10**297)) == "needs at least 5e+297"
    assert exponent_form("-" + "9" * 400 + " frames") == "-1e+400 frames"  # beyond any float


def test_numbers_people_read_are_left_as_they_are():
    text = "line 12 of run_20261126123456789.csv: 123456789012345 counts at 1234.567890123456789 mm, id 0x1234567890abcdef0"
    assert exponent_form(text) == text


@given(st.floats(allow_nan=False, allow_infinity=False), st.sampled_from(["{:.3f}", "{:+.1f}", "{:.0f}", "{:g}", "{}"]))
def test_no_message_holds_a_long_number(value, fmt):
    message = str(AxiscalError(f"the value {fmt.format(value)} mm is refused", path="run.csv", line=3))
    assert not LONG.search(message), message
    shown = float(re.search(r"value (\S+) mm", message).group(1))
    assert shown == pytest.approx(float(fmt.format(value)), rel=1e-5)


@pytest.mark.parametrize("check", [lambda v: check_count("trials", v), lambda v: check_integer("trials", float(v))])
def test_an_argument_is_shown_whole_never_cut_into_another_number(check):
    """A 301-digit count was cut to its first 37 digits and shown as that (another) number."""
    with pytest.raises(AxiscalError) as caught:
        check(-(10**300))
    assert str(caught.value).endswith(" -1e+300")


@pytest.mark.parametrize(
    ("argv", "expected"),
    [
        (("plan", "--start-mm", "0", "--end-mm", "1e300", "--targets", "11"),
         "1e+300 is not in the range -99999.999<=x<=99999.999"),
        (("export", "skew", "--firmware", "klipper", "--xy-arcsec", "1e300"), "the XY squareness +2.77778e+296 deg is beyond"),
        (("simulate", "frames", "--path", "raster", "--rate", "1e300", "--duration", "2"), "gives 2e+300 frames"),
    ],
)
def test_the_command_line_shows_no_300_digit_number(run_cli, tmp_path, argv, expected):
    status, out, err = run_cli(*argv, "-o", tmp_path / "out.txt") if argv[0] == "simulate" else run_cli(*argv)
    assert status == 2 and err.count("\n") == 1 and expected in err and not LONG.search(err), err
