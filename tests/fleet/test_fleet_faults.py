"""``fleet report -o OUT`` under SIGKILL: OUT is always the earlier fleet report or the new one, whole.

A helper process generates two plants with the same campaign folders but other readings (seeds 0
and 1), writes each plant's fleet report as a reference, then for each trial forks a writer of one
plant's report over the current OUT (Dask's threads) and kills it with SIGKILL after a delay spread
over one and a half times a whole run (and one kill after twice it). After every kill the campaign
folders and fleet.json in OUT must all belong to one plant (their results.json byte for byte, fleet.json's rows), with no
campaign folder of the other; the next run removes the temporary folders killed runs left.
"""

from __future__ import annotations

import hashlib
import json
import os
import random
import subprocess
import sys
import threading
from pathlib import Path

import pytest

from axiscal.errors import AxiscalError
from axiscal.fleet import fleet_report

pytestmark = pytest.mark.filterwarnings("ignore::UserWarning")

TRIALS = 5

HELPER = r"""
import json, os, shutil, signal, sys, time
from pathlib import Path
from axiscal.fleet import fleet_report, generated_fleet

root = Path(sys.argv[1])
out = root / "out"
for which, seed in (("a", 0), ("b", 1)):
    generated_fleet(root / f"plant_{which}", machines=1, campaigns=3, seed=seed)


def forked(which, target):
    # every run in a fresh child: this process never starts threads that a fork would lose
    pid = os.fork()
    if pid == 0:
        try:
            fleet_report(root / f"plant_{which}", target, scheduler="threads", workers=1)
        finally:
            os._exit(0)
    return pid


os.waitpid(forked("b", root / "reference_b"), 0)
began = time.perf_counter()  # how long a forked writer takes, start to exit
os.waitpid(forked("a", root / "reference_a"), 0)
seconds = time.perf_counter() - began
shutil.copytree(root / "reference_a", out)
print(json.dumps({"seconds": seconds}), flush=True)
for line in sys.stdin:
    which, delay = line.split()
    pid = forked(which, out)
    time.sleep(float(delay))
    os.kill(pid, signal.SIGKILL)
    os.waitpid(pid, 0)
    print("killed", flush=True)
"""


def _state(folder: Path) -> dict:
    """What identifies a fleet report: its campaign folders' results.json and fleet.json's rows."""
    fleet = json.loads((folder / "fleet.json").read_text())
    return {
        "folders": sorted(p.name for p in folder.iterdir()),
        "results": {p.parent.name: hashlib.sha256(p.read_bytes()).hexdigest() for p in sorted(folder.glob("*/results.json"))},
        "reports": sorted(p.parent.name for p in folder.glob("*/report.html")),
        "machines": fleet["machines"],
        "campaigns": [(Path(c["folder"]).name, c["verdict"]) for c in fleet["campaigns"]],
    }


def test_a_killed_fleet_report_leaves_the_old_or_the_new_output_whole(tmp_path):
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1", MPLBACKEND="Agg",
               PYTHONPATH=os.pathsep.join([str(Path(__file__).resolve().parents[2] / "src"), os.environ.get("PYTHONPATH", "")]))
    helper = subprocess.Popen([sys.executable, "-W", "ignore", "-c", HELPER, str(tmp_path)],
                              stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True, env=env)
    out = tmp_path / "out"
    watchdog = threading.Timer(240.0, helper.kill)  # a hung helper fails the test instead of stalling the suite
    watchdog.start()
    try:
        seconds = json.loads(helper.stdout.readline())["seconds"]
        versions = {which: _state(tmp_path / f"reference_{which}") for which in "ab"}
        for state in versions.values():
            state["machines"] = [{k: v for k, v in m.items() if k != "report"} for m in state["machines"]]
        assert versions["a"]["folders"] == versions["b"]["folders"] and versions["a"]["results"] != versions["b"]["results"]
        delays = [1.5 * seconds * (k + random.Random(9 + k).random()) / (TRIALS - 1) for k in range(TRIALS - 1)]
        random.Random(9).shuffle(delays)
        current, seen = "a", set()
        for trial, delay in enumerate(delays + [2.0 * seconds]):
            target = "b" if current == "a" else "a"
            helper.stdin.write(f"{target} {delay:.4f}\n")
            helper.stdin.flush()
            assert helper.stdout.readline().strip() == "killed"
            now = _state(out)
            now["machines"] = [{k: v for k, v in m.items() if k != "report"} for m in now["machines"]]
            state = next((which for which, files in versions.items() if files == now), None)
            assert state in (current, target), f"trial {trial}: OUT mixes two runs: {now['folders']}"
            seen.add("new" if state == target else "old")
            current = state
        helper.stdin.close()
        assert helper.wait(timeout=120) == 0
    finally:
        watchdog.cancel()
        if helper.poll() is None:
            helper.kill()
            helper.wait()
    assert seen == {"old", "new"}, "the kills should land both before and after the swap"
    # a later run removes the temporary folders the killed runs left beside OUT
    fleet_report(tmp_path / "plant_b", out, scheduler="threads")
    assert sorted(p.name for p in tmp_path.iterdir() if p.name.startswith(".")) == []
    assert sorted(p.name for p in out.iterdir()) == versions["b"]["folders"]


def test_an_output_folder_of_something_else_is_refused_and_left_alone(run_cli, tmp_path):
    from axiscal.fleet import generated_fleet

    generated_fleet(tmp_path / "plant", machines=1, campaigns=1)
    folder = tmp_path / "notes"
    folder.mkdir()
    (folder / "mine.txt").write_text("my notes\n")
    status, out, err = run_cli("fleet", "report", tmp_path / "plant", "-o", folder, "--scheduler", "threads")
    assert status == 2 and out == "" and len(err.splitlines()) == 1
    assert "notes: holds files that are not an earlier output of this command (no fleet.json)" in err
    assert [p.name for p in folder.iterdir()] == ["mine.txt"]
    with pytest.raises(AxiscalError, match="exists and is not a folder"):
        fleet_report(tmp_path / "plant", folder / "mine.txt", scheduler="threads")
