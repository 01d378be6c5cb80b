"""The formats by name, their JSON Schemas and the key tables of the formats pages."""

from __future__ import annotations

import json
from typing import Any

from pydantic import BaseModel

__all__ = ["FORMATS", "FORMAT_FILES", "format_model", "json_schema", "json_schema_text", "key_table", "key_tables"]


def _formats() -> dict[str, Any]:
    from axiscal.io.formats.artefact import ArtefactFile
    from axiscal.io.formats.budget import BudgetFile
    from axiscal.io.formats.campaign import CampaignFile
    from axiscal.io.formats.flatness import FlatnessFile
    from axiscal.io.formats.importmap import ImportMapFile
    from axiscal.io.formats.machine import MachineFile

    return {"campaign": CampaignFile, "machine": MachineFile, "budget": BudgetFile, "artefact": ArtefactFile,
            "flatness": FlatnessFile, "import-map": ImportMapFile}


#: format name (as ``axiscal schema NAME`` takes it) -> its model (the artefact's: a tagged union of one model per kind)
FORMATS: dict[str, Any] = _formats()
#: what each format is, for ``axiscal schema --help`` and the formats pages
FORMAT_FILES = {
    "campaign": "campaign.toml of a campaign folder (docs/campaign.md)",
    "machine": "machine description, machine.toml (docs/formats.md)",
    "budget": "uncertainty budget (docs/uncertainty.md)",
    "artefact": "artefact file of axiscal identify (docs/identification.md)",
    "flatness": "flatness lines file (docs/flatness.md)",
    "import-map": "column map of axiscal import (docs/importing.md)",
}


def format_model(name: str) -> Any:
    """The model of the format ``name``.

    Parameters
    ----------
    name : str
        One of :data:`FORMATS`.

    Returns
    -------
    type of FormatModel or pydantic.TypeAdapter

    Raises
    ------
    AxiscalError
        For an unknown name.
    """
    from axiscal.io.arguments import check_choice

    check_choice("format", name, FORMATS)
    return FORMATS[name]


def json_schema(name: str) -> dict[str, Any]:
    """The JSON Schema (draft 7, which Taplo reads) of the format ``name``, for editors (Taplo, Even Better TOML).

    Parameters
    ----------
    name : str
        One of :data:`FORMATS`.

    Returns
    -------
    dict
        The schema, with ``$schema``, ``title`` and ``description``.

    Examples
    --------
    >>> json_schema("budget")["properties"]["setup"]["anyOf"][0]["$ref"]
    '#/$defs/BudgetSetup'
    """
    from pydantic import TypeAdapter

    model = format_model(name)
    schema = model.json_schema(mode="validation") if isinstance(model, TypeAdapter) else model.model_json_schema(mode="validation")
    schema = _tidy(schema)
    schema.pop("title", None)
    return {"$schema": "http://json-schema.org/draft-07/schema#", "title": f"axiscal {name} file", "description": FORMAT_FILES[name], **schema}


def _tidy(node: Any) -> Any:
    """A schema as a TOML editor needs it: no null (TOML has none), no per-key titles, descriptions of
    one paragraph (the docstrings' first)."""
    if isinstance(node, list):
        return [_tidy(n) for n in node]
    if not isinstance(node, dict):
        return node
    out = {}
    for key, value in node.items():
        if key == "title" and isinstance(value, str):
            continue
        if key == "default" and value is None:
            continue
        if key == "description" and isinstance(value, str):
            value = value.split("\n\n")[0].replace("\n", " ")
        out[key] = _tidy(value)
    if "properties" in node:  # keys are names here, never schema words
        out["properties"] = {name: _tidy(sub) for name, sub in node["properties"].items()}
    options = out.get("anyOf")
    if isinstance(options, list):
        options = [o for o in options if o != {"type": "null"}]
        if len(options) == 1:
            del out["anyOf"]
            out = {**options[0], **out}
        else:
            out["anyOf"] = options
    return out


def json_schema_text(name: str) -> str:
    """The JSON Schema of ``name`` as the text committed in docs/schemas/ (indented, ending in a newline)."""
    return json.dumps(json_schema(name), indent=2, ensure_ascii=False) + "\n"


def _words(node: dict[str, Any]) -> str:
    """What a key takes, in the words of the formats pages, from its JSON Schema."""
    if "$ref" in node:
        return "table (below)"
    if "const" in node:
        return f"`{node['const']}`"
    if "enum" in node:
        return " \\| ".join(f"`{v}`" for v in node["enum"])
    for union in ("oneOf", "anyOf"):
        if union in node:
            return " or ".join(dict.fromkeys(_words(o) for o in node[union]))
    kind = node.get("type")
    if kind == "string":
        pattern = node.get("pattern", "")
        if node.get("format") == "path":
            return "file name"
        if node.get("format") == "date":
            return "date (2026-11-20)"
        if "XYZABC" in pattern:
            return "axis letter"
        if "[Xx][Yy]" in pattern:
            return "plane XY, XZ or YZ"
        return "text"
    if kind in ("number", "integer"):
        text = "number" if kind == "number" else "whole number"
        if "exclusiveMinimum" in node:
            text += f" > {node['exclusiveMinimum']:g}"
        if "minimum" in node and "maximum" in node:
            text += f", {node['minimum']:g} to {node['maximum']:g}"
        elif "minimum" in node:
            text += f" >= {node['minimum']:g}"
        elif "maximum" in node:
            text += f" <= {node['maximum']:g}"
        return text
    if kind == "boolean":
        return "true or false"
    if kind == "array":
        items = _words(node.get("items", {}))
        if node.get("minItems") is not None and node.get("minItems") == node.get("maxItems"):
            return f"{node['minItems']} × {items}"
        return f"list of: {items}"
    if kind == "object":
        values = node.get("additionalProperties") or next(iter(node.get("patternProperties", {}).values()), None)
        names = node.get("propertyNames", {}).get("pattern") or next(iter(node.get("patternProperties", {})), None)
        text = f"table of: {_words(values)}" if isinstance(values, dict) and values else "table"
        return text + (f" (keys `{names}`)".replace("|", "\\|") if names else "")
    return "any value"


def key_table(model: type[BaseModel], *, prefix: str = "") -> str:
    """The Markdown key table of ``model`` (key, kind, required, meaning), as the formats pages show it.

    Parameters
    ----------
    model : type of pydantic.BaseModel
        A format or one of its tables.
    prefix : str, keyword-only
        Written before every key (``"[machine] "``).

    Returns
    -------
    str
        The table, ending in a newline.

    Examples
    --------
    >>> from axiscal.io.formats import BudgetFile
    >>> print(key_table(BudgetFile).splitlines()[2])
    | `instrument` | table (below) |  | the [instrument] table |
    """
    schema = _tidy(model.model_json_schema(mode="validation"))
    required = set(schema.get("required", ()))
    rows = ["| key | kind | required | meaning |", "|---|---|---|---|"]
    for key, node in schema.get("properties", {}).items():
        meaning = node.get("description", "").replace("|", "\\|")
        rows.append(f"| `{prefix}{key}` | {_words(node)} | {'yes' if key in required else ''} | {meaning} |")
    return "\n".join(rows) + "\n"


def _tables_of(model: Any, label: str, seen: dict[int, str], out: list[tuple[str, type[BaseModel]]]) -> None:
    """Every table model of a format, depth first, with how the file writes it."""
    from axiscal.io.formats.base import _models_in, _tag_of

    if id(model) in seen:
        return
    seen[id(model)] = label
    out.append((label, model))
    for name, field in model.model_fields.items():
        key = field.alias or name
        inner = _models_in(field.annotation)
        if not inner:
            continue
        text = repr(field.annotation)
        below = key if label == "top level" else f"{label.strip('[]')}.{key}"
        for sub in inner:
            tag = _tag_of(sub) if len(inner) > 1 else None
            if "list[" in text:
                sub_label = f"[[{below}]]" + (f" with kind = \"{tag}\"" if tag else "")
            elif "dict[" in text:
                sub_label = f"[{below}.<name>]"
            else:
                sub_label = f"[{below}]"
            _tables_of(sub, sub_label, seen, out)


def key_tables(name: str) -> str:
    """The Markdown key tables of every table of the format ``name``, as docs/formats.md shows them.

    Parameters
    ----------
    name : str
        One of :data:`FORMATS`.

    Returns
    -------
    str
        One paragraph naming each table, then its key table; ending in a newline.
    """
    from pydantic import TypeAdapter

    from axiscal.io.formats.artefact import ARTEFACT_MODELS

    model = format_model(name)
    roots = list(ARTEFACT_MODELS.values()) if isinstance(model, TypeAdapter) else [model]
    found: list[tuple[str, type[BaseModel]]] = []
    seen: dict[int, str] = {}
    for root in roots:
        label = f"kind = \"{root.model_fields['kind'].annotation.__args__[0]}\"" if len(roots) > 1 else "top level"
        _tables_of(root, label, seen, found)
    parts = []
    for label, table in found:
        parts.append(f"**{label}**\n\n{key_table(table)}")
    return "\n".join(parts)
