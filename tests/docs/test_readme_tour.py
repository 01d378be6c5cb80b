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


def test_every_line_of_the_tour_runs_in_order(copy):
    root, env = copy
    before = _tree(root / "examples")
    said = {}
    for number, line in enumerate(LINES, start=1):
        done = subprocess.run(["bash", "-c", line], cwd=root, env=env, capture_output=True, text=True, timeout=600)
        assert done.returncode == 0, f"tour line {number}: {line}\n{done.stderr[-2000:]}"
        assert "Traceback" not in done.stderr, f"tour line {number}: {line}\n{done.stderr[-2000:]}"
        said[line.split("#")[0].strip()] = done.stdout
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
