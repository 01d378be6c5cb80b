"""Compensated axis commands: the inverse of the machine model (docs/conventions.md, volumetric error).

:func:`inverse_commands` is the job of ``axiscal inverse``: wanted tool points (relative to the
workpiece point, in the workpiece frame) to the axis commands that put the tool there, solved by
:meth:`axiscal.model.machine.Machine.command_for` to better than a nanometre.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array
from axiscal.model.inputs import read_targets
from axiscal.model.machine import Machine, as_machine
from axiscal.model.output import TableResult
from axiscal.units import MM

__all__ = ["InverseResult", "inverse_commands"]


@dataclass(frozen=True)
class InverseResult(TableResult):
    """Axis commands for wanted tool points (SI units).

    Attributes
    ----------
    target_m : ndarray, shape (N, 3)
        Wanted tool points relative to the workpiece point, in the workpiece frame, metres.
    command_m : dict of str to ndarray, shape (N,)
        Command of every axis, in the machine's chain order, metres.
    sources : tuple of str
        Files the commands were computed from.
    """

    target_m: np.ndarray
    command_m: dict[str, np.ndarray]
    sources: tuple[str, ...] = field(default=())

    csv_format = "{:.7f}"  # 0.1 nm
    csv_kind = "compensated axis commands"

    def columns(self) -> dict[str, np.ndarray]:
        """Columns in display units: ``x_mm, y_mm, z_mm``, then ``<axis>_command_mm``.

        Returns
        -------
        dict of str to ndarray, shape (N,)
        """
        columns = {f"{c}_mm": self.target_m[:, i] / MM for i, c in enumerate("xyz")}
        columns |= {f"{k.lower()}_command_mm": q / MM for k, q in self.command_m.items()}
        return columns



def inverse_commands(machine: Machine | str | Path, targets: np.ndarray | str | Path) -> InverseResult:
    """Axis commands that put the tool point on wanted points.

    Parameters
    ----------
    machine : Machine, str or Path
        The machine, or its description file (TOML, docs/formats.md).
    targets : ndarray, shape (N, 3), or str or Path
        Wanted tool points relative to the workpiece point, workpiece frame: metres, or a CSV
        ``x_mm, y_mm, z_mm``. With fewer than 3 axes, the components no axis moves along are ignored.

    Returns
    -------
    InverseResult
        Targets and commands, SI.

    Raises
    ------
    AxiscalError
        A bad machine or targets file, or points the solution does not converge for (outside
        the error tables, for instance), naming the file and the point's line.

    Examples
    --------
    >>> result = inverse_commands("machine.toml", [[0.05, -0.04, 0.15]])  # doctest: +SKIP
    >>> result.command_m["X"]  # doctest: +SKIP
    """
    model = as_machine(machine)
    sources = [str(machine)] if isinstance(machine, (str, Path)) else []
    if isinstance(targets, (str, Path)):
        target, lines = read_targets(targets)
        sources.append(str(targets))
        command, bad, message = model._solve(target, 1e-12, 50)
        if bad is not None:
            raise AxiscalError(message, path=str(targets), line=lines[bad])
    else:
        targets = check_array("targets", targets)
        if targets.size == 0:
            raise AxiscalError("targets must hold at least one point (x, y, z) in metres")
        command = model.command_for(targets)
        target = np.atleast_2d(np.asarray(targets, dtype=float))
    return InverseResult(target, {k: command[k] for k in model.letters}, sources=tuple(sources))
