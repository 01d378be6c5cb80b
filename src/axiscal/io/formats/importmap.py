"""Column maps declared (docs/importing.md): where a positioning test's quantities stand in an
instrument's export, and in which units."""

from __future__ import annotations

from typing import Annotated, Literal, Union

from annotated_types import Ge
from pydantic import Discriminator, Field, Strict, Tag

from axiscal.io.formats.base import Bool, FormatModel, Text

__all__ = ["IMPORT_UNIT_NAMES", "DELIMITERS", "ColumnRef", "MapColumns", "MapUnits", "ImportMapFile"]

#: the length units a column map may name
IMPORT_UNIT_NAMES = ("nm", "um", "mm", "m", "in")
#: how a map may name its cell separator
DELIMITERS = (",", ";", "tab", "\t", "whitespace", "space")


def _text_or_number(value: object) -> str:
    return "=number" if isinstance(value, int) and not isinstance(value, bool) else "=text"


#: a column: its header text, or its 1-based number when the file has no header
ColumnRef = Annotated[
    Union[Annotated[Text, Tag("=text")], Annotated[Annotated[int, Strict(), Ge(1)], Tag("=number")]],
    Discriminator(_text_or_number),
]


class MapColumns(FormatModel):
    """``[columns]``: where each quantity stands.

    Attributes
    ----------
    target : str or int
    reading, run, direction : str or int or None
        ``run`` and ``direction`` may be ``"infer"``; ``direction`` may be ``"+"`` or ``"-"``.
    readings : list of (str or int), or str or int, or None
        One reading column per run (layout ``runs``).
    """

    target: ColumnRef = Field(description="the target column: header text, or number from 1")
    reading: ColumnRef | None = Field(None, description="the reading column (layout rows)")
    run: ColumnRef | None = Field(None, description='the run column, or "infer" (layout rows)')
    direction: ColumnRef | None = Field(None, description='the direction column, "+" or "-" for one direction, or "infer"')
    readings: list[ColumnRef] | ColumnRef | None = Field(None, description="one reading column per run (layout runs)")


class MapUnits(FormatModel):
    """``[units]``: the length units of the target and the reading.

    Attributes
    ----------
    target, reading : str or None
    """

    target: Literal[IMPORT_UNIT_NAMES] | None = Field(None, description="unit of the target (default mm)")  # type: ignore[valid-type]
    reading: Literal[IMPORT_UNIT_NAMES] | None = Field(None, description="unit of the reading (default um)")  # type: ignore[valid-type]


class ImportMapFile(FormatModel):
    """A column map (TOML) for ``axiscal import``.

    Attributes
    ----------
    layout, delimiter, decimal, reading : str or None
    skip_lines : int or None
    header : bool or None
    sign : int or None
    columns : MapColumns
    units : MapUnits or None
    direction_values : dict of str to str, or None
    runs : list of (str or int), or None
    """

    layout: Literal["rows", "runs"] | None = Field(None, description="rows: one row per reading; runs: one column per run")
    delimiter: Literal[DELIMITERS] | None = Field(None, description="cell separator (default ,)")  # type: ignore[valid-type]
    decimal: Literal[".", ","] | None = Field(None, description="decimal mark (a comma needs another delimiter)")
    skip_lines: Annotated[int, Strict(), Ge(0)] | None = Field(None, description="lines before the header")
    header: Bool | None = Field(None, description="the first line read holds column names (default true)")
    reading: Literal["deviation", "position"] | None = Field(None, description="what a reading is (default deviation)")
    sign: Literal[1, -1] | None = Field(None, description="-1 for software that reports target - actual")
    columns: MapColumns = Field(description="where each quantity stands, [columns]")
    units: MapUnits | None = Field(None, description="length units, [units]")
    direction_values: dict[str, Literal["+", "-"]] | None = Field(None, description="extra words of the direction column")
    runs: list[Union[Text, Annotated[int, Strict()]]] | None = Field(None, description="labels of the runs (layout runs)")
