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
import subprocess
import sys
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
#: argument) so that every module it uses is loaded, then for each line (a delay, or none, and a
#: JSON argv) forks a child that runs the command, kills it after the delay if it is still running
#: (the child is not reaped before, so its pid is its own), and prints how it ended and when
FORKER = r"""
import json, os, signal, sys, time
from axiscal.cli.main import main
assert main(json.loads(sys.argv[1])) == 0
print("ready", flush=True)
for line in sys.stdin:
    delay, argv = json.loads(line)
    began = time.monotonic()
    pid = os.fork()
    if pid == 0:
        os._exit(main(argv))
    killed = False
    while True:
        done, status = os.waitpid(pid, os.WNOHANG)
        if done:
            break
        if delay is not None and time.monotonic() - began >= delay:
            os.kill(pid, signal.SIGKILL)
            killed = True
            done, status = os.waitpid(pid, 0)
            break
        time.sleep(0.001)
    print(json.dumps([status, killed, time.monotonic() - began]), flush=True)
"""


class Forker:
    """Runs ``axiscal`` commands in forked processes, killed after a delay."""

    def __init__(self, warm_up: list[str]):
        env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(Path(axiscal.__file__).parents[1]), os.environ.get("PYTHONPATH", "")]))
        self.process = subprocess.Popen([sys.executable, "-c", FORKER, json.dumps(warm_up)], stdin=subprocess.PIPE,
                                        stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True, env=env)
        assert self.process.stdout.readline().strip() == "ready"

    def run(self, argv: list[str], kill_after_s: float | None = None) -> tuple[int, bool, float]:
        """Run the command; kill it after ``kill_after_s`` (None: let it finish). Its wait status, whether it was
        killed, and how long it ran."""
        self.process.stdin.write(json.dumps([kill_after_s, argv]) + "\n")
        self.process.stdin.flush()
        status, killed, took = json.loads(self.process.stdout.readline())
        return status, killed, took

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
    status, _, took = forker.run(["capture", str(folder / "plan.csv"), "--from", str(folder / "rec.csv"), "-o", str(folder / "new.csv")])
    assert status == 0
    yield {"folder": folder, "forker": forker, "took": took, "old": (folder / "old.csv").read_bytes(),
           "old_json": (folder / "old.json").read_bytes(), "new": (folder / "new.csv").read_bytes()}
    forker.close()


def test_a_killed_capture_leaves_the_old_run_or_the_new_one_and_a_resumable_partial(setup, tmp_path):
    rng = np.random.default_rng(2028)
    folder, forker = setup["folder"], setup["forker"]
    outcomes = {"killed": 0, "old": 0, "new": 0, "partial": 0, "resumes killed": 0, "temporaries left": 0}
    for trial in range(TRIALS):
        here = tmp_path / f"trial{trial}"
        here.mkdir()
        out = here / "run.csv"
        out.write_bytes(setup["old"])
        (here / "run.json").write_bytes(setup["old_json"])
        argv = ["capture", str(folder / "plan.csv"), "--from", str(folder / "rec.csv"), "-o", str(out)]
        _, killed, _ = forker.run(argv, kill_after_s=float(rng.uniform(0.0, 1.2 * setup["took"])))
        outcomes["killed"] += killed
        written = out.read_bytes()
        assert written in (setup["old"], setup["new"]), f"trial {trial}: RUN.csv mixed"
        check_pair(out, setup, trial)
        outcomes["old" if written == setup["old"] else "new"] += 1
        if partial_path(out).exists():
            outcomes["partial"] += 1
            # a resume killed in its turn, then one that finishes: the run of a capture never interrupted
            _, killed, _ = forker.run(argv + ["--resume"], kill_after_s=float(rng.uniform(0.0, 1.2 * setup["took"])))
            outcomes["resumes killed"] += killed
            assert out.read_bytes() in (setup["old"], setup["new"]), f"trial {trial}: RUN.csv mixed by a killed resume"
            check_pair(out, setup, trial)
        # what the user does next: resume what is left, or capture again where nothing is
        if partial_path(out).exists():
            capture_to_file(folder / "plan.csv", folder / "rec.csv", out, resume=True)
        elif out.read_bytes() == setup["old"]:
            # killed before its first stop (a partial that held none is started afresh, so a killed resume may leave none)
            capture_to_file(folder / "plan.csv", folder / "rec.csv", out)
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
