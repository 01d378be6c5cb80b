"""Plain-text reports rendered from the Jinja2 templates shipped under ``axiscal/templates/``.

Commands print multi-line reports; their wording and layout live in template files, not in code.
"""

from __future__ import annotations

from functools import lru_cache
from typing import Any

__all__ = ["render_report"]


@lru_cache(maxsize=None)
def _environment():
    from jinja2 import Environment, PackageLoader, StrictUndefined

    return Environment(loader=PackageLoader("axiscal", "templates"), undefined=StrictUndefined, keep_trailing_newline=True)


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
    jinja2.UndefinedError
        If the template uses a value not given (a programming error, not a user's).
    """
    return _environment().get_template(name).render(**context)
