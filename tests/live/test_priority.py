"""The live loop's scheduling priority: real-time where allowed, a lower nice value else, said plainly when refused."""

from __future__ import annotations

import errno
import os
import threading

import pytest

from axiscal.errors import AxiscalError
from axiscal.live import priority as priority_module
from axiscal.live.priority import raise_priority, restore_priority
from axiscal.live.session import LiveSession

pytestmark = pytest.mark.skipif(not hasattr(os, "sched_setscheduler"), reason="scheduling policies are Linux's")


def in_thread(work):
    """Run ``work`` in a thread of its own (the priority is a thread's: the test's own stays as it is)."""
    result = {}

    def target():
        try:
            result["value"] = work()
        except BaseException as exc:  # handed to the test
            result["error"] = exc

    thread = threading.Thread(target=target)
    thread.start()
    thread.join(30)
    if "error" in result:
        raise result["error"]
    return result["value"]


def refuse(*args):
    raise PermissionError(errno.EPERM, os.strerror(errno.EPERM))


def test_refused_real_time_and_nice_are_said_and_nothing_changes(monkeypatch):
    # a thread started by an earlier test of this worker may have left the process real-time: start from normal
    monkeypatch.setattr(priority_module.os, "sched_getscheduler", lambda pid: os.SCHED_OTHER)
    monkeypatch.setattr(priority_module.os, "sched_setscheduler", refuse)
    monkeypatch.setattr(priority_module.os, "setpriority", refuse)
    got = raise_priority()
    assert got.kind == "normal"
    assert "real-time refused: Operation not permitted" in got.text
    assert "nice value refused" in got.text
    restore_priority(got)  # nothing to restore, and no error


def test_refused_real_time_falls_back_to_a_lower_nice_value(monkeypatch):
    asked = []
    monkeypatch.setattr(priority_module.os, "sched_getscheduler", lambda pid: os.SCHED_OTHER)
    monkeypatch.setattr(priority_module.os, "sched_setscheduler", refuse)
    monkeypatch.setattr(priority_module.os, "getpriority", lambda *args: 0)
    monkeypatch.setattr(priority_module.os, "setpriority", lambda which, who, value: asked.append(value))
    got = raise_priority(nice=10)
    assert got.kind == "raised"
    assert got.text == "priority: nice -10 (real-time refused: Operation not permitted)"
    restore_priority(got)
    assert asked == [-10, 0]


def test_the_thread_is_raised_and_restored_as_the_system_allows():
    def work():
        before = os.sched_getscheduler(0), os.getpriority(os.PRIO_PROCESS, 0)
        got = raise_priority()
        during = os.sched_getscheduler(0), os.getpriority(os.PRIO_PROCESS, 0)
        restore_priority(got)
        return before, got, during, (os.sched_getscheduler(0), os.getpriority(os.PRIO_PROCESS, 0))

    before, got, during, after = in_thread(work)
    if got.kind == "real-time":
        assert during[0] == os.SCHED_FIFO
    elif got.kind == "raised":
        assert during[1] < before[1]
    else:
        assert "refused" in got.text
    assert after == before


@pytest.mark.parametrize("keywords", [{"realtime_priority": 0}, {"realtime_priority": 100}, {"nice": 0}, {"nice": 21}, {"nice": 1.5}])
def test_bad_arguments_are_refused(keywords):
    with pytest.raises(AxiscalError):
        raise_priority(**keywords)


def test_a_live_session_raises_its_thread_and_gives_it_back_on_close():
    def work():
        before = os.sched_getscheduler(0), os.getpriority(os.PRIO_PROCESS, 0)
        with LiveSession(server=False, rate_hz=1000.0, realtime=True) as session:
            got = session.priority
            shown = session.pipeline.priority
        return before, got, shown, (os.sched_getscheduler(0), os.getpriority(os.PRIO_PROCESS, 0))

    before, got, shown, after = in_thread(work)
    assert got is not None and shown == got.text and shown.startswith("priority: ")
    assert after == before


def test_a_session_not_asked_to_raise_or_replaying_as_fast_as_possible_stays_normal(tmp_path):
    with LiveSession(server=False) as session:  # a library caller keeps its priority unless it asks
        assert session.priority is None
    with LiveSession(server=False, duration_s=0.2, record=tmp_path / "run.csv") as session:
        session.run(duration_s=0.2)
    with LiveSession(server=False, source=f"replay:{tmp_path / 'run.csv'}", pace=False, realtime=True) as session:
        assert session.priority is None


def test_the_dashboard_s_thread_goes_one_real_time_step_below_the_loop():
    """A thread that inherited the loop's SCHED_FIFO 10 goes to 9 (the loop then takes the core from it);
    one at a normal policy, or refused, stays as it was."""
    from axiscal.live.priority import below_the_loop

    def work():
        got = raise_priority(realtime_priority=10)
        if got.kind != "real-time":
            restore_priority(got)
            return got, None

        def child():  # started after the raise: it inherits SCHED_FIFO 10
            below_the_loop()
            return os.sched_getscheduler(0), os.sched_getparam(0).sched_priority

        seen = in_thread(child)
        restore_priority(got)
        return got, seen

    got, seen = in_thread(work)
    if got.kind != "real-time":
        pytest.skip(f"this system refuses a real-time priority: {got.text}")
    assert seen == (os.SCHED_FIFO, 9)


def test_below_the_loop_leaves_a_normal_or_refusing_thread_alone(monkeypatch):
    from axiscal.live.priority import below_the_loop

    in_thread(below_the_loop)  # at a normal policy: nothing changes and nothing is raised
    monkeypatch.setattr(priority_module.os, "sched_getscheduler", lambda pid: os.SCHED_FIFO)
    monkeypatch.setattr(priority_module.os, "sched_getparam", lambda pid: os.sched_param(10))
    monkeypatch.setattr(priority_module.os, "sched_setscheduler", refuse)
    below_the_loop()  # refused: kept as it is, no error
