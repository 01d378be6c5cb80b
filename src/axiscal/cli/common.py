"""Helpers shared by the command modules: JSON on standard output, output files and finite-number options."""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Mapping
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import click

from axiscal.errors import AxiscalError

__all__ = ["FINITE", "FiniteFloat", "FiniteRange", "finite", "flags_named", "echo_json", "given_options", "hidden_alias", "write_output"]


def echo_json(payload: dict[str, Any]) -> None:
    """Print one JSON object; NaN and infinities become null (JSON has no NaN)."""
    from axiscal.io.jsonio import dumps

    click.echo(dumps(payload), nl=False)


def given_options(**values: Any) -> dict[str, Any]:
    """The options of the running command that were typed on its command line, by parameter name.

    Options left at their default are dropped, so that the library function called applies its own
    defaults and can refuse an option that does not apply rather than ignore it.
    """
    ctx = click.get_current_context()
    return {name: value for name, value in values.items()
            if ctx.get_parameter_source(name) == click.core.ParameterSource.COMMANDLINE}


#: a flag's unit (its name's end), the library argument's (its name's end), the factor from the flag's to the
#: argument's, and the flag's unit as a message says it
_FLAG_UNITS = (
    ("-mm-min", "_m_per_s", 1e-3 / 60.0, "mm/min"), ("-mm-s", "_m_s", 1e-3, "mm/s"), ("-um", "_m", 1e-6, "um"),
    ("-mm", "_m", 1e-3, "mm"), ("-nm", "_m", 1e-9, "nm"), ("-ms", "_s", 1e-3, "ms"),
)
#: how a library message speaks of the argument's unit
_SI_WORDS = r"(metres per second|metres|seconds|m/s|m|s)"


def _in_flag_unit(rest: str, key: str, flag: str) -> str:
    """``must be ... of metres, not 1e-06`` of ``key`` said in ``flag``'s unit: ``must be ... of um, not 1``."""
    for flag_end, key_end, factor, words in _FLAG_UNITS:
        # only a message in the argument's SI unit is said again in the flag's (one in the flag's unit already stays)
        if flag.endswith(flag_end) and key.endswith(key_end) and rest.startswith("must be ") \
                and re.search(rf"(?<![\w/]){_SI_WORDS}(?=,|$)", rest):
            rest = re.sub(r"(?<![\w.])[-+]?\d+(\.\d*)?([eE][-+]?\d+)?(?![\w.])", lambda m: f"{float(m.group(0)) / factor:g}", rest)
            return re.sub(rf"(?<![\w/]){_SI_WORDS}(?=,|$)", words, rest)
    return rest


@contextmanager
def flags_named(flags: Mapping[str, str]):
    """Within the block, an AxiscalError that names a library argument names the command-line flag instead.

    A message that opens with a keyword of ``flags`` (``interval_m applies to ...``) opens with its
    flag (``--interval-mm applies to ...``). A key that is not a plain word (``rate_hz``,
    ``force=True``, ``a source replay:FILE``) is replaced wherever it stands in the message, as a
    whole: ``rate_hz x duration_s gives ...`` becomes ``--rate x --duration gives ...``.
    """
    try:
        yield
    except AxiscalError as exc:
        head, sep, rest = exc.message.partition(" ")
        message = flags[head] + sep + _in_flag_unit(rest, head, flags[head]) if head in flags else exc.message
        for key in sorted((k for k in flags if not k.isalpha()), key=len, reverse=True):
            message = re.sub(rf"(?<![\w-]){re.escape(key)}(?![\w-])", lambda _, k=key: flags[k], message)
        if message != exc.message:
            raise AxiscalError(message, path=exc.path, line=exc.line) from None
        raise


def write_output(path: str | Path, write: Callable[[Path], Any]) -> Path:
    """Produce ``path`` atomically with ``write``; a failure is an AxiscalError naming the file."""
    from axiscal.io.atomic import atomic_write

    return atomic_write(path, write)


class FiniteFloat(click.types.FloatParamType):
    """A number option that refuses ``nan`` and infinities (Click's ``float`` takes them).

    Every value typed is checked where it is parsed, whether or not the command goes on to use it:
    ``--dwell-s must be a finite number, got nan`` (an :class:`AxiscalError`, so one line and exit 2).
    """

    def convert(self, value: Any, param: click.Parameter | None, ctx: click.Context | None) -> float:
        number = super().convert(value, param, ctx)
        if not math.isfinite(number):
            if param is None:
                self.fail(f"{value!r} is not a finite number", param, ctx)
            flag = max(param.opts, key=len) if param.opts else param.name
            raise AxiscalError(f"{flag} must be a finite number, got {value}")
        return number


class FiniteRange(click.FloatRange):
    """A finite number within a range (Click's ``FloatRange`` lets ``nan`` through and ``inf`` past no maximum)."""

    def convert(self, value: Any, param: click.Parameter | None, ctx: click.Context | None) -> float:
        return super().convert(FINITE.convert(value, param, ctx), param, ctx)


FINITE = FiniteFloat()
"""The type of every number option: ``@click.option("--dwell-s", type=FINITE)``."""


def finite(min: float | None = None, max: float | None = None, *, min_open: bool = False,
           max_open: bool = False) -> click.ParamType:
    """The type of a number option with bounds (:data:`FINITE` when there are none).

    Parameters
    ----------
    min, max : float, optional
        The bounds (as :class:`click.FloatRange` takes them).
    min_open, max_open : bool, keyword-only
        Whether a bound itself is refused.

    Returns
    -------
    click.ParamType
    """
    if min is None and max is None:
        return FINITE
    return FiniteRange(min=min, max=max, min_open=min_open, max_open=max_open)


def hidden_alias(command: click.Command, old_name: str, new_name: str) -> click.Command:
    """``command`` under its old name, left out of ``--help``, saying its new name on standard error.

    Parameters
    ----------
    command : click.Command
        The command as it is now named.
    old_name : str
        The name it had (``"simulate-probes"``).
    new_name : str
        What to type instead (``"simulate probes"``).

    Returns
    -------
    click.Command
        A command that takes the same options and runs the same code.
    """

    def callback(**values: Any) -> Any:
        click.echo(f"axiscal: '{old_name}' is now '{new_name}'; the old name will go", err=True)
        return command.callback(**values) if command.callback is not None else None

    return click.Command(old_name, params=command.params, callback=callback, hidden=True,
                         help=f"Old name of 'axiscal {new_name}'.", context_settings=command.context_settings)
