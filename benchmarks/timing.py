"""Timing helpers shared by the benchmark scripts."""

from __future__ import annotations

import statistics
import time
from collections.abc import Callable


def best_time(function: Callable[[], object], repeat: int) -> float:
    """Smallest wall-clock time of ``repeat`` calls, seconds (the least disturbed run)."""
    best = float("inf")
    for _ in range(repeat):
        start = time.perf_counter()
        function()
        best = min(best, time.perf_counter() - start)
    return best


def interleaved(functions: dict[str, Callable[[], object]], runs: int) -> dict[str, list[float]]:
    """Wall-clock times of ``runs`` rounds, each calling every function once in turn (A B A B ...),
    so that a drift of the machine's load touches them alike; seconds per call, by name."""
    times: dict[str, list[float]] = {name: [] for name in functions}
    for _ in range(runs):
        for name, function in functions.items():
            start = time.perf_counter()
            function()
            times[name].append(time.perf_counter() - start)
    return times


def median(times: list[float]) -> float:
    """The median of a list of times."""
    return statistics.median(times)


def median_ratio(times: list[float], reference: list[float]) -> float:
    """The median over rounds of ``times[k] / reference[k]`` (each ratio taken within one round)."""
    return statistics.median(a / b for a, b in zip(times, reference))
