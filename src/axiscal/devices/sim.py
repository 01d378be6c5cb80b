"""The virtual controller: one axis moved in real time, its carriage where a machine model puts it.

``sim`` in ``--controller`` is this driver: each move is a trapezoidal velocity profile at the feed
asked (acceleration 1 m/s^2), run against the clock; the motor is at the commanded position plus the
compensation loaded (``correction(commanded, direction)``, read back from a controller's file as the
virtual machine of the capture does); the carriage is where ``carriage(motor, direction)`` says (the
machine model's error along the axis and its reversal) plus a decaying ring after each arrival. A
simulated instrument reads :meth:`SimController.carriage_now`.
"""

from __future__ import annotations

import math
import threading
import time
from collections.abc import Callable

from axiscal.devices.controller import Controller, move_words
from axiscal.errors import AxiscalError

__all__ = ["SimController"]


class SimController(Controller):
    """A virtual axis in real time.

    Parameters
    ----------
    carriage : callable, optional
        ``carriage(motor_m, direction) -> metres``: where the carriage is for a motor position and the
        direction of the last move (+1 or -1); the motor position itself by default.
    travel_m : tuple of float
        Soft limits, metres.
    correction : callable, optional
        ``correction(commanded_m, "+"|"-") -> metres``: the compensation loaded.
    acceleration_m_s2 : float
    ring_m, ring_hz, ring_s : float
        Amplitude, frequency and decay time of the ring after each arrival.
    axis : str
        The axis letter it moves.
    """

    def __init__(self, *, carriage: Callable[[float, float], float] | None = None, travel_m: tuple[float, float] = (-0.001, 1.0),
                 correction: Callable[[float, str], float] | None = None, acceleration_m_s2: float = 1.0,
                 ring_m: float = 1e-6, ring_hz: float = 25.0, ring_s: float = 0.05, axis: str = "X"):
        self.description = "virtual controller (sim)"
        super().__init__()
        self.carriage = carriage or (lambda motor, direction: motor)
        self.travel_m = travel_m
        self.correction = correction
        self.acceleration = acceleration_m_s2
        self.ring_m, self.ring_hz, self.ring_s = ring_m, ring_hz, ring_s
        self.axis = axis.upper()
        self._lock = threading.Lock()
        self._move = (time.monotonic(), 0.0, 0.0, 1.0, 0.0, 1.0)  # t0, start, end, v, duration, direction
        self._stopped = threading.Event()
        self.homed = True
        self.alarm: str | None = None
        self.moves = 0

    # -- the motion ---------------------------------------------------------------------------
    def _profile(self, start: float, end: float, speed: float) -> float:
        distance = abs(end - start)
        if distance == 0:
            return 0.0
        a = self.acceleration
        if distance < speed * speed / a:
            return 2.0 * math.sqrt(distance / a)
        return distance / speed + speed / a

    def _commanded_at(self, now: float) -> tuple[float, float, float]:
        t0, start, end, speed, duration, direction = self._move
        t = max(now - t0, 0.0)
        if t >= duration or duration == 0:
            return end, direction, t - duration
        a = self.acceleration
        distance = abs(end - start)
        v = min(speed, math.sqrt(distance * a))
        ramp = v / a
        if t < ramp:
            s = 0.5 * a * t * t
        elif t < duration - ramp:
            s = 0.5 * a * ramp * ramp + v * (t - ramp)
        else:
            r = duration - t
            s = distance - 0.5 * a * r * r
        return start + direction * s, direction, -1.0

    def motor_now(self) -> float:
        """Where the motor is now, metres (commanded plus the compensation loaded)."""
        with self._lock:
            commanded, direction, _ = self._commanded_at(time.monotonic())
        if self.correction is not None:
            commanded += float(self.correction(commanded, "+" if direction > 0 else "-"))
        return commanded

    def carriage_now(self) -> float:
        """Where the carriage is now, metres (what an instrument on it reads)."""
        return self.carriage_at(time.monotonic())

    def carriage_at(self, when: float) -> float:
        """Where the carriage is at a moment of the monotonic clock (of the move under way), metres.

        Parameters
        ----------
        when : float, seconds
            ``time.monotonic()`` of the moment.

        Returns
        -------
        float
        """
        with self._lock:
            commanded, direction, since = self._commanded_at(when)
        motor = commanded
        if self.correction is not None:
            motor += float(self.correction(commanded, "+" if direction > 0 else "-"))
        ring = 0.0
        if since >= 0 and self.ring_m:
            ring = direction * self.ring_m * math.exp(-since / self.ring_s) * math.sin(2 * math.pi * self.ring_hz * since)
        return float(self.carriage(motor, direction)) + ring

    # -- the controller's interface -----------------------------------------------------------
    def check_ready(self, axis: str) -> None:
        if axis.upper() != self.axis:
            raise AxiscalError(f"the virtual controller moves {self.axis}, not {axis}")
        if not self.homed:
            raise AxiscalError(f"{self.description}: axis {self.axis} is not homed: home the machine first (axiscal run never homes)")
        if self.alarm:
            raise AxiscalError(f"{self.description} is in alarm: {self.alarm}")

    def limits(self, axis: str) -> tuple[float, float] | None:
        return self.travel_m

    def position(self, axis: str) -> float:
        with self._lock:
            return self._commanded_at(time.monotonic())[0]

    def move_to(self, axis: str, position_m: float, feed_m_per_s: float) -> None:
        move_words(axis, position_m, feed_m_per_s)  # what a real controller would be sent: bounded alike
        low, high = self.travel_m
        if not low <= position_m <= high:
            raise AxiscalError(f"{self.description} refused the move to {axis} {position_m * 1e3:.4f} mm: beyond its soft"
                               f" limits {low * 1e3:g} .. {high * 1e3:g} mm")
        self._stopped.clear()
        now = time.monotonic()
        with self._lock:
            here, direction, _ = self._commanded_at(now)
            duration = self._profile(here, position_m, feed_m_per_s)
            direction = direction if position_m == here else (1.0 if position_m > here else -1.0)
            self._move = (now, here, position_m, feed_m_per_s, duration, direction)
        self.status.state = "moving"
        if self._stopped.wait(duration):
            with self._lock:
                stopped_at, direction, _ = self._commanded_at(time.monotonic())
                self._move = (time.monotonic(), stopped_at, stopped_at, 1.0, 0.0, direction)
            raise AxiscalError(f"{self.description}: the move was aborted")
        self.moves += 1
        self.status.state = "idle"
        self.status.position_m = position_m

    def stop(self) -> None:
        self._stopped.set()
