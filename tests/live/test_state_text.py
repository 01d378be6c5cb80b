"""The dashboard's state text: made in parts, it is the text one json.dumps makes; the lists, Python's rounding."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.live.server import _json_in_parts
from axiscal.live.state import _plain

leaves = st.one_of(st.none(), st.booleans(), st.integers(), st.floats(allow_nan=False, allow_infinity=False), st.text())
values = st.recursive(leaves, lambda inner: st.lists(inner, max_size=4) | st.dictionaries(st.text(), inner, max_size=4),
                      max_leaves=30)


@settings(max_examples=200, deadline=None)
@given(values)
def test_the_text_made_in_parts_is_json_dumps(value):
    assert _json_in_parts(value) == json.dumps(value, allow_nan=False)


def test_a_nan_is_refused_as_json_dumps_refuses_it():
    with pytest.raises(ValueError):
        _json_in_parts({"history": {"e_um": [1.0, math.nan]}})


def test_the_lists_are_rounded_as_python_rounds_and_nan_is_none():
    """Against the plain reference (round() of each value) over seeded random values: the same text up to
    10^4 (the dashboard's µm and mm); beyond, where value x 10^digits is no longer exact, one unit of the
    last decimal at most (2389736.948808 for round()'s ...809)."""
    rng = np.random.default_rng(0)
    x = rng.normal(size=20_000) * rng.choice([1e-7, 1e-3, 1.0, 1e3, 1e6], 20_000)
    x[rng.integers(0, len(x), 500)] = np.nan
    for digits in (3, 6):
        reference = [None if v != v else round(v, digits) for v in x.tolist()]
        made = _plain(x, digits)
        assert [v is None for v in made] == [v is None for v in reference]
        for value, ours, theirs in zip(x.tolist(), made, reference):
            if ours is not None and abs(value) < 1e4:
                assert repr(ours) == repr(theirs), value
            elif ours is not None:
                assert abs(ours - theirs) <= 1.01 * 10.0**-digits, value  # the two doubles nearest adjacent decimals
