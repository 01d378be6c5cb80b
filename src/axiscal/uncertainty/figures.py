"""The uncertainty of a test's figures and a verdict on each under a decision rule (ISO 230-2:2014 Annex A, ISO 14253-1:2017), for a campaign.

For the test kinds whose uncertainty this room computes from a budget file:

- ``positioning`` (ISO 230-2 figures, :func:`positioning_uncertainty`): the figures that compare
  positions along the travel, ``E``, ``E_up``, ``E_down``, ``A``, ``A_up``, ``A_down`` and ``M``,
  carry every component; those formed at one target, ``R``, ``R_up``, ``R_down``, ``B`` and
  ``B_mean``, the environmental variation only (module :mod:`axiscal.uncertainty.positioning`).
  ``S_up`` and ``S_down`` (estimates of s) get none;
- ``straightness`` (:func:`straightness_uncertainty`): ``straightness_um``;
- ``squareness`` (:func:`squareness_uncertainty`): ``squareness_arcsec`` and
  ``iso_value_arcsec`` (the same angle in the other sign convention, the same U).

Figures are keyed and scaled as the test's figures of a campaign (those of the command of the same
name's ``--json``): um for lengths, arcsec for angles. The verdicts hold |figure| against each
tolerance (keyed as in campaign.toml: ``E_um`` applies to figure ``E``, ``straightness_um`` to
``straightness_um``) under simple acceptance or the guard band of ISO 14253-1
(:func:`axiscal.uncertainty.decide`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_choice, check_mapping, is_real
from axiscal.io.arguments import type_name
from axiscal.positioning.evaluation import ISO_SYMBOLS, Iso230Result, PositioningRun
from axiscal.positioning.report import PositioningEvaluation
from axiscal.squareness.evaluation import SquarenessEvaluation
from axiscal.straightness.files import StraightnessEvaluation
from axiscal.uncertainty.budget import Budget, as_budget
from axiscal.uncertainty.decision import DECISION_RULES, Decision, decide
from axiscal.uncertainty.positioning import FIGURES, positioning_uncertainty
from axiscal.uncertainty.straightness import (
    squareness_uncertainty,
    straightness_uncertainty,
)
from axiscal.units import ARCSEC, UM

__all__ = ["UNCERTAINTY_KINDS", "figure_uncertainties", "figure_verdicts"]

#: the test kinds whose figures get an uncertainty from a budget
UNCERTAINTY_KINDS = ("positioning", "straightness", "squareness")


def _positioning_figures(evaluation, run) -> tuple[dict[str, float], PositioningRun | float]:
    """The ISO 230-2 figures in um and the run (or travel, m) the budget is taken over."""
    if isinstance(evaluation, PositioningEvaluation):
        if not isinstance(evaluation.result, Iso230Result):
            raise AxiscalError(f"the uncertainty budget gives U of the ISO 230-2 figures, not of {evaluation.result.standard}")
        return {k: v / UM for k, v in evaluation.result.figures().items()}, evaluation.run if run is None else run
    if isinstance(evaluation, Mapping):
        if run is None:
            raise AxiscalError("positioning figures given as a mapping need run= (the PositioningRun or its travel in m)")
        return {k: evaluation[k] for k in ISO_SYMBOLS if k in evaluation}, run
    raise AxiscalError(f"evaluation of a positioning test must be a PositioningEvaluation or its figures, not {type_name(evaluation)}")


def _figures_and_U(kind: str, evaluation, budget: Budget, run) -> tuple[dict[str, Any], dict[str, float]]:
    """(the figures, U of each figure that has one), in the figures' display units."""
    if not isinstance(kind, str) or kind not in UNCERTAINTY_KINDS:
        raise AxiscalError(f"no uncertainty for tests of kind '{kind}'; the budget covers {', '.join(UNCERTAINTY_KINDS)}")
    if kind == "positioning":
        figures, length = _positioning_figures(evaluation, run)
        U_m = positioning_uncertainty(budget, length).U
        bases = {symbol: symbol.split("_")[0] for symbol in figures}
        return figures, {symbol: U_m[base] / UM for symbol, base in bases.items() if base in FIGURES}
    if kind == "straightness":
        if not isinstance(evaluation, StraightnessEvaluation):
            raise AxiscalError(f"evaluation of a straightness test must be a StraightnessEvaluation, not {type_name(evaluation)}")
        profile = evaluation.profile
        U = straightness_uncertainty(budget, profile.position_m, profile.deviation_m, reference=evaluation.line.reference).U
        return evaluation.payload(), {"straightness_um": U / UM}
    if not isinstance(evaluation, SquarenessEvaluation):
        raise AxiscalError(f"evaluation of a squareness test must be a SquarenessEvaluation, not {type_name(evaluation)}")
    result, first, second = evaluation.result, evaluation.first, evaluation.second
    reference = result.first_line.reference if result.first_line is not None else "least-squares"
    U = squareness_uncertainty(budget, first.position_m, first.deviation_m, second.position_m, second.deviation_m,
                               plane=result.plane, prism_deviation_rad=result.prism_deviation_rad, reference=reference).U
    return evaluation.payload(), {"squareness_arcsec": U / ARCSEC, "iso_value_arcsec": U / ARCSEC}


def figure_uncertainties(
    kind: str, evaluation, budget: Budget | str | Path, *, run: PositioningRun | float | None = None
) -> dict[str, float]:
    """U (k = 2) of each figure of a test, in the figure's display unit (module docstring).

    Parameters
    ----------
    kind : {"positioning", "straightness", "squareness"}
        The test's kind, as in campaign.toml.
    evaluation : PositioningEvaluation, StraightnessEvaluation, SquarenessEvaluation or mapping
        What the test's library call returned (:func:`axiscal.positioning.evaluate_positioning_file`,
        :func:`axiscal.straightness.evaluate_straightness_file`,
        :func:`axiscal.squareness.squareness_from_files`); for positioning also the figures by
        symbol (um) with ``run``.
    budget : Budget, str or Path
        The uncertainty budget or its TOML file.
    run : PositioningRun or float, optional, keyword-only
        Positioning only: the run (or its travel, m) the budget is taken over; default the
        evaluation's run.

    Returns
    -------
    dict of str to float
        Figure key (``"E"``, ``"R_up"``, ``"straightness_um"``, ``"squareness_arcsec"`` ...) to
        its expanded uncertainty, um or arcsec.

    Raises
    ------
    AxiscalError
        A kind without an uncertainty here, an evaluation of another kind or of a standard other
        than ISO 230-2, a bad budget file (naming file and line).

    Examples
    --------
    >>> from axiscal.positioning import evaluate_positioning_file
    >>> evaluation = evaluate_positioning_file("examples/positioning_run.csv")
    >>> U = figure_uncertainties("positioning", evaluation, "examples/uncertainty_budget.toml")
    >>> round(U["E"], 3), round(U["R_up"], 3)
    (6.874, 0.577)
    """
    return _figures_and_U(kind, evaluation, as_budget(budget), run)[1]


def figure_verdicts(
    kind: str,
    evaluation,
    budget: Budget | str | Path,
    tolerances: Mapping[str, float],
    *,
    rule: str = "simple",
    run: PositioningRun | float | None = None,
) -> dict[str, Decision]:
    """The verdict on each toleranced figure of a test, with its U, under a decision rule.

    Parameters
    ----------
    kind, evaluation, budget, run
        As :func:`figure_uncertainties`.
    tolerances : mapping of str to float
        Tolerance key as in campaign.toml (``"E_um"``, ``"R_up_um"``, ``"straightness_um"``,
        ``"squareness_arcsec"``) to its upper limit, in the unit of its name.
    rule : {"simple", "guard-band"}, keyword-only
        Simple acceptance, or guarded per ISO 14253-1 (:func:`axiscal.uncertainty.decide`).

    Returns
    -------
    dict of str to Decision
        Per tolerance key, the verdict on |figure| with the figure's U, in the tolerance's unit.
        A figure that could not be computed (NaN, e.g. R from one run) fails, as in a campaign.

    Raises
    ------
    AxiscalError
        A tolerance for a figure that has no uncertainty here, a negative or non-finite limit, an
        unknown rule, or what :func:`figure_uncertainties` raises.

    Examples
    --------
    >>> from axiscal.positioning import evaluate_positioning_file
    >>> evaluation = evaluate_positioning_file("examples/positioning_run.csv")
    >>> verdicts = figure_verdicts("positioning", evaluation, "examples/uncertainty_budget.toml",
    ...                            {"E_um": 15.0, "R_um": 10.0}, rule="guard-band")
    >>> {key: d.verdict for key, d in verdicts.items()}
    {'E_um': 'inconclusive', 'R_um': 'pass'}
    """
    check_choice("decision rule", rule, DECISION_RULES)
    check_mapping("tolerances", tolerances, what="a mapping of tolerance keys to limits")
    figures, U = _figures_and_U(kind, evaluation, as_budget(budget), run)
    out: dict[str, Decision] = {}
    for key, limit in tolerances.items():
        figure = key if key in U else key.rsplit("_", 1)[0]
        if figure not in U:
            raise AxiscalError(f"tolerance '{key}': no figure with an uncertainty; {kind} has {', '.join(U)}")
        if not is_real(limit) or not math.isfinite(limit) or limit < 0:
            raise AxiscalError(f"tolerance '{key}' must be a non-negative number, got {limit!r}")
        value = figures.get(figure)
        if value is not None and not is_real(value):
            raise AxiscalError(f"evaluation: figure '{figure}' must be a number (or None when not available), not {value!r}")
        value = math.nan if value is None else abs(float(value))
        if math.isfinite(value):
            out[key] = decide(value, float(limit), U[figure], rule=rule)
        else:
            acceptance = float(limit) - (U[figure] if rule == "guard-band" else 0.0)
            out[key] = Decision("fail", rule, DECISION_RULES[rule], value, float(limit), U[figure], acceptance)
    return out
