"""README's command tour runs as written, line after line, in a copy of the repository's examples.

Every ``axiscal ...`` line of the section "A tour of the command line" runs in order (a later line
reads what an earlier one wrote) by the shell, from the root of a temporary copy holding README.md
and examples/, with ``axiscal`` this source tree's command. Each must succeed, and the tour must
write only into ``tour/`` (ignored by git) and leave the examples as shipped.
"""

from __future__ import annotations

import filecmp
import os
import shutil
import stat
import subprocess
import sys
from concurrent.futures import Future, ThreadPoolExecutor

import pytest

from docs_pages import ROOT, code_blocks, section

TOUR = section((ROOT / "README.md").read_text(encoding="utf-8"), "A tour of the command line")
LINES = [line.strip() for _, block in code_blocks(TOUR, "sh") for line in block.splitlines() if line.strip().startswith("axiscal")]


def _tree(folder):
    return sorted(str(p.relative_to(folder)) for p in folder.rglob("*") if "__pycache__" not in p.parts)


@pytest.fixture(scope="module")
def copy(tmp_path_factory):
    root = tmp_path_factory.mktemp("repository")
    shutil.copytree(ROOT / "examples", root / "examples", ignore=shutil.ignore_patterns("__pycache__", "report"))
    shutil.copy(ROOT / "README.md", root / "README.md")
    bin_dir = tmp_path_factory.mktemp("bin")
    command = bin_dir / "axiscal"
    command.write_text(f'#!/bin/sh\nexec "{sys.executable}" -m axiscal.cli.main "$@"\n')
    command.chmod(command.stat().st_mode | stat.S_IEXEC)
    env = {**os.environ, "PATH": f"{bin_dir}{os.pathsep}{os.environ.get('PATH', '')}",
           "PYTHONPATH": str(ROOT / "src"), "MPLBACKEND": "Agg", "HOME": str(root / "home")}
    env.pop("AXISCAL_DB", None)
    return root, env


def test_the_tour_has_its_lines_and_writes_into_tour():
    assert len(LINES) >= 30 and LINES[-1].startswith("axiscal --help")
    assert any(line.startswith("axiscal history trend") for line in LINES)
    assert "tour/" in (ROOT / ".gitignore").read_text(encoding="utf-8").split()


def _files(line: str) -> set[str]:
    """The paths under tour/ a line names (what it reads or writes there)."""
    return {word.strip("'\"") for word in line.split("#")[0].split() if word.strip("'\"").startswith("tour/")}


def _after(line: str, earlier: str) -> bool:
    """Whether ``line`` must wait for ``earlier``: both name one path under tour/, or one a folder of the other."""
    return any(a == b or a.startswith(b + "/") or b.startswith(a + "/") for a in _files(line) for b in _files(earlier))


def test_the_tour_s_order_is_kept_where_lines_share_a_file():
    chain = [LINES.index(line) for line in LINES if "tour/history.sqlite" in line]
    assert len(chain) >= 3 and all(_after(LINES[b], LINES[a]) for a, b in zip(chain, chain[1:]))
    assert not _after("axiscal compensate examples/positioning_run.csv", LINES[0])


def test_every_line_of_the_tour_runs_in_order(copy):
    """Each line starts once every earlier line naming one of its tour/ files has ended (a later line reads
    what an earlier one wrote); the others run beside it, three at a time: the driven run and the live
    session mostly wait on the clock."""
    root, env = copy
    before = _tree(root / "examples")

    def run(number: int, line: str, after: list[Future]) -> str:
        for future in after:  # started earlier (the pool takes its work in order): no deadlock
            future.result()
        done = subprocess.run(["bash", "-c", line], cwd=root, env=env, capture_output=True, text=True, timeout=600)
        assert done.returncode == 0, f"tour line {number}: {line}\n{done.stderr[-2000:]}"
        assert "Traceback" not in done.stderr, f"tour line {number}: {line}\n{done.stderr[-2000:]}"
        return done.stdout

    with ThreadPoolExecutor(max_workers=3) as pool:
        started: list[Future] = []
        for number, line in enumerate(LINES, start=1):
            after = [started[earlier] for earlier in range(number - 1) if _after(line, LINES[earlier])]
            started.append(pool.submit(run, number, line, after))
        said = {line.split("#")[0].strip(): future.result() for line, future in zip(LINES, started)}
    # the tour writes into tour/ only: the examples are as shipped and nothing lands beside them
    assert _tree(root / "examples") == before
    comparison = filecmp.dircmp(ROOT / "examples", root / "examples", ignore=["__pycache__", "report"])
    assert comparison.diff_files == []
    assert sorted(p.name for p in root.iterdir()) == ["README.md", "examples", "home", "tour"] or \
        sorted(p.name for p in root.iterdir()) == ["README.md", "examples", "tour"]
    assert not (root / "home").exists() or not any((root / "home").rglob("*.sqlite"))  # the history went to tour/
    # the trend is over the shipped visits and the campaign the tour stored
    trend = next(text for line, text in said.items() if line.startswith("axiscal history trend"))
    assert "over 5 campaigns" in trend and "next calibration" in trend
    assert "status 1: the verdict is fail" in next(text for line, text in said.items() if "--exit-code" in line)
