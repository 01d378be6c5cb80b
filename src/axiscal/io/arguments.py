"""Checks of the arguments a Python user passes to a public function: numbers, counts, arrays and
option strings, each refused with an :class:`~axiscal.errors.AxiscalError` naming the argument.

No standard clause: the house rule that a public function never lets a bad argument through to an
IndexError, a NumPy broadcast error, a division by zero or a silent NaN deep inside. The unit in a
message is read from the argument's name (``spacing_ab_m`` is in metres, ``pressure_pa`` in
pascals) unless given.

Every check is importable from here: the checks of single values are
:mod:`axiscal.io.scalar_checks`, those of arrays :mod:`axiscal.io.array_checks`; the checks of
choices, mappings, paths and kinds of object are here.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterable, Mapping
from pathlib import Path
from typing import Any

from axiscal.errors import AxiscalError
from axiscal.io.array_checks import check_array, check_broadcast, check_same_length
from axiscal.io.scalar_checks import (
    _shown,
    check_count,
    check_integer,
    check_number,
    check_optional_number,
    is_real,
    type_name,
    unit_words,
)

__all__ = [
    "unit_words", "check_number", "check_count", "check_array", "check_same_length", "check_broadcast", "check_choice",
    "check_mapping", "check_path", "render_checked", "is_real", "check_instance", "check_optional_number", "check_integer",
    "type_name",
]


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
