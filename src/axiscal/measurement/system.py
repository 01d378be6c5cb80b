"""The measurement system a command works with: a machine TOML's, or the built-in virtual module's."""

from __future__ import annotations

from pathlib import Path

from axiscal.io.arguments import check_path
from axiscal.measurement.pipeline import MeasurementSystem
from axiscal.measurement.virtual import VirtualModule

__all__ = ["load_system"]


def load_system(machine: str | Path | None = None, *, seed: int = 0, load_kg: float = 0.0) -> MeasurementSystem:
    """The measurement system of a machine TOML, or of the built-in virtual module.

    Parameters
    ----------
    machine : str or Path, optional
        Machine TOML with ``[axes.<L>.sensors]`` sections; None: the virtual XZ module.
    seed : int
        Seed of the virtual module (only without ``machine``).
    load_kg : float
        Mass on the virtual module's Z slide, kg (only without ``machine``).

    Returns
    -------
    MeasurementSystem

    Raises
    ------
    AxiscalError
        If the machine file is missing or wrong (naming the file).
    """
    if machine is None:
        return VirtualModule(seed=seed, load_kg=load_kg).measurement_system()
    return MeasurementSystem.from_toml(check_path("machine", machine))
