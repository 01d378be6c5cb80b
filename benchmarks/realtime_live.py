"""Live latency: delay from a frame's time stamp to its result being in the record, at a 10 kHz source.

    .venv/bin/python benchmarks/realtime_live.py [--rate 10000] [--seconds 5] [--runs 1] [--busy 0] [--only tcp,dashboard,sim] [--state-cost]

``--busy N`` starts N processes that each keep a core busy (``yes > /dev/null``) for every run, as a
shop-floor laptop running other work does (the machine's core count: both cores busy on two). The
load average is printed with every run: on a shared machine a figure means little without it.

Three kinds of run, each printing frames sent and recorded, whether any frame was lost (the record's t_s
must be exactly k / rate, k = 0, 1, 2, ...) and the delay percentiles:

1. ``tcp``: a separate sender process plays the virtual module's frames over the TCP line protocol
   on 127.0.0.1, each frame sent once its time stamp has passed on the shared monotonic clock
   (CLOCK_MONOTONIC is one clock for all processes on Linux);
2. ``tcp + dashboard``: the same with the dashboard served by a process of its own
   (:class:`axiscal.live.dashboard.DashboardProcess`, as ``axiscal live`` serves it) and one
   WebSocket client reading; ``dashboard-thread`` (not run unless named in ``--only``) serves it
   from a thread of the loop's process instead (:class:`axiscal.live.server.LiveServer`), to
   compare the two side by side;
3. ``sim``: the in-process virtual instrument at the same rate.

The loop runs at the priority ``axiscal live`` gives it (:func:`axiscal.live.priority.raise_priority`:
real-time where allowed; ``--normal-priority`` to measure without). The TCP sender stands for the
acquisition box, which has a processor of its own: it keeps the loop's priority, so a busy core
delays the receiving side only (``--sender-normal-priority`` shares the cores with the busy
processes instead). The dashboard's client stands for a browser and runs at normal priority.

The delay is measured by the pipeline right after the batch's ``os.write`` to the record returned
(the frame then survives a crash of the process; ``fsync`` follows within the record's sync interval).

``--state-cost`` instead times what handing a batch of 20 frames (2 ms at 10 kHz) to the dashboard's
state costs the loop, at its priority and its 2 ms rhythm: kept and folded in the loop's process
(a dashboard in a thread), or written to the pipe of a dashboard in its own process (drained by ``cat``).
"""

from __future__ import annotations

import argparse
import gc
import json
import os
import socket
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from axiscal.live.pipeline import MS, SWITCH_INTERVAL_S, Pipeline
from axiscal.live.priority import raise_priority, restore_priority
from axiscal.live.recorder import Recorder, read_record
from axiscal.live.sources import Backoff, SimSource, TcpSource
from axiscal.live.state import LiveState, result_columns
from axiscal.measurement.virtual import VirtualModule


def sender(rate: float, seconds: float) -> None:
    """Child process: listen on a free loopback port, print 'port t0', send frames on time, close."""
    from axiscal.live.protocol import encode_lines

    module = VirtualModule(seed=0)
    system = module.measurement_system()
    n = int(rate * seconds)
    t = np.arange(n) / rate
    frames, _ = module.frames(t)
    lines = encode_lines(t, np.column_stack([frames[name] for name in system.channels])).splitlines(keepends=True)
    listener = socket.create_server(("127.0.0.1", 0))
    listener.settimeout(30.0)
    print(listener.getsockname()[1], flush=True)
    connection, _ = listener.accept()
    connection.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
    t0 = time.monotonic() + 0.2
    print(repr(t0), flush=True)
    sent = 0
    deadline = t0 + seconds + 10.0
    while sent < n and time.monotonic() < deadline:
        due = min(n, int((time.monotonic() - t0) * rate) + 1)
        if due > sent:
            connection.sendall(b"".join(lines[sent:due]))
            sent = due
        else:
            time.sleep(max(0.0, t0 + sent / rate - time.monotonic()))
    time.sleep(0.2)
    connection.close()
    listener.close()


def reader(port: int, seconds: float) -> None:
    """Child process: a dashboard client reading every state it is sent; prints how many it got."""
    from websockets.exceptions import ConnectionClosed
    from websockets.sync.client import connect

    received = 0
    deadline = time.monotonic() + seconds
    with connect(f"ws://127.0.0.1:{port}/ws", max_size=None) as client:
        while time.monotonic() < deadline:
            try:
                json.loads(client.recv(timeout=0.5))
                received += 1
            except TimeoutError:
                continue
            except ConnectionClosed:
                break
    print(received, flush=True)


def normal_priority() -> None:
    """In a child: drop the priority the loop's thread passed on (the sender and the browser are other programs)."""
    os.sched_setscheduler(0, os.SCHED_OTHER, os.sched_param(0))
    os.setpriority(os.PRIO_PROCESS, 0, 0)


def run(kind: str, rate: float, seconds: float, *, dashboard: str = "", raise_to_realtime: bool = True, sender_normal: bool = False) -> dict:
    """One run; ``dashboard`` is "" (none), "process" or "thread"."""
    priority = raise_priority() if raise_to_realtime else None  # as axiscal live does, before any thread starts
    try:
        return _run(kind, rate, seconds, dashboard=dashboard, sender_normal=sender_normal)
    finally:
        if priority is not None:
            restore_priority(priority)


def _run(kind: str, rate: float, seconds: float, *, dashboard: str, sender_normal: bool) -> dict:
    module = VirtualModule(seed=0)
    system = module.measurement_system()
    expected = int(rate * seconds)
    child = None
    if kind == "tcp":
        child = subprocess.Popen(
            [sys.executable, __file__, "--sender", "--rate", str(rate), "--seconds", str(seconds)],
            stdout=subprocess.PIPE,
            text=True,
            preexec_fn=normal_priority if sender_normal else None,  # else it keeps the loop's priority: the box has its own processor
        )
        port = int(child.stdout.readline())
        source = TcpSource("127.0.0.1", port, system.channels, backoff=Backoff(initial_s=0.01, maximum_s=0.1))
    else:
        source = SimSource(module, system.channels, rate_hz=rate)
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "record.csv"
        recorder = Recorder(path, system.channels, result_columns(system.axes))
        state = LiveState(system)
        pipeline = Pipeline(system, source, recorder=recorder, state=state)
        server = client = None
        if dashboard == "process":
            from axiscal.live.dashboard import DashboardProcess

            server = DashboardProcess(state, port=0, update_hz=10.0).start()
        elif dashboard == "thread":
            from axiscal.live.server import LiveServer, create_app

            server = LiveServer(create_app(state, update_hz=10.0), port=0).start()
        if server is not None:
            client = subprocess.Popen(
                [sys.executable, __file__, "--reader", str(server.port), "--seconds", str(seconds + 1.0)],
                stdout=subprocess.PIPE,
                text=True,
                preexec_fn=normal_priority,
            )
        if child is not None:
            while len(source.read(0.05)) == 0 and source.status.connections == 0:
                pass
            source.clock_offset_s = float(child.stdout.readline())
        deadline = time.monotonic() + seconds + 10.0
        gc.freeze()  # as Pipeline.run does
        switch = sys.getswitchinterval()
        sys.setswitchinterval(min(switch, SWITCH_INTERVAL_S))
        try:
            while pipeline.frames < expected and time.monotonic() < deadline:
                pipeline.step(0.02)
        finally:
            gc.unfreeze()
            sys.setswitchinterval(switch)
        summary = pipeline.summary(seconds)
        delays = pipeline.latencies_s() / MS
        received = 0
        if server is not None:
            received = int(client.stdout.readline() or 0)
            client.wait(timeout=10)
            server.stop()
        recorder.close()
        source.close()
        if child is not None:
            child.wait(timeout=30)
        record = read_record(path)
    t = record.columns["t_s"][:expected]
    lost = expected - len(t)
    in_order = len(t) == expected and np.allclose(t, np.arange(expected) / rate, atol=1e-9)
    return {
        "run": kind + {"": "", "process": " + dashboard", "thread": " + dash. thread"}[dashboard],
        "sent": expected,
        "recorded": len(t),
        "lost": lost,
        "exact": bool(in_order),
        "batches": summary.batches,
        "p50": np.percentile(delays, 50),
        "p99": np.percentile(delays, 99),
        "p999": np.percentile(delays, 99.9),
        "max": delays.max(),
        "dashboard_states": received,
    }


def state_cost(batches: int = 3000) -> None:
    """Print what ``LiveState.update`` costs the loop per 20-frame batch: kept in the state, or written to a dashboard's pipe."""
    from axiscal.live.dashboard import _Feed
    from axiscal.live.protocol import FrameBatch
    from axiscal.measurement.display import to_display

    priority = raise_priority()
    gc.freeze()
    module = VirtualModule(seed=0)
    system = module.measurement_system()
    frames, _ = module.frames(np.arange(20) / 10000.0)
    batch = FrameBatch.from_frames(frames, system.channels)
    fault, results = Pipeline(system, None).process(batch)
    shown = to_display(results)
    read_end, write_end = os.pipe()
    os.set_blocking(write_end, False)
    drain = subprocess.Popen(["cat"], stdin=read_end, stdout=subprocess.DEVNULL)
    os.close(read_end)
    kept, fed = LiveState(system), LiveState(system)
    fed._feed = _Feed(write_end)
    print(priority.text)
    try:
        for label, state in (("kept and folded in the loop's process", kept), ("written to the dashboard process's pipe", fed)):
            times = []
            for k in range(batches):  # the clock goes on from batch to batch, as in a run
                time.sleep(0.002)
                shifted = FrameBatch(batch.t_s + k * 0.002, batch.values, batch.malformed)
                start = time.perf_counter()
                state.update(shifted, fault, shown)
                times.append(time.perf_counter() - start)
            us = np.array(times) / MS * 1000.0
            print(f"{label:<42} per batch: mean {us.mean():7.1f} us  p50 {np.percentile(us, 50):7.1f}  p99 {np.percentile(us, 99):7.1f}  "
                  f"max {us.max():7.1f} us")
    finally:
        fed._feed.close()
        drain.wait(timeout=10)
        gc.unfreeze()
        restore_priority(priority)
    print("load average " + " ".join(f"{value:.2f}" for value in os.getloadavg()))


def busy_processes(count: int) -> list[subprocess.Popen]:
    """``count`` processes that each keep a core busy (``yes > /dev/null``), started at normal priority."""
    return [subprocess.Popen(["yes"], stdout=subprocess.DEVNULL, preexec_fn=normal_priority) for _ in range(count)]


KINDS = {"tcp": ("tcp", ""), "dashboard": ("tcp", "process"), "dashboard-thread": ("tcp", "thread"), "sim": ("sim", "")}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--rate", type=float, default=10000.0)
    parser.add_argument("--seconds", type=float, default=5.0)
    parser.add_argument("--runs", type=int, default=1, help="runs of each kind (the summary gives the worst)")
    parser.add_argument("--busy", type=int, default=0, help="processes keeping a core busy each during the runs")
    parser.add_argument("--only", default="tcp,dashboard,sim", help="kinds of run, comma-separated: tcp, dashboard, dashboard-thread, sim")
    parser.add_argument("--normal-priority", action="store_true", help="run the loop at normal priority (as without the rights to raise it)")
    parser.add_argument("--sender-normal-priority", action="store_true", help="the TCP sender at normal priority (default: the loop's)")
    parser.add_argument("--state-cost", action="store_true", help="time what handing a batch to the dashboard's state costs the loop, and stop")
    parser.add_argument("--sender", action="store_true", help=argparse.SUPPRESS)
    parser.add_argument("--reader", type=int, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.sender:
        sender(args.rate, args.seconds)
        return
    if args.reader:
        reader(args.reader, args.seconds)
        return
    if args.state_cost:
        state_cost()
        return
    kinds = [name.strip() for name in args.only.split(",") if name.strip()]
    unknown = [name for name in kinds if name not in KINDS]
    if unknown:
        parser.error(f"unknown kind(s) {', '.join(unknown)}; use {', '.join(KINDS)}")
    print(
        f"live latency at {args.rate:.0f} Hz for {args.seconds:g} s per run, {args.runs} run(s) of each kind, "
        f"{args.busy} busy process(es) (delay: time stamp -> written to the record)"
    )
    if args.normal_priority:
        print("priority: normal (--normal-priority)")
    else:
        priority = raise_priority()
        restore_priority(priority)
        print(priority.text + ("; TCP sender at normal priority" if args.sender_normal_priority else "; the TCP sender (the acquisition box) at the same"))
    print(
        f"{'run':<18} {'sent':>7} {'recorded':>8} {'lost':>5} {'t_s exact':>9} {'batches':>7} {'p50 ms':>7} {'p99 ms':>7} "
        f"{'p99.9 ms':>8} {'max ms':>7}  load average"
    )
    worst: dict[str, list[dict]] = {}
    for _ in range(args.runs):
        for name in kinds:
            kind, dashboard = KINDS[name]
            hogs = busy_processes(args.busy)
            try:
                time.sleep(0.2 if hogs else 0.0)
                r = run(
                    kind,
                    args.rate,
                    args.seconds,
                    dashboard=dashboard,
                    raise_to_realtime=not args.normal_priority,
                    sender_normal=args.sender_normal_priority,
                )
            finally:
                for hog in hogs:
                    hog.kill()
                    hog.wait()
            load = " ".join(f"{value:.2f}" for value in os.getloadavg())
            worst.setdefault(r["run"], []).append(r)
            print(
                f"{r['run']:<18} {r['sent']:>7} {r['recorded']:>8} {r['lost']:>5} {str(r['exact']):>9} {r['batches']:>7} "
                f"{r['p50']:>7.2f} {r['p99']:>7.2f} {r['p999']:>8.2f} {r['max']:>7.2f}  {load}"
                + (f"   (dashboard client got {r['dashboard_states']} states)" if dashboard else ""),
                flush=True,
            )
    if args.runs > 1:
        print("over all runs: p99 ms (lowest-highest), frames lost in all")
        for label, results in worst.items():
            p99 = [r["p99"] for r in results]
            print(f"{label:<18} p99 {min(p99):.2f}-{max(p99):.2f}  lost {sum(r['lost'] for r in results)}  exact {all(r['exact'] for r in results)}")


if __name__ == "__main__":
    main()
