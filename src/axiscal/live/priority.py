"""Scheduling priority of the live loop: real-time where the system allows it, said plainly where it refuses.

On a computer whose cores are busy with other work, a frame waits for the loop to be given a
core again; at normal priority that wait is the scheduler's time slice, milliseconds. A thread
with a real-time policy (``SCHED_FIFO``) is given a core as soon as its frames arrive, ahead of
every normal process. Linux allows it to root, to a process with ``CAP_SYS_NICE`` and to a user
whose ``RLIMIT_RTPRIO`` is raised (``ulimit -r``, ``/etc/security/limits.conf``); otherwise it
refuses, and :func:`raise_priority` asks for a lower nice value instead (allowed by
``RLIMIT_NICE``), and failing that leaves the priority as it was. Either way
:attr:`Priority.text` says what was obtained and what was refused.

The priority is the calling thread's (Linux schedules threads), and threads it starts afterwards
inherit it: the live session raises it before it starts the record's sync thread, so that thread
never holds the interpreter lock while descheduled behind other work. The dashboard's process
(:mod:`axiscal.live.dashboard`) drops it as it starts.
:func:`restore_priority` puts the thread back as it was.
"""

from __future__ import annotations

import os
from dataclasses import dataclass

from axiscal.io.arguments import check_count

__all__ = ["Priority", "raise_priority", "restore_priority", "below_the_loop"]


@dataclass(frozen=True)
class Priority:
    """What :func:`raise_priority` obtained, and how to go back.

    Attributes
    ----------
    kind : str
        ``"real-time"`` (``SCHED_FIFO``), ``"raised"`` (a lower nice value) or ``"normal"``.
    text : str
        One line for the user: what the loop runs at and, when real-time was refused, why.
    previous_policy, previous_nice : int
        The thread's scheduling policy and nice value before (for :func:`restore_priority`).
    """

    kind: str
    text: str
    previous_policy: int
    previous_nice: int


def _refusal(exc: OSError) -> str:
    return exc.strerror or str(exc)


def raise_priority(*, realtime_priority: int = 10, nice: int = 10) -> Priority:
    """Give the calling thread a real-time priority, else a lower nice value, else leave it; say which.

    Parameters
    ----------
    realtime_priority : int, keyword-only
        ``SCHED_FIFO`` priority asked for, 1 to 99 (10, as ``chrt -f 10`` gives: above every
        normal process, below the kernel's own real-time threads).
    nice : int, keyword-only
        How far to lower the nice value when real-time is refused, 1 to 20 (10: nice -10 from 0).

    Returns
    -------
    Priority
        What was obtained; ``text`` names what was refused and why (e.g. ``Operation not
        permitted``).

    Raises
    ------
    AxiscalError
        For a priority outside 1-99 or a nice step outside 1-20.
    """
    realtime_priority = check_count("realtime_priority", realtime_priority, minimum=1, maximum=99)
    nice = check_count("nice", nice, minimum=1, maximum=20)
    if not hasattr(os, "sched_setscheduler"):
        return Priority("normal", "priority: normal (this system has no real-time scheduling for processes)", 0, 0)
    policy = os.sched_getscheduler(0)
    current = os.getpriority(os.PRIO_PROCESS, 0)
    if policy in (os.SCHED_FIFO, os.SCHED_RR):
        return Priority("real-time", "priority: real-time, as started (already a real-time policy)", policy, current)
    try:
        os.sched_setscheduler(0, os.SCHED_FIFO, os.sched_param(realtime_priority))
    except OSError as exc:
        refused = _refusal(exc)
    else:
        return Priority("real-time", f"priority: real-time (SCHED_FIFO {realtime_priority})", policy, current)
    target = max(current - nice, -20)
    try:
        os.setpriority(os.PRIO_PROCESS, 0, target)
    except OSError as exc:
        return Priority(
            "normal",
            f"priority: normal (real-time refused: {refused}; a lower nice value refused: {_refusal(exc)}); "
            "other work on this computer can delay the frames by milliseconds",
            policy,
            current,
        )
    return Priority("raised", f"priority: nice {target} (real-time refused: {refused})", policy, current)


def restore_priority(priority: Priority) -> None:
    """Put the calling thread back to the policy and nice value it had before :func:`raise_priority`.

    Parameters
    ----------
    priority : Priority
        What :func:`raise_priority` returned (in this thread).

    Returns
    -------
    None
    """
    from axiscal.io.arguments import check_instance

    check_instance("priority", priority, Priority, what="what raise_priority returned")
    if priority.kind == "real-time" and priority.previous_policy not in (os.SCHED_FIFO, os.SCHED_RR):
        try:
            os.sched_setscheduler(0, priority.previous_policy, os.sched_param(0))
        except OSError:
            pass
    if priority.kind == "raised":
        try:
            os.setpriority(os.PRIO_PROCESS, 0, priority.previous_nice)
        except OSError:
            pass


def below_the_loop() -> None:
    """Put the calling thread one real-time step below the real-time priority it inherited, if any.

    A dashboard's server thread in the loop's process (:class:`~axiscal.live.server.LiveServer`) calls it as it
    starts. Inheriting the loop's ``SCHED_FIFO`` priority, it kept
    a core whenever it had work (a state made and sent ten times a second) and the loop, of the same priority,
    waited for the core: real-time threads of one priority do not preempt each other. One step below, the
    loop takes the core from it at once, while it still runs ahead of every normal process (so it is never
    left holding the interpreter lock behind them). At a normal policy nothing changes.

    Returns
    -------
    None
        A system that refuses the change leaves the thread as it was, without an error.
    """
    try:
        if os.sched_getscheduler(0) != os.SCHED_FIFO:
            return
        level = os.sched_getparam(0).sched_priority
        if level > 1:
            os.sched_setscheduler(0, os.SCHED_FIFO, os.sched_param(level - 1))
    except OSError:  # a system that refuses: the thread keeps what it has
        return
