"""What every declared file format shares: the pydantic base model, the value types people write
by hand, and the one reading path (TOML parsed once, validated once, every error one line).

A format is a pydantic model: frozen, unknown keys refused. :func:`validate_data` turns its first
validation error into one :class:`~axiscal.errors.AxiscalError` naming the file, the line of the
key (found with :class:`~axiscal.io.schema.TomlLines`), the key path and what was expected; an
unknown key is answered with the nearest valid name (:mod:`difflib`).
"""

from __future__ import annotations

import datetime as _dt
import difflib
import re
from pathlib import Path
from typing import Annotated, Any, TypeVar

from annotated_types import Gt, Len
from pydantic import (
    AllowInfNan,
    BaseModel,
    ConfigDict,
    Field,
    PrivateAttr,
    Strict,
    StringConstraints,
    ValidationError,
    model_validator,
)

from axiscal.errors import AxiscalError
from axiscal.io.schema import TomlLines

__all__ = [
    "FormatModel",
    "Number",
    "Positive",
    "Text",
    "Name",
    "FileName",
    "Vector3",
    "Pair",
    "Numbers",
    "Bool",
    "Count",
    "validate_data",
    "read_format",
    "line_of",
    "key_path",
]

#: a finite number (an int or a float; a bool, NaN and infinities are refused)
Number = Annotated[float, Strict(), AllowInfNan(False)]
#: a finite number above zero
Positive = Annotated[float, Strict(), AllowInfNan(False), Gt(0)]
#: a text in quotes
Text = Annotated[str, Strict()]
#: a text that is not blank
Name = Annotated[str, Strict(), StringConstraints(pattern=r"\S")]
#: a file name, relative to the folder of the file that names it
FileName = Annotated[str, Strict(), StringConstraints(pattern=r"\S"), Field(json_schema_extra={"format": "path"})]
#: ``true`` or ``false`` (not ``"false"``)
Bool = Annotated[bool, Strict()]
#: a whole number of 1 or more
Count = Annotated[int, Strict(), Gt(0)]
#: three finite numbers
Vector3 = Annotated[list[Number], Len(3, 3)]
#: two finite numbers
Pair = Annotated[list[Number], Len(2, 2)]
#: one finite number or more
Numbers = Annotated[list[Number], Len(1)]

M = TypeVar("M", bound="FormatModel")


class FormatModel(BaseModel):
    """The base of every declared file format: immutable, unknown keys refused, nothing coerced.

    Attributes
    ----------
    model_config : pydantic.ConfigDict
        ``frozen``, ``extra="forbid"``, strict types.
    """

    model_config = ConfigDict(frozen=True, extra="forbid", strict=True, populate_by_name=True)
    _order: tuple[str, ...] = PrivateAttr(default=())

    @model_validator(mode="wrap")
    @classmethod
    def _keep_order(cls, data: Any, handler: Any) -> Any:
        made = handler(data)
        if isinstance(data, dict) and isinstance(made, FormatModel):
            made._order = tuple(str(k) for k in data)
        return made

    def given(self) -> dict[str, Any]:
        """The keys the file gave, in the file's order, with their validated values.

        Parameters
        ----------
        self : FormatModel

        Returns
        -------
        dict
            Key as written (the field's alias, if any) -> validated value (sub-tables stay models).
        """
        by_key = {(f.alias or name): name for name, f in type(self).model_fields.items()}
        out = {}
        for key in self._order:  # as written; a key spelled with "-" for "_" (an option's spelling) too
            name = by_key.get(key) or by_key.get(key.replace("-", "_"))
            if name is not None:
                out[key] = getattr(self, name)
        return out


def key_path(loc: tuple[Any, ...]) -> str:
    """A pydantic error location as people read a key path: ``tests[2].spacing_mm``.

    Parameters
    ----------
    loc : tuple of str and int
        The location (0-based list indices).

    Returns
    -------
    str

    Examples
    --------
    >>> key_path(("tests", 2, "spacing_mm"))
    'tests[3].spacing_mm'
    """
    out = ""
    for part in loc:
        if isinstance(part, int):
            out += f"[{part + 1}]"
        else:
            out += ("." if out else "") + str(part)
    return out


def line_of(lines: TomlLines | None, loc: tuple[Any, ...]) -> int | None:
    """The line of the key at ``loc`` in a TOML text, else of the nearest table or key above it.

    Parameters
    ----------
    lines : TomlLines or None
        Where each key stands (None: no line is known).
    loc : tuple of str and int
        The key path (list indices 0-based, as in an array of tables).

    Returns
    -------
    int or None

    Examples
    --------
    >>> line_of(TomlLines('[[tests]]\\nkind = "a"\\n[[tests]]\\nkind = "b"\\n'), ("tests", 1, "kind"))
    4
    """
    if lines is None:
        return None
    for end in range(len(loc), 0, -1):
        parts = loc[:end]
        index = 0
        names: list[str] = []
        for part in parts:
            if isinstance(part, int):
                index = part
            else:
                names.append(str(part))
        names = [n for n in names if not n.startswith("=")]
        if not names:
            continue
        for split in range(len(names) - 1, -1, -1):
            table, key = ".".join(names[:split]), ".".join(names[split:])
            found = lines.keys.get((table, index, key))
            if found is not None:
                return found
        found = lines.of(".".join(names), index)
        if found is not None:
            return found
    return None


def _models_in(kind: Any) -> list[type[BaseModel]]:
    """The models a field's annotation holds (through lists, optionals, unions)."""
    import typing

    out, pending = [], [kind]
    while pending:
        kind = pending.pop()
        if isinstance(kind, type) and issubclass(kind, BaseModel):
            out.append(kind)
        else:
            pending.extend(a for a in typing.get_args(kind) if a is not type(None))
    return out


def _tag_of(model: type[BaseModel]) -> str | None:
    """The literal value of a union member's ``kind`` key (its tag), else None."""
    import typing

    field = model.model_fields.get("kind")
    if field is None:
        return None
    args = typing.get_args(field.annotation)
    return str(args[0]) if len(args) == 1 else None


def _walk(model: type[BaseModel], loc: tuple[Any, ...]) -> tuple[tuple[Any, ...], type[BaseModel] | None]:
    """``loc`` without the tags pydantic adds for tagged unions, and the model the last key belongs to."""
    clean: list[Any] = []
    current: type[BaseModel] | None = model
    candidates: list[type[BaseModel]] = []
    parent: type[BaseModel] | None = model
    dict_key = False
    for part in loc:
        if isinstance(part, int):
            clean.append(part)
            continue
        if part.startswith("="):  # the tag of a union told apart by a function: "=file", "=table"
            continue
        if dict_key:  # a key of a table of tables ([axes.X]): the model stays the values' model
            clean.append(part)
            dict_key = False
            continue
        if candidates:
            tagged = {_tag_of(m): m for m in candidates}
            if part in tagged and len(candidates) > 1:
                current, candidates = tagged[part], []
                continue
            current = candidates[0] if len(candidates) == 1 else current
            candidates = []
        clean.append(part)
        parent = current
        field = current.model_fields.get(str(part)) if current is not None else None
        if field is None:
            current = None
            continue
        candidates = _models_in(field.annotation)
        dict_key = "dict[" in repr(field.annotation) and bool(candidates)
        current = candidates[0] if len(candidates) == 1 else None
        if len(candidates) == 1:
            candidates = []
    return tuple(clean), parent


def _show(value: Any) -> str:
    if isinstance(value, (_dt.date, _dt.datetime)):
        text = value.isoformat()
    else:
        text = repr(value)
    return text if len(text) <= 40 else text[:37] + "..."


#: the longest key a message quotes whole; a longer one is cut, with its length said
_LONGEST_SHOWN = 40


def _shown_name(name: str) -> str:
    """A key as a message quotes it: whole up to 40 characters, else its start and its length."""
    return name if len(name) <= _LONGEST_SHOWN else f"{name[:_LONGEST_SHOWN - 3]}... ({len(name)} characters)"


def _shown_path(loc: tuple[Any, ...]) -> str:
    """:func:`key_path` with every key as :func:`_shown_name` quotes it."""
    return key_path(tuple(_shown_name(part) if isinstance(part, str) else part for part in loc))


def _expected(error: dict[str, Any]) -> str:
    """What a pydantic error says was expected, in the words of the formats pages."""
    kind, ctx = error["type"], error.get("ctx", {})
    words = {
        "float_type": "a finite number", "int_type": "a whole number", "bool_type": "true or false",
        "string_type": "a string in quotes", "list_type": "a list [...]", "dict_type": "a table",
        "model_type": "a table", "date_type": "a date (2026-11-20)", "dict_type_": "a table", "finite_number": "a finite number",
        "model_attributes_type": "a table",
    }
    if kind in words:
        return words[kind]
    if kind == "greater_than":
        return f"a number above {ctx.get('gt')}"
    if kind == "greater_than_equal":
        return f"at least {ctx.get('ge')}"
    if kind == "less_than_equal":
        return f"at most {ctx.get('le')}"
    if kind in ("too_short", "too_long"):
        return f"{ctx.get('min_length')} to {ctx.get('max_length')} values" if ctx.get("min_length") != ctx.get(
            "max_length") else f"exactly {ctx.get('min_length')} values"
    if kind == "literal_error":
        expected = str(ctx.get("expected"))
        return expected if expected.count(" or ") == 1 and "," not in expected else f"one of {expected}"
    if kind == "string_pattern_mismatch":
        return "a text that is not empty"
    if kind == "string_too_long":
        return f"a text of at most {ctx.get('max_length')} characters"
    if kind == "union_tag_invalid":
        return f"one of {ctx.get('expected_tags')}"
    return error["msg"][0].lower() + error["msg"][1:]


def _label(loc: tuple[Any, ...]) -> str:
    """``[table] key`` for a key in a table, ``key`` at the top level: the words of the formats pages."""
    strings = [i for i, part in enumerate(loc) if isinstance(part, str)]
    if not strings:
        return _shown_path(loc)
    last = strings[-1]
    table, key = _shown_path(loc[:last]), _shown_path(loc[last:])
    return f"[{table}] {key}" if table else key


def _value_at(data: Any, loc: tuple[Any, ...]) -> Any:
    for part in loc:
        try:
            data = data[part]
        except (KeyError, IndexError, TypeError):
            return None
    return data


def _list_words(model: type[BaseModel] | None, key: Any) -> str | None:
    """``3 finite numbers`` for a key whose value is a list of numbers of a fixed length (with their bounds)."""
    field = model.model_fields.get(key) if model is not None and isinstance(key, str) else None
    if field is None or not re.search(r"list\[(typing\.)?Annotated\[float", repr(field.annotation)):
        return None
    text = repr(field.annotation) + repr(field.metadata)
    size = next((m for m in (*field.metadata, *_annotated_meta(field.annotation)) if type(m).__name__ == "Len"), None)
    count = f"{size.min_length}" if size is not None and size.min_length == size.max_length else "a list of"
    words = f"{count} finite numbers"
    if "Le(le=" in text:
        high = float(text.split("Le(le=")[1].split(")")[0])
        words += f", each within +-{high:g}"
    return words


def _annotated_meta(annotation: Any) -> list[Any]:
    import typing

    out, pending = [], [annotation]
    while pending:
        kind = pending.pop()
        if typing.get_origin(kind) is typing.Annotated:
            out.extend(typing.get_args(kind)[1:])
            pending.append(typing.get_args(kind)[0])
        else:
            pending.extend(a for a in typing.get_args(kind) if a is not type(None) and typing.get_origin(a) is not list)
    return out


def _message(model: type[BaseModel], error: dict[str, Any], data: Any = None) -> str:
    loc, parent_model = _walk(model, tuple(error["loc"]))
    kind, ctx = error["type"], error.get("ctx", {})
    raw = tuple(error["loc"])
    item = raw[:-1] if raw and isinstance(raw[-1], int) else raw
    item_loc, owner = _walk(model, item)
    words = _list_words(owner, item_loc[-1] if item_loc else None)
    if words is not None and kind != "missing":
        return f"{_label(item_loc)} must be {words}, not {_show(_value_at(data, item_loc))}"
    if kind == "extra_forbidden":
        name = str(loc[-1])
        valid = [f.alias or n for n, f in parent_model.model_fields.items()] if parent_model is not None else []
        near = difflib.get_close_matches(name, valid, n=1, cutoff=0.6) if len(name) <= _LONGEST_SHOWN else []
        hint = f"; did you mean '{near[0]}'?" if near else ""
        parent = _shown_path(loc[:-1])
        inside = f" in [{parent}]" if parent else ""
        return f"unknown key '{_shown_name(name)}'{inside}{hint} (known: {', '.join(valid)})"
    if "[key]" in loc:  # a key of a table that is not of the kind the table's keys are
        parent = _shown_path(loc[: loc.index("[key]") - 1])
        return f"[{parent}] key {_show(loc[loc.index('[key]') - 1])} must be {_expected(error)}"
    if kind == "invalid_key":
        return f"unknown key {_show(error['input'])}: keys are texts"
    if kind == "missing":
        parent = _shown_path(loc[:-1])
        tag = _tag_of(parent_model) if parent_model is not None else None
        if tag is not None and parent:
            return f"[{parent}]: a {tag} test needs '{loc[-1]}'"
        return f"[{parent}] needs '{loc[-1]}'" if parent else f"needs [{loc[-1]}]" if parent_model is not None and _is_table(
            parent_model, str(loc[-1])) else f"needs '{loc[-1]}'"
    if kind == "union_tag_not_found":
        return f"[{_shown_path(loc)}] needs '{ctx['discriminator'].strip(chr(39))}'"
    if kind == "union_tag_invalid":
        tag = ctx["discriminator"].strip("'")
        tags = [t.strip(" '") for t in str(ctx.get("expected_tags", "")).split(",")]
        near = difflib.get_close_matches(str(ctx["tag"]), tags, n=1, cutoff=0.6)
        hint = f"; did you mean '{near[0]}'?" if near else ""
        return f"{_label((*loc, tag))}: unknown {tag} {_show(ctx['tag'])}{hint} (known: {', '.join(tags)})"
    if kind == "value_error":
        return f"{_label(loc)}: {ctx['error']}"
    if kind == "greater_than_equal" and ctx.get("ge") == 0:
        return f"{_label(loc)} must not be negative, not {_show(error['input'])}"
    if kind in ("greater_than_equal", "less_than_equal") and parent_model is not None:
        field = parent_model.model_fields.get(str(loc[-1]))
        low = next((m.ge for m in getattr(field, "metadata", ()) if hasattr(m, "ge")), None)
        high = next((m.le for m in getattr(field, "metadata", ()) if hasattr(m, "le")), None)
        if low is not None and high is not None:
            return f"{_label(loc)} must be {low:g} to {high:g}, not {error['input']:g}"
    container = kind in ("dict_type", "list_type", "model_type", "model_attributes_type")
    words = None if container else _field_words(parent_model, loc)
    return f"{_label(loc)} must be {words or _expected(error)}, not {_show(error['input'])}"


def _field_words(model: type[BaseModel] | None, loc: tuple[Any, ...]) -> str | None:
    """What the key at ``loc`` takes when its type says more than pydantic's error (a file, an axis)."""
    if model is None or not loc or not isinstance(loc[-1], str):
        return None
    field = model.model_fields.get(loc[-1])
    if field is None:
        return None
    text = repr(field.annotation) + repr(field.metadata) + repr(field.json_schema_extra)
    if "Discriminator" in text and field.description:  # a file name or a table: say both
        return field.description
    if "'format': 'path'" in text:
        return "a file name (a string in quotes)"
    if "'format': 'date'" in text:
        return "a date (2026-11-20)"
    if "XYZABCxyzabc" in text:
        return "an axis letter (X, Y, Z, A, B, C)"
    if "[Xx][Yy]" in text:
        return "a plane XY, XZ or YZ"
    if "Gt(gt=0)" in text and "float" in text:
        return "a positive number"
    return None


def _is_table(model: type[BaseModel], name: str) -> bool:
    field = model.model_fields.get(name)
    return field is not None and bool(_models_in(field.annotation))


def validate_data(model: type[M], data: Any, *, path: str | Path | None = None, lines: TomlLines | None = None) -> M:
    """Validate parsed data into ``model``; the first error is one line naming the key and its line.

    Parameters
    ----------
    model : type of FormatModel
        The format.
    data : mapping
        The parsed file.
    path : str or Path, optional, keyword-only
        The file, named in the error.
    lines : TomlLines, optional, keyword-only
        Where each key stands in the file's text.

    Returns
    -------
    FormatModel
        The validated, immutable object.

    Raises
    ------
    AxiscalError
        ``path:line: key.path: expected ..., not ...``; an unknown key names the nearest valid one.
    """
    try:
        return model.model_validate(data)
    except ValidationError as exc:
        errors = exc.errors(include_url=False)
        # a misspelt key is both unknown and missing: the unknown one, with its nearest name, says more
        error = next((e for e in errors if e["type"] == "extra_forbidden"), errors[0])
        loc, _ = _walk(model, tuple(error["loc"]))
        if error["type"] in ("union_tag_invalid", "union_tag_not_found"):
            loc = (*loc, error["ctx"]["discriminator"].strip("'"))
        line = line_of(lines, loc)
        raise AxiscalError(_message(model, error, data), path=path, line=line) from None


def read_format(model: type[M], path: str | Path) -> tuple[M, TomlLines]:
    """Read a TOML file once and validate it into ``model``.

    Parameters
    ----------
    model : type of FormatModel
        The format of the file.
    path : Path
        The file (its path checked once, by the caller's public entry).

    Returns
    -------
    (FormatModel, TomlLines)
        The validated object and where each key stands (for the errors only the file's meaning
        can find: a missing data file, a chain without that axis).

    Raises
    ------
    AxiscalError
        A missing, unreadable or malformed file, an unknown key, a value of the wrong kind,
        naming the file and the line.
    """
    from axiscal.io.tabular import parse_toml, read_checked_text

    text = read_checked_text(Path(path))
    data = parse_toml(text, path=path)
    lines = TomlLines(text)
    return validate_data(model, data, path=path, lines=lines), lines
