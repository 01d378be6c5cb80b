"""Plots placed inline in the report: a plot written as SVG and returned as text; data files named from the campaign."""

from __future__ import annotations

import re
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import Any

from axiscal.campaign.config import Campaign
from axiscal.errors import AxiscalError
from axiscal.io.arguments import type_name

__all__ = ["svg_of"]


def svg_of(draw: Callable[[Path], Any]) -> str:
    """The SVG text of a plot, for placing inline in a page.

    Parameters
    ----------
    draw : callable
        Writes the plot to the ``.svg`` path it is given.

    Returns
    -------
    str
        The ``<svg>`` element, without XML prolog and metadata.

    Raises
    ------
    AxiscalError
        For a ``draw`` that is not callable.
    """
    if not callable(draw):
        raise AxiscalError(f"draw must be a function that writes a plot to the path it is given, not {type_name(draw)}")
    with tempfile.TemporaryDirectory(prefix="axiscal-plot-") as folder:
        path = Path(folder) / "plot.svg"
        draw(path)
        text = path.read_text(encoding="utf-8")
    start = text.find("<svg")
    text = text[start:] if start >= 0 else text
    return re.sub(r"\s*<metadata>.*?</metadata>", "", text, count=1, flags=re.S)


def relative_name(campaign: Campaign, path: Path) -> str:
    """A data file's name relative to the campaign's folder, as results.json names it.

    Parameters
    ----------
    campaign : Campaign
    path : Path
        A file inside the campaign's folder.

    Returns
    -------
    str
    """
    return path.relative_to(campaign.folder).as_posix()
