"""LinuxCNC compensation table: the joint ``COMP_FILE`` of ``COMP_FILE_TYPE`` 0 and 1.

As LinuxCNC reads and applies it: ``usrmotLoadComp`` (``src/emc/motion/usrmotintf.cc``) reads
``nominal forward reverse`` triplets; the motion controller interpolates the trims linearly.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from axiscal.compensation.curve import ErrorCurve, _check_direction
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_count, check_instance, check_integer, check_number
from axiscal.units import MM

LINUXCNC_MAX_ENTRIES = 256

__all__ = ["LINUXCNC_MAX_ENTRIES", "LinuxcncTable", "linuxcnc_table", "parse_linuxcnc"]


@dataclass(frozen=True)
class LinuxcncTable:
    """A LinuxCNC joint compensation file (``[JOINT_n] COMP_FILE``, ``COMP_FILE_TYPE``).

    One line per entry, ``nominal forward reverse`` in machine units, nothing else: LinuxCNC
    reads triplets with ``sscanf("%lf %lf %lf")`` and stops at the first line that is not
    three numbers. Nominals strictly increase; at most 256 entries.

    ``comp_type`` 0: ``forward``/``reverse`` are the positions actually reached at ``nominal``
    when travelling forward (+) / in reverse (-); LinuxCNC uses ``nominal - forward`` as the
    correction. ``comp_type`` 1: they are the corrections themselves (trims), added to the
    commanded position. Between entries LinuxCNC interpolates linearly; beyond the first and
    last entry it holds their values.

    Attributes
    ----------
    nominal, forward, reverse : ndarray, shape (k,), machine units as written to the file
    comp_type : int
    unit_m : float
        Metres per machine unit (1e-3 for a metric machine).
    decimals : int
        Decimals written; the resolution is 10**-decimals machine units.

    Examples
    --------
    >>> from axiscal.compensation.curve import error_curve
    >>> from axiscal.positioning import paper003_table4_run, target_statistics
    >>> curve = error_curve(target_statistics(paper003_table4_run()))
    >>> print(linuxcnc_table(curve).text(), end="")
    0.000000 -0.000733 -0.002233
    20.000000 -0.001600 -0.002733
    """

    nominal: np.ndarray
    forward: np.ndarray
    reverse: np.ndarray
    comp_type: int
    unit_m: float = MM
    decimals: int = 6

    @property
    def resolution(self) -> float:
        """Smallest step of a written value, metres."""
        return 10.0 ** (-self.decimals) * self.unit_m

    @property
    def nodes(self) -> np.ndarray:
        """The nominal positions, metres, shape (k,)."""
        return self.nominal * self.unit_m

    def text(self) -> str:
        """The file: one ``nominal forward reverse`` line per entry, nothing else."""
        d = self.decimals
        return "".join(f"{n:.{d}f} {f:.{d}f} {r:.{d}f}\n" for n, f, r in zip(self.nominal, self.forward, self.reverse))

    def correction(self, x, direction: str) -> np.ndarray:
        """The correction LinuxCNC adds to commanded positions ``x`` (metres) moving in ``direction``.

        Parameters
        ----------
        x : float or array_like, metres
            Commanded positions.
        direction : {"+", "-"}
            Direction of travel.

        Returns
        -------
        ndarray, shape of ``x``, metres
        """
        _check_direction(direction)
        values = self.forward if direction == "+" else self.reverse
        trims = self.nominal - values if self.comp_type == 0 else values
        x_units = check_array("x", x, unit="metres") / self.unit_m
        return np.interp(x_units, self.nominal, trims) * self.unit_m


def linuxcnc_table(curve: ErrorCurve, *, comp_type: int = 1, unit_m: float = MM, decimals: int = 6) -> LinuxcncTable:
    """LinuxCNC compensation file at the measured targets.

    Parameters
    ----------
    curve : ErrorCurve
        Mean deviations per direction.
    comp_type : {0, 1}, keyword-only
        ``COMP_FILE_TYPE`` (default 1): 0 writes the positions reached (``nominal + e``), 1 writes
        the corrections (``-e``).
    unit_m : float, keyword-only
        Metres per machine unit (default 1e-3: a metric machine).
    decimals : int, keyword-only
        Decimals written (default 6: 1 nm on a metric machine).

    Returns
    -------
    LinuxcncTable
        One entry per measured target.

    Raises
    ------
    AxiscalError
        For a ``comp_type`` other than 0 or 1, more than 256 targets, or targets so close that
        the written nominals would not increase.

    Examples
    --------
    >>> from axiscal.compensation.curve import error_curve
    >>> from axiscal.positioning import paper003_table4_run, target_statistics
    >>> curve = error_curve(target_statistics(paper003_table4_run()))
    >>> linuxcnc_table(curve, comp_type=0).forward.tolist()
    [0.000733, 20.0016]
    """
    check_instance("curve", curve, ErrorCurve)
    if check_integer("comp_type", comp_type) not in (0, 1):
        raise AxiscalError(f"LinuxCNC COMP_FILE_TYPE is 0 or 1, got {comp_type}")
    unit_m = check_number("unit_m", unit_m, positive=True)
    decimals = check_count("decimals", decimals, minimum=0, maximum=12)
    if curve.positions.size > LINUXCNC_MAX_ENTRIES:
        raise AxiscalError(
            f"{curve.positions.size} targets: a LinuxCNC compensation file holds at most {LINUXCNC_MAX_ENTRIES} entries"
        )
    nominal = np.round(curve.positions / unit_m, decimals)
    if np.any(np.diff(nominal) <= 0):
        raise AxiscalError(f"targets closer than {10.0 ** -decimals:g} machine units: nominals would not increase")
    if comp_type == 1:
        forward, reverse = -curve.up / unit_m, -curve.down / unit_m
    else:
        forward, reverse = nominal + curve.up / unit_m, nominal + curve.down / unit_m
    return LinuxcncTable(nominal, np.round(forward, decimals) + 0.0, np.round(reverse, decimals) + 0.0, comp_type, unit_m, decimals)


def parse_linuxcnc(text: str) -> np.ndarray:
    """Read a compensation file as LinuxCNC does: triplets until the first line that is not one.

    Parameters
    ----------
    text : str
        The content of a ``COMP_FILE``.

    Returns
    -------
    ndarray, shape (k, 3)
        ``nominal, forward, reverse`` per entry, machine units.

    Raises
    ------
    AxiscalError
        If any line after the first one that is not three numbers would be ignored, if the
        nominals do not strictly increase or if there are more than 256 entries (LinuxCNC rejects
        those with "compensation values must increase" / "too many compensation entries").

    Examples
    --------
    >>> parse_linuxcnc("0 0 0\\n10 0.001 -0.001\\n").shape
    (2, 3)
    """
    check_instance("text", text, str, what="the text of a LinuxCNC compensation file")
    lines = text.splitlines()
    rows = []
    for line in lines:
        cells = line.split()
        try:
            values = [float(c) for c in cells[:3]]
        except ValueError:
            break
        if len(values) < 3:
            break
        rows.append(values)
    if len(rows) != len(lines):
        raise AxiscalError(f"LinuxCNC would stop reading at line {len(rows) + 1}: not three numbers", line=len(rows) + 1)
    table = np.array(rows, dtype=float).reshape(-1, 3)
    if table.shape[0] > LINUXCNC_MAX_ENTRIES:
        raise AxiscalError(f"{table.shape[0]} entries: LinuxCNC accepts at most {LINUXCNC_MAX_ENTRIES}")
    if np.any(np.diff(table[:, 0]) <= 0):
        raise AxiscalError("nominal positions must strictly increase")
    return table
