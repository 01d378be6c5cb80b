"""Probe readings simulated from a profile file and a slide-motion file (``axiscal simulate probes``):
paper 001's multi-probe set-up, written as the readings file :func:`~axiscal.straightness.readers.read_probe_readings`
reads, with its JSON sidecar."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_count, check_instance, check_number, check_path
from axiscal.io.tabular import write_csv
from axiscal.straightness.readers import Profile, _text_and_metadata, _write_data, read_profile
from axiscal.straightness.probes import ProbeReadings, simulate_readings
from axiscal.units import MM, UM

__all__ = ["MAX_READINGS", "SimulatedReadings", "simulate_probe_readings"]

#: the most readings :func:`simulate_probe_readings` simulates
MAX_READINGS = 10**7




@dataclass(frozen=True)
class SimulatedReadings:
    """Probe readings simulated from a profile file and a motion file.

    Attributes
    ----------
    readings : ProbeReadings
        The readings, SI.
    csv_text : str
        The CSV (``position_mm, a_um, b_um[, c_um]``) as written.
    metadata : dict
        What the sidecar holds besides kind and sources: spacings, step, noise, offsets, seed.
    """

    readings: ProbeReadings
    csv_text: str
    metadata: dict[str, Any]

    def __post_init__(self) -> None:
        check_instance("readings", self.readings, ProbeReadings, what="ProbeReadings")
        _text_and_metadata(self.csv_text, self.metadata)


def _interpolator(profile: Profile, values: np.ndarray, what: str) -> Callable[[np.ndarray], np.ndarray]:
    x = profile.position_m

    def at(p: np.ndarray) -> np.ndarray:
        if p.min() < x[0] - 1e-12 or p.max() > x[-1] + 1e-12:
            raise AxiscalError(
                f"{what} covers {x[0] / MM:g}..{x[-1] / MM:g} mm but the probes reach {p.min() / MM:g}..{p.max() / MM:g} mm",
                path=profile.path,
            )
        return np.interp(p, x, values)

    return at


def simulate_probe_readings(
    profile_path: str | Path,
    motion_path: str | Path,
    *,
    spacing_ab_m: float,
    spacing_bc_m: float | None = None,
    probes: int = 3,
    step_m: float,
    noise_m: float = 0.0,
    offsets_m: tuple[float, float, float] = (0.0, 0.0, 0.0),
    seed: int = 0,
    output: str | Path | None = None,
) -> SimulatedReadings:
    """The readings a probe set-up would give on a profile and a slide (paper 001 eq 1).

    ``a = R(x) - S(x)``, ``b = R(x + d1) - S(x) - d1 yaw(x)``,
    ``c = R(x + d1 + d2) - S(x) - (d1 + d2) yaw(x)``, minus the zero offsets (eq 8), plus
    Gaussian noise. Probe A runs from the profile's first position in steps of ``step_m`` as far
    as the last probe stays on the profile.

    Parameters
    ----------
    profile_path : str or Path
        Workpiece profile R (read by :func:`read_profile`, increasing positions).
    motion_path : str or Path
        Slide motion S, with the yaw when it has a ``yaw_urad`` column.
    spacing_ab_m, spacing_bc_m : float, keyword-only
        Probe spacings, metres (B-C defaults to A-B).
    probes : {2, 3}, keyword-only
        Number of probes (default 3).
    step_m : float, keyword-only
        Sampling step of the carriage, metres.
    noise_m : float, keyword-only
        Standard deviation of the probe noise, metres.
    offsets_m : (float, float, float), keyword-only
        Zero offsets of probes A, B, C, metres.
    seed : int, keyword-only
        Seed of the noise.
    output : str or Path, optional, keyword-only
        Write the CSV here, with its JSON sidecar.

    Returns
    -------
    SimulatedReadings

    Raises
    ------
    AxiscalError
        A bad file, a profile or motion that does not cover the probes' reach, a profile too
        short for the probes, or more than :data:`MAX_READINGS` readings.
    """
    if isinstance(probes, bool) or probes not in (2, 3):
        raise AxiscalError(f"the simulation uses 2 or 3 probes, not {probes!r}")
    check_path("profile_path", profile_path)
    check_path("motion_path", motion_path)
    spacing_ab_m = check_number("spacing_ab_m", spacing_ab_m, positive=True)
    if spacing_bc_m is not None:
        spacing_bc_m = check_number("spacing_bc_m", spacing_bc_m, positive=True)
    step_m = check_number("step_m", step_m, positive=True)
    check_number("noise_m", noise_m, nonnegative=True)
    seed = check_count("seed", seed, minimum=0)
    profile_run = read_profile(profile_path, increasing=True)
    motion_run = read_profile(motion_path, increasing=True)
    profile = _interpolator(profile_run, profile_run.deviation_m, "the profile")
    motion = _interpolator(motion_run, motion_run.deviation_m, "the motion")
    yaw = None
    if motion_run.yaw_rad is not None:
        missing = np.flatnonzero(~np.isfinite(motion_run.yaw_rad))
        if missing.size:
            raise AxiscalError("column 'yaw_urad': empty cell", path=motion_run.path, line=motion_run.lines[missing[0]])
        yaw = _interpolator(motion_run, motion_run.yaw_rad, "the yaw")
    px = profile_run.position_m
    d2 = (spacing_ab_m if spacing_bc_m is None else spacing_bc_m) if probes == 3 else None
    reach = spacing_ab_m + (d2 or 0.0)
    steps = (px[-1] - px[0] - reach) / step_m
    if steps >= MAX_READINGS:
        raise AxiscalError(f"a step of {step_m / MM:g} mm gives {steps:.3g} readings; at most {MAX_READINGS} are simulated")
    count = int(np.floor(steps + 1e-9)) + 1
    if count < 2:
        raise AxiscalError(
            f"the profile ({(px[-1] - px[0]) / MM:g} mm) is too short for probes {reach / MM:g} mm apart", path=profile_path
        )
    x = px[0] + step_m * np.arange(count)
    data = simulate_readings(
        x,
        profile,
        motion,
        yaw,
        spacing_ab_m=spacing_ab_m,
        spacing_bc_m=d2,
        offsets_m=offsets_m,
        noise_m=noise_m,
        rng=np.random.default_rng(seed),
    )
    columns = {"position_mm": data.position_m / MM, "a_um": data.a_m / UM, "b_um": data.b_m / UM}
    if data.c_m is not None:
        columns["c_um"] = data.c_m / UM
    formats = {"position_mm": "{:.4f}", "a_um": "{:.6f}", "b_um": "{:.6f}", "c_um": "{:.6f}"}
    text = write_csv(None, columns, fmt=formats)
    metadata: dict[str, Any] = {
        "model": "paper 001 eq (1)",
        "spacing_ab_mm": spacing_ab_m / MM,
        "spacing_bc_mm": None if d2 is None else d2 / MM,
        "step_mm": step_m / MM,
        "noise_um": noise_m / UM,
        "offsets_um": [o / UM for o in offsets_m],
        "seed": seed,
    }
    if output is not None:
        _write_data(output, text, kind="probe readings", sources=[profile_path, motion_path], **metadata)
    return SimulatedReadings(data, text, metadata)
