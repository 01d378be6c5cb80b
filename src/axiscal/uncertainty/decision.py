"""Decision rules for acceptance with a stated measurement uncertainty (ISO 14253-1:2017, ILAC-G8).

``simple``: the measured value is compared with the limit as it is (simple acceptance, ILAC-G8
4.2.1; the uncertainty is stated but not used). ``guard-band``: ISO 14253-1 5.2 and 5.3 — conformance
is proven when the value lies inside the tolerance reduced by the expanded uncertainty U (value <=
limit - U), non-conformance when it lies outside the tolerance enlarged by U (value > limit + U);
in between neither is proven and the verdict is ``inconclusive``.
"""

from __future__ import annotations

from dataclasses import dataclass

from axiscal.io.arguments import check_choice, check_number

__all__ = ["DECISION_RULES", "Decision", "decide"]

#: rule name -> how a report states it
DECISION_RULES: dict[str, str] = {
    "simple": "simple acceptance (ILAC-G8): pass when the value is within the limit; U is stated, not used",
    "guard-band": "guard-banded per ISO 14253-1: pass when value + U is within the limit, fail when value - U exceeds it",
}


@dataclass(frozen=True)
class Decision:
    """The verdict on one figure against its upper limit.

    Attributes
    ----------
    verdict : {"pass", "fail", "inconclusive"}
    rule : str
        The rule name (a key of :data:`DECISION_RULES`).
    statement : str
        The rule as a report states it.
    value, limit, U : float
        The measured figure, its upper limit and expanded uncertainty (same unit).
    acceptance_limit : float
        The value up to which the figure passes (limit, or limit - U with the guard band).
    """

    verdict: str
    rule: str
    statement: str
    value: float
    limit: float
    U: float
    acceptance_limit: float


def decide(value: float, limit: float, U: float = 0.0, *, rule: str = "simple") -> Decision:
    """Pass, fail or inconclusive for a figure with an upper limit (a tolerance such as E <= 10 um).

    Parameters
    ----------
    value : float
        The measured figure (any unit, e.g. m).
    limit : float
        Its upper specification limit, same unit.
    U : float
        Expanded uncertainty of the value, same unit, >= 0.
    rule : {"simple", "guard-band"}, keyword-only
        The decision rule (module docstring).

    Returns
    -------
    Decision

    Raises
    ------
    AxiscalError
        An unknown rule, a negative or non-finite U, a non-finite value or limit.

    Examples
    --------
    >>> decide(9.0, 10.0, 1.5, rule="guard-band").verdict
    'inconclusive'
    >>> decide(9.0, 10.0, 1.5).verdict
    'pass'
    """
    check_choice("decision rule", rule, DECISION_RULES)
    value = check_number("value", value, unit="")
    limit = check_number("limit", limit, unit="")
    U = check_number("U", U, unit="", nonnegative=True)
    if rule == "simple":
        verdict, acceptance = ("pass" if value <= limit else "fail"), limit
    else:
        acceptance = limit - U
        verdict = "pass" if value <= acceptance else "fail" if value > limit + U else "inconclusive"
    return Decision(verdict, rule, DECISION_RULES[rule], float(value), float(limit), float(U), float(acceptance))
