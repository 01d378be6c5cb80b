"""Reading README.md and the docs pages for the tests that run their examples."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
_FENCE = re.compile(r"^(\s*)(```|~~~)\s*([\w+-]*)")


def code_blocks(text: str, language: str) -> list[tuple[int, str]]:
    """``(line, code)`` of every fenced block of ``language`` (```python ...```), in page order.

    The line is the 1-based line of the opening fence; indented fences (in lists) are dedented.
    """
    blocks: list[tuple[int, str]] = []
    lines = text.splitlines()
    number = 0
    while number < len(lines):
        match = _FENCE.match(lines[number])
        if match is None:
            number += 1
            continue
        indent, fence, lang = match.groups()
        body, end = [], number + 1
        while end < len(lines) and not lines[end].strip().startswith(fence):
            body.append(lines[end][len(indent):] if lines[end].startswith(indent) else lines[end].lstrip())
            end += 1
        if lang == language:
            blocks.append((number + 1, "\n".join(body) + "\n"))
        number = end + 1
    return blocks


def section(text: str, heading: str) -> str:
    """The text of the ``## heading`` section, up to the next heading of the same level."""
    start = text.index(f"## {heading}\n")
    following = text.find("\n## ", start + 1)
    return text[start:] if following < 0 else text[start:following]
