"""Concurrent writers: several `history add` processes at once store every campaign once; a SIGKILLed
writer loses nothing it committed and leaves no partial campaign. (benchmarks/history_writers.py runs
the full 8 processes x 50 campaigns.)"""

from __future__ import annotations

import os
import signal
import subprocess
import sys

from axiscal.history import Drift, drifting_results, integrity_problems, list_campaigns, machine_history, write_results

_FIGURES = {f"positioning.{axis}.{name}": Drift(10.0, 1.0, 1.0, 30.0) for axis in "XYZ" for name in "AEBR"}


def _files(folder, machines: int, campaigns: int):
    out = []
    for m in range(machines):
        out.append(write_results(folder / f"m{m}", drifting_results(_FIGURES, machine=f"M{m}", campaigns=campaigns,
                                                                    seed=m)))
    return out


def _add(files, db_url, **kwargs):
    return subprocess.Popen([sys.executable, "-m", "axiscal.cli.main", "history", "add", *map(str, files),
                             "--db", db_url], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, **kwargs)


def test_four_writers_at_once_store_every_campaign_once(db_url, tmp_path):
    batches = _files(tmp_path, 4, 10)
    # each writer also adds the first three campaigns of the next: those must be stored once
    jobs = [_add(batch + batches[(n + 1) % 4][:3], db_url) for n, batch in enumerate(batches)]
    for job in jobs:
        out, err = job.communicate(timeout=300)
        assert job.returncode == 0, err
    assert len(list_campaigns(url=db_url)) == 40
    assert integrity_problems(db_url) == []
    assert all(len(c.figures) == len(_FIGURES) for c in machine_history("M2", url=db_url).campaigns)


def test_a_killed_writer_loses_nothing_committed_and_leaves_no_partial_campaign(db_url, tmp_path):
    files = _files(tmp_path, 1, 60)[0]
    job = _add(files, db_url, start_new_session=True)
    committed = []
    for line in job.stdout:
        committed.append(int(line.split()[2].rstrip(":")))
        if len(committed) == 5:
            os.kill(job.pid, signal.SIGKILL)
            break
    job.wait(timeout=60)
    job.stdout.close()
    job.stderr.close()
    stored = {c.id for c in list_campaigns(url=db_url)}
    assert set(committed) <= stored and len(stored) < 60
    assert integrity_problems(db_url) == []
