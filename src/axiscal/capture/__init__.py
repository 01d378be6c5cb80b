"""Capture: the readings of a positioning test taken from a stream or a recording, stop by stop."""

from axiscal.capture.stops import Stop, StopDetector, detect_stops

__all__ = ["Stop", "StopDetector", "detect_stops"]
