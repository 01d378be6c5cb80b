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
from pathlib import Path
from typing import Any

import click

import axiscal
from axiscal.errors import AxiscalError

__all__ = ["LazyGroup", "cli", "main"]

# Click 8.2 and later raise this for a group called without its command; 8.1 printed the help itself
_NoArgsIsHelp = getattr(click.exceptions, "NoArgsIsHelpError", ())


class LazyGroup(click.Group):
    """A group whose commands come from the modules of :mod:`axiscal.cli`, imported when needed.

    Each module that defines ``register(group)`` adds its commands with it, as before. Running a
    command imports only the modules whose source names it (``"straightness"``), so that a command
    does not pay for importing every other one; listing the commands (``--help``) or a name no
    module spells out imports them all.
    """

    def __init__(self, *args: Any, package: str = "axiscal.cli", **kwargs: Any):
        super().__init__(*args, **kwargs)
        self._package = package
        self._loaded: set[str] = set()

    def _modules(self) -> list[tuple[str, Path]]:
        package = importlib.import_module(self._package)
        return [
            (info.name, Path(info.module_finder.path) / f"{info.name}.py")  # type: ignore[union-attr]
            for info in sorted(pkgutil.iter_modules(package.__path__), key=lambda m: m.name)
            if info.name != "main"
        ]

    def _load(self, name: str) -> None:
        if name in self._loaded:
            return
        self._loaded.add(name)
        module = importlib.import_module(f"{self._package}.{name}")
        register = getattr(module, "register", None)
        if register is not None:
            register(self)

    def load_all(self) -> None:
        """Import every command module (and so register every command)."""
        for name, _ in self._modules():
            self._load(name)

    def get_command(self, ctx: click.Context, cmd_name: str) -> click.Command | None:
        command = super().get_command(ctx, cmd_name)
        if command is not None:
            return command
        spelled = (f'"{cmd_name}"', f"'{cmd_name}'")
        for name, source in self._modules():
            try:
                text = source.read_text(encoding="utf-8")
            except OSError:
                text = ""
            if name == cmd_name.replace("-", "_") or any(s in text for s in spelled):
                self._load(name)
        command = super().get_command(ctx, cmd_name)
        if command is None:
            self.load_all()
            command = super().get_command(ctx, cmd_name)
        return command

    def list_commands(self, ctx: click.Context) -> list[str]:
        self.load_all()
        return super().list_commands(ctx)


@click.group(cls=LazyGroup, context_settings={"help_option_names": ["-h", "--help"], "max_content_width": 100})
@click.version_option(axiscal.__version__, prog_name="axiscal")
def cli() -> None:
    """Measure, model and compensate the geometric errors of machine axes.

    Python API in SI units; files and flags carry their units in their names (position_mm, EXX_um,
    --pressure-pa). See docs/ for conventions and file formats.
    """


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; return the exit status (tests call this directly)."""
    try:
        # outside standalone mode click returns ctx.exit(N)'s status (commands themselves return None)
        status = cli.main(args=list(argv) if argv is not None else None, prog_name="axiscal", standalone_mode=False)
    except AxiscalError as exc:
        click.echo(f"axiscal: error: {exc}", err=True)
        return 2
    except click.exceptions.Abort:
        click.echo("axiscal: aborted", err=True)
        return 1
    except _NoArgsIsHelp as exc:  # a bare `axiscal` or group: its help, as git and pip do
        click.echo(exc.ctx.get_help() if exc.ctx is not None else cli.get_help(click.Context(cli, info_name="axiscal")))
        return 0
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
    return status if isinstance(status, int) and not isinstance(status, bool) else 0


if __name__ == "__main__":
    sys.exit(main())
