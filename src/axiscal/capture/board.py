"""What the capture's live page shows: the plan, the step awaited with its target, the reading, the stops taken."""

from __future__ import annotations

import math
import threading
from typing import Any

from axiscal.capture.run import CaptureProgress, StopReading
from axiscal.capture.steps import PlanSteps
from axiscal.io.arguments import check_instance
from axiscal.units import MM, UM

__all__ = ["CaptureBoard"]


class CaptureBoard:
    """The state of a capture for its page, replaced whole at each change (readers never see it half made).

    Parameters
    ----------
    steps : PlanSteps
        The plan being captured.
    source : str
        What is read (shown in the page's title).
    """

    def __init__(self, steps: PlanSteps, source: str = ""):
        self._steps = check_instance("steps", steps, PlanSteps)
        check_instance("source", source, str)
        self._lock = threading.Lock()
        targets = [k for k in range(steps.step.size) if math.isfinite(steps.target_m[k])]
        self._plan = [{"step": int(steps.step[k]), "target_mm": float(steps.target_m[k] / MM), "run": int(steps.run[k]),
                       "direction": str(steps.direction[k])} for k in targets]
        self._taken: list[dict[str, Any]] = []
        self._state: dict[str, Any] = {"source": source, "plan": self._plan, "taken": [], "current": None}

    def _publish(self, **changes: Any) -> None:
        with self._lock:
            self._state = {**self._state, **changes}

    def stop(self, reading: StopReading) -> None:
        """A stop was taken."""
        s = self._steps
        self._taken = self._taken + [{"step": int(s.step[reading.index]), "target_mm": float(s.target_m[reading.index] / MM),
                                      "run": int(s.run[reading.index]), "direction": str(s.direction[reading.index]),
                                      "deviation_um": reading.deviation_m / UM, "window_std_um": reading.window_std_m / UM}]
        self._publish(taken=self._taken)

    def progress(self, p: CaptureProgress) -> None:
        """The capture's latest progress."""
        self._publish(current={"taken": p.taken, "total": p.total, "step": p.step,
                               "target_mm": None if math.isnan(p.target_m) else p.target_m / MM,
                               "reading_mm": None if math.isnan(p.reading_m) else p.reading_m / MM,
                               "still": p.still, "samples": p.samples})

    def snapshot(self) -> dict[str, Any]:
        """The state as the page reads it (JSON-able)."""
        with self._lock:
            return self._state
