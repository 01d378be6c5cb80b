"""Text reports of the straightness and squareness rooms, rendered from Jinja2 templates.

The templates ship as package data under ``axiscal/templates/``; every number reaches them
already in the unit it is printed in, so a template only lays out and formats.
"""

from __future__ import annotations

from typing import Any

from axiscal.io.arguments import render_checked
from axiscal.io.templates import render_template

__all__ = ["render_report"]


def render_report(template: str, **context: Any) -> str:
    """Render one of the shipped text templates.

    Parameters
    ----------
    template : str
        File name under ``axiscal/templates/``, e.g. ``"straightness.txt.j2"``.
    **context
        The values the template prints, already in display units.

    Returns
    -------
    str
        The report, without a trailing newline.

    Raises
    ------
    AxiscalError
        For a template that is not shipped, or a value the template uses that is not given.

    Examples
    --------
    >>> text = render_report("straightness.txt.j2", straightness_um=1.0, slope_urad=0.5,
    ...                      intercept_um=0.0, reference="least-squares")
    >>> text.splitlines()[0]
    'straightness  1.0000 um  (least-squares reference line)'
    """
    return render_checked(render_template, template, **context).rstrip("\n")
