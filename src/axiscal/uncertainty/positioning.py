"""Uncertainty of the ISO 230-2 figures E, R, B, A and M of a positioning test (ISO 230-2:2014 Annex A, ISO/TR 230-9).

The figures that compare positions along the travel (E, M and A) carry every contribution of the
budget at the measured length L (the travel, last target minus first):
``U(E) = U(M) = U(A) = k sqrt(u_device^2 + u_air^2 + u_machine_expansion^2 + u_machine_temperature^2
+ u_misalignment^2 + u_eve^2)``. The reversal value B and the repeatability R are formed at one
target: what is proportional to the position (the length scale of laser, air and machine, and the
cosine error) cancels, and what is left is the environmental variation during the test,
``U(B) = U(R) = k u_eve``. k = 2.

:func:`positioning_monte_carlo` propagates the same model by Monte Carlo (JCGM 101): the air
through the full refractive-index equation and the misalignment through the cosine, both not
linear, where the analytic budget linearises.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_choice, check_count, check_mapping, check_number, is_real
from axiscal.io.arguments import check_instance, type_name
from axiscal.instruments.air import refractive_index
from axiscal.positioning.evaluation import Iso230Result, PositioningRun
from axiscal.uncertainty.budget import (
    COMPONENTS,
    Budget,
    as_budget,
    check_budget,
    length_components,
    length_model,
)
from axiscal.uncertainty.decision import DECISION_RULES, Decision, decide
from axiscal.uncertainty.montecarlo import (
    CoverageInterval,
    _whole_draws,
    coverage_interval,
)
from axiscal.units import UM

__all__ = [
    "PositioningWithUncertainty",
    "evaluate_positioning_with_uncertainty",
    "FIGURES",
    "FIGURE_COMPONENTS",
    "COVERAGE_FACTOR",
    "MAX_POSITIONING_DRAWS",
    "PositioningUncertainty",
    "positioning_uncertainty",
    "positioning_monte_carlo",
    "uncertainty_payload",
    "budget_report",
    "positioning_decisions",
]

#: the ISO 230-2 figures that get an uncertainty
FIGURES = ("E", "R", "B", "A", "M")
#: the components each figure carries (module docstring)
FIGURE_COMPONENTS: dict[str, tuple[str, ...]] = {
    "E": COMPONENTS,
    "M": COMPONENTS,
    "A": COMPONENTS,
    "B": ("eve",),
    "R": ("eve",),
}
#: coverage factor of the expanded uncertainties
COVERAGE_FACTOR = 2.0
#: the most Monte Carlo draws of a positioning budget (about 100 bytes each are held at once)
MAX_POSITIONING_DRAWS = 10**7


@dataclass(frozen=True)
class PositioningUncertainty:
    """Expanded uncertainties of the ISO 230-2 figures of one axis, SI.

    Attributes
    ----------
    length_m : float
        The measured length L the components are taken at, m.
    components : dict of str to float
        Standard uncertainty of each contribution (:data:`axiscal.uncertainty.budget.COMPONENTS`), m.
    U : dict of str to float
        Expanded uncertainty (k = 2) of each figure of :data:`FIGURES`, m.
    k : float
        Coverage factor.
    degrees_of_freedom : float
        Effective degrees of freedom of U(E) (Welch-Satterthwaite, from GTC; infinite for a
        budget of type B contributions only).
    monte_carlo : dict of str to CoverageInterval
        The 95 % coverage intervals of the figures' errors by Monte Carlo, m (empty unless asked for).
    """

    length_m: float
    components: dict[str, float]
    U: dict[str, float]
    k: float = COVERAGE_FACTOR
    degrees_of_freedom: float = math.inf
    monte_carlo: dict[str, CoverageInterval] = field(default_factory=dict)

    def shares(self) -> dict[str, float]:
        """Each component's share of the combined variance of E (fractions summing to 1)."""
        total = sum(u**2 for u in self.components.values())
        return {name: (u**2 / total if total > 0 else 0.0) for name, u in self.components.items()}


def _travel(run: PositioningRun | float, name: str = "run") -> float:
    if isinstance(run, PositioningRun):
        return float(run.targets[-1] - run.targets[0])
    if not is_real(run):
        raise AxiscalError(f"{name} must be a PositioningRun or its travel in metres, not {type_name(run)}")
    length = float(run)
    if not math.isfinite(length) or length < 0:
        raise AxiscalError(f"{name} (the measured length) must be a finite non-negative number of metres, got {run!r}")
    return length


def positioning_uncertainty(
    budget: Budget | str | Path, run: PositioningRun | float, *, monte_carlo: int = 0, seed: int = 0
) -> PositioningUncertainty:
    """U (k = 2) of E, R, B, A and M of a positioning test from a budget.

    Parameters
    ----------
    budget : Budget, str or Path
        The uncertainty budget, or the path of a budget file (:func:`axiscal.uncertainty.read_budget`).
    run : PositioningRun or float
        The test (its travel, last target minus first, is the length L) or L itself in metres.
    monte_carlo : int, keyword-only
        Number of Monte Carlo draws to add the 95 % coverage intervals (0: none).
    seed : int, keyword-only
        Seed of the Monte Carlo draws.

    Returns
    -------
    PositioningUncertainty

    Raises
    ------
    AxiscalError
        A negative or non-finite length, a number of draws that is not 0 or a whole number up to
        :data:`MAX_POSITIONING_DRAWS`, a bad budget file.

    Examples
    --------
    >>> from axiscal.uncertainty import Budget
    >>> result = positioning_uncertainty(Budget(length_U_rel=0.5e-6), 1.0)
    >>> round(result.U["E"] * 1e6, 3)
    0.5
    """
    budget = as_budget(budget)
    if not is_real(monte_carlo) or monte_carlo != 0:  # 0: no Monte Carlo
        monte_carlo = _whole_draws(monte_carlo, "monte_carlo (the number of Monte Carlo draws)", at_most=MAX_POSITIONING_DRAWS)
    seed = check_count("seed", seed, minimum=0)
    length = _travel(run)
    components = length_components(budget, length)
    U = {
        figure: COVERAGE_FACTOR * math.hypot(*(components[c] for c in names))
        for figure, names in FIGURE_COMPONENTS.items()
    }
    U = {figure: U[figure] for figure in FIGURES}
    dof = float(length_model(budget, length).df)
    intervals = positioning_monte_carlo(budget, length, monte_carlo, seed=seed) if monte_carlo else {}
    return PositioningUncertainty(length, components, U, COVERAGE_FACTOR, dof, intervals)


def _draw_errors(budget: Budget, length_m: float, draws: int, rng: np.random.Generator) -> dict[str, np.ndarray]:
    """Draws of each contribution to the error of a length reading, m (the model of length_model)."""
    L = length_m
    out: dict[str, np.ndarray] = {}
    out["device"] = L * rng.normal(0.0, budget.length_U_rel / 2.0, draws)
    t = rng.normal(budget.air_temperature_C, budget.air_temperature_u_K, draws)
    p = rng.normal(budget.air_pressure_Pa, budget.air_pressure_u_Pa, draws)
    h = np.clip(rng.normal(budget.air_humidity_percent, budget.air_humidity_u_percent, draws), 0.0, 100.0)
    n = refractive_index(t, p, h, budget.wavelength_nm, method=budget.method)
    n0 = refractive_index(budget.air_temperature_C, budget.air_pressure_Pa, budget.air_humidity_percent,
                          budget.wavelength_nm, method=budget.method)
    out["air"] = L * (n - n0)
    alpha = rng.normal(budget.expansion_per_K, budget.expansion_u_per_K, draws)
    out["machine_expansion"] = L * (alpha - budget.expansion_per_K) * (budget.machine_temperature_C - 20.0)
    temperature = rng.normal(budget.machine_temperature_C, budget.machine_temperature_u_K, draws)
    out["machine_temperature"] = L * alpha * (temperature - budget.machine_temperature_C)
    theta = rng.uniform(-budget.misalignment_rad, budget.misalignment_rad, draws)
    out["misalignment"] = L * (1.0 - np.cos(theta))
    out["eve"] = rng.uniform(-0.5 * budget.eve_m, 0.5 * budget.eve_m, draws)
    return out


def positioning_monte_carlo(
    budget: Budget, length_m: float, draws: int, *, seed: int = 0, probability: float = 0.95
) -> dict[str, CoverageInterval]:
    """Monte Carlo propagation (JCGM 101) of the budget to the errors of the figures E, R, B, A, M.

    Each influence is drawn from its distribution (normal for standard uncertainties; rectangular
    for the misalignment angle, within +-bound, and the EVE, over its full range); the air error
    goes through the full refractive-index equation and the misalignment through
    ``L (1 - cos theta)``.

    Parameters
    ----------
    budget : Budget
    length_m : float
        Measured length L, m.
    draws : int
        Number of draws M (at least 1 / (1 - probability)).
    seed : int, keyword-only
        Seed of the NumPy generator.
    probability : float, keyword-only
        Coverage probability (default 0.95).

    Returns
    -------
    dict of str to CoverageInterval
        The probabilistically symmetric coverage interval of each figure's error, m.

    Raises
    ------
    AxiscalError
        Too few draws or more than :data:`MAX_POSITIONING_DRAWS`, a negative length.
    """
    check_budget(budget)
    length = _travel(length_m, "length_m")
    draws = _whole_draws(draws, "draws (the number of Monte Carlo draws)", at_most=MAX_POSITIONING_DRAWS)
    seed = check_count("seed", seed, minimum=0)
    parts = _draw_errors(budget, length, draws, np.random.default_rng(seed))
    out = {}
    for figure in FIGURES:
        total = sum(parts[c] for c in FIGURE_COMPONENTS[figure])
        out[figure] = coverage_interval(total, probability)
    return out


def uncertainty_payload(result: PositioningUncertainty) -> dict:
    """The ``"uncertainty"`` object of ``axiscal positioning --json``, in um.

    Parameters
    ----------
    result : PositioningUncertainty

    Returns
    -------
    dict
        ``{"k": 2, "E": {"U": ...}, ..., "M": {"U": ...}, "components_um": {...}}``; with Monte
        Carlo also ``"monte_carlo": {"draws": M, "probability": 0.95, "E": {"low": ..., "high": ...,
        "U": half width}, ...}``.

    Raises
    ------
    AxiscalError
        For a ``result`` that is not a :class:`PositioningUncertainty`.
    """
    check_instance("result", result, PositioningUncertainty)
    body: dict = {"k": int(result.k) if float(result.k).is_integer() else result.k}
    body.update({figure: {"U": result.U[figure] / UM} for figure in FIGURES})
    body["components_um"] = {name: u / UM for name, u in result.components.items()}
    if result.monte_carlo:
        first = next(iter(result.monte_carlo.values()))
        mc: dict = {"draws": first.draws, "probability": first.probability}
        for figure, ci in result.monte_carlo.items():
            mc[figure] = {"low": ci.low / UM, "high": ci.high / UM, "U": ci.half_width / UM}
        body["monte_carlo"] = mc
    return body


def budget_report(result: PositioningUncertainty) -> str:
    """The budget as text: component, standard uncertainty and share of the total, then U per figure.

    Parameters
    ----------
    result : PositioningUncertainty

    Returns
    -------
    str
        Rendered from the package template ``templates/uncertainty/budget.txt.j2``.

    Raises
    ------
    AxiscalError
        For a ``result`` that is not a :class:`PositioningUncertainty`.
    """
    from jinja2 import Environment, PackageLoader, StrictUndefined

    check_instance("result", result, PositioningUncertainty)
    env = Environment(loader=PackageLoader("axiscal", "templates"), undefined=StrictUndefined,
                      keep_trailing_newline=False, trim_blocks=True, lstrip_blocks=True)
    shares = result.shares()
    rows = [(name, result.components[name] / UM, 100.0 * shares[name]) for name in result.components]
    combined = math.sqrt(sum(u**2 for u in result.components.values())) / UM
    figures = [(f, result.U[f] / UM, ", ".join(FIGURE_COMPONENTS[f]) if FIGURE_COMPONENTS[f] != COMPONENTS else "all")
               for f in FIGURES]
    mc = [(f, ci.low / UM, ci.high / UM, ci.half_width / UM) for f, ci in result.monte_carlo.items()]
    draws = next(iter(result.monte_carlo.values())).draws if result.monte_carlo else 0
    text = env.get_template("uncertainty/budget.txt.j2").render(
        length_mm=result.length_m * 1e3, k=result.k, rows=rows, combined=combined, figures=figures, mc=mc, draws=draws
    )
    return text.rstrip("\n")


def positioning_decisions(
    result: Iso230Result, uncertainty: PositioningUncertainty, limits: dict[str, float], *, rule: str = "simple"
) -> dict[str, Decision]:
    """Verdicts on the ISO 230-2 figures against their limits, with the figures' U (for a campaign report).

    Parameters
    ----------
    result : Iso230Result
        The evaluated test (figures in m).
    uncertainty : PositioningUncertainty
        Their uncertainties (:func:`positioning_uncertainty`).
    limits : dict of str to float
        Upper limit of each figure to judge, by symbol of :data:`FIGURES` (``{"E": 10e-6}``), m.
    rule : {"simple", "guard-band"}, keyword-only
        Decision rule (:func:`axiscal.uncertainty.decide`).

    Returns
    -------
    dict of str to Decision
        One verdict per figure in ``limits``, each stating its rule.

    Raises
    ------
    AxiscalError
        A figure that has no uncertainty here, a figure that is not available (NaN with one run),
        an unknown rule.
    """
    check_instance("result", result, Iso230Result)
    check_instance("uncertainty", uncertainty, PositioningUncertainty)
    check_mapping("limits", limits, what="a mapping of figures to limits in metres")
    check_choice("decision rule", rule, DECISION_RULES)
    out = {}
    for figure, limit in limits.items():
        if not isinstance(figure, str) or figure not in FIGURES:
            raise AxiscalError(f"no uncertainty for figure '{figure}'; use one of {', '.join(FIGURES)}")
        value = getattr(result, figure)
        if not math.isfinite(value):
            raise AxiscalError(f"figure {figure} is not available for this test (one run per direction)")
        limit = check_number(f"limits['{figure}']", limit, unit="metres", nonnegative=True)
        out[figure] = decide(value, limit, uncertainty.U[figure], rule=rule)
    return out


@dataclass(frozen=True)
class PositioningWithUncertainty:
    """A positioning evaluation with the uncertainty of its figures (``axiscal positioning --uncertainty``).

    Attributes
    ----------
    evaluation : PositioningEvaluation
        The test read and evaluated (SI).
    uncertainty : PositioningUncertainty
        U (k = 2) of E, R, B, A, M and the budget's components.
    """

    evaluation: Any
    uncertainty: PositioningUncertainty

    @property
    def run(self) -> PositioningRun:
        """The run evaluated."""
        return self.evaluation.run

    @property
    def warnings(self) -> tuple[str, ...]:
        """The evaluation's warnings."""
        return self.evaluation.warnings

    def plot(self, path, *, title: str = ""):
        """The positioning plot (see :meth:`PositioningEvaluation.plot`)."""
        return self.evaluation.plot(path, title=title)

    def to_dict(self) -> dict:
        """The evaluation's JSON object with its ``uncertainty`` object (um)."""
        return {**self.evaluation.to_dict(), "uncertainty": uncertainty_payload(self.uncertainty)}

    def report(self) -> str:
        """The evaluation's table followed by the budget table."""
        return self.evaluation.report() + "\n\n" + budget_report(self.uncertainty)


def evaluate_positioning_with_uncertainty(
    path,
    budget,
    *,
    standard: str = "iso230-2:2014",
    wavelength_nm: float | None = None,
    expansion_per_k: float | None = None,
    monte_carlo: int = 0,
) -> PositioningWithUncertainty:
    """Evaluate a positioning test file and the uncertainty of its figures from a budget.

    Parameters
    ----------
    path : str or Path
        The run file, as :func:`axiscal.positioning.report.evaluate_positioning_file` reads it.
    budget : Budget, str or Path
        The uncertainty budget or its TOML file.
    standard : str, keyword-only
        An ISO 230-2 edition (the budget gives U of the ISO 230-2 figures).
    wavelength_nm, expansion_per_k : float, optional, keyword-only
        For raw laser readings, as for the evaluation.
    monte_carlo : int, keyword-only
        Draws of the Monte Carlo propagation (0: analytic only).

    Returns
    -------
    PositioningWithUncertainty

    Raises
    ------
    AxiscalError
        For a bad file or budget, a standard other than ISO 230-2, or a test of a rotary axis or
        in one direction only (the budget is in lengths, for the bidirectional figures).
    """
    from axiscal.positioning.report import evaluate_positioning_file

    budget = as_budget(budget)
    evaluation = evaluate_positioning_file(
        path, standard=standard, wavelength_nm=wavelength_nm, expansion_per_k=expansion_per_k
    )
    if not isinstance(evaluation.result, Iso230Result):
        raise AxiscalError("the uncertainty budget gives U of the ISO 230-2 figures; use an iso230-2 standard")
    if evaluation.run.rotary or not evaluation.run.bidirectional:
        kind = "a rotary axis" if evaluation.run.rotary else f"one direction ({evaluation.run.directions[0]} only)"
        raise AxiscalError(
            f"the uncertainty budget is that of a bidirectional test of a linear axis (lengths); this test is of {kind}",
            path=evaluation.run.source,
        )
    return PositioningWithUncertainty(evaluation, positioning_uncertainty(budget, evaluation.run, monte_carlo=monte_carlo))
