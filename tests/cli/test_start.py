"""The command line answers at once: ``--help`` and argument errors import no computing library.

``axiscal --help`` lists the commands from the table of :mod:`axiscal.cli.main` without importing
any of them; a command's ``--help`` or a mistyped argument imports that command's module only, and
command modules import the library inside their functions. The figure (whole process, median of 5)
is printed by benchmarks/cli_start.py; these tests check the cause, not a time.
"""

from __future__ import annotations

import importlib
import pkgutil
import subprocess
import sys
import textwrap

import click
import pytest

import axiscal.cli
from axiscal.cli.main import _HELPERS, COMMANDS, SIMULATE_COMMANDS, cli
from cli_commands import leaf_commands

#: what a --help must not pay for
HEAVY = ("numpy", "pandas", "scipy", "matplotlib", "jinja2", "sqlalchemy", "starlette", "rich", "pydantic", "GTC")


def _modules_after(code: str) -> list[str]:
    script = textwrap.dedent(code) + "\nimport sys\nprint('\\n'.join(sorted(sys.modules)))\n"
    return subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, check=True).stdout.split()


def test_axiscal_help_imports_no_command_and_no_library():
    modules = _modules_after("""
        from axiscal.cli.main import main
        assert main(["--help"]) == 0
        """)
    assert [m for m in modules if m.split(".")[0] in HEAVY] == []
    assert [m for m in modules if m.startswith("axiscal.cli.") and m.rsplit(".", 1)[1] not in _HELPERS] == []


def test_every_help_and_argument_error_imports_no_library():
    paths = [list(path) for path, _ in leaf_commands()]
    groups = sorted({tuple(path[:-1]) for path in paths if len(path) > 1})
    modules = _modules_after(f"""
        import contextlib, io
        from axiscal.cli.main import main
        for path in {paths!r} + [list(g) for g in {groups!r}]:
            with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
                assert main(path + ["--help"]) == 0, path
                assert main(path + ["--no-such-option"]) == 2, path
        """)
    assert [m for m in modules if m.split(".")[0] in HEAVY] == []
    assert [m for m in modules if m.startswith("axiscal.") and m.split(".")[1] not in ("cli", "errors", "units", "materials", "version")] == []


@pytest.mark.parametrize("table", [COMMANDS, SIMULATE_COMMANDS], ids=["axiscal", "simulate"])
def test_the_table_summary_is_the_command_short_help(table):
    for name, (spec, summary) in table.items():
        module, _, attribute = spec.partition(":")
        command = getattr(importlib.import_module(module), attribute)
        assert isinstance(command, click.Command), name
        if summary is None:
            assert command.hidden, f"{name}: a command without a summary must be hidden"
        else:
            assert summary == command.get_short_help_str(limit=10**6), f"{name}: table summary differs from its help"


def test_every_command_module_is_in_the_table():
    tabled = {spec.partition(":")[0] for spec, _ in {**COMMANDS, **SIMULATE_COMMANDS}.values()}
    modules = {f"axiscal.cli.{m.name}" for m in pkgutil.iter_modules(axiscal.cli.__path__) if m.name not in _HELPERS}
    assert modules - tabled == set(), "add one line per command to COMMANDS in axiscal/cli/main.py"


def test_help_lists_the_table_in_order_and_hides_the_old_names(run_cli):
    status, out, _ = run_cli("--help")
    assert status == 0
    listed = [line.split()[0] for line in out.split("Commands:")[1].splitlines() if line.startswith("  ")]
    assert listed == sorted(name for name, (_, summary) in COMMANDS.items() if summary is not None)
    status, out, _ = run_cli("simulate", "--help")
    assert "capture" in out and "probes" in out


def test_every_leaf_command_is_reached_through_the_table():
    names = {path[0] for path, _ in leaf_commands(cli)}
    assert names <= set(COMMANDS)
