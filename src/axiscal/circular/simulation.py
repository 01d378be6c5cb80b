"""A virtual machine run round a ballbar circle: the trace of chosen squareness, scale, backlash, spikes, cyclic error and servo mismatch.

The path is computed exactly (no first-order approximation): each axis follows its command
late by its servo lag, scaled, with half its backlash against its direction of motion, a spike
after each reversal and a cyclic error of its position; the second axis is turned by the
squareness; the ballbar reads the distance from the table ball. docs/ballbar.md sets out the
model; :func:`axiscal.circular.diagnostics.diagnose` reads the errors back.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np

from axiscal.circular.evaluation import DIRECTIONS, MM_PER_MIN, BallbarTrace, plane_axes
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_count, check_instance, check_path, is_real
from axiscal.io.atomic import write_text
from axiscal.io.jsonio import write_sidecar
from axiscal.io.tabular import write_csv
from axiscal.units import MM, UM

__all__ = ["SPIKE_WIDTH_DEG", "simulate_ballbar", "trace_csv", "write_trace"]

#: angular width (deg, one standard deviation of a half-Gaussian) over which a reversal spike dies away
SPIKE_WIDTH_DEG = 1.5


def _per_axis(name: str, values: Mapping[str, float] | None, axes: tuple[str, str]) -> tuple[float, float]:
    if values is not None and not isinstance(values, Mapping):
        raise AxiscalError(f"{name}: give a mapping of axis letter to value, not {values!r}")
    values = dict(values or {})
    if not all(isinstance(k, str) for k in values) or not all(is_real(v) for v in values.values()):
        raise AxiscalError(f"{name}: values must be finite numbers keyed by axis letter")
    unknown = sorted(set(k.upper() for k in values) - set(axes))
    if unknown:
        raise AxiscalError(f"{name}: axis '{unknown[0]}' is not in the plane {''.join(axes)}")
    upper = {k.upper(): float(v) for k, v in values.items()}
    pair = (upper.get(axes[0], 0.0), upper.get(axes[1], 0.0))
    if not all(math.isfinite(v) for v in pair):
        raise AxiscalError(f"{name}: values must be finite numbers")
    return pair


def simulate_ballbar(
    *,
    radius: float = 0.1,
    plane: str = "XY",
    feed: float = 1000.0 * MM_PER_MIN,
    squareness: float = 0.0,
    scale: Mapping[str, float] | None = None,
    backlash: Mapping[str, float] | None = None,
    servo_mismatch: float = 0.0,
    reversal_spike: Mapping[str, float] | None = None,
    cyclic_error: Mapping[str, float] | None = None,
    cyclic_pitch: Mapping[str, float] | None = None,
    centre_offset: Mapping[str, float] | None = None,
    directions: Sequence[str] = DIRECTIONS,
    step: float = math.radians(0.1),
    noise: float = 0.0,
    seed: int = 0,
) -> BallbarTrace:
    """The ballbar trace of a virtual machine with the errors given (SI units; per-axis values keyed by letter).

    Parameters
    ----------
    radius : float, metres, keyword-only
        Nominal radius of the circle.
    plane : str
        First and second axis, e.g. ``"XY"``; the angle runs from the first towards the second.
    feed : float, m/s
        Tangential speed (sets the angle an axis lags by: ``feed * lag / radius``).
    squareness : float, radians
        Included angle between +first and +second axis minus 90 degrees.
    scale : mapping of letter to float
        Scale error of each axis (dimensionless, 1e-6 = 1 ppm).
    backlash : mapping of letter to float, metres
        Lost motion of each axis on reversal.
    servo_mismatch : float, seconds
        Lag of the first axis minus lag of the second (each lags by half of it either way).
    reversal_spike : mapping of letter to float, metres
        Extra lag of an axis just after it reverses, dying away over :data:`SPIKE_WIDTH_DEG`.
    cyclic_error, cyclic_pitch : mapping of letter to float, metres
        Amplitude and pitch of a sinusoidal error of each axis' position; a pitch is needed
        for each non-zero amplitude.
    centre_offset : mapping of letter to float, metres
        Centre of the path relative to the table ball, along each axis of the plane.
    directions : sequence of str
        ``"ccw"``, ``"cw"`` or both, in the order run.
    step : float, radians
        Angle between readings; the first reading is half a step after 0.
    noise : float, metres
        Standard deviation of Gaussian noise added to each reading.
    seed : int
        Seed of the noise.

    Returns
    -------
    BallbarTrace
        The readings, each direction in the order travelled.

    Raises
    ------
    AxiscalError
        On a radius, feed or step that is not positive, a step over 1 degree, an axis not in the
        plane, a cyclic amplitude without a positive pitch, negative noise or an unknown direction.

    Examples
    --------
    >>> t = simulate_ballbar(squareness=10e-6, step=math.radians(1.0))
    >>> t.present, t.angles.size
    (('ccw', 'cw'), 720)
    """
    axes = plane_axes(plane)
    for name, value in (("radius", radius), ("feed", feed), ("step", step)):
        if not (is_real(value) and math.isfinite(value) and value > 0):
            raise AxiscalError(f"the {name} must be positive, got {value!r}")
    if step > math.radians(1.0):
        raise AxiscalError(f"the step must be at most 1 deg, got {math.degrees(step):g} deg")
    if not (is_real(noise) and math.isfinite(noise) and noise >= 0):
        raise AxiscalError(f"the noise must be zero or positive, got {noise!r} m")
    for name, value in (("squareness", squareness), ("servo mismatch", servo_mismatch)):
        if not (is_real(value) and math.isfinite(value)):
            raise AxiscalError(f"the {name} must be a finite number")
    sc = _per_axis("scale", scale, axes)
    bl = _per_axis("backlash", backlash, axes)
    sp = _per_axis("reversal spike", reversal_spike, axes)
    cy = _per_axis("cyclic error", cyclic_error, axes)
    pitch = _per_axis("cyclic pitch", cyclic_pitch, axes)
    centre = _per_axis("centre offset", centre_offset, axes)
    for k in (0, 1):
        if cy[k] != 0.0 and not pitch[k] > 0:
            raise AxiscalError(f"cyclic error of {axes[k]}: give its pitch (a positive length)")
    seed = check_count("seed", seed, minimum=0)
    if isinstance(directions, str):
        directions = (directions,)
    runs = [str(d).lower() for d in directions]
    if not runs or any(d not in DIRECTIONS for d in runs):
        raise AxiscalError(f"directions must be ccw and/or cw, got {', '.join(map(str, directions)) or 'none'}")

    rng = np.random.default_rng(seed)
    lag_angle = feed * servo_mismatch / radius  # angle the first axis trails the second by
    width = math.radians(SPIKE_WIDTH_DEG)
    n = int(round(2 * math.pi / step))
    angles, labels, readings = [], [], []
    for d in runs:
        sign = 1.0 if d == "ccw" else -1.0
        k = np.arange(n)
        theta = (step / 2 + k * step) if sign > 0 else (2 * math.pi - step / 2 - k * step)
        lagged = (theta - sign * lag_angle / 2, theta + sign * lag_angle / 2)
        command = (radius * np.cos(lagged[0]), radius * np.sin(lagged[1]))
        # direction of motion of each axis, and the angle it has travelled since its last reversal
        moving = (-sign * np.sign(np.sin(lagged[0])), sign * np.sign(np.cos(lagged[1])))
        since = (np.mod(sign * lagged[0], math.pi), np.mod(sign * (lagged[1] - math.pi / 2), math.pi))
        actual = []
        for i in (0, 1):
            error = sc[i] * command[i] - moving[i] * (bl[i] / 2 + sp[i] * np.exp(-0.5 * (since[i] / width) ** 2))
            if cy[i]:
                error = error + cy[i] * np.sin(2 * math.pi * command[i] / pitch[i])
            actual.append(command[i] + error)
        first = actual[0] - actual[1] * math.sin(squareness) + centre[0]
        second = actual[1] * math.cos(squareness) + centre[1]
        reading = np.hypot(first, second) - radius
        if noise:
            reading = reading + rng.normal(0.0, noise, n)
        angles.append(np.mod(theta, 2 * math.pi))
        labels.extend([d] * n)
        readings.append(reading)
    return BallbarTrace(np.concatenate(angles), tuple(labels), np.concatenate(readings), radius=radius,
                        plane="".join(axes), source="simulation")


def _trace(trace: BallbarTrace) -> BallbarTrace:
    check_instance("trace", trace, BallbarTrace, what="a BallbarTrace")
    return trace


def trace_csv(trace: BallbarTrace) -> str:
    """The CSV text of a trace: ``angle_deg, direction, radius_deviation_um`` (header first, no comments).

    Parameters
    ----------
    trace : BallbarTrace

    Returns
    -------
    str
    """
    _trace(trace)
    return write_csv(
        None,
        {
            "angle_deg": np.degrees(trace.angles),
            "direction": list(trace.directions),
            "radius_deviation_um": trace.deviations / UM,
        },
        fmt={"angle_deg": "{:.4f}", "radius_deviation_um": "{:.4f}"},
    )


def write_trace(path: str | Path, trace: BallbarTrace, **metadata) -> Path:
    """Write a trace as CSV (see :func:`trace_csv`) atomically, with its JSON sidecar.

    Parameters
    ----------
    path : str or Path
        The CSV file; the sidecar is the same name ending in ``.json``.
    trace : BallbarTrace
    **metadata
        Written into the sidecar (e.g. the simulated errors).

    Returns
    -------
    Path
        ``path``.
    """
    path = check_path("path", path)
    write_text(path, trace_csv(trace))
    write_sidecar(
        path,
        kind="ballbar trace",
        units={"angle_deg": "deg", "radius_deviation_um": "um"},
        plane=trace.plane,
        radius_mm=trace.radius / MM,
        **metadata,
    )
    return Path(path)
