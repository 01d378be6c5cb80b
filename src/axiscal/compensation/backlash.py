"""Backlash parameters of CNC controllers and firmware, from the ISO 230-2 reversal value.

ISO 230-2 (2014) clause 2.17 and 3.3: the reversal value at a target is ``B_i = mean_up - mean_down``
(mean deviation approaching in the + direction minus that approaching in the - direction); the
mean reversal value of the axis is ``B_mean``, the mean of ``B_i`` over the targets. A drive with
play ``b`` between the measuring system and the slide leaves the slide ``b / 2`` behind the mean
moving up and ``b / 2`` ahead moving down, so ``B_i = -b``. The controllers below all add ``b`` to
the command at a reversal: their parameter is ``-B_i`` (positive for the usual play, the
encoder ahead of the slide).

Each controller's parameter, unit and range come from its own documentation (see
docs/compensation.md, "Backlash").
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_choice, check_instance, check_integer, check_number, check_optional_number
from axiscal.positioning import PositioningRun, read_positioning_run, target_statistics
from axiscal.units import MM, UM

__all__ = [
    "BACKLASH_CONTROLLERS",
    "BACKLASH_METHODS",
    "BacklashSetting",
    "reversal_backlash",
    "backlash_setting",
    "backlash_from_run",
]

#: controller -> (parameter, unit of the value, signed values accepted)
BACKLASH_CONTROLLERS: dict[str, tuple[str, str, bool]] = {
    "linuxcnc": ("[JOINT_n] BACKLASH", "machine unit (mm)", False),
    "fanuc": ("parameter 1851", "detection unit", True),
    "siemens": ("MD32450 $MA_BACKLASH", "mm", True),
    "heidenhain": ("MP_backLash", "mm", True),
    "twincat": ("P-AXIS-00103 getriebe[0].lose", "0.1 um", True),
    "grblhal": ("$160..$165 (X, Y, Z, A, B, C)", "mm", False),
    "marlin": ("M425 / BACKLASH_DISTANCE_MM", "mm", False),
    "rrf": ("M425", "mm", False),
}
BACKLASH_METHODS = ("mean", "max", "target")
_AXES = ("X", "Y", "Z", "A", "B", "C")
_FANUC_RANGE = 9999
_TWINCAT_RANGE = 32767  # SGN16
_TWINCAT_UNIT = 0.1 * UM


@dataclass(frozen=True)
class BacklashSetting:
    """A backlash value in a controller's parameter.

    Attributes
    ----------
    controller : str
        One of :data:`BACKLASH_CONTROLLERS`.
    axis : str
        Axis letter.
    backlash_m : float
        The backlash to compensate, metres (positive: the usual play).
    written_m : float
        The value as the controller will hold it after rounding to its unit, metres.
    parameter : str
        The controller's parameter name.
    lines : tuple of str
        What to enter: a configuration line, a G-code line or a parameter assignment.
    notes : tuple of str
        What the controller needs besides.
    """

    controller: str
    axis: str
    backlash_m: float
    written_m: float
    parameter: str
    lines: tuple[str, ...]
    notes: tuple[str, ...]

    def text(self) -> str:
        """The notes as ``;`` comment lines, then the lines."""
        return "".join(f"; {note}\n" for note in self.notes) + "".join(f"{line}\n" for line in self.lines)


def _counts(value_m: float, unit_m: float, limit: int, unit: str, parameter: str) -> int:
    """``value_m`` in whole ``unit_m``, refused beyond +-``limit`` (the parameter's range)."""
    counts = round(value_m / unit_m)
    if abs(counts) > limit:
        raise AxiscalError(f"{counts} {unit} is beyond {parameter}'s range of +-{limit}")
    return counts


def reversal_backlash(run: PositioningRun, *, method: str = "mean", target_m: float | None = None) -> float:
    """The backlash to compensate from a bidirectional positioning test, metres (``-B``).

    Parameters
    ----------
    run : PositioningRun
        The test (both directions at every target).
    method : str, keyword-only
        ``"mean"``: ``-B_mean`` (mean reversal value of the axis, ISO 230-2); ``"max"``: ``-B_i`` at
        the target where ``|B_i|`` is largest (the reversal value B); ``"target"``: ``-B_i`` at
        ``target_m``.
    target_m : float, optional, keyword-only
        The target for ``method="target"``, metres; it must be one of the run's targets (1 um slack).

    Returns
    -------
    float
        Backlash, metres; positive for the usual play.

    Raises
    ------
    AxiscalError
        For an unknown method, a missing or unknown target.

    Examples
    --------
    >>> import numpy as np
    >>> run = PositioningRun(np.array([0.0, 0.1]), np.array([[-5e-6], [-6e-6]]), np.array([[5e-6], [6e-6]]))
    >>> round(reversal_backlash(run) / 1e-6, 6)
    11.0
    """
    check_instance("run", run, PositioningRun)
    check_choice("method", method, BACKLASH_METHODS)
    target_m = check_optional_number("target_m", target_m)
    reversal = target_statistics(run).reversal
    if method == "mean":
        return -float(np.mean(reversal))
    if method == "max":
        return -float(reversal[int(np.argmax(np.abs(reversal)))])
    if target_m is None:
        raise AxiscalError("method 'target' needs the target position")
    k = int(np.argmin(np.abs(run.targets - target_m)))
    if abs(run.targets[k] - target_m) > UM:
        raise AxiscalError(f"{target_m / MM:g} mm is not a target of the run (nearest {run.targets[k] / MM:g} mm)")
    return -float(reversal[k])


def backlash_setting(controller: str, backlash_m: float, *, axis: str = "X", axis_number: int | None = None) -> BacklashSetting:
    """The backlash parameter of a controller, as its documentation asks for it.

    Parameters
    ----------
    controller : str
        ``linuxcnc``, ``fanuc``, ``siemens``, ``heidenhain``, ``twincat`` (TwinCAT CNC,
        TF5200), ``grblhal``, ``marlin`` or ``rrf`` (RepRapFirmware 3.5 and later).
    backlash_m : float
        Backlash, metres (as :func:`reversal_backlash` gives it).
    axis : str, keyword-only
        Axis letter (X, Y, Z, A, B, C).
    axis_number : int, optional, keyword-only
        1-based axis number (LinuxCNC joint number + 1, SINUMERIK AXn); default: X = 1, Y = 2, ...

    Returns
    -------
    BacklashSetting

    Raises
    ------
    AxiscalError
        For an unknown controller or axis, a non-finite value, a negative backlash where the
        controller takes only a distance (LinuxCNC, grblHAL, Marlin, RepRapFirmware), or a value
        beyond the parameter's range (FANUC +-9999 detection units, TwinCAT +-32767 x 0.1 um).

    Examples
    --------
    >>> backlash_setting("siemens", 0.012e-3, axis="X").lines
    ('$MA_BACKLASH[0,AX1]=0.012',)
    """
    check_choice("controller", controller, BACKLASH_CONTROLLERS)
    axis = check_instance("axis", axis, str, what="an axis letter").upper()
    if axis not in _AXES:
        raise AxiscalError(f"unknown axis '{axis}'; use one of {', '.join(_AXES)}")
    backlash_m = check_number("backlash_m", backlash_m)
    if axis_number is not None:
        check_integer("axis_number", axis_number)
    number = axis_number if axis_number is not None else _AXES.index(axis) + 1
    if number < 1:
        raise AxiscalError(f"axis numbers start at 1, not {number}")
    parameter, _, signed = BACKLASH_CONTROLLERS[controller]
    if backlash_m < 0 and not signed:
        raise AxiscalError(
            f"the backlash is negative ({backlash_m / UM:+.2f} um: the slide leads the encoder);"
            f" {controller} takes only a positive distance"
        )
    mm = backlash_m / MM
    notes: tuple[str, ...] = ()
    if controller == "linuxcnc":
        written = round(mm, 6)
        lines = (f"[JOINT_{number - 1}]", f"BACKLASH = {written:.6f}")
        notes = ("LinuxCNC: machine units (mm assumed); 0 when a COMP_FILE of both directions already holds the reversal",)
    elif controller == "fanuc":
        counts = _counts(backlash_m, UM, _FANUC_RANGE, "detection units", "parameter 1851")
        written = counts * UM / MM
        lines = (f"1851 {axis} {counts}",)
        notes = (
            "FANUC: parameter 1851 (backlash compensating value), word axis, in detection units (1 um assumed);"
            " 1852 holds a rapid traverse value when bit RBK of 1800 is set",
        )
    elif controller == "siemens":
        written = round(mm, 6)
        lines = (f"$MA_BACKLASH[0,AX{number}]={written:.6g}",)
        notes = ("SINUMERIK: MD32450 $MA_BACKLASH[0] of the first measuring system, mm; active after homing",)
    elif controller == "heidenhain":
        written = round(mm, 4)
        lines = (f"MP_backLash {axis} {written:.4f}",)
        notes = ("HEIDENHAIN: MP_backLash of the axis (mm); MP_filterTime sets the time the reversal is made up in",)
    elif controller == "twincat":
        counts = _counts(backlash_m, _TWINCAT_UNIT, _TWINCAT_RANGE, "x 0.1 um", "P-AXIS-00103")
        written = counts * _TWINCAT_UNIT / MM
        lines = (f"getriebe[0].lose {counts}",)
        notes = (
            f"TwinCAT CNC: axis parameter list of axis {axis}, P-AXIS-00103 in 0.1 um; P-AXIS-00021"
            " lr_param.anwahl_losekomp switches it on (1 or 2: the direction of the axis' last motion at start-up)",
        )
    elif controller == "grblhal":
        written = round(mm, 3)
        lines = (f"${160 + _AXES.index(axis)}={written:.3f}",)
        notes = ("grblHAL: built with ENABLE_BACKLASH_COMPENSATION; the setting is in mm",)
    elif controller == "marlin":
        written = round(mm, 4)
        lines = (f"M425 {axis}{written:.4f}",)
        notes = (
            "Marlin: needs BACKLASH_COMPENSATION and BACKLASH_GCODE; M500 stores it,"
            f" or BACKLASH_DISTANCE_MM in Configuration_adv.h ({axis} = {written:.4f})",
        )
    else:
        written = round(mm, 4)
        lines = (f"M425 {axis}{written:.4f}",)
        notes = ("RepRapFirmware 3.5 or later: put the line in config.g",)
    return BacklashSetting(
        controller=controller,
        axis=axis,
        backlash_m=backlash_m,
        written_m=written * MM,
        parameter=parameter,
        lines=lines,
        notes=notes,
    )



def backlash_from_run(
    controller: str,
    run: PositioningRun | str | Path,
    *,
    method: str = "mean",
    target_m: float | None = None,
    axis: str = "X",
    axis_number: int | None = None,
) -> BacklashSetting:
    """The backlash parameter of a controller from a bidirectional positioning test.

    :func:`reversal_backlash` then :func:`backlash_setting`.

    Parameters
    ----------
    controller : str
        One of :data:`BACKLASH_CONTROLLERS`.
    run : PositioningRun, or str or Path
        The test (both directions at every target), metres; or a positioning run file, read with
        :func:`axiscal.positioning.read_positioning_run`.
    method : str, keyword-only
        ``"mean"``, ``"max"`` or ``"target"`` (see :func:`reversal_backlash`).
    target_m : float, optional, keyword-only
        The target for ``method="target"``, metres.
    axis : str, keyword-only
        Axis letter.
    axis_number : int, optional, keyword-only
        1-based axis number (default: X = 1, Y = 2, ...).

    Returns
    -------
    BacklashSetting

    Raises
    ------
    AxiscalError
        As the two functions do, and as the reader does for a file.
    """
    check_choice("controller", controller, BACKLASH_CONTROLLERS)
    if isinstance(run, (str, os.PathLike)):
        run = read_positioning_run(run).run
    value = reversal_backlash(run, method=method, target_m=target_m)
    return backlash_setting(controller, value, axis=axis, axis_number=axis_number)
