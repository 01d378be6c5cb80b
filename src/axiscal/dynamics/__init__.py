"""Dynamics and periodic errors of an axis: a timebase recording's moves and stops; the short-period error.

:func:`axis_dynamics` (``axiscal dynamics``) differentiates a laser's recording with a
Savitzky-Golay differentiator, takes Welch's spectrum, and gives every move's largest velocity,
acceleration and jerk and every stop's settling time, overshoot, ringing frequency and damping;
:func:`periodic_error` (``axiscal periodic``) finds the amplitude and period of a periodic
positioning error (ISO 230-2 Annexes B and C) by a least-squares fit and by a spectrum.
"""

from __future__ import annotations

from axiscal.dynamics.motion import (
    Derivatives,
    MoveDynamics,
    Spectrum,
    StopDynamics,
    derivatives,
    savgol_bandwidth_hz,
    welch_spectrum,
)
from axiscal.dynamics.analysis import (
    AxisDynamics,
    DynamicsSettings,
    axis_dynamics,
    dynamics_from_file,
)
from axiscal.dynamics.periodic import (
    PeriodicComponent,
    PeriodicError,
    amplitude_spectrum,
    periodic_error,
    periodic_from_file,
)
from axiscal.dynamics.plot import plot_dynamics, plot_periodic

__all__ = [
    "Derivatives",
    "MoveDynamics",
    "Spectrum",
    "StopDynamics",
    "derivatives",
    "savgol_bandwidth_hz",
    "welch_spectrum",
    "AxisDynamics",
    "DynamicsSettings",
    "axis_dynamics",
    "dynamics_from_file",
    "PeriodicComponent",
    "PeriodicError",
    "amplitude_spectrum",
    "periodic_error",
    "periodic_from_file",
    "plot_dynamics",
    "plot_periodic",
]
