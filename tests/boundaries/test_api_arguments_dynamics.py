"""Every public callable of the dynamics room refuses bad arguments with AxiscalError naming them.

The same table harness as the other rooms (api_cases.CaseTable). The result objects the room
returns (derivatives, spectra, moves, stops, the dynamics and the periodic error) are made by the
room itself and are exempt.
"""

from __future__ import annotations

import numpy as np

from api_cases import EXAMPLES, CaseTable, api

from axiscal.capture import Recording
from axiscal.positioning import PositioningRun

ROOMS = ("dynamics",)
NAN, INF = float("nan"), float("inf")
TABLE = CaseTable(ROOMS)
bad = TABLE.bad
dy = api("dynamics")
D = "dynamics"
RECORDING = EXAMPLES / "capture" / "recording_x.csv"
NEVER = EXAMPLES / "no such folder" / "x.png"
T = np.arange(20.0) * 1e-3
REC = Recording(T, np.zeros(20))
RUN = PositioningRun(np.arange(8) * 1e-3, np.zeros((8, 2)), None)

bad(D, "derivatives", "time_s", lambda: dy.derivatives("t", T), lambda: dy.derivatives(np.array([0.0, NAN]), np.zeros(2)))
bad(D, "derivatives", "one reading per time", lambda: dy.derivatives(T, np.zeros(3)))
bad(D, "derivatives", "window_s", lambda: dy.derivatives(T, T, window_s=0.0), lambda: dy.derivatives(T, T, window_s=1.0))
bad(D, "derivatives", "polyorder", lambda: dy.derivatives(T, T, polyorder=2), lambda: dy.derivatives(T, T, polyorder=True))
bad(D, "derivatives", "go back", lambda: dy.derivatives(T[::-1].copy(), T))
bad(D, "derivatives", "given twice", lambda: dy.derivatives(np.r_[T, T[-1]], np.zeros(21)))
bad(D, "derivatives", "a gap of", lambda: dy.derivatives(np.r_[T, 1e6], np.zeros(21)))
bad(D, "welch_spectrum", "made up", lambda: dy.welch_spectrum(np.r_[T, 1e6], np.zeros(21)))
bad(D, "axis_dynamics", "given twice", lambda: dy.axis_dynamics(Recording(np.r_[T, T[-1]], np.zeros(21))))
bad(D, "dynamics_from_file", "sensor", lambda: dy.dynamics_from_file(RECORDING, channel="air_temperature_c", unit="mm"))
bad(D, "savgol_bandwidth_hz", "window", lambda: dy.savgol_bandwidth_hz(20, 3, 1000.0), lambda: dy.savgol_bandwidth_hz(3, 3, 1000.0))
bad(D, "savgol_bandwidth_hz", "rate_hz", lambda: dy.savgol_bandwidth_hz(21, 3, 0.0), lambda: dy.savgol_bandwidth_hz(21, 3, NAN))
bad(D, "welch_spectrum", "time_s", lambda: dy.welch_spectrum(T[:4], T[:4]))
bad(D, "welch_spectrum", "segment_s", lambda: dy.welch_spectrum(T, T, segment_s=-1.0))
bad(D, "welch_spectrum", "one reading per time", lambda: dy.welch_spectrum(T, T[:5]))
bad(D, "DynamicsSettings", "window_s", lambda: dy.DynamicsSettings(window_s=0.0))
bad(D, "DynamicsSettings", "band_m", lambda: dy.DynamicsSettings(band_m=NAN))
bad(D, "DynamicsSettings", "polyorder", lambda: dy.DynamicsSettings(polyorder=1))
bad(D, "axis_dynamics", "recording", lambda: dy.axis_dynamics(None), lambda: dy.axis_dynamics(RECORDING))
bad(D, "axis_dynamics", "settings", lambda: dy.axis_dynamics(REC, settings={"window_s": 0.02}))
bad(D, "axis_dynamics", "plan", lambda: dy.axis_dynamics(REC, 5))
bad(D, "axis_dynamics", "missing", lambda: dy.axis_dynamics(Recording(T, np.r_[np.zeros(19), NAN])))
bad(D, "dynamics_from_file", "path", lambda: dy.dynamics_from_file(None))
bad(D, "dynamics_from_file", "settings", lambda: dy.dynamics_from_file(RECORDING, settings=5))
bad(D, "amplitude_spectrum", "positions_m", lambda: dy.amplitude_spectrum(np.arange(3.0), np.zeros(3)))
bad(D, "amplitude_spectrum", "increase", lambda: dy.amplitude_spectrum(np.arange(8.0)[::-1].copy(), np.zeros(8)))
bad(D, "amplitude_spectrum", "one value per position", lambda: dy.amplitude_spectrum(np.arange(8.0), np.zeros(7)))
bad(D, "amplitude_spectrum", "oversample", lambda: dy.amplitude_spectrum(np.arange(8.0), np.zeros(8), oversample=0))
bad(D, "periodic_error", "run", lambda: dy.periodic_error(None), lambda: dy.periodic_error(RECORDING))
bad(D, "periodic_error", "period_m", lambda: dy.periodic_error(RUN, period_m=-1.0), lambda: dy.periodic_error(RUN, period_m=1.0),
    lambda: dy.periodic_error(RUN, period_m=NAN))
bad(D, "periodic_error", "at least 6", lambda: dy.periodic_error(PositioningRun(np.arange(5) * 1e-3, np.zeros((5, 1)), None)))
bad(D, "periodic_from_file", "period_m", lambda: dy.periodic_from_file(EXAMPLES / "positioning_run.csv", period_m=0.0))
bad(D, "plot_dynamics", "result", lambda: dy.plot_dynamics(NEVER, None))
bad(D, "plot_periodic", "result", lambda: dy.plot_periodic(NEVER, None))

EXEMPT = {D: {"Derivatives", "Spectrum", "MoveDynamics", "StopDynamics", "AxisDynamics", "PeriodicComponent", "PeriodicError"}}

test_bad_arguments_raise_axiscal_error_naming_them, test_every_public_callable_has_a_bad_argument_case = TABLE.tests(EXEMPT)
