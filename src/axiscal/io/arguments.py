"""Checks of the arguments a Python user passes to a public function: numbers, counts, arrays and
option strings, each refused with an :class:`~axiscal.errors.AxiscalError` naming the argument.

No standard clause: the house rule that a public function never lets a bad argument through to an
IndexError, a NumPy broadcast error, a division by zero or a silent NaN deep inside. The unit in a
message is read from the argument's name (``spacing_ab_m`` is in metres, ``pressure_pa`` in
pascals) unless given.
"""

from __future__ import annotations

import math
import numbers
import os
from collections.abc import Callable, Iterable, Mapping
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.errors import AxiscalError, exponent_form

__all__ = [
    "unit_words", "check_number", "check_count", "check_array", "check_same_length", "check_broadcast", "check_choice",
    "check_mapping", "check_path", "render_checked", "is_real", "check_instance", "check_optional_number", "check_integer",
    "type_name",
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


def check_array(
    name: str,
    values: Any,
    *,
    unit: str | None = None,
    ndim: int | None = None,
    min_len: int = 0,
    last: int | None = None,
    finite: bool = True,
    limit: float | None = None,
) -> np.ndarray:
    """``values`` as a float array, refused when not numbers, of the wrong shape or not finite.

    Parameters
    ----------
    name : str
        The argument's name, for the message.
    values : array_like
        Numbers (a NumPy array, list or scalar); not strings, None or bools.
    unit : str, optional
        The unit as the message says it; read from ``name`` when not given.
    ndim : int, optional
        The number of dimensions required (``1`` for a series).
    min_len : int
        The least number of entries along the first dimension (``0``: any, even empty).
    last : int, optional
        The length required of the last dimension (``3`` for points in space).
    finite : bool
        Refuse NaN and infinity (default).
    limit : float, optional
        The largest magnitude accepted: beyond it a value has no physical meaning and would
        overflow the arithmetic that follows.

    Returns
    -------
    ndarray of float

    Raises
    ------
    AxiscalError
        Naming ``name`` and what is wrong: not numbers, the shape, too few values, not finite.

    Examples
    --------
    >>> check_array("position_m", [0.0, 0.1], ndim=1, min_len=2)
    array([0. , 0.1])
    >>> check_array("position_m", [0.0, float("inf")], ndim=1)
    Traceback (most recent call last):
    ...
    axiscal.errors.AxiscalError: position_m must hold finite numbers of metres, not inf (entry 1)
    """
    raw = values
    if isinstance(raw, (str, bytes)) or raw is None:
        raise AxiscalError(f"{name} must be numbers{_of(name, unit)}, not {_shown(raw)}")
    try:
        array = np.asarray(raw)
        if array.dtype.kind in "bUSMmV" or array.dtype.kind == "O" and any(
            isinstance(v, (bool, np.bool_, str, bytes)) or v is None for v in array.ravel()
        ):
            raise TypeError
        array = np.asarray(array, dtype=float)
    except (TypeError, ValueError):
        raise AxiscalError(f"{name} must be numbers{_of(name, unit)}, not {_shown(raw)}") from None
    if ndim is not None and array.ndim != ndim:
        words = {0: "a single number", 1: "a one-dimensional array", 2: "a two-dimensional array"}.get(ndim, f"{ndim}-D")
        raise AxiscalError(f"{name} must be {words}, not of shape {array.shape}")
    if last is not None and (array.ndim == 0 or array.shape[-1] != last):
        raise AxiscalError(f"{name} must have {last} components in its last dimension, not shape {array.shape}")
    if min_len and (array.ndim == 0 or array.shape[0] < min_len):
        got = "a single number" if array.ndim == 0 else f"{array.shape[0]}"
        raise AxiscalError(f"{name} needs at least {min_len} values, got {got}")
    if finite and not np.all(np.isfinite(array)):
        where = int(np.argmax(~np.isfinite(array.ravel())))
        at = f" (entry {where})" if array.ndim else ""
        raise AxiscalError(f"{name} must hold finite numbers{_of(name, unit)}, not {array.ravel()[where]}{at}")
    if limit is not None and array.size and np.nanmax(np.abs(array)) > limit:
        raise AxiscalError(f"{name} holds {np.nanmax(np.abs(array)):g}, beyond any physical value (more than {limit:g}{_of(name, unit, ' ')})")
    return array


def check_same_length(**arrays: np.ndarray) -> int:
    """The common length of 1-D arrays, refused when they differ.

    Parameters
    ----------
    **arrays : ndarray
        The arrays by argument name (``None`` values are skipped).

    Returns
    -------
    int
        The common length (0 when none is given).

    Raises
    ------
    AxiscalError
        ``"position_m and deviation_m must have the same length, not 5 and 4"``.

    Examples
    --------
    >>> check_same_length(a_m=[1, 2], b_m=[3, 4])
    2
    """
    given = {k: len(v) for k, v in arrays.items() if v is not None}
    if len(set(given.values())) > 1:
        raise AxiscalError(f"{' and '.join(given)} must have the same length, not {' and '.join(map(str, given.values()))}")
    return next(iter(given.values()), 0)


def check_choice(name: str, value: Any, choices: Iterable[str]) -> str:
    """``value`` if it is one of ``choices``, else refused naming them.

    Parameters
    ----------
    name : str
        The argument's name, for the message.
    value : object
        What the caller passed.
    choices : iterable of str
        The accepted strings.

    Returns
    -------
    str

    Raises
    ------
    AxiscalError
        ``"unknown method 'x'; use one of a, b"``.

    Examples
    --------
    >>> check_choice("plane", "XY", ("XY", "YZ", "ZX"))
    'XY'
    """
    choices = tuple(choices)
    if not isinstance(value, str) or value not in choices:
        raise AxiscalError(f"unknown {name} {_shown(value)}; use one of {', '.join(choices)}")
    return value


def check_broadcast(**arrays: np.ndarray) -> list[np.ndarray]:
    """The arrays broadcast to one shape, refused when they do not match.

    Parameters
    ----------
    **arrays : ndarray
        The (already checked) arrays by argument name.

    Returns
    -------
    list of ndarray
        In the order given, all of the broadcast shape.

    Raises
    ------
    AxiscalError
        ``"length_m and misalignment_rad do not match in shape: (2,) and (3,)"``.

    Examples
    --------
    >>> [a.shape for a in check_broadcast(a_m=np.zeros((2, 1)), b_m=np.zeros(3))]
    [(2, 3), (2, 3)]
    """
    try:
        return list(np.broadcast_arrays(*arrays.values()))
    except ValueError:
        shapes = " and ".join(str(np.shape(a)) for a in arrays.values())
        names = ", ".join(arrays)
        raise AxiscalError(f"{names} do not match in shape: {shapes}") from None


def check_mapping(name: str, value: Any, keys: Iterable[str] = (), *, what: str = "a mapping") -> Mapping:
    """``value`` if it is a mapping holding ``keys``, else refused naming the first one missing.

    Parameters
    ----------
    name : str
        The argument's name, for the message.
    value : object
        What the caller passed.
    keys : iterable of str
        Keys that must be present.
    what : str
        What the mapping should be, for the message (``"the dict air_report returns"``).

    Returns
    -------
    Mapping

    Raises
    ------
    AxiscalError
        ``"report must be the dict air_report returns, not None"`` or ``"... (no 'refractive_index')"``.

    Examples
    --------
    >>> check_mapping("report", {"a": 1}, ("a",))
    {'a': 1}
    """
    if not isinstance(value, Mapping):
        raise AxiscalError(f"{name} must be {what}, not {_shown(value)}")
    missing = [k for k in keys if k not in value]
    if missing:
        raise AxiscalError(f"{name} must be {what} (it has no '{missing[0]}')")
    return value


def render_checked(render: Callable[..., str], template: Any, /, **context: Any) -> str:
    """``render(template, **context)`` with an unknown template or a missing value refused.

    Parameters
    ----------
    render : callable
        The room's renderer (a wrapper of :func:`axiscal.io.templates.render_template`).
    template : str
        The template path under ``axiscal/templates/``.
    **context
        The values the template prints.

    Returns
    -------
    str
        What ``render`` returns.

    Raises
    ------
    AxiscalError
        For a template name that is not a string or not shipped, or a value the template uses
        that is not given.
    """
    import jinja2

    if not isinstance(template, str):
        raise AxiscalError(f"template must be the name of a shipped template, not {_shown(template)}")
    try:
        return render(template, **context)
    except jinja2.TemplateNotFound:
        raise AxiscalError(f"template '{template}' is not one axiscal ships") from None
    except jinja2.UndefinedError as exc:
        raise AxiscalError(f"template '{template}' needs a value not given: {exc.message}") from None


def check_path(name: str, value: Any) -> Path:
    """``value`` as a :class:`~pathlib.Path`, refused when it is not a str or path-like.

    Parameters
    ----------
    name : str
        The argument's name, for the message.
    value : object
        A file name (str or os.PathLike).

    Returns
    -------
    Path

    Raises
    ------
    AxiscalError
        ``"path must be a file name (str or Path), not None"``.

    Examples
    --------
    >>> check_path("path", "run.csv").name
    'run.csv'
    """
    if isinstance(value, (str, os.PathLike)) and str(value).strip():
        return Path(value)
    raise AxiscalError(f"{name} must be a file name (str or Path), not {_shown(value)}")


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


def check_instance(name: str, value: Any, kind: type | tuple[type, ...], *, what: str | None = None) -> Any:
    """``value`` if it is an instance of ``kind``, else refused naming the type expected.

    Parameters
    ----------
    name : str
        The argument's name, for the message.
    value : object
        What the caller passed.
    kind : type or tuple of types
        The class (or classes) accepted.
    what : str, optional
        What the message calls the expected value; ``"a <ClassName>"`` when not given.

    Returns
    -------
    object
        ``value`` unchanged.

    Raises
    ------
    AxiscalError
        ``"run must be a PositioningRun, not None"``.

    Examples
    --------
    >>> check_instance("count", 3, int)
    3
    >>> check_instance("run", None, Path)
    Traceback (most recent call last):
    ...
    axiscal.errors.AxiscalError: run must be a Path, not None
    """
    if isinstance(value, kind):
        return value
    if what is None:
        kinds = kind if isinstance(kind, tuple) else (kind,)
        what = " or ".join(f"{'an' if k.__name__[0] in 'AEIOU' else 'a'} {k.__name__}" for k in kinds)
    # a plain value is shown as it is, an object of another kind by the name of its type
    plain = value is None or isinstance(value, (str, bool, int, float))
    raise AxiscalError(f"{name} must be {what}, not {_shown(value) if plain else type_name(value)}")


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
