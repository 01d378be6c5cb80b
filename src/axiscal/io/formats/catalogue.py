"""The formats by name, their JSON Schemas and the key tables of the formats pages."""

from __future__ import annotations

import json
import typing
from typing import Any

from pydantic import BaseModel

from axiscal.io.formats.base import FormatModel

__all__ = ["FORMATS", "format_model", "json_schema", "key_table"]


def _formats() -> dict[str, type[FormatModel]]:
    from axiscal.io.formats.budget import BudgetFile
    from axiscal.io.formats.campaign import CampaignFile

    found: dict[str, type[FormatModel]] = {"campaign": CampaignFile, "budget": BudgetFile}
    try:
        from axiscal.io.formats.machine import MachineFile

        found["machine"] = MachineFile
    except ImportError:  # pragma: no cover - while the module is written
        pass
    for name, module, model in (("artefact", "artefact", "ArtefactFile"), ("flatness", "flatness", "FlatnessFile"),
                                ("import-map", "importmap", "ImportMapFile")):
        try:
            found[name] = getattr(__import__(f"axiscal.io.formats.{module}", fromlist=[model]), model)
        except ImportError:  # pragma: no cover
            pass
    return found


#: format name (as ``axiscal schema NAME`` takes it) -> its model
FORMATS: dict[str, type[FormatModel]] = _formats()


def format_model(name: str) -> type[FormatModel]:
    """The model of the format ``name``.

    Parameters
    ----------
    name : str
        One of :data:`FORMATS`.

    Returns
    -------
    type of FormatModel

    Raises
    ------
    AxiscalError
        For an unknown name.
    """
    from axiscal.io.arguments import check_choice

    check_choice("format", name, FORMATS)
    return FORMATS[name]


def json_schema(name: str) -> dict[str, Any]:
    """The JSON Schema (draft 2020-12) of the format ``name``, for editors (Taplo, Even Better TOML).

    Parameters
    ----------
    name : str
        One of :data:`FORMATS`.

    Returns
    -------
    dict
        The schema, with ``$schema``, ``$id`` and ``title``.

    Examples
    --------
    >>> json_schema("budget")["properties"]["setup"]["anyOf"][0]["$ref"]
    '#/$defs/BudgetSetup'
    """
    model = format_model(name)
    schema = model.model_json_schema(mode="validation")
    return {"$schema": "https://json-schema.org/draft/2020-12/schema", "$id": f"axiscal-{name}.schema.json", **schema}


def json_schema_text(name: str) -> str:
    """The JSON Schema of ``name`` as the text committed in docs/schemas/ (indented, ending in a newline)."""
    return json.dumps(json_schema(name), indent=2, ensure_ascii=False) + "\n"


def _kind(annotation: Any) -> str:
    """What a key takes, in the words of the formats pages."""
    args = [a for a in typing.get_args(annotation) if a is not type(None)]
    origin = typing.get_origin(annotation)
    if origin is typing.Literal:
        return " \\| ".join(f"`{a}`" for a in typing.get_args(annotation))
    if origin is typing.Annotated:
        base, *meta = typing.get_args(annotation)
        text = _kind(base)
        for m in meta:
            pattern = getattr(m, "pattern", None)
            if getattr(m, "json_schema_extra", None) == {"format": "path"}:
                return "file name"
            if getattr(m, "json_schema_extra", None) == {"format": "date"}:
                return "date (2026-11-20)"
            if pattern and "XYZ" in pattern:
                return "axis letter"
            if pattern and "Yy" in pattern:
                return "plane XY, XZ or YZ"
            if type(m).__name__ == "Len":
                count = m.min_length if m.min_length == m.max_length else None
                text = text.replace("list of", f"{count} of" if count else "list of")
            if type(m).__name__ == "Gt":
                text = f"{text} > {m.gt}"
        return text
    if origin in (typing.Union, getattr(__import__("types"), "UnionType", None)):
        return " or ".join(_kind(a) for a in args)
    if origin is list:
        return f"list of {_kind(args[0])}s" if args else "list"
    if origin is dict:
        return f"table of {_kind(args[1])}s" if len(args) == 2 else "table"
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return f"table `[{annotation.__name__}]`"
    return {float: "number", int: "whole number", bool: "true or false", str: "text"}.get(annotation, str(annotation))


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
    """
    rows = ["| key | kind | required | meaning |", "|---|---|---|---|"]
    for name, field in model.model_fields.items():
        key = field.alias or name
        kind = _kind(field.annotation)
        for meta in field.metadata:
            if type(meta).__name__ == "Ge":
                kind += f", at least {meta.ge:g}"
            if type(meta).__name__ == "Le":
                kind += f", at most {meta.le:g}"
        required = "yes" if field.is_required() else ""
        rows.append(f"| `{prefix}{key}` | {kind} | {required} | {field.description or ''} |")
    return "\n".join(rows) + "\n"
