"""The check that an argument is an object of the kind a function works on (a Budget, a Campaign).

No standard clause: the house rule that a public function refuses, naming the argument, a None or
a value of another type where it expects one of the library's objects, instead of failing with an
AttributeError deep inside.
"""

from __future__ import annotations

from typing import Any

from axiscal.errors import AxiscalError

__all__ = ["check_instance", "type_name"]


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


def check_instance(name: str, value: Any, kind: type | tuple[type, ...], *, what: str | None = None) -> Any:
    """``value`` if it is a ``kind``, else refused naming ``name``.

    Parameters
    ----------
    name : str
        The argument's name, for the message.
    value : object
        What the caller passed.
    kind : type or tuple of types
        The accepted types.
    what : str, optional, keyword-only
        How the message speaks of them (default ``"a <Kind>"``).

    Returns
    -------
    object
        ``value``.

    Raises
    ------
    AxiscalError
        ``"run must be a PositioningRun, not None"``; also for a ``name`` that is not a str or a
        ``kind`` that is not a type.

    Examples
    --------
    >>> check_instance("count", 3, int)
    3
    >>> check_instance("run", None, float)
    Traceback (most recent call last):
    ...
    axiscal.errors.AxiscalError: run must be a float, not None
    """
    if not isinstance(name, str):
        raise AxiscalError(f"name must be the argument's name (a str), not {type_name(name)}")
    if not (isinstance(kind, type) or isinstance(kind, tuple) and kind and all(isinstance(k, type) for k in kind)):
        raise AxiscalError(f"kind must be a type or a tuple of types, not {kind!r}")
    if isinstance(value, kind):
        return value
    if what is None:
        first = (kind if isinstance(kind, type) else kind[0]).__name__
        what = ("an " if first[0].lower() in "aeiou" else "a ") + first
    raise AxiscalError(f"{name} must be {what}, not {type_name(value)}")
