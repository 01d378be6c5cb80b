"""`axiscal capture` killed (SIGKILL) at random moments while it writes RUN.csv over an older one.

After every kill RUN.csv is the old run or the new one, whole, never a mix, and what the capture
left can be finished: the partial file is resumed (a resume that is itself killed included) and
gives the same run as a capture that was never interrupted.

The command runs in processes forked from one that has already imported axiscal (the command's
own code, ``axiscal.cli.main.main``, in a fresh process), so that each kill lands somewhere in the
capture's work rather than in Python's start-up.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

import axiscal
from axiscal.capture import capture_to_file, partial_path, plan_steps
from axiscal.capture.sources import plan_motions
from axiscal.capture.virtual import simulate_motions, write_recording
from axiscal.model.machine import load_machine
from axiscal.positioning.plan import plan_test, write_plan
from axiscal.report.demo import builtin_example

#: kills of a capture writing over an older run (each followed, when it left a partial file, by a killed resume)
TRIALS = 16

#: the process the commands are forked from: it runs the command once (its argv the script's
#: argument) so that every module it uses is loaded, then for each line (a JSON argv) forks a child
#: that runs the command, prints its pid, then how it ended
FORKER = r"""
import json, os, sys
from axiscal.cli.main import main
assert main(json.loads(sys.argv[1])) == 0
print("ready", flush=True)
for line in sys.stdin:
    pid = os.fork()
    if pid == 0:
        os._exit(main(json.loads(line)))
    print(pid, flush=True)
    print(os.waitpid(pid, 0)[1], flush=True)
"""


class Forker:
    """Runs ``axiscal`` commands in forked processes; kills them after a delay."""

    def __init__(self, warm_up: list[str]):
        env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(Path(axiscal.__file__).parents[1]), os.environ.get("PYTHONPATH", "")]))
        self.process = subprocess.Popen([sys.executable, "-c", FORKER, json.dumps(warm_up)], stdin=subprocess.PIPE,
                                        stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True, env=env)
        assert self.process.stdout.readline().strip() == "ready"

    def run(self, argv: list[str], kill_after_s: float | None = None) -> tuple[int, float]:
        """Run the command; kill it after ``kill_after_s`` (None: let it finish). Its wait status and how long it ran."""
        began = time.monotonic()
        self.process.stdin.write(json.dumps(argv) + "\n")
        self.process.stdin.flush()
        pid = int(self.process.stdout.readline())
        if kill_after_s is not None:
            time.sleep(kill_after_s)
            try:
                os.kill(pid, signal.SIGKILL)
            except ProcessLookupError:
                pass  # it had finished
        status = int(self.process.stdout.readline())
        return status, time.monotonic() - began

    def close(self) -> None:
        self.process.stdin.close()
        self.process.wait(timeout=10)


@pytest.fixture(scope="module")
def setup(tmp_path_factory):
    """A 5-run plan of 80 stops, its recording, the run it gives (new) and an older run of another recording (old)."""
    folder = tmp_path_factory.mktemp("faults")
    plan = plan_test(0.0, 0.19, 8, runs=5, seed=3)
    write_plan(plan, folder / "plan.csv")
    machine = load_machine(builtin_example() / "machine.toml")
    motions = plan_motions(plan_steps(plan), dwell_s=1.0)
    for name, seed in (("rec.csv", 1), ("older.csv", 2)):
        write_recording(simulate_motions(motions, machine, axis="X", rate_hz=200.0, seed=seed), folder / name)
    forker = Forker(["capture", str(folder / "plan.csv"), "--from", str(folder / "older.csv"), "-o", str(folder / "old.csv")])
    status, took = forker.run(["capture", str(folder / "plan.csv"), "--from", str(folder / "rec.csv"), "-o", str(folder / "new.csv")])
    assert status == 0
    yield {"folder": folder, "forker": forker, "took": took, "old": (folder / "old.csv").read_bytes(),
           "old_json": (folder / "old.json").read_bytes(), "new": (folder / "new.csv").read_bytes()}
    forker.close()


def test_a_killed_capture_leaves_the_old_run_or_the_new_one_and_a_resumable_partial(setup, tmp_path):
    rng = np.random.default_rng(2028)
    folder, forker = setup["folder"], setup["forker"]
    outcomes = {"old": 0, "new": 0, "partial": 0, "temporaries left": 0}
    for trial in range(TRIALS):
        here = tmp_path / f"trial{trial}"
        here.mkdir()
        out = here / "run.csv"
        out.write_bytes(setup["old"])
        (here / "run.json").write_bytes(setup["old_json"])
        argv = ["capture", str(folder / "plan.csv"), "--from", str(folder / "rec.csv"), "-o", str(out)]
        forker.run(argv, kill_after_s=float(rng.uniform(0.0, 1.2 * setup["took"])))
        written = out.read_bytes()
        assert written in (setup["old"], setup["new"]), f"trial {trial}: RUN.csv mixed"
        check_pair(out, setup, trial)
        outcomes["old" if written == setup["old"] else "new"] += 1
        if partial_path(out).exists():
            outcomes["partial"] += 1
            # a resume killed in its turn, then one that finishes: the run of a capture never interrupted
            forker.run(argv + ["--resume"], kill_after_s=float(rng.uniform(0.0, 1.2 * setup["took"])))
            assert out.read_bytes() in (setup["old"], setup["new"]), f"trial {trial}: RUN.csv mixed by a killed resume"
            check_pair(out, setup, trial)
            if partial_path(out).exists():
                capture_to_file(folder / "plan.csv", folder / "rec.csv", out, resume=True)
        elif out.read_bytes() == setup["old"]:
            capture_to_file(folder / "plan.csv", folder / "rec.csv", out)  # killed before its first stop: nothing to resume
        assert out.read_bytes() == setup["new"], f"trial {trial}: the finished run differs from an uninterrupted one"
        assert not partial_path(out).exists()
        outcomes["temporaries left"] += len(list(here.glob(".run.csv.*")) + list(here.glob(".run.json.*")))
    print(f"\n{TRIALS} kills over {setup['took']:.2f} s of capture: {outcomes}")


def check_pair(out, setup, trial):
    """The sidecar is whole; without a partial file (the capture done) it is the one of the run beside it."""
    sidecar = json.loads(out.with_suffix(".json").read_text())
    if not partial_path(out).exists():
        old = out.read_bytes() == setup["old"]
        assert ("older.csv" in sidecar["source"]) == old, f"trial {trial}: RUN.csv and RUN.json of two captures"
