"""Every example session of docs/devices.md runs as written, in order, in a scratch folder."""

from __future__ import annotations

import re
import shlex
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).parents[2]


def _sessions() -> list[str]:
    text = (ROOT / "docs" / "devices.md").read_text(encoding="utf-8")
    part = text.split("## Example sessions", 1)[1].split("## From Python", 1)[0]
    lines = []
    for block in re.findall(r"```text\n(.*?)```", part, flags=re.S):
        lines += [line for line in block.splitlines() if line.startswith("axiscal ")]
    return lines


def test_the_example_sessions_run_in_order(tmp_path):
    lines = _sessions()
    assert len(lines) >= 7
    env = {"PYTHONPATH": str(ROOT / "src")}
    import os

    env = {**os.environ, **env}
    for line in lines:
        args = shlex.split(line)
        done = subprocess.run([sys.executable, "-m", "axiscal.cli.main", *args[1:]], cwd=tmp_path, capture_output=True,
                              text=True, env=env, timeout=300)
        assert done.returncode == 0, f"{line}\n{done.stderr[-2000:]}"
    assert (tmp_path / "cycle" / "cycle.json").is_file()
    for name in ("run.csv", "sylvac.csv", "scale.csv", "ids.csv"):
        assert (tmp_path / name).is_file()


def test_the_python_example_runs():
    text = (ROOT / "docs" / "devices.md").read_text(encoding="utf-8")
    code = re.findall(r"```python\n(.*?)```", text, flags=re.S)[0]
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300,
                          env={**__import__("os").environ, "PYTHONPATH": str(ROOT / "src")})
    assert done.returncode == 0, done.stderr[-2000:]
    assert "10 steps read" in done.stdout
