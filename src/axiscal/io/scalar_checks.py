"""Checks of single values a public function is given: real numbers within their physical range, counts, integers; and how a message names an argument's unit and shows a refused value.

The unit in a message is read from the argument's name (``spacing_ab_m`` is in metres,
``pressure_pa`` in pascals) unless given. :mod:`axiscal.io.arguments` gathers every check.
"""

from __future__ import annotations

import math
import numbers
from typing import Any

import numpy as np

from axiscal.errors import AxiscalError, exponent_form

__all__ = [
    "unit_words",
    "is_real",
    "type_name",
    "check_number",
    "check_optional_number",
    "check_count",
    "check_integer",
]


# name suffix -> how a message speaks of the unit; longest suffix first
_UNIT_WORDS = (
    ("_rad_per_step", "radians per step"),
    ("_per_k", "per kelvin"),
    ("_rad", "radians"),
    ("_deg", "degrees"),
    ("_nm", "nanometres"),
    ("_um", "micrometres"),
    ("_mm", "millimetres"),
    ("_m", "metres"),
    ("_c", "degC"),
    ("_pa", "pascals"),
    ("_pct", "percent"),
    ("_ppm", "ppm"),
    ("_kg", "kilograms"),
    ("_hz", "hertz"),
    ("_s", "seconds"),
)


def unit_words(name: str) -> str:
    """The unit of an argument as a message speaks of it, read from the end of its name.

    Parameters
    ----------
    name : str
        The argument's name, e.g. ``spacing_ab_m``.

    Returns
    -------
    str
        ``"metres"`` for ``spacing_ab_m``, ``"pascals"`` for ``pressure_pa``; ``""`` for a name
        without a unit.

    Examples
    --------
    >>> unit_words("spacing_ab_m"), unit_words("pressure_pa"), unit_words("index")
    ('metres', 'pascals', '')
    """
    for suffix, words in _UNIT_WORDS:
        if name.endswith(suffix):
            return words
    return ""


def _of(name: str, unit: str | None, lead: str = " of ") -> str:
    """`` of metres`` for ``spacing_m`` (or the ``unit`` given); empty for a name without a unit.
    Worked out only when a message is written."""
    words = unit_words(name) if unit is None else unit
    return f"{lead}{words}" if words else ""


def _shown(value: Any) -> str:
    """What a message shows of a value: a string quoted, a number whole (a long one in exponent form,
    never cut short into another number), anything else cut at 40 characters."""
    if isinstance(value, str):
        text = repr(value)
    elif is_real(value):
        return exponent_form(str(value))
    else:
        text = str(value)
    return text if len(text) <= 40 else text[:37] + "..."


def check_number(
    name: str,
    value: Any,
    *,
    unit: str | None = None,
    positive: bool = False,
    nonnegative: bool = False,
    low: float | None = None,
    high: float | None = None,
) -> float:
    """``value`` as a finite float, refused when it is not a number or outside its bounds.

    Parameters
    ----------
    name : str
        The argument's name, for the message.
    value : object
        What the caller passed: an int or float (a NumPy scalar or 0-d array too), not a bool,
        string or None.
    unit : str, optional
        The unit as the message says it; read from ``name`` when not given.
    positive, nonnegative : bool
        Require ``value > 0`` or ``value >= 0``.
    low, high : float, optional
        Inclusive bounds.

    Returns
    -------
    float

    Raises
    ------
    AxiscalError
        ``"<name> must be a [positive ]finite number [of <unit>], not <value>"``, or naming the
        bound it breaks.

    Examples
    --------
    >>> check_number("spacing_ab_m", 0.02, positive=True)
    0.02
    >>> check_number("spacing_ab_m", float("nan"), positive=True)
    Traceback (most recent call last):
    ...
    axiscal.errors.AxiscalError: spacing_ab_m must be a positive finite number of metres, not nan
    """
    kind = "positive " if positive else "non-negative " if nonnegative else ""
    if isinstance(value, np.ndarray) and value.ndim == 0:
        value = value[()]
    good = is_real(value)
    if good:
        value = float(value)
        good = math.isfinite(value) and not (positive and value <= 0.0) and not (nonnegative and value < 0.0)
    if not good:
        raise AxiscalError(f"{name} must be a {kind}finite number{_of(name, unit)}, not {_shown(value)}")
    if low is not None and value < low or high is not None and value > high:
        bounds = f"between {low:g} and {high:g}" if low is not None and high is not None else (
            f"at least {low:g}" if low is not None else f"at most {high:g}"
        )
        raise AxiscalError(f"{name} must be {bounds}{_of(name, unit, ' ')}, not {value:g}")
    return value


def check_count(name: str, value: Any, *, minimum: int = 1, maximum: int | None = None) -> int:
    """``value`` as a whole number of at least ``minimum`` (and at most ``maximum``).

    Parameters
    ----------
    name : str
        The argument's name, for the message.
    value : object
        An int (a NumPy integer too), not a bool, float or string.
    minimum : int
        The smallest count accepted.
    maximum : int, optional
        The largest count accepted.

    Returns
    -------
    int

    Raises
    ------
    AxiscalError
        ``"<name> must be a whole number of at least <minimum>, not <value>"``.

    Examples
    --------
    >>> check_count("trials", 10)
    10
    """
    if isinstance(value, numbers.Integral) and not isinstance(value, (bool, np.bool_)):
        value = int(value)
        if value >= minimum and (maximum is None or value <= maximum):
            return value
    upto = f" and at most {maximum}" if maximum is not None else ""
    raise AxiscalError(f"{name} must be a whole number of at least {minimum}{upto}, not {_shown(value)}")


def is_real(value: Any) -> bool:
    """True for an int or float, NumPy's too, that is not a bool (finite or not).

    Parameters
    ----------
    value : object

    Returns
    -------
    bool

    Examples
    --------
    >>> is_real(np.float32(1.5)), is_real(True), is_real("1")
    (True, False, False)
    """
    return isinstance(value, numbers.Real) and not isinstance(value, (bool, np.bool_))


def check_optional_number(name: str, value: Any, **bounds: Any) -> float | None:
    """None when ``value`` is None (an option not given), else :func:`check_number` of it.

    Parameters
    ----------
    name : str
        The argument's name, for the message.
    value : object
        None, or a number.
    **bounds
        ``unit``, ``positive``, ``nonnegative``, ``low``, ``high`` as :func:`check_number` takes them.

    Returns
    -------
    float or None

    Raises
    ------
    AxiscalError
        As :func:`check_number`.

    Examples
    --------
    >>> check_optional_number("step_m", None) is None, check_optional_number("step_m", 0.01, positive=True)
    (True, 0.01)
    """
    return None if value is None else check_number(name, value, **bounds)


def check_integer(name: str, value: Any) -> int:
    """``value`` as an int, refused when it is not a whole number; its range is left to the caller.

    For an argument whose bounds the caller checks with its own message (a controller's
    parameter range, say), so that a float, bool, string or None never reaches a comparison.

    Parameters
    ----------
    name : str
        The argument's name, for the message.
    value : object
        An int (a NumPy integer too), not a bool, float or string.

    Returns
    -------
    int

    Raises
    ------
    AxiscalError
        ``"magnification must be a whole number, not 1.5"``.

    Examples
    --------
    >>> check_integer("axis_number", np.int64(3))
    3
    """
    if isinstance(value, numbers.Integral) and not isinstance(value, (bool, np.bool_)):
        return int(value)
    raise AxiscalError(f"{name} must be a whole number, not {_shown(value)}")


def type_name(value: Any) -> str:
    """``None``, or the name of ``value``'s type, for a message refusing it.

    Parameters
    ----------
    value : object

    Returns
    -------
    str

    Examples
    --------
    >>> type_name(None), type_name(1.5)
    ('None', 'float')
    """
    return "None" if value is None else type(value).__name__
