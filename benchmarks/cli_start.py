"""Start-up of the command line: ``axiscal --help``, every command's ``--help`` and an argument error.

Run from the repository root::

    .venv/bin/python benchmarks/cli_start.py [--runs 5]

Each line is a whole process (``python -m axiscal.cli.main ...``), started ``--runs`` times in turn
with a plain ``python -c pass`` (A B A B ...), so that the load of a shared machine touches both
alike. Printed: the median wall-clock time of each, seconds, and the slowest command's help.
Goal: every ``--help`` and every argument error within 0.5 s on a quiet machine.
"""

from __future__ import annotations

import argparse
import subprocess
import sys
from pathlib import Path

from timing import interleaved, median

ROOT = Path(__file__).resolve().parents[1]


def _process(*argv: str):
    command = [sys.executable, *argv]

    def run() -> None:
        subprocess.run(command, cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=False)

    return run


def _command_paths() -> list[tuple[str, ...]]:
    sys.path.insert(0, str(ROOT / "tests" / "cli"))
    from cli_commands import leaf_commands

    return [path for path, command in leaf_commands() if not command.hidden]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=5, help="starts of each process (the median is printed)")
    parser.add_argument("--all", action="store_true", help="also time --help of every command, not only a few")
    args = parser.parse_args()
    module = ("-m", "axiscal.cli.main")
    cases = {
        "python -c pass": _process("-c", "pass"),
        "axiscal --version": _process(*module, "--version"),
        "axiscal --help": _process(*module, "--help"),
        "axiscal report --help": _process(*module, "report", "--help"),
        "axiscal history trend --help": _process(*module, "history", "trend", "--help"),
        "axiscal positioning (no argument)": _process(*module, "positioning"),
        "axiscal plan --targets x": _process(*module, "plan", "--targets", "x"),
    }
    if args.all:
        for path in _command_paths():
            cases[f"axiscal {' '.join(path)} --help"] = _process(*module, *path, "--help")
    times = interleaved(cases, args.runs)
    width = max(len(name) for name in cases)
    print(f"median of {args.runs} starts, whole process (seconds)")
    for name, values in times.items():
        print(f"  {name:<{width}}  {median(values):.3f}")
    slowest = max((name for name in times if name != "python -c pass"), key=lambda n: median(times[n]))
    print(f"slowest: {slowest} {median(times[slowest]):.3f} s; plain python start {median(times['python -c pass']):.3f} s")


if __name__ == "__main__":
    main()
