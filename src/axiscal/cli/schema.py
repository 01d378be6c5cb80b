"""``axiscal schema NAME``: the JSON Schema of a file format people write by hand, for their editor.

Thin wrapper over :func:`axiscal.io.formats.json_schema_text`; the same files are in docs/schemas/.
"""

from __future__ import annotations

import click

from axiscal.io.formats.catalogue import FORMAT_FILES, json_schema_text

__all__ = ["schema_command", "register"]


@click.command("schema")
@click.argument("name", type=click.Choice(tuple(FORMAT_FILES)), metavar="NAME")
def schema_command(name):
    """Print the JSON Schema of a TOML format (draft 7).

    NAME is campaign (campaign.toml), machine (machine.toml), budget (uncertainty budget),
    artefact (axiscal identify), flatness (lines file) or import-map (axiscal import). Editors
    such as VS Code with Even Better TOML (Taplo) use it to complete and check keys as you type:
    see docs/formats.md.
    """
    click.echo(json_schema_text(name), nl=False)


def register(group: click.Group) -> None:
    group.add_command(schema_command)
