"""The page's forms: a good form is read in the units of its field names, any other JSON is named field by field."""

from __future__ import annotations

import datetime as dt

import pytest
from hypothesis import given, settings
from hypothesis import strategies as hs

from axiscal.errors import AxiscalError
from axiscal.workbench import FORMS, FormErrors, checked

VISIT = {"title": "Acceptance", "date": "2026-11-26", "operator": "J. Doe", "machine": "VMC 1", "instrument": "Laser",
         "A_um": 45, "E_um": 40, "R_um": 5, "B_um": 6}
PLAN = {"start_mm": 0, "end_mm": 150, "targets": 5, "runs": 2, "overrun_mm": 5, "dwell_s": 1}


def test_a_good_visit_is_read_with_its_defaults():
    form = checked("visit", VISIT)
    assert form.date == dt.date(2026, 11, 26) and form.controller == "linuxcnc" and form.wavelength_nm == 632.99137


def test_every_wrong_field_is_named_once():
    with pytest.raises(FormErrors) as caught:
        checked("visit", VISIT | {"operator": " ", "wavelength_nm": 10.0, "controller": "okuma", "axes": ["X"]})
    assert set(caught.value.fields) == {"operator", "wavelength_nm", "controller", "axes"}  # no field of the form
    assert isinstance(caught.value, AxiscalError)


def test_a_plan_that_goes_backwards_is_named_by_its_end():
    with pytest.raises(FormErrors) as caught:
        checked("plan", PLAN | {"end_mm": 0})
    assert caught.value.fields == {"end_mm": "the end must lie beyond the start"}


def test_a_dwell_the_stop_detector_cannot_use_is_refused_saying_the_least():
    # 0.5 s (the capture's window, with no time to settle) ran the whole program, then found no stop at all
    for dwell_s in (0.5, 0.69):
        with pytest.raises(FormErrors) as caught:
            checked("plan", PLAN | {"dwell_s": dwell_s})
        assert set(caught.value.fields) == {"dwell_s"}
        assert caught.value.fields["dwell_s"].startswith("the least dwell is 0.7 s: the stop detector needs the axis"
                                                         " still for a whole 0.5 s window after it settles")
    assert checked("plan", PLAN | {"dwell_s": 0.7}).dwell_s == 0.7


JSON = hs.recursive(hs.none() | hs.booleans() | hs.floats(allow_nan=True) | hs.integers() | hs.text(max_size=5),
                    lambda inner: hs.lists(inner, max_size=3) | hs.dictionaries(hs.text(max_size=5), inner, max_size=3),
                    max_leaves=10)


@settings(max_examples=60)
@given(name=hs.sampled_from(sorted(FORMS)), changes=hs.dictionaries(
    hs.sampled_from(sorted({*VISIT, *PLAN, "instrument", "controller", "dialect", "seed"})), JSON, max_size=4))
def test_any_json_is_a_form_or_named_fields(name, changes):
    base = {"visit": VISIT, "plan": PLAN, "connect": {}}[name]
    try:
        checked(name, base | changes)
    except FormErrors as exc:
        assert exc.fields and all(isinstance(v, str) and v for v in exc.fields.values())
