"""Every ``axiscal ...`` command line that README.md and docs/ show in code exists: its --help runs, its flags are its own.

The pages are read when the tests are collected, so a page added or changed later is checked too.
"""

from __future__ import annotations

import re
import shlex
from pathlib import Path

import click
import pytest

from axiscal.cli.main import cli

ROOT = Path(__file__).resolve().parents[2]
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
FENCE = re.compile(r"^\s*(```|~~~)")
STOP = {"|", ">", ">>", "&&", ";", "..."}


def command_lines(text: str) -> list[tuple[int, str]]:
    """``(line, "axiscal ...")`` for each command line of a page: in code blocks (joined over a trailing
    backslash) and in inline code spans."""
    found: list[tuple[int, str]] = []
    in_block, pending, start = False, "", 0
    for number, line in enumerate(text.splitlines(), start=1):
        if FENCE.match(line):
            in_block, pending = not in_block, ""
            continue
        if not in_block:
            found += [(number, span) for span in re.findall(r"`(axiscal(?:\s[^`]*)?)`", line)]
            continue
        stripped = line.strip()
        if not pending:
            if not re.match(r"^(\$ )?axiscal(\s|$)", stripped):
                continue
            stripped, start = stripped.removeprefix("$ "), number
        pending = f"{pending} {stripped}".strip()
        if pending.endswith("\\"):
            pending = pending[:-1].rstrip()
            continue
        found.append((start, pending))
        pending = ""
    return found


def resolve(line: str) -> tuple[tuple[str, ...], click.Command, list[str]]:
    """The command path a line names, the command, and the flags it types (placeholders in [] kept)."""
    tokens = shlex.split(line, comments=True)[1:]
    command: click.Command = cli
    path: list[str] = []
    ctx = click.Context(cli, info_name="axiscal")
    while isinstance(command, click.Group) and tokens and not tokens[0].startswith("-") and tokens[0] not in STOP:
        sub = command.get_command(ctx, tokens[0])
        if sub is None:
            raise LookupError(f"'axiscal {' '.join([*path, tokens[0]])}' is not a command")
        path.append(tokens.pop(0))
        command = sub
    flags = []
    for token in tokens:
        if token in STOP:
            break
        token = token.strip("[](){}")
        if token.startswith("-") and len(token) > 1 and not re.match(r"^-[\d.]", token):
            flags.append(token.split("=")[0])
    return tuple(path), command, flags


SHOWN = [
    pytest.param(page, number, line, id=f"{page.name}:{number}")
    for page in PAGES
    for number, line in command_lines(page.read_text(encoding="utf-8"))
]


def test_the_pages_show_commands():
    assert len(SHOWN) > 100 and any("simulate ballbar" in p.values[2] for p in SHOWN)


@pytest.mark.parametrize("page, number, line", SHOWN)
def test_a_command_line_in_the_docs_exists(run_cli, page, number, line):
    try:
        path, command, flags = resolve(line)
    except LookupError as exc:
        pytest.fail(f"{page.name}:{number}: {exc} ({line})")
    known = {name for param in command.params for name in (*param.opts, *param.secondary_opts)}
    unknown = [flag for flag in flags if flag not in known | {"-h", "--help", "--version"}]
    assert not unknown, f"{page.name}:{number}: axiscal {' '.join(path)} has no {', '.join(unknown)}"
    status, out, err = run_cli(*path, "--help")
    assert status == 0 and err == "" and out.startswith("Usage: axiscal"), f"{page.name}:{number}: {err}"


def test_the_reader_of_pages_finds_what_a_page_shows():
    page = "\n".join([
        "Run `axiscal simulate ballbar` or:", "```sh", "$ axiscal report examples/campaign \\", "    --pdf  # comment",
        "make demo", "```", "```python", "import axiscal", "```",
    ])
    assert command_lines(page) == [(1, "axiscal simulate ballbar"), (3, "axiscal report examples/campaign --pdf  # comment")]
    assert resolve("axiscal report DIR --pdf [--compare R.json] | less")[0] == ("report",)
    assert resolve("axiscal report DIR --pdf [--compare R.json]")[2] == ["--pdf", "--compare"]
    with pytest.raises(LookupError, match="'axiscal no-such' is not a command"):
        resolve("axiscal no-such --help")
