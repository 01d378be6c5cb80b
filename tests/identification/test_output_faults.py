"""``identify -o OUT`` under SIGKILL: OUT is always the earlier output or the new one, whole.

A helper process computes two identifications (A: one plate, poly:1; B: two plates, poly:2), then
for each trial forks a writer of A or B over the current OUT and kills it with SIGKILL after a
delay spread over twice the time a whole write takes. After every kill OUT must hold exactly the files
of A or of B (byte for byte), and the next write removes the temporary folders the killed ones left.
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

from axiscal.identification import identify, write_identification
from axiscal.errors import AxiscalError

TRIALS = 8

HELPER = r"""
import json, os, shutil, signal, sys, time
from pathlib import Path
from axiscal.identification import identify, write_identification

examples, out = Path(sys.argv[1]), Path(sys.argv[2])
start = examples / "start" / "machine.toml"
results = {"a": identify(start, [examples / "plate_xy.toml"], model="poly:1"),
           "b": identify(start, [examples / "plate_xy.toml", examples / "plate_xz.toml"], model="poly:2")}
write_identification(results["b"], out.parent / "reference_b")
began = time.perf_counter()  # how long a forked writer takes, start to exit
pid = os.fork()
if pid == 0:
    try:
        write_identification(results["a"], out.parent / "reference_a")
    finally:
        os._exit(0)
os.waitpid(pid, 0)
seconds = time.perf_counter() - began
shutil.copytree(out.parent / "reference_a", out)
print(json.dumps({"seconds": seconds}), flush=True)
for line in sys.stdin:
    which, delay = line.split()
    pid = os.fork()
    if pid == 0:
        try:
            write_identification(results[which], out)
        finally:
            os._exit(0)
    time.sleep(float(delay))
    os.kill(pid, signal.SIGKILL)
    os.waitpid(pid, 0)
    print("killed", flush=True)
"""


def _snapshot(folder: Path) -> dict[str, str]:
    return {p.relative_to(folder).as_posix(): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(folder.rglob("*")) if p.is_file()}


def test_a_killed_identify_leaves_the_old_or_the_new_output_whole(tmp_path, examples):
    out = tmp_path / "out"
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1", MPLBACKEND="Agg",
               PYTHONPATH=os.pathsep.join([str(Path(__file__).resolve().parents[2] / "src"), os.environ.get("PYTHONPATH", "")]))
    helper = subprocess.Popen([sys.executable, "-c", HELPER, str(examples / "identification"), str(out)],
                              stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True, env=env)
    watchdog = threading.Timer(240.0, helper.kill)  # a hung helper fails the test instead of stalling the suite
    watchdog.start()
    try:
        seconds = json.loads(helper.stdout.readline())["seconds"]
        versions = {which: _snapshot(tmp_path / f"reference_{which}") for which in "ab"}
        assert versions["a"] != versions["b"] and set(versions["a"]) != set(versions["b"])
        # kill moments spread over twice a whole write, in random order, and one well after it
        delays = [2.0 * seconds * (k + random.Random(28 + k).random()) / TRIALS for k in range(TRIALS - 1)]
        random.Random(28).shuffle(delays)
        current, seen = "a", set()
        for trial, delay in enumerate(delays + [3.0 * seconds]):
            target = "b" if current == "a" else "a"
            helper.stdin.write(f"{target} {delay:.4f}\n")
            helper.stdin.flush()
            assert helper.stdout.readline().strip() == "killed"
            now = _snapshot(out)
            state = next((which for which, files in versions.items() if files == now), None)
            assert state in (current, target), f"trial {trial}: OUT is neither A nor B whole: {sorted(now)}"
            seen.add("new" if state == target else "old")
            current = state
        helper.stdin.close()
        assert helper.wait(timeout=60) == 0
    finally:
        watchdog.cancel()
        if helper.poll() is None:
            helper.kill()
            helper.wait()
    assert seen == {"old", "new"}, "the kills should land both before and after the swap"
    # a later run removes the temporary folders the killed writers left beside OUT
    result = identify(examples / "identification" / "start" / "machine.toml",
                      [examples / "identification" / "plate_xy.toml"], model="poly:1")
    write_identification(result, out)
    assert _snapshot(out) == versions["a"]
    assert [p.name for p in tmp_path.iterdir() if p.name.startswith(".")] == []


def test_an_output_folder_of_something_else_is_refused_and_left_alone(tmp_path, examples):
    folder = tmp_path / "notes"
    folder.mkdir()
    (folder / "mine.txt").write_text("my notes\n")
    result = identify(examples / "identification" / "start" / "machine.toml",
                      [examples / "identification" / "plate_xy.toml"], model="poly:1")
    with pytest.raises(AxiscalError, match=r"notes: holds files that are not an earlier output of this command \(no identify.json\)"):
        write_identification(result, folder)
    assert [p.name for p in folder.iterdir()] == ["mine.txt"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["notes"]
    files = write_identification(result, tmp_path / "new")
    assert files["json"] == tmp_path / "new" / "identify.json" and files["json"].is_file()
    assert all(path.is_file() and path.parent == tmp_path / "new" for key, path in files.items() if key != "machine")
