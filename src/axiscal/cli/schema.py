"""``axiscal schema NAME``: the JSON Schema of a file format people write by hand, for their editor.

Thin wrapper over :func:`axiscal.io.formats.json_schema_text`; the same files are in docs/schemas/.
"""

from __future__ import annotations

import click

from axiscal.cli.choices import SCHEMA_FORMATS

__all__ = ["schema_command"]


@click.command("schema")
@click.argument("name", type=click.Choice(SCHEMA_FORMATS), metavar="NAME")
def schema_command(name):
    """Print the JSON Schema of a TOML format (draft 7).

    NAME is campaign (campaign.toml), machine (machine.toml), budget (uncertainty budget),
    artefact (axiscal identify), flatness (lines file) or import-map (axiscal import). Editors
    such as VS Code with Even Better TOML (Taplo) use it to complete and check keys as you type:
    see docs/formats.md.
    """
    from axiscal.io.formats.catalogue import json_schema_text

    click.echo(json_schema_text(name), nl=False)
