"""Helpers shared by the command modules: JSON on standard output and output files."""

from __future__ import annotations

from collections.abc import Callable, Mapping
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import click

from axiscal.errors import AxiscalError
from axiscal.io.atomic import atomic_write
from axiscal.io.jsonio import dumps

__all__ = ["flags_named", "echo_json", "given_options", "write_output"]


def echo_json(payload: dict[str, Any]) -> None:
    """Print one JSON object; NaN and infinities become null (JSON has no NaN)."""
    click.echo(dumps(payload), nl=False)


def given_options(**values: Any) -> dict[str, Any]:
    """The options of the running command that were typed on its command line, by parameter name.

    Options left at their default are dropped, so that the library function called applies its own
    defaults and can refuse an option that does not apply rather than ignore it.
    """
    ctx = click.get_current_context()
    return {name: value for name, value in values.items()
            if ctx.get_parameter_source(name) == click.core.ParameterSource.COMMANDLINE}


@contextmanager
def flags_named(flags: Mapping[str, str]):
    """Within the block, an AxiscalError that opens with a library keyword (``interval_m applies
    to ...``) names the command-line flag instead (``--interval-mm applies to ...``)."""
    try:
        yield
    except AxiscalError as exc:
        head, sep, rest = exc.message.partition(" ")
        if head in flags:
            raise AxiscalError(flags[head] + sep + rest, path=exc.path, line=exc.line) from None
        raise


def write_output(path: str | Path, write: Callable[[Path], Any]) -> Path:
    """Produce ``path`` atomically with ``write``; a failure is an AxiscalError naming the file."""
    return atomic_write(path, write)

