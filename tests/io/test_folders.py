"""Atomic folders: the old or the new folder whole, temporaries of killed runs removed, others' kept."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

from axiscal.errors import AxiscalError
from axiscal.io import atomic_folder, stale_temporaries
import axiscal.io.folders as folders


def _fill(files):
    def fill(staging):
        for name, text in files.items():
            (staging / name).parent.mkdir(parents=True, exist_ok=True)
            (staging / name).write_text(text)
        return sorted(files)
    return fill


def _tree(folder):
    return {p.relative_to(folder).as_posix(): p.read_text() for p in folder.rglob("*") if p.is_file()}


@pytest.mark.parametrize("exchange", [True, False], ids=["renameat2", "two renames"])
def test_the_new_folder_replaces_the_old_one_whole(tmp_path, monkeypatch, exchange):
    if not exchange:
        monkeypatch.setattr(folders, "_exchange", lambda a, b: False)
    out = tmp_path / "deep" / "out"
    assert atomic_folder(out, _fill({"a.txt": "1", "sub/b.txt": "2", "marker.json": "{}"}), marker="marker.json") == \
        ["a.txt", "marker.json", "sub/b.txt"]
    atomic_folder(out, _fill({"c.txt": "3", "marker.json": "{}"}), marker="marker.json")
    assert _tree(out) == {"c.txt": "3", "marker.json": "{}"}
    assert [p.name for p in out.parent.iterdir()] == ["out"]


def test_a_failing_fill_leaves_the_old_folder_and_no_temporary(tmp_path):
    out = tmp_path / "out"
    atomic_folder(out, _fill({"a.txt": "old"}))

    def broken(staging):
        (staging / "a.txt").write_text("half")
        raise AxiscalError("the data are bad")

    with pytest.raises(AxiscalError, match="the data are bad"):
        atomic_folder(out, broken)
    assert _tree(out) == {"a.txt": "old"} and [p.name for p in tmp_path.iterdir()] == ["out"]


def test_a_file_or_a_folder_of_something_else_is_refused(tmp_path):
    (tmp_path / "file").write_text("x")
    with pytest.raises(AxiscalError, match="exists and is not a folder"):
        atomic_folder(tmp_path / "file", _fill({}))
    (tmp_path / "mine").mkdir()
    (tmp_path / "mine" / "notes.txt").write_text("keep me")
    with pytest.raises(AxiscalError, match=r"holds files that are not an earlier output of this command \(no out.json\)"):
        atomic_folder(tmp_path / "mine", _fill({"out.json": "{}"}), marker="out.json")
    assert _tree(tmp_path / "mine") == {"notes.txt": "keep me"}
    (tmp_path / "empty").mkdir()
    atomic_folder(tmp_path / "empty", _fill({"out.json": "{}"}), marker="out.json")
    assert _tree(tmp_path / "empty") == {"out.json": "{}"}


def test_only_the_temporaries_of_processes_that_are_gone_are_removed(tmp_path):
    gone = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True, text=True)
    dead = int(gone.stdout)
    out = tmp_path / "out"
    left = tmp_path / f".out.axiscal-{dead}-abc123"
    left.mkdir()
    (left / "half.csv").write_text("x")
    running = tmp_path / f".out.axiscal-{os.getppid()}-def456"  # a run still going (our parent is alive)
    running.mkdir()
    other = tmp_path / f".other.axiscal-{dead}-xyz"  # another output's
    other.mkdir()
    assert stale_temporaries(out) == [left]
    atomic_folder(out, _fill({"a.txt": "1"}))
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(["out", running.name, other.name])
