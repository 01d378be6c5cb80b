"""Plain-text reports rendered from the Jinja2 templates shipped under ``axiscal/templates/``.

Commands print multi-line reports; their wording and layout live in template files, not in code.
"""

from __future__ import annotations

from typing import Any

from axiscal.io.arguments import render_checked
from axiscal.io.templates import render_template

__all__ = ["render_report"]


def render_report(name: str, **context: Any) -> str:
    """Render the template ``name`` (a path under ``axiscal/templates/``) with ``context``.

    Parameters
    ----------
    name : str
        Template path, e.g. ``"instruments/air.txt.j2"``.
    **context
        The values the template uses (a missing one is an error, not an empty string).

    Returns
    -------
    str
        The report text, ending with a newline.

    Raises
    ------
    AxiscalError
        For a template that is not shipped, or a value the template uses that is not given.
    """
    return render_checked(_render, name, **context)


def _render(name: str, **context: Any) -> str:
    return render_template(name, keep_trailing_newline=True, trim_blocks=False, **context)
