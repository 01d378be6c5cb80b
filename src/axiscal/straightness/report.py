"""Text reports of the straightness and squareness rooms, rendered from Jinja2 templates.

The templates ship as package data under ``axiscal/templates/``; every number reaches them
already in the unit it is printed in, so a template only lays out and formats.
"""

from __future__ import annotations

from functools import lru_cache
from typing import Any

__all__ = ["render_report"]


@lru_cache(maxsize=1)
def _environment():
    from jinja2 import Environment, PackageLoader, StrictUndefined

    return Environment(
        loader=PackageLoader("axiscal", "templates"),
        undefined=StrictUndefined,
        trim_blocks=True,
        lstrip_blocks=True,
        keep_trailing_newline=False,
        autoescape=False,
    )


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

    Examples
    --------
    >>> text = render_report("straightness.txt.j2", straightness_um=1.0, slope_urad=0.5,
    ...                      intercept_um=0.0, reference="least-squares")
    >>> text.splitlines()[0]
    'straightness  1.0000 um  (least-squares reference line)'
    """
    return _environment().get_template(template).render(**context).rstrip("\n")
