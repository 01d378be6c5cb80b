"""Atomic writes: a failure part-way, or the process killed part-way, leaves the old file whole."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap

import pytest

from axiscal.errors import AxiscalError
from axiscal.io.atomic import atomic_write, write_text


def test_a_failure_while_writing_leaves_the_old_file_and_no_temporary(tmp_path):
    target = tmp_path / "table.csv"
    target.write_text("old table\n")

    def half_then_fail(path):
        path.write_text("new ta")
        raise OSError(28, "No space left on device")

    with pytest.raises(AxiscalError, match="No space left on device") as caught:
        atomic_write(target, half_then_fail)
    assert caught.value.path == str(target)
    assert target.read_text() == "old table\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["table.csv"]


def test_an_exception_of_the_caller_also_leaves_the_old_file(tmp_path):
    target = tmp_path / "table.csv"
    target.write_text("old table\n")
    with pytest.raises(ZeroDivisionError):
        atomic_write(target, lambda path: (path.write_text("new"), 1 / 0))
    assert target.read_text() == "old table\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["table.csv"]


def test_writes_replace_keep_the_mode_and_make_folders(tmp_path):
    target = tmp_path / "deep" / "er" / "table.csv"
    write_text(target, "one\n")
    os.chmod(target, 0o640)
    write_text(target, "two\n")
    assert target.read_text() == "two\n" and (target.stat().st_mode & 0o777) == 0o640


@pytest.mark.parametrize("where", ["/dev/full", "folder"])
def test_an_unwritable_target_is_one_error(tmp_path, where):
    target = tmp_path if where == "folder" else "/dev/full"
    with pytest.raises(AxiscalError):
        write_text(target, "x\n")


def test_sigkill_in_the_middle_of_a_write_leaves_the_old_file(tmp_path):
    target = tmp_path / "table.csv"
    target.write_text("old table\n")
    script = textwrap.dedent(
        f"""
        import sys, time
        from axiscal.io.atomic import atomic_write

        def slow(path):
            with open(path, "w") as handle:
                handle.write("new table, first half")
                handle.flush()
                print("writing", flush=True)
                time.sleep(60)
                handle.write(" and the rest\\n")

        atomic_write({str(target)!r}, slow)
        """
    )
    process = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, text=True)
    try:
        assert process.stdout.readline().strip() == "writing"
        process.send_signal(signal.SIGKILL)
        process.wait(timeout=10)
    finally:
        if process.poll() is None:
            process.kill()
    assert process.returncode == -signal.SIGKILL
    assert target.read_text() == "old table\n"


def test_a_device_is_written_not_replaced(tmp_path):
    before = os.stat("/dev/null")
    write_text("/dev/null", "discarded\n")
    after = os.stat("/dev/null")
    assert (after.st_rdev, after.st_mode) == (before.st_rdev, before.st_mode)
    assert os.path.exists("/dev/full") and not os.path.isfile("/dev/full")


def test_a_link_is_followed(tmp_path):
    real = tmp_path / "real.csv"
    real.write_text("old\n")
    link = tmp_path / "link.csv"
    link.symlink_to(real)
    write_text(link, "new\n")
    assert link.is_symlink() and real.read_text() == "new\n"


def _dead_pid() -> int:
    """The id of a process that has ended (a child that exited and was reaped)."""
    child = subprocess.Popen([sys.executable, "-c", "pass"])
    child.wait()
    return child.pid


def test_stale_temporaries_of_a_killed_write_are_removed_and_live_ones_kept(tmp_path):
    from axiscal.io.atomic import LEGACY_STALE_S, remove_stale_temporaries

    target = tmp_path / "part.ngc"
    target.write_text("old\n")
    dead = tmp_path / f".part.ngc.{_dead_pid()}-abcd1234.ngc"
    live = tmp_path / f".part.ngc.{os.getpid()}-abcd1234.ngc"
    legacy_old = tmp_path / ".part.ngc.k2j4h5g6.ngc"
    legacy_new = tmp_path / ".part.ngc.q8w7e6r5.ngc"
    other = tmp_path / f".other.ngc.{_dead_pid()}-abcd1234.ngc"
    for path in (dead, live, legacy_old, legacy_new, other):
        path.write_text("half a program")
    os.utime(legacy_old, (0, os.stat(legacy_old).st_mtime - LEGACY_STALE_S - 5))
    assert sorted(remove_stale_temporaries(target)) == sorted([dead, legacy_old])
    assert not dead.exists() and not legacy_old.exists()
    assert live.exists() and legacy_new.exists() and other.exists() and target.read_text() == "old\n"


def test_the_temporary_is_named_with_the_writing_process(tmp_path):
    seen = []
    write_text_to = tmp_path / "t.csv"
    atomic_write(write_text_to, lambda path: seen.append(path.name) or path.write_text("x\n"))
    assert seen[0].startswith(f".t.csv.{os.getpid()}-") and seen[0].endswith(".csv")
