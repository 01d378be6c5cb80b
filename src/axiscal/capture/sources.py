"""Live sources for a capture: the streams ``axiscal live`` reads, asked for the laser's channel and the air sensors.

``tcp:HOST:PORT`` and ``serial:DEVICE[:BAUD]`` speak the line protocol of :mod:`axiscal.live.protocol`
(a header line naming the columns, then ``t_s`` and the channels); the capture asks them for the
reading's channel and the air sensors, which a stream may or may not carry. ``sim`` is the virtual
machine (:mod:`axiscal.capture.virtual`) running the plan on the built-in XZ module's X axis,
streamed at the pace of its clock, as a laser on a real machine would stream.
"""

from __future__ import annotations

from collections.abc import Sequence
from importlib import resources
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.capture.recording import ENVIRONMENT_COLUMNS
from axiscal.capture.steps import PlanSteps
from axiscal.capture.virtual import simulate_motions
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_number
from axiscal.io.gcode import Motion
from axiscal.live.sources import ReplaySource, open_source, parse_source
from axiscal.units import MM

__all__ = ["plan_motions", "open_capture_source"]


def plan_motions(steps: PlanSteps, *, axis: str = "X", dwell_s: float = 2.0, feed_mm_per_min: float = 2000.0) -> tuple[Motion, ...]:
    """The plan's moves as a program runs them: a feed move per step and a dwell after each target.

    Parameters
    ----------
    steps : PlanSteps
    axis : str, keyword-only
        The axis moved.
    dwell_s : float, keyword-only
        Dwell at each target, seconds (default 2).
    feed_mm_per_min : float, keyword-only
        Feed of the moves (default 2000 mm/min).

    Returns
    -------
    tuple of Motion
    """
    dwell_s = check_number("dwell_s", dwell_s, nonnegative=True, unit="s")
    feed = check_number("feed_mm_per_min", feed_mm_per_min, positive=True, unit="mm/min") * MM / 60.0
    out: list[Motion] = []
    for k in range(steps.step.size):
        out.append(Motion(k + 1, "feed", {axis: float(steps.move_to_m[k])}, feed, 0.0))
        if np.isfinite(steps.target_m[k]):
            out.append(Motion(k + 1, "dwell", {axis: float(steps.move_to_m[k])}, None, dwell_s))
    return tuple(out)


class _SimCaptureSource(ReplaySource):
    """The virtual machine's laser streamed at its own pace."""

    def __init__(self, steps: PlanSteps, channels: Sequence[str], *, rate_hz: float, seed: int, pace: bool):
        from axiscal.model.machine import load_machine

        machine = load_machine(Path(str(resources.files("axiscal") / "data" / "xz_module" / "machine.toml")))
        simulated = simulate_motions(plan_motions(steps), machine, axis="X", rate_hz=rate_hz, seed=seed)
        rec = simulated.recording
        values = np.column_stack([rec.reading_m / MM] + [rec.channels[name] for name in channels[1:]])
        self._play(f"sim (virtual XZ module, X axis, {rate_hz:g} Hz)", channels, rec.time_s, values, pace=pace, max_batch=5000)


def _virtual_position(steps: PlanSteps, seed: int):
    """Where the virtual XZ module's X carriage is, t seconds after it starts the plan (metres, in vacuum)."""
    from axiscal.instruments.air import refractive_index
    from axiscal.instruments.interferometer import HENE_WAVELENGTH_NM
    from axiscal.model.machine import load_machine

    machine = load_machine(Path(str(resources.files("axiscal") / "data" / "xz_module" / "machine.toml")))
    simulated = simulate_motions(plan_motions(steps), machine, axis="X", rate_hz=200.0, seed=seed)
    rec = simulated.recording
    n = refractive_index(rec.channels["air_temperature_c"], rec.channels["pressure_pa"], rec.channels["humidity_pct"],
                         HENE_WAVELENGTH_NM)
    position = simulated.clean_m / n
    return lambda t: float(np.interp(t, rec.time_s, position))


def open_capture_source(
    spec: str,
    *,
    steps: PlanSteps | None = None,
    channel: str | None = None,
    rate_hz: float = 1000.0,
    seed: int = 0,
    pace: bool = True,
    instrument: Any = None,
) -> Any:
    """The live source a ``--source`` value names, asked for the reading's channel and the air sensors.

    Parameters
    ----------
    spec : str
        ``sim``, ``tcp:HOST:PORT``, ``serial:DEVICE[:BAUD]`` (also ``replay:FILE`` and
        ``rtx:FILE:UNIT:CHANNEL`` as ``axiscal live`` takes them), or an instrument of
        :mod:`axiscal.devices` (``umd:PORT``, ``sylvac:PORT`` ..., ``sim:KIND``: its simulator reading
        the virtual machine as it runs the plan).
    steps : PlanSteps, optional, keyword-only
        The plan (``sim`` runs it).
    channel : str, optional, keyword-only
        The reading's channel (default ``reading_mm``).
    rate_hz, seed : keyword-only
        Sample rate and noise seed of ``sim``.
    pace : bool, keyword-only
        ``sim`` and replays at their clock's pace (default) or as fast as read.
    instrument : InstrumentOptions, optional, keyword-only
        The instrument's flags (:class:`axiscal.devices.instruments.InstrumentOptions`).

    Returns
    -------
    a source of :mod:`axiscal.live.sources`

    Raises
    ------
    AxiscalError
        For a spec :func:`axiscal.live.sources.parse_source` refuses, or ``sim`` without a plan.
    """
    from axiscal.devices.instruments import is_instrument_spec, open_instrument

    if is_instrument_spec(spec):
        position = None
        if spec.strip().lower().startswith("sim:"):
            if steps is None:
                raise AxiscalError("a simulated instrument reads the virtual machine running the plan: it needs the plan's steps")
            position = _virtual_position(steps, seed)
        return open_instrument(spec, instrument, position=position, seed=seed, pace=pace)
    kind, _ = parse_source(spec)
    channel = channel or "reading_mm"
    channels = (channel,) + ENVIRONMENT_COLUMNS[:3]
    if kind == "sim":
        if steps is None:
            raise AxiscalError("the sim source runs the plan: it needs the plan's steps")
        return _SimCaptureSource(steps, ("reading_mm",) + ENVIRONMENT_COLUMNS[:3], rate_hz=rate_hz, seed=seed, pace=pace)
    return open_source(spec, channels, pace=pace)
