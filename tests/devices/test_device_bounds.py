"""What reaches a device is bounded where it comes in: the words sent to a controller, the simulators' settings, the specs."""

from __future__ import annotations

import re

import pytest

from axiscal.devices.controller import move_words
from axiscal.devices.controllers import open_controller
from axiscal.devices.instruments import InstrumentOptions, open_instrument
from axiscal.errors import AxiscalError


def test_the_words_of_a_move_are_bounded_and_never_an_exponent():
    assert move_words("X", 0.0123456, 1000 / 60e3) == "X12.3456 F1000"
    assert move_words("X", -1e-12, 100_000 / 60e3) == "X0.0000 F100000"  # the largest feed, written whole
    assert not re.search(r"\de[+-]?\d", move_words("Z", -99.999999, 100_000 / 60e3, places=6, feed_places=3))
    with pytest.raises(AxiscalError, match="feed_mm_min must be at most 100000 mm/min"):
        move_words("X", 0.0, 1e6 / 60e3)  # was sent as F1000000.0 (F1e+06 shown by the dry run)
    with pytest.raises(AxiscalError, match=r"X position in mm must be within \+/-99999.999"):
        move_words("X", 1e297, 0.01)


def test_the_virtual_controller_refuses_what_no_control_is_sent():
    from axiscal.capture.connected import sim_machine

    controller = sim_machine().controller()
    try:
        with pytest.raises(AxiscalError, match="feed_mm_min must be at most"):
            controller.move_to("X", 0.01, 1e300)  # was driven
    finally:
        controller.close()


@pytest.mark.parametrize(("kwargs", "words"), [
    ({"wavelength_m": 0.0}, "wavelength_m must be between 1e-07 and 2e-05"),  # the simulator's thread died on it
    ({"counts_per_mm": 1e300}, "counts_per_mm must be at most 1e"),
    ({"rate_hz": 0.0}, "rate_hz"), ({"optics_multiplier": 3}, "optics_multiplier"), ({"unit": "furlong"}, "unit"),
])
def test_instrument_options_are_checked_before_a_simulator_starts_on_them(kwargs, words):
    with pytest.raises(AxiscalError, match=words):
        InstrumentOptions(**kwargs)


def test_a_negative_seed_is_one_line():
    with pytest.raises(AxiscalError, match="seed must be"):
        open_instrument("sim:umd", position=lambda t: 0.0, seed=-1)


@pytest.mark.parametrize("spec", ["moonraker:not a url", "moonraker:http://host:abc", "moonraker:http://host:99999",
                                  "moonraker:http://host:0", "moonraker:http://exa mple"])
def test_a_moonraker_address_http_will_not_send_is_one_line(spec):
    with pytest.raises(AxiscalError, match="moonraker:URL needs an http:// address"):
        open_controller(spec)  # was http.client.InvalidURL, a traceback
