"""Entry point of the ``axiscal`` command.

User mistakes (:class:`axiscal.AxiscalError`) become one line on stderr, ``axiscal: error: FILE:LINE:
problem``, and exit status 2; no traceback. Usage errors from Click also exit with 2.
"""

from __future__ import annotations

import importlib
import pkgutil
import sys
from collections.abc import Sequence

import click

import axiscal
from axiscal.errors import AxiscalError


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
    except click.ClickException as exc:
        exc.show()
        return exc.exit_code
    except click.exceptions.Exit as exc:
        return exc.exit_code
    except BrokenPipeError:
        return 0
    return 0


if __name__ == "__main__":
    sys.exit(main())
