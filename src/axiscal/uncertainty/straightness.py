"""Uncertainty of straightness (ISO 230-1) and of squareness from two straightness runs (paper 002 eqs 1, 21), from a budget file.

Straightness ``T = max r - min r`` of the residuals r about the reference line. Its components,
standard uncertainties in metres:

- ``device``: the straightness instrument, ``sqrt(2) * straightness_U / 2`` (``[instrument]
  straightness_U_um``, expanded k = 2, per reading; T is the difference of two readings);
- ``fit``: the reference line's tilt, ``s_k * L`` with ``s_k`` the standard error of the
  least-squares slope from the residual scatter (``s_res / sqrt(sum (x - mean x)^2)``, n - 2 degrees
  of freedom) and L the travel. This treats the profile's shape as if it were scatter, a
  conservative bound;
- ``eve``: the environmental variation error over the run, ``eve_um / (2 sqrt 3)``.

Squareness ``s = 90 deg - atan(k1) - atan(k2) - D - 90 deg`` (paper 002 eqs 1 and 21), with k1, k2 the
slopes of the two runs and D the pentaprism's deviation: each slope carries its fit's standard
error (with n - 2 degrees of freedom) and the instrument, ``sqrt(2) * straightness_U / 2 / L_i``;
D carries ``[setup] prism_deviation_u_arcsec`` (paper 002 eq 22 measures it; paper 004 eqs 2-5 by
reversal). The combination and the effective degrees of freedom (Welch-Satterthwaite) come from
GTC; U = k u with k = 2.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from axiscal.squareness.evaluation import squareness as squareness_of_runs
from axiscal.straightness.reference import reference_line
from axiscal.io.arguments import check_array
from axiscal.uncertainty.budget import Budget, as_budget

__all__ = ["LineUncertainty", "straightness_uncertainty", "squareness_uncertainty"]

_RECTANGULAR = 2.0 * math.sqrt(3.0)
_K = 2.0


@dataclass(frozen=True)
class LineUncertainty:
    """A straightness or squareness value with its expanded uncertainty, SI.

    Attributes
    ----------
    value : float
        The straightness (m) or the squareness (rad, the included-angle convention of
        :func:`axiscal.squareness.squareness`).
    U : float
        Expanded uncertainty, k = 2, same unit.
    components : dict of str to float
        Standard uncertainty of each contribution, same unit.
    degrees_of_freedom : float
        Effective degrees of freedom (Welch-Satterthwaite).
    k : float
        Coverage factor.
    """

    value: float
    U: float
    components: dict[str, float]
    degrees_of_freedom: float
    k: float = _K


def _slope_standard_error(position: np.ndarray, deviation: np.ndarray) -> tuple[float, int]:
    """Standard error of the least-squares slope from the residuals, and its degrees of freedom."""
    line = reference_line(position, deviation, reference="least-squares")
    residual = line.residuals(position, deviation)
    dof = position.size - 2
    if dof < 1:
        return 0.0, 0
    sxx = float(np.sum((position - position.mean()) ** 2))
    return math.sqrt(float(np.sum(residual**2)) / dof / sxx), dof


def _ureal(value: float, u: float, label: str, dof: float = math.inf):
    from GTC import ureal

    return ureal(value, u, df=dof if dof >= 1 else math.inf, label=label)


def _result(value: float, model, labels: dict[str, str]) -> LineUncertainty:
    from GTC import reporting

    components = dict.fromkeys(dict.fromkeys(labels.values()), 0.0)
    for influence in reporting.budget(model, trim=0):
        key = labels[influence.label]
        components[key] = math.hypot(components[key], abs(influence.u))
    return LineUncertainty(float(value), _K * model.u, components, float(model.df))


def straightness_uncertainty(
    budget: Budget | str, position_m, deviation_m, *, reference: str = "least-squares"
) -> LineUncertainty:
    """Straightness of a profile and its expanded uncertainty (module docstring).

    Parameters
    ----------
    budget : Budget or str
        The budget (or its file): ``[instrument] straightness_U_um`` and ``[setup] eve_um``.
    position_m, deviation_m : array_like, shape (n,)
        Positions along the axis and deviations across it, metres.
    reference : {"least-squares", "end-points", "minimum-zone"}, keyword-only
        Reference line of the straightness value.

    Returns
    -------
    LineUncertainty
        Components ``device``, ``fit``, ``eve``.

    Raises
    ------
    AxiscalError
        What :func:`axiscal.straightness.reference_line` raises; a bad budget.

    Examples
    --------
    >>> from axiscal.uncertainty import Budget
    >>> r = straightness_uncertainty(Budget(straightness_U_m=1e-6), [0.0, 0.5, 1.0], [0.0, 1e-6, 0.0])
    >>> round(r.components["device"] * 1e6, 4)
    0.7071
    """
    budget = as_budget(budget)
    position = check_array("position_m", position_m, ndim=1)
    deviation = check_array("deviation_m", deviation_m, ndim=1)
    line = reference_line(position, deviation, reference=reference)
    s_k, dof = _slope_standard_error(position, deviation)
    travel = float(position.max() - position.min())
    model = (
        _ureal(0.0, math.sqrt(2.0) * budget.straightness_U_m / 2.0, "device")
        + travel * _ureal(0.0, s_k, "fit", dof)
        + _ureal(0.0, budget.eve_m / _RECTANGULAR, "eve")
    )
    return _result(line.straightness_m, model, {"device": "device", "fit": "fit", "eve": "eve"})


def squareness_uncertainty(
    budget: Budget | str,
    first_position_m,
    first_deviation_m,
    second_position_m,
    second_deviation_m,
    *,
    plane: str = "XY",
    prism_deviation_rad: float = 0.0,
    reference: str = "least-squares",
) -> LineUncertainty:
    """Squareness from two straightness runs and its expanded uncertainty (module docstring).

    Parameters
    ----------
    budget : Budget or str
        The budget (or its file): ``[instrument] straightness_U_um`` and ``[setup]
        prism_deviation_u_arcsec``.
    first_position_m, first_deviation_m, second_position_m, second_deviation_m : array_like
        The two runs, metres, as :func:`axiscal.squareness.squareness` takes them.
    plane, prism_deviation_rad, reference : keyword-only
        As :func:`axiscal.squareness.squareness`.

    Returns
    -------
    LineUncertainty
        Value in the included-angle convention, rad; components ``first_run``, ``second_run``
        (fit and instrument of each slope) and ``prism``.

    Raises
    ------
    AxiscalError
        What :func:`axiscal.squareness.squareness` raises; a bad budget.
    """
    from GTC import atan

    budget = as_budget(budget)
    first_position_m, first_deviation_m, second_position_m, second_deviation_m = (
        check_array(name, values, ndim=1) for name, values in (
            ("first_position_m", first_position_m), ("first_deviation_m", first_deviation_m),
            ("second_position_m", second_position_m), ("second_deviation_m", second_deviation_m))
    )
    result = squareness_of_runs(first_position_m, first_deviation_m, second_position_m, second_deviation_m,
                                plane=plane, prism_deviation_rad=prism_deviation_rad, reference=reference)
    slopes = []
    for name, position, deviation, slope in (
        ("first_run", first_position_m, first_deviation_m, result.slope_first),
        ("second_run", second_position_m, second_deviation_m, result.slope_second),
    ):
        position = np.asarray(position, dtype=float)
        s_k, dof = _slope_standard_error(position, np.asarray(deviation, dtype=float))
        travel = float(position.max() - position.min())
        instrument = math.sqrt(2.0) * budget.straightness_U_m / 2.0 / travel
        slopes.append(_ureal(slope, s_k, f"{name} fit", dof) + _ureal(0.0, instrument, f"{name} instrument"))
    prism = _ureal(prism_deviation_rad, budget.prism_deviation_u_rad, "prism")
    model = -atan(slopes[0]) - atan(slopes[1]) - prism
    labels = {"first_run fit": "first_run", "first_run instrument": "first_run",
              "second_run fit": "second_run", "second_run instrument": "second_run", "prism": "prism"}
    return _result(result.included_angle_rad - math.pi / 2.0, model, labels)
