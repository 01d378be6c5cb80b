"""The text and page templates shipped with axiscal (``axiscal/templates/``), rendered with Jinja2.

Every report axiscal prints or writes is a template here, never an f-string in code. One place
loads them, so that all rooms share the same rules: a variable a template uses but is not given is
an error (a program error, not a user's), and nothing is HTML-escaped unless the template is HTML.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from functools import lru_cache
from typing import Any

__all__ = ["environment", "render_template"]


@lru_cache(maxsize=None)
def _environment(keep_trailing_newline: bool, trim_blocks: bool, filters: tuple[tuple[str, Callable], ...]):
    import jinja2

    env = jinja2.Environment(
        loader=jinja2.PackageLoader("axiscal", "templates"),
        undefined=jinja2.StrictUndefined,
        keep_trailing_newline=keep_trailing_newline,
        trim_blocks=trim_blocks,
        lstrip_blocks=trim_blocks,
        autoescape=jinja2.select_autoescape(("html", "html.j2")),
    )
    env.filters.update(dict(filters))
    return env


def environment(
    *, keep_trailing_newline: bool = False, trim_blocks: bool = True, filters: Mapping[str, Callable] | None = None
):
    """The Jinja2 environment over the shipped templates.

    Parameters
    ----------
    keep_trailing_newline : bool, keyword-only
        Keep a template's last newline in the output.
    trim_blocks : bool, keyword-only
        Drop the newline after a block tag and the white space before it (Jinja2's
        ``trim_blocks`` and ``lstrip_blocks``).
    filters : mapping, keyword-only
        Extra filters by name.

    Returns
    -------
    jinja2.Environment
        Cached per set of options; undefined variables raise; HTML templates are autoescaped.
    """
    return _environment(keep_trailing_newline, trim_blocks, tuple(sorted((filters or {}).items())))


def render_template(
    name: str,
    /,
    *,
    keep_trailing_newline: bool = False,
    trim_blocks: bool = True,
    filters: Mapping[str, Callable] | None = None,
    **context: Any,
) -> str:
    """Render the template ``axiscal/templates/<name>`` with ``context``.

    Parameters
    ----------
    name : str
        Path of the template under ``axiscal/templates``, e.g. ``"positioning_report.txt.j2"``.
    keep_trailing_newline, trim_blocks, filters : keyword-only
        See :func:`environment`.
    **context
        The template's variables.

    Returns
    -------
    str
        The rendered text.

    Raises
    ------
    jinja2.TemplateNotFound, jinja2.UndefinedError
        A template that is not shipped, or a variable it uses that is not given (program errors).

    Examples
    --------
    >>> render_template("demo_summary.txt.j2", report="r.md", summary={})  # doctest: +SKIP
    """
    env = environment(keep_trailing_newline=keep_trailing_newline, trim_blocks=trim_blocks, filters=filters)
    return env.get_template(name).render(**context)
