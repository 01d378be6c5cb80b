"""Concurrent writers of the calibration history: 8 `axiscal history add` processes of 50 campaigns each.

Run: .venv/bin/python benchmarks/history_writers.py [--writers 8] [--campaigns 50] [--db URL]

Generates writers x campaigns results files (one machine per writer, 12 toleranced figures each,
axiscal.history.synthetic), starts every writer at once on one database (a new SQLite file by
default; give --db for a PostgreSQL database), waits, and prints the campaigns stored, the wall
time, campaigns per second, and the integrity check's findings (none expected). Then it starts
one more writer of 200 campaigns, SIGKILLs it after 20 commits, and checks again that every
campaign it reported committed is there and no campaign is partial.
"""

from __future__ import annotations

import argparse
import os
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from axiscal.history import Drift, drifting_results, integrity_problems, list_campaigns, write_results

FIGURES = {f"positioning.{axis}.{name}": Drift(10.0, 1.0, 1.0, 30.0) for axis in "XYZ" for name in "AEBR"}


def writer(files: list[Path], db: str, **kwargs) -> subprocess.Popen:
    return subprocess.Popen([sys.executable, "-m", "axiscal.cli.main", "history", "add", *map(str, files), "--db", db],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, **kwargs)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--writers", type=int, default=8)
    parser.add_argument("--campaigns", type=int, default=50)
    parser.add_argument("--db", help="database URL (default: a new SQLite file)")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        folder = Path(folder)
        db = args.db or f"sqlite:///{folder / 'history.sqlite'}"
        batches = [write_results(folder / f"w{n}", drifting_results(FIGURES, machine=f"M{n}", campaigns=args.campaigns,
                                                                    seed=n)) for n in range(args.writers)]
        start = time.perf_counter()
        jobs = [writer(batch, db) for batch in batches]
        for job in jobs:
            _, err = job.communicate()
            if job.returncode:
                raise SystemExit(err)
        elapsed = time.perf_counter() - start
        stored = len(list_campaigns(url=db))
        problems = integrity_problems(db)
        print(f"{args.writers} writers x {args.campaigns} campaigns: {stored} stored in {elapsed:.1f} s "
              f"({stored / elapsed:.1f} campaigns/s); integrity problems: {len(problems)}")
        files = write_results(folder / "killed", drifting_results(FIGURES, machine="K", campaigns=200, seed=99))
        job = writer(files, db, start_new_session=True)
        committed = []
        for line in job.stdout:
            committed.append(int(line.split()[2].rstrip(":")))
            if len(committed) == 20:
                os.kill(job.pid, signal.SIGKILL)
                break
        job.wait()
        ids = {c.id for c in list_campaigns("K", url=db)}
        print(f"SIGKILLed writer: {len(committed)} reported committed, {len(ids)} stored, all reported present: "
              f"{set(committed) <= ids}; integrity problems: {len(integrity_problems(db))}")


if __name__ == "__main__":
    main()
