"""The results of a campaign: each test's figures against its tolerances, the verdict, results.json.

A figure passes when its magnitude is at most its tolerance (simple acceptance: the measured value
is compared with the limit as it is). A test with no tolerance for any of its figures is ``"not
assessed"``; the campaign fails when any test fails, passes when at least one test was assessed
and none failed. The schema of results.json (``axiscal-results/1``) is documented in
docs/campaign.md.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_choice, check_mapping, is_real
from axiscal.io.arguments import check_instance
from axiscal.version import __version__

__all__ = [
    "SCHEMA",
    "VERDICTS",
    "Check",
    "Figure",
    "Plot",
    "TestResult",
    "CampaignResults",
    "check_figures",
    "overall_verdict",
    "results_payload",
]

SCHEMA = "axiscal-results/1"
VERDICTS = ("pass", "fail", "inconclusive", "not assessed")


@dataclass(frozen=True)
class Check:
    """One figure held against its tolerance.

    Attributes
    ----------
    figure : str
        The figure's key in the test's figures (``"E"``, ``"straightness_um"`` ...).
    tolerance_key : str
        The tolerance's key as written in campaign.toml (``"E_um"`` ...).
    value : float
        The figure's magnitude in the tolerance's unit.
    limit : float
        The tolerance.
    unit : str
        ``"um"`` or ``"arcsec"``.
    U : float or None
        Expanded uncertainty (k = 2) of the figure in the same unit, when a budget gives it.
    rule : str
        The decision rule: ``"simple"`` or ``"guard-band"``.
    """

    figure: str
    tolerance_key: str
    value: float
    limit: float
    unit: str
    U: float | None = None
    rule: str = "simple"

    @property
    def result(self) -> str:
        """``"pass"``, ``"fail"`` or (guard band only) ``"inconclusive"``.

        Simple acceptance: pass when ``|value| <= limit``. Guard band (ISO 14253-1): pass when
        ``|value| + U <= limit``, fail when ``|value| - U > limit``, else inconclusive. A figure
        that could not be computed does not pass.
        """
        if not math.isfinite(self.value):
            return "fail"
        value = abs(self.value)
        if self.rule == "guard-band" and self.U is not None:
            if value + self.U <= self.limit:
                return "pass"
            return "fail" if value - self.U > self.limit else "inconclusive"
        return "pass" if value <= self.limit else "fail"

    @property
    def passed(self) -> bool:
        """True when the figure passes under its rule."""
        return self.result == "pass"


@dataclass(frozen=True)
class Plot:
    """A plot of the report.

    Attributes
    ----------
    title : str
        Its caption.
    svg : str
        Its SVG text, placed inline in the HTML page.
    """

    title: str
    svg: str = field(repr=False)


@dataclass(frozen=True)
class Figure:
    """A figure as the report's tables show it.

    Attributes
    ----------
    label : str
    value : float
    unit : str
    """

    label: str
    value: float | str
    unit: str


@dataclass
class TestResult:
    """What one test of the campaign gave.

    Attributes
    ----------
    id, kind : str
        From the campaign.
    axis : str or None
        The axis, or the plane for squareness.
    files : list of str
        The data files, relative to the campaign folder.
    figures : dict
        The figures under the keys and units of the command of the same name's ``--json``.
    checks : list of Check
        Each toleranced figure against its limit.
    plots : list of Plot
    table : list of Figure
        The figures the report shows in its axis section.
    environment : dict
        Per-run statistics of air and material sensors, when the file has them.
    warnings : list of str
    compensation : list of dict
        ``{"controller", "axis", "file"}`` for each compensation file written.
    method : str
        The method and standard used, one line.
    uncertainty : dict
        Expanded uncertainty (k = 2) of figures, by figure key, in the figure's unit.
    """

    id: str
    kind: str
    axis: str | None
    files: list[str]
    figures: dict[str, Any]
    checks: list[Check] = field(default_factory=list)
    plots: list[Plot] = field(default_factory=list)
    table: list[Figure] = field(default_factory=list)
    environment: dict[str, Any] = field(default_factory=dict)
    warnings: list[str] = field(default_factory=list)
    compensation: list[dict[str, str]] = field(default_factory=list)
    method: str = ""
    uncertainty: dict[str, float] = field(default_factory=dict)

    __test__ = False  # not a pytest test class

    @property
    def verdict(self) -> str:
        """``"pass"``, ``"fail"`` or ``"not assessed"``."""
        if not self.checks:
            return "not assessed"
        results = [c.result for c in self.checks]
        return "fail" if "fail" in results else "inconclusive" if "inconclusive" in results else "pass"

    @property
    def tolerances(self) -> dict[str, float]:
        """The tolerances held against this test's figures, as keyed in campaign.toml."""
        return {c.tolerance_key: c.limit for c in self.checks}


@dataclass
class CampaignResults:
    """The whole campaign's results: what :func:`axiscal.campaign.run_campaign` returns.

    Attributes
    ----------
    campaign, machine, instrument : dict
        The campaign.toml tables as written.
    tests : list of TestResult
        One per ``[[tests]]`` entry, in order.
    warnings : list of str
        Warnings about the campaign as a whole.
    model : dict
        The volumetric section when the campaign names a machine model.
    decision_rule : str
        How figures were held against tolerances: ``"simple"`` or ``"guard-band"``.
    issuer : dict
        What a calibration certificate adds, when the campaign states it: ``laboratory``,
        ``certificate`` (tables as written) and ``signatories`` (a list); empty otherwise.
    """

    campaign: dict[str, Any]
    machine: dict[str, Any]
    instrument: dict[str, Any]
    tests: list[TestResult]
    warnings: list[str] = field(default_factory=list)
    model: dict[str, Any] = field(default_factory=dict)
    decision_rule: str = "simple"
    issuer: dict[str, Any] = field(default_factory=dict)

    @property
    def verdict(self) -> str:
        """The campaign's verdict, see :func:`overall_verdict`."""
        return overall_verdict([t.verdict for t in self.tests])

    @property
    def all_warnings(self) -> list[str]:
        """The campaign's warnings, then each test's, prefixed with its id (results.json's ``warnings``)."""
        return [*self.warnings, *(f"{t.id}: {w}" for t in self.tests for w in t.warnings)]

    @property
    def compensation(self) -> list[dict[str, str]]:
        """Every compensation file written, over all tests."""
        return [entry for t in self.tests for entry in t.compensation]


def check_figures(
    figures: Mapping[str, Any],
    tolerances: Mapping[str, float],
    units: Mapping[str, str],
    *,
    uncertainty: Mapping[str, float] | None = None,
    rule: str = "simple",
) -> list[Check]:
    """Hold figures against tolerances.

    Parameters
    ----------
    figures : mapping
        Figure key -> value (in the tolerance's unit).
    tolerances : mapping
        Tolerance key -> limit. ``E_um`` applies to figure ``E``; ``straightness_um`` to
        ``straightness_um``.
    units : mapping
        Tolerance key -> unit shown in the report.
    uncertainty : mapping, keyword-only
        Figure key -> expanded uncertainty in the figure's unit, where a budget gives one.
    rule : {"simple", "guard-band"}, keyword-only
        The decision rule.

    Returns
    -------
    list of Check
        One per tolerance whose figure exists.

    Raises
    ------
    AxiscalError
        For arguments that are not mappings, a limit that is not a non-negative number, a figure
        that is not a number, an unknown rule.
    """
    from axiscal.uncertainty.decision import DECISION_RULES

    check_mapping("figures", figures, what="a mapping of figure keys to values")
    check_mapping("tolerances", tolerances, what="a mapping of tolerance keys to limits")
    check_mapping("units", units, what="a mapping of tolerance keys to units")
    if uncertainty is not None:
        check_mapping("uncertainty", uncertainty, what="a mapping of figure keys to expanded uncertainties")
        for figure, U in uncertainty.items():
            if not is_real(U) or not math.isfinite(U) or U < 0:
                raise AxiscalError(f"uncertainty['{figure}'] must be a non-negative number, not {U!r}")
    for key, unit in units.items():
        if not isinstance(unit, str):
            raise AxiscalError(f"units['{key}'] must be a unit (a str), not {unit!r}")
    check_choice("decision rule", rule, DECISION_RULES)
    out = []
    for key, limit in tolerances.items():
        if not isinstance(key, str):
            raise AxiscalError(f"tolerances must be keyed by figure names (str), not {key!r}")
        if not is_real(limit) or not math.isfinite(limit) or limit < 0:
            raise AxiscalError(f"tolerance '{key}' must be a non-negative number, not {limit!r}")
        figure = key if key in figures else key.rsplit("_", 1)[0]
        if figure not in figures:
            continue
        value = figures[figure]
        if value is not None and not is_real(value):
            raise AxiscalError(f"figures['{figure}'] must be a number (or None when not available), not {value!r}")
        value = float("nan") if value is None else float(value)
        U = None if uncertainty is None else uncertainty.get(figure)
        out.append(Check(figure, key, value, float(limit), units.get(key, key.rsplit("_", 1)[-1]), U, rule))
    return out


def overall_verdict(verdicts: Sequence[str]) -> str:
    """The campaign's verdict from its tests' verdicts.

    Parameters
    ----------
    verdicts : sequence of str
        Each test's ``"pass"``, ``"fail"``, ``"inconclusive"`` or ``"not assessed"``.

    Returns
    -------
    str
        ``"fail"`` if any test failed; else ``"inconclusive"`` if any test was (guard band); else
        ``"pass"`` if any passed; else ``"not assessed"``.

    Raises
    ------
    AxiscalError
        For ``verdicts`` that are not a sequence of the :data:`VERDICTS`.

    Examples
    --------
    >>> overall_verdict(["pass", "not assessed"])
    'pass'
    """
    if isinstance(verdicts, (str, bytes)) or not isinstance(verdicts, (Sequence, set, frozenset)):
        raise AxiscalError(f"verdicts must be a sequence of test verdicts, not {verdicts!r}")
    for verdict in verdicts:
        check_choice("verdict", verdict, VERDICTS)
    if "fail" in verdicts:
        return "fail"
    if "inconclusive" in verdicts:
        return "inconclusive"
    if "pass" in verdicts:
        return "pass"
    return "not assessed"


def results_payload(results: CampaignResults) -> dict[str, Any]:
    """The results.json object (schema ``axiscal-results/1``), values in the units of their keys.

    Parameters
    ----------
    results : CampaignResults

    Returns
    -------
    dict
        Ready for :func:`axiscal.io.dumps` (NaN becomes null there).

    Raises
    ------
    AxiscalError
        For ``results`` that are not a :class:`CampaignResults`.
    """
    check_instance("results", results, CampaignResults)
    tests = []
    for t in results.tests:
        entry: dict[str, Any] = {"id": t.id, "kind": t.kind}
        if t.kind == "squareness":
            entry["axes"] = t.axis
        elif t.axis is not None:
            entry["axis"] = t.axis
        entry["file"] = t.files[0] if len(t.files) == 1 else t.files
        entry.update(figures=t.figures, tolerances=t.tolerances, verdict=t.verdict)
        if t.uncertainty:
            entry["uncertainty"] = {"k": 2, **t.uncertainty}
        if t.environment:
            entry["environment"] = t.environment
        if t.warnings:
            entry["warnings"] = list(t.warnings)
        tests.append(entry)
    return {
        "schema": SCHEMA,
        "software": {"name": "axiscal", "version": __version__},
        "campaign": {"campaign": results.campaign, "machine": results.machine, "instrument": results.instrument,
                     **{k: v for k, v in results.issuer.items() if v}},
        "verdict": results.verdict,
        "decision_rule": results.decision_rule,
        "tests": tests,
        "compensation": [{k: v for k, v in entry.items() if k != "text"} for entry in results.compensation],
        **({"volumetric": results.model["figures"]} if results.model else {}),
        "warnings": results.all_warnings,
    }
