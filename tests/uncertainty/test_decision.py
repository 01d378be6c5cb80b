"""Decision rules: simple acceptance and the ISO 14253-1 guard band."""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st

from axiscal.errors import AxiscalError
from axiscal.uncertainty import DECISION_RULES, decide


@pytest.mark.parametrize(
    "value, rule, verdict",
    [
        (8.0, "simple", "pass"), (10.0, "simple", "pass"), (10.5, "simple", "fail"),
        (8.0, "guard-band", "pass"), (8.5, "guard-band", "pass"), (9.0, "guard-band", "inconclusive"),
        (11.5, "guard-band", "inconclusive"), (11.6, "guard-band", "fail"),
    ],
)
def test_verdicts(value, rule, verdict):
    d = decide(value, 10.0, 1.5, rule=rule)
    assert d.verdict == verdict and d.statement == DECISION_RULES[rule]
    assert d.acceptance_limit == (10.0 if rule == "simple" else 8.5)


@given(value=st.floats(0, 100), limit=st.floats(0, 100), U=st.floats(0, 10))
def test_a_guard_banded_pass_is_a_simple_pass(value, limit, U):
    if decide(value, limit, U, rule="guard-band").verdict == "pass":
        assert decide(value, limit, U).verdict == "pass"
    if decide(value, limit, U, rule="guard-band").verdict == "fail":
        assert decide(value, limit, U).verdict == "fail"


def test_bad_input():
    with pytest.raises(AxiscalError, match="rule"):
        decide(1.0, 2.0, rule="shared-risk")
    with pytest.raises(AxiscalError, match="negative"):
        decide(1.0, 2.0, -0.1)
    with pytest.raises(AxiscalError, match="finite"):
        decide(float("nan"), 2.0)
