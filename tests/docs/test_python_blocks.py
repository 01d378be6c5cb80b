"""Every ```python block of README.md and docs/ runs as written.

The blocks of a page run in order in one fresh interpreter (a later block may use what an earlier
one made), from the root of a copy of the repository's examples with a scratch folder ``tour/``, as
a reader would paste them at the repository root. A block that needs names from its page shows
their set-up itself; none is skipped.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys

import pytest

from docs_pages import PAGES, ROOT, code_blocks

BLOCKS = {page.name: code_blocks(page.read_text(encoding="utf-8"), "python") for page in PAGES}
WITH_CODE = [name for name, blocks in BLOCKS.items() if blocks]

RUNNER = """
import json, sys
namespace = {"__name__": "__main__"}
for page, line, code in json.loads(sys.argv[1]):
    exec(compile(code, f"{page}, block at line {line}", "exec"), namespace)
"""


@pytest.fixture(scope="module")
def root(tmp_path_factory):
    folder = tmp_path_factory.mktemp("repository")
    shutil.copytree(ROOT / "examples", folder / "examples", ignore=shutil.ignore_patterns("__pycache__", "report"))
    (folder / "tour").mkdir()
    return folder


def test_the_pages_have_their_python_blocks():
    assert sum(len(blocks) for blocks in BLOCKS.values()) >= 25 and "README.md" in WITH_CODE


@pytest.mark.parametrize("page", WITH_CODE)
def test_the_python_blocks_of_a_page_run_in_order(page, root):
    blocks = [(page, line, code) for line, code in BLOCKS[page]]
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src"), "MPLBACKEND": "Agg", "HOME": str(root / "home")}
    env.pop("AXISCAL_DB", None)
    done = subprocess.run([sys.executable, "-c", RUNNER, json.dumps(blocks)], cwd=root, env=env, capture_output=True,
                          text=True, timeout=600)
    assert done.returncode == 0, done.stderr[-3000:]
    assert sorted(p.name for p in root.iterdir()) in (["examples", "tour"], ["examples", "home", "tour"])
