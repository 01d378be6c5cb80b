"""The entry point: commands load lazily yet all show in --help; a bare group prints its help."""

from __future__ import annotations

import subprocess
import sys
import textwrap

import click
import click.testing

from axiscal.cli.main import LazyGroup


def test_bare_axiscal_and_bare_group_print_help_and_succeed(run_cli):
    status, out, err = run_cli()
    assert status == 0 and out.startswith("Usage: axiscal") and "straightness" in out and err == ""
    status, out, err = run_cli("cmm")
    assert status == 0 and out.startswith("Usage: axiscal cmm") and "gauge-blocks" in out and err == ""


def test_help_lists_every_registered_command_with_its_short_help(run_cli):
    status, out, _ = run_cli("--help")
    assert status == 0
    for name in ("air", "fringes", "separate", "simulate", "straightness", "volumetric", "inverse", "live"):
        assert f"\n  {name} " in out


def test_a_command_imports_only_its_own_module(examples):
    code = textwrap.dedent(
        f"""
        import sys
        from axiscal.cli.main import main
        assert main(["straightness", {str(examples / "straightness_profile.csv")!r}]) == 0
        print(sorted(m for m in sys.modules if m.startswith("axiscal.cli.")))
        """
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert "'axiscal.cli.straightness'" in out
    assert "axiscal.cli.volumetric" not in out and "axiscal.cli.live" not in out


def _package(tmp_path, monkeypatch, name: str, modules: dict[str, str]) -> str:
    folder = tmp_path / name
    folder.mkdir()
    (folder / "__init__.py").write_text("")
    for module, source in modules.items():
        (folder / f"{module}.py").write_text(textwrap.dedent(source))
    monkeypatch.syspath_prepend(str(tmp_path))
    return name


def test_a_new_module_with_register_plugs_in_unchanged(tmp_path, monkeypatch):
    source = """
        import click

        @click.command("{command}")
        def command():
            '''Say {command}.'''
            click.echo("{command} ran")

        def register(group):
            group.add_command(command)
        """
    package = _package(
        tmp_path,
        monkeypatch,
        "plugin_cli_pkg",
        {
            "alpha": source.format(command="alpha"),
            # the command's name is built, not spelled: found by importing every module
            "beta": source.replace('"{command}"', '"be" + "ta"').format(command="beta"),
            "helpers": "X = 1\n",
        },
    )
    group = LazyGroup(package=package, name="tool")
    runner = click.testing.CliRunner()
    result = runner.invoke(group, ["alpha"])
    assert result.exit_code == 0 and result.output == "alpha ran\n"
    assert group._loaded == {"alpha"}
    result = runner.invoke(group, ["beta"])
    assert result.exit_code == 0 and result.output == "beta ran\n"
    result = runner.invoke(group, ["--help"])
    assert "alpha  Say alpha." in result.output and "beta   Say beta." in result.output
