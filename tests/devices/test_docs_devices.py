"""Every example session of docs/devices.md runs as written, in order, in a scratch folder."""

from __future__ import annotations

import os
import re
import shlex
import subprocess
import sys
from concurrent.futures import Future, ThreadPoolExecutor
from pathlib import Path

ROOT = Path(__file__).parents[2]


def _sessions() -> list[str]:
    text = (ROOT / "docs" / "devices.md").read_text(encoding="utf-8")
    part = text.split("## Example sessions", 1)[1].split("## From Python", 1)[0]
    lines = []
    for block in re.findall(r"```text\n(.*?)```", part, flags=re.S):
        lines += [line for line in block.splitlines() if line.startswith("axiscal ")]
    return lines


def _needs(line: str, earlier: str) -> bool:
    """Whether ``line`` reads a file the ``earlier`` line writes (its -o argument)."""
    args = shlex.split(earlier)
    written = {args[i + 1] for i, arg in enumerate(args[:-1]) if arg in ("-o", "--output")}
    return bool(written & set(shlex.split(line)[1:]))


def test_the_example_sessions_run_in_order(tmp_path):
    """Each line starts once the lines whose files it reads have ended: the driven runs, which mostly wait
    on the virtual machine's motion, run side by side (58 s one after another, about 20 s so)."""
    lines = _sessions()
    assert len(lines) >= 7
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src")}

    def run(line: str, after: list[Future]) -> None:
        for future in after:  # started before this one (the pool takes its work in order): no deadlock
            future.result()
        args = shlex.split(line)
        done = subprocess.run([sys.executable, "-m", "axiscal.cli.main", *args[1:]], cwd=tmp_path, capture_output=True,
                              text=True, env=env, timeout=300)
        assert done.returncode == 0, f"{line}\n{done.stderr[-2000:]}"

    with ThreadPoolExecutor(max_workers=4) as pool:
        started: list[Future] = []
        for number, line in enumerate(lines):
            after = [started[before] for before in range(number) if _needs(line, lines[before])]
            started.append(pool.submit(run, line, after))
        for future in started:
            future.result()
    assert (tmp_path / "cycle" / "cycle.json").is_file()
    for name in ("run.csv", "sylvac.csv", "scale.csv", "ids.csv"):
        assert (tmp_path / name).is_file()


def test_the_python_example_runs():
    text = (ROOT / "docs" / "devices.md").read_text(encoding="utf-8")
    code = re.findall(r"```python\n(.*?)```", text, flags=re.S)[0]
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300,
                          env={**os.environ, "PYTHONPATH": str(ROOT / "src")})
    assert done.returncode == 0, done.stderr[-2000:]
    assert "10 steps read" in done.stdout
