"""Volumetric error map of a machine at given axis positions (paper 000 eqs 9-10; ISO 230-7; docs/conventions.md).

The volumetric error is the actual minus the nominal tool point relative to the workpiece, in the
workpiece frame (:meth:`axiscal.model.machine.Machine.volumetric_error`). :func:`volumetric_map`
is the job of ``axiscal volumetric``: positions from a points file, a grid or arrays, one result.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.model.inputs import check_travel, read_points
from axiscal.model.machine import (
    AXIS_UNITS,
    Machine,
    as_machine,
    axis_positions_from_grid,
)
from axiscal.model.output import TableResult
from axiscal.model.tables import _floats
from axiscal.units import ANGLE_UNITS, UM

__all__ = ["VolumetricMap", "volumetric_map"]

_COMPONENTS = ("ex", "ey", "ez")


@dataclass(frozen=True)
class VolumetricMap(TableResult):
    """The volumetric error at a set of axis positions (SI units).

    Attributes
    ----------
    positions_m: dict of str to ndarray, shape (N,)
        Position of every axis, in the machine's chain order: metres, radians for rotary axes.
    error_m : ndarray, shape (N, 3)
        Volumetric error (ex, ey, ez): actual minus nominal tool point relative to the workpiece,
        in the workpiece frame, metres.
    name : str
        The machine's name (or chain), for titles.
    sources : tuple of str
        Files the map was computed from.
    orientation_rad : ndarray, shape (N, 2), optional
        For a chain with rotary axes: the orientation error ``(ei, ej)`` of the tool axis, radians
        (docs/conventions.md).
    """

    positions_m: dict[str, np.ndarray]
    error_m: np.ndarray
    name: str = ""
    sources: tuple[str, ...] = field(default=())
    orientation_rad: np.ndarray | None = None

    csv_format = "{:.4f}"
    csv_kind = "volumetric error"

    @property
    def magnitude_m(self) -> np.ndarray:
        """Length of the error vector at each point, shape (N,), metres."""
        return np.linalg.norm(self.error_m, axis=1)

    @property
    def max_m(self) -> float:
        """The largest error length, metres."""
        return float(self.magnitude_m.max())

    @property
    def max_at_m(self) -> dict[str, float]:
        """Axis positions of the largest error length (the first, if several), metres."""
        worst = int(np.argmax(self.magnitude_m))
        return {k: float(q[worst]) for k, q in self.positions_m.items()}

    @property
    def rms_m(self) -> float:
        """Root mean square of the error length over the points, metres."""
        return float(np.sqrt(np.mean(self.magnitude_m**2)))

    def columns(self) -> dict[str, np.ndarray]:
        """Columns in display units: ``<axis>_mm`` (``<axis>_deg``), ``ex_um, ey_um, ez_um``, ``e_um``
        (the length) and, for a chain with rotary axes, ``ei_urad, ej_urad``.

        Returns
        -------
        dict of str to ndarray, shape (N,)
        """
        columns = {}
        for k, q in self.positions_m.items():
            factor, unit = AXIS_UNITS[k]
            columns[f"{k.lower()}_{unit}"] = q / factor
        columns |= {f"{c}_um": self.error_m[:, i] / UM for i, c in enumerate(_COMPONENTS)}
        columns["e_um"] = self.magnitude_m / UM
        if self.orientation_rad is not None:
            columns["ei_urad"] = self.orientation_rad[:, 0] / ANGLE_UNITS["urad"]
            columns["ej_urad"] = self.orientation_rad[:, 1] / ANGLE_UNITS["urad"]
        return columns

    def sidecar_metadata(self) -> dict[str, str]:
        """The frame of the error, for the sidecar.

        Returns
        -------
        dict
        """
        meta = {"frame": "tool point relative to the workpiece, workpiece frame"}
        if self.orientation_rad is not None:
            meta["orientation"] = "ei, ej: turn of the tool axis about the nominal tool frame's X and Y axes"
        return meta

    def plot(self, path: str | Path, *, title: str | None = None) -> Path:
        """Write the map of :func:`axiscal.model.plot.plot_volumetric` to ``path``.

        Parameters
        ----------
        path : str or Path
            Figure file; the format follows the suffix.
        title : str, optional
            Default: ``"Volumetric error: <machine>"``.

        Returns
        -------
        Path
            ``path``.

        Raises
        ------
        AxiscalError
            If the suffix is not a figure format or the file cannot be written.
        """
        from axiscal.model.plot import plot_volumetric

        plot_volumetric(
            self.positions_m,
            self.error_m,
            path,
            title=f"Volumetric error: {self.name}" if title is None else title,
            orientation_rad=self.orientation_rad,
        )
        return Path(path)


def volumetric_map(
    machine: Machine | str | Path,
    *,
    points: str | Path | None = None,
    grid: str | None = None,
    positions: Mapping[str, np.ndarray] | None = None,
) -> VolumetricMap:
    """Volumetric error of the functional point at the given axis positions.

    Give exactly one of ``points``, ``grid`` or ``positions``.

    Parameters
    ----------
    machine : Machine, str or Path
        The machine, or its description file (TOML, docs/formats.md).
    points : str or Path, optional
        CSV with one ``<axis>_mm`` column per linear axis of the chain, ``<axis>_deg`` per rotary axis.
    grid : str, optional
        Grid of positions in mm (deg for rotary axes), ``"X=0:190:10,C=0:360:15"``
        (start:end:step, ends inclusive).
    positions : mapping of str to ndarray, shape (N,), optional
        Position of every axis of the chain: metres, radians for rotary axes.

    Returns
    -------
    VolumetricMap
        Positions and errors in SI; with the tool axis orientation error when the chain has
        rotary axes.

    Raises
    ------
    AxiscalError
        Not exactly one source of positions, a bad file (naming file and line), a grid that
        misses or adds an axis of the chain, or a position outside an error table.

    Examples
    --------
    >>> result = volumetric_map("machine.toml", grid="X=0:190:10,Z=0:190:10")  # doctest: +SKIP
    >>> result.error_m.shape  # doctest: +SKIP
    (400, 3)
    """
    if sum(source is not None for source in (points, grid, positions)) != 1:
        raise AxiscalError("give exactly one of points, grid or positions")
    model = as_machine(machine)
    sources = [str(machine)] if isinstance(machine, (str, Path)) else []
    if points is not None:
        q, _ = read_points(points, model)
        sources.append(str(points))
    else:
        if grid is not None:
            q = axis_positions_from_grid(grid)
        elif isinstance(positions, Mapping):
            q = {k: np.atleast_1d(_floats(v, f"positions of axis {k}")) for k, v in positions.items()}
        else:
            raise AxiscalError("positions must map axis letters to arrays of positions")
        what = f"grid '{grid}'" if grid is not None else "positions"
        missing = sorted(set(model.letters) - set(q))
        if missing:
            raise AxiscalError(f"{what} gives no positions for axis {', '.join(missing)} of chain '{model.chain}'")
        extra = sorted(set(q) - set(model.letters))
        if extra:
            raise AxiscalError(f"{what} names axis {', '.join(extra)}, which is not in chain '{model.chain}'")
        check_travel(model, q, path=what if grid is not None else None)
    q = {k: q[k] for k in model.letters}
    if model.rotary:
        error, orientation = model.pose_error(q)
        return VolumetricMap(q, error, name=model.name or model.chain, sources=tuple(sources), orientation_rad=orientation)
    return VolumetricMap(q, model.volumetric_error(q), name=model.name or model.chain, sources=tuple(sources))
