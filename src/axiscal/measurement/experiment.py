"""Paper 000 section 5 on the virtual module: the XZ diagonal against a laser interferometer, before and after the model (eq 13).

:func:`diagonal_experiment` simulates it on a :class:`~axiscal.measurement.virtual.VirtualModule`
(SI result); :func:`run_diagonal_experiment` is ``axiscal experiment diagonal``: the experiment, its
figure and the paper's published values beside it.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.instruments.reports import render_report
from axiscal.io.arguments import check_count, check_instance, check_mapping, check_number
from axiscal.measurement.pipeline import MeasurementSystem, diagonal_errors
from axiscal.measurement.virtual import SQUARENESS_EB0Z_RAD, STROKE_M, VirtualModule
from axiscal.units import MM, UM

__all__ = ["DiagonalExperiment", "diagonal_experiment", "DiagonalReport", "run_diagonal_experiment"]

#: the paper's published diagonal errors (paper 000 section 5, Fig. 22), um, by load in kg
PAPER_DIAGONAL_UM = {0.0: {"before": 68.0, "after": 13.0}, 2.0: {"before": 56.0, "after": 14.0}}


@dataclass(frozen=True)
class DiagonalExperiment:
    """Paper 000 section 5 in simulation: the XZ diagonal against a laser interferometer (eq 13).

    Arrays have shape (n,), one entry per point (the start, where the interferometer is zeroed,
    is the first); all values SI (metres).

    Attributes
    ----------
    load_kg : float
        Mass on the Z slide, kg.
    x_m, z_m : ndarray
        Nominal moves of X and Z from the start, m.
    laser_m : ndarray
        Interferometer reading along the diagonal, m.
    before_m, after_m : ndarray
        E_BD and E_AD of eq (13), m.
    scales_only_m : ndarray
        The diagonal error with only the scales' positions, m.
    true_after_m : ndarray
        E_AD with the true spatial error (what a perfect measuring system leaves), m.
    """

    load_kg: float
    x_m: np.ndarray
    z_m: np.ndarray
    laser_m: np.ndarray
    before_m: np.ndarray
    after_m: np.ndarray
    scales_only_m: np.ndarray
    true_after_m: np.ndarray

    @property
    def before_max_m(self) -> float:
        """Largest |E_BD|: the diagonal error without the model, m."""
        return float(np.max(np.abs(self.before_m)))

    @property
    def after_max_m(self) -> float:
        """Largest |E_AD|: the diagonal error left with the measured errors in the model, m."""
        return float(np.max(np.abs(self.after_m)))

    @property
    def scales_only_max_m(self) -> float:
        """Largest error when only the scale readings are used (the traditional way of section 3), m."""
        return float(np.max(np.abs(self.scales_only_m)))


def diagonal_experiment(
    module: VirtualModule,
    *,
    points: int = 19,
    step_m: float = 0.010,
    samples: int = 1,
    squareness_error_rad: float = 0.0,
) -> DiagonalExperiment:
    """Simulate paper 000's diagonal comparison (section 5, eq 13) on a virtual module.

    Both axes step ``step_m`` at a time from 0 for ``points`` steps; at each stop the module's
    measurement system averages ``samples`` frames and a laser interferometer, aligned with the
    nominal diagonal and zeroed at the start, reads the functional point's move along it.
    ``squareness_error_rad`` is added to the squareness the measuring system's model uses (the
    module keeps its true one): e.g. the 8.18 arcsec of the paper's marble square, to see what a
    squareness measured against an uncorrected reference leaves behind.

    Parameters
    ----------
    module : VirtualModule
        The simulated module (its load and seed).
    points : int
        Steps from the start (default 19).
    step_m : float
        Move of each axis per step, m (default 0.010).
    samples : int
        Frames averaged at each stop (default 1).
    squareness_error_rad : float
        Error added to the model's squareness EB0Z, rad (default 0).

    Returns
    -------
    DiagonalExperiment
        E_BD (nominal moves), E_AD (moves plus measured spatial error, relative to the start),
        the same with only the scales' positions, and E_AD with the true spatial error (what a
        perfect measuring system would leave: the interferometer's own noise).

    Examples
    --------
    >>> result = diagonal_experiment(VirtualModule(seed=0))
    >>> result.after_max_m < result.before_max_m
    True
    """
    check_instance("module", module, VirtualModule, what="a VirtualModule")
    points = check_count("points", points)
    step_m = check_number("step_m", step_m, positive=True)
    if points * step_m > STROKE_M + 1e-12:
        raise AxiscalError(f"points x step_m: {points} steps of {step_m / MM:g} mm leave the {STROKE_M / MM:g} mm stroke")
    samples = check_count("samples", samples)
    squareness_error_rad = check_number("squareness_error_rad", squareness_error_rad)
    system = module.measurement_system()
    if squareness_error_rad:
        squareness = {"EB0Z": SQUARENESS_EB0Z_RAD + squareness_error_rad}
        system = MeasurementSystem(replace(module.machine, squareness_rad=squareness), module.heads, module.calibration)
    q = np.arange(points + 1) * step_m
    repeated = {"X": np.repeat(q, samples), "Z": np.repeat(q, samples)}
    frames, _ = module.frames_at(repeated)
    out = system.process(frames)
    mean = {k: np.nanmean(out[k].reshape(points + 1, samples), axis=1) for k in ("ex_m", "ey_m", "ez_m", "x_m", "z_m")}
    measured = np.column_stack([mean["ex_m"], mean["ey_m"], mean["ez_m"]])
    positions = {"X": q, "Z": q.copy()}
    actual = module.true_point(positions)
    laser = module.laser_diagonal(positions)
    before, after = diagonal_errors(q, q, measured - measured[0], laser)
    true_error = actual - module.machine.nominal_point(positions)
    _, true_after = diagonal_errors(q, q, true_error - true_error[0], laser)
    scales_only = np.hypot(mean["x_m"] - mean["x_m"][0], mean["z_m"] - mean["z_m"][0]) - laser
    return DiagonalExperiment(
        load_kg=module.load_kg,
        x_m=q,
        z_m=q.copy(),
        laser_m=laser,
        before_m=before,
        after_m=after,
        scales_only_m=scales_only,
        true_after_m=true_after,
    )


@dataclass(frozen=True)
class DiagonalReport:
    """The diagonal experiment with what is shown of it (``axiscal experiment diagonal``).

    Attributes
    ----------
    experiment : DiagonalExperiment
        The SI result.
    paper_um : dict or None
        The paper's published before/after values for this load (um), if it published any.
    """

    experiment: DiagonalExperiment
    paper_um: dict[str, float] | None = field(default=None)

    def __post_init__(self) -> None:
        check_instance("experiment", self.experiment, DiagonalExperiment, what="a DiagonalExperiment (diagonal_experiment)")
        if self.paper_um is not None:
            check_mapping("paper_um", self.paper_um, ("before", "after"), what="the paper's before and after values in um")

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary and points, display units (mm, um)."""
        e = self.experiment
        return {
            "load_kg": e.load_kg,
            "before_max_um": e.before_max_m / UM,
            "after_max_um": e.after_max_m / UM,
            "scales_only_max_um": e.scales_only_max_m / UM,
            "paper_um": self.paper_um,
            "points": [
                {"x_mm": x / MM, "z_mm": z / MM, "laser_mm": p / MM, "before_um": b / UM, "after_um": a / UM, "scales_only_um": s / UM}
                for x, z, p, b, a, s in zip(e.x_m, e.z_m, e.laser_m, e.before_m, e.after_m, e.scales_only_m)
            ],
        }

    def text(self) -> str:
        """The plain-text report (template ``templates/measurement/diagonal_experiment.txt.j2``)."""
        return render_report("measurement/diagonal_experiment.txt.j2", report=self.to_dict(), steps=self.experiment.x_m.size - 1)


def run_diagonal_experiment(
    *,
    load_kg: float = 0.0,
    seed: int = 0,
    samples: int = 1,
    squareness_error_rad: float = 0.0,
    plot: str | Path | None = None,
) -> DiagonalReport:
    """Paper 000 section 5 on the virtual module: the XZ diagonal against a laser, before and after the model.

    Parameters
    ----------
    load_kg : float
        Mass on the Z slide, kg (the paper's second run uses 2).
    seed : int
        Seed of the sensors and the noise.
    samples : int
        Frames averaged at each stop.
    squareness_error_rad : float
        Error of the squareness in the model, rad.
    plot : str or Path, optional
        Write the figure (like paper 000 Fig. 22) here.

    Returns
    -------
    DiagonalReport

    Raises
    ------
    AxiscalError
        For a negative load or a figure that cannot be written.
    """
    load_kg = check_number("load_kg", load_kg)
    if load_kg < 0:
        raise AxiscalError(f"load_kg must not be negative, got {load_kg:g}")
    experiment = diagonal_experiment(VirtualModule(seed=seed, load_kg=load_kg), samples=samples, squareness_error_rad=squareness_error_rad)
    if plot is not None:
        from axiscal.model.plot import plot_diagonal_experiment

        plot_diagonal_experiment(experiment, plot)
    return DiagonalReport(experiment, PAPER_DIAGONAL_UM.get(float(load_kg)))
