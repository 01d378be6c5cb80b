"""The commands of ``axiscal``, walked for the tests that check every command at once."""

from __future__ import annotations

import click

from axiscal.cli.main import cli


def leaf_commands(group: click.Group = cli, path: tuple[str, ...] = ()) -> list[tuple[tuple[str, ...], click.Command]]:
    """``(("simulate", "probes"), command)`` for every command that runs (not a group), hidden ones too."""
    if hasattr(group, "load_all"):
        group.load_all()
    found = []
    for name in sorted(group.commands):
        command = group.commands[name]
        if isinstance(command, click.Group):
            found += leaf_commands(command, path + (name,))
        else:
            found.append((path + (name,), command))
    return found
