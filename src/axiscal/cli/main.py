"""Entry point of the ``axiscal`` command.

User mistakes (:class:`axiscal.AxiscalError`) become one line on stderr, ``axiscal: error: FILE:LINE:
problem``, and exit status 2; no traceback. Usage errors from Click (a missing option, a flag given a
word where a number belongs) are one line too, naming the command's --help, with status 2.
"""

from __future__ import annotations

import importlib
import pkgutil
import sys
from collections.abc import Sequence

import click

import axiscal
from axiscal.errors import AxiscalError

__all__ = ["cli", "main"]


@click.group(context_settings={"help_option_names": ["-h", "--help"], "max_content_width": 100})
@click.version_option(axiscal.__version__, prog_name="axiscal")
def cli() -> None:
    """Measure, model and compensate the geometric errors of machine axes.

    Python API in SI units; files and flags carry their units in their names (position_mm, EXX_um,
    --pressure-pa). See docs/ for conventions and file formats.
    """


def _register_commands() -> None:
    import axiscal.cli as package

    for info in sorted(pkgutil.iter_modules(package.__path__), key=lambda m: m.name):
        if info.name == "main":
            continue
        module = importlib.import_module(f"axiscal.cli.{info.name}")
        register = getattr(module, "register", None)
        if register is not None:
            register(cli)


_register_commands()


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; return the exit status (tests call this directly)."""
    try:
        cli.main(args=list(argv) if argv is not None else None, prog_name="axiscal", standalone_mode=False)
    except AxiscalError as exc:
        click.echo(f"axiscal: error: {exc}", err=True)
        return 2
    except click.exceptions.Abort:
        click.echo("axiscal: aborted", err=True)
        return 1
    except click.UsageError as exc:
        command = exc.ctx.command_path if exc.ctx is not None else "axiscal"
        message = " ".join(exc.format_message().split())
        click.echo(f"axiscal: error: {message} (see '{command} --help')", err=True)
        return exc.exit_code
    except click.ClickException as exc:
        click.echo(f"axiscal: error: {' '.join(exc.format_message().split())}", err=True)
        return exc.exit_code
    except click.exceptions.Exit as exc:
        return exc.exit_code
    except BrokenPipeError:
        return 0
    return 0


if __name__ == "__main__":
    sys.exit(main())
