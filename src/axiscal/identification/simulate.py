"""Artefacts measured on a virtual machine: the readings each artefact would give on a machine with known errors, plus noise.

The readings follow the measurement equations of :mod:`axiscal.identification.artefacts` exactly,
through the machine's own :meth:`~axiscal.model.Machine.volumetric_error`: where the machine must
reach a true point p, the reported point x solves ``x + e(x) = p`` (fixed-point iteration, the
error's slope being of order 1e-4).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from axiscal.identification.artefacts import BallbarNetwork, BallPlate, Multilateration, RTest, StepGauge, axis_positions
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_count, check_instance, check_number
from axiscal.model.machine import Machine

__all__ = [
    "simulate_ball_plate",
    "simulate_step_gauge",
    "simulate_ballbar",
    "simulate_multilateration",
    "simulate_r_test",
    "plate_grid",
]


def _tooled(machine: Machine, tool_m) -> Machine:
    tool = check_array("tool_m", tool_m, ndim=1, last=3)
    return dataclasses.replace(machine, tool_m=tuple(float(v) for v in tool))


def _checked(machine, noise_m, rng) -> float:
    """The arguments every simulation shares, checked at its entry."""
    check_instance("machine", machine, Machine)
    check_instance("rng", rng, np.random.Generator, what="a numpy.random.Generator (numpy.random.default_rng(seed))")
    return check_number("noise_m", noise_m, nonnegative=True)


def _reported(machine: Machine, true_m: np.ndarray) -> np.ndarray:
    """Points the machine reports when its tool point truly is at ``true_m`` (N, 3)."""
    x = true_m.copy()
    for _ in range(6):
        x = true_m - machine.volumetric_error(axis_positions(machine, x, np.array(machine.tool_m)), workers=1)
    return x


def plate_grid(count: int, pitch_m: float) -> np.ndarray:
    """Ball centres of a square plate of ``count`` x ``count`` balls at ``pitch_m``, in its frame (z = 0).

    Parameters
    ----------
    count : int
        Balls per side.
    pitch_m : float
        Distance between neighbouring balls, metres.

    Returns
    -------
    ndarray, shape (count², 3)
        Metres.
    """
    count = check_count("count", count)
    pitch_m = check_number("pitch_m", pitch_m, positive=True)
    i, j = np.meshgrid(np.arange(count), np.arange(count), indexing="ij")
    return np.column_stack([i.ravel() * pitch_m, j.ravel() * pitch_m, np.zeros(count * count)])


def simulate_ball_plate(machine, centres_m, rotation, origin_m, tool_m, *, noise_m, rng, repeats=1, name="plate", centre_u_m=0.0):
    """A ball plate in one pose measured on ``machine`` (pose left to be fitted).

    Parameters
    ----------
    machine : Machine
        The true machine (a chain of linear axes).
    centres_m : ndarray, shape (B, 3)
        Ball centres in the plate frame, metres.
    rotation : ndarray, shape (3, 3)
        The plate's axes in machine axes (columns).
    origin_m : ndarray, shape (3,)
        The plate's origin in machine axes, metres.
    tool_m : ndarray, shape (3,)
        The stylus tip in the last tool-side carriage, metres.
    noise_m : float
        Standard deviation of each measured coordinate, metres.
    rng : numpy.random.Generator
        The noise source.
    repeats : int
        Measurements of every ball.
    name : str
        The artefact's name.
    centre_u_m : float
        Stated standard uncertainty of the certified centres, metres.

    Returns
    -------
    BallPlate
    """
    noise = _checked(machine, noise_m, rng)
    centres = check_array("centres_m", centres_m, ndim=2, last=3)
    check_count("repeats", repeats)
    true = centres @ np.asarray(rotation, dtype=float).T + check_array("origin_m", origin_m, ndim=1, last=3)
    tooled = _tooled(machine, tool_m)
    reported = _reported(tooled, true)
    ball = np.tile(np.arange(len(centres)), repeats)
    measured = reported[ball] + noise * rng.standard_normal((len(ball), 3))
    return BallPlate(name, np.asarray(tool_m, dtype=float), centres_m=centres, centre_u_m=np.full(len(centres), centre_u_m),
                     ball=ball, measured_m=measured)


def simulate_step_gauge(machine, start_m, direction, faces_m, tool_m, *, noise_m, rng, repeats=1, name="gauge"):
    """A step gauge along a line measured on ``machine``: faces probed along the line.

    Parameters
    ----------
    machine : Machine
        The true machine (linear axes).
    start_m, direction : ndarray, shape (3,)
        The line (its direction a unit vector); the gauge's zero face is at ``start_m``.
    faces_m : ndarray, shape (F,)
        Face positions along the gauge, metres.
    tool_m : ndarray, shape (3,)
        The stylus tip, metres.
    noise_m : float
        Standard deviation of each reading along the line, metres.
    rng : numpy.random.Generator
    repeats : int
    name : str

    Returns
    -------
    StepGauge
    """
    noise_m = _checked(machine, noise_m, rng)
    direction = check_array("direction", direction, ndim=1, last=3)
    if not 0.999 < np.linalg.norm(direction) < 1.001:
        raise AxiscalError(f"direction must be a unit vector, not of length {np.linalg.norm(direction):.6g}")
    direction = direction / np.linalg.norm(direction)
    faces = check_array("faces_m", faces_m, ndim=1)
    check_count("repeats", repeats)
    true = np.asarray(start_m, dtype=float) + faces[:, None] * direction
    reported = _reported(_tooled(machine, tool_m), true)
    face = np.tile(np.arange(len(faces)), repeats)
    measured = reported[face] + noise_m * rng.standard_normal(len(face))[:, None] * direction
    return StepGauge(name, np.asarray(tool_m, dtype=float), start_m=np.asarray(start_m, dtype=float), direction=direction,
                     faces_m=faces, face_u_m=np.zeros(len(faces)), face=face, measured_m=measured)


def simulate_ballbar(machine, centres_m, ends_m, setup, length_m, tool_m, *, noise_m, rng, name="ballbar"):
    """Ballbar lengths from fixed centre balls to the tool ball at commanded points.

    Parameters
    ----------
    machine : Machine
        The true machine (linear axes).
    centres_m : ndarray, shape (S, 3)
        True centre-ball positions, metres.
    ends_m : ndarray, shape (N, 3)
        Commanded (reported) tool-ball positions, metres.
    setup : ndarray of int, shape (N,)
        The centre of each reading.
    length_m : float
        The bar's calibrated length, metres.
    tool_m : ndarray, shape (3,)
    noise_m : float
        Standard deviation of each length, metres.
    rng : numpy.random.Generator
    name : str

    Returns
    -------
    BallbarNetwork
    """
    noise_m = _checked(machine, noise_m, rng)
    tooled = _tooled(machine, tool_m)
    ends = check_array("ends_m", ends_m, ndim=2, last=3)
    centres_m = check_array("centres_m", centres_m, ndim=2, last=3)
    setup = check_array("setup", setup, ndim=1).astype(int)
    if setup.size != len(ends) or setup.min() < 0 or setup.max() >= len(centres_m):
        raise AxiscalError("setup must give the centre (0 .. S-1) of every reading")
    actual = ends + tooled.volumetric_error(axis_positions(tooled, ends, np.array(tooled.tool_m)), workers=1)
    lengths = np.linalg.norm(actual - np.asarray(centres_m)[setup], axis=1) + noise_m * rng.standard_normal(len(ends))
    return BallbarNetwork(name, np.asarray(tool_m, dtype=float), setup=setup, centres_m=np.asarray(centres_m, dtype=float),
                          ends_m=ends, lengths_m=lengths, length_u_m=0.0)


def simulate_multilateration(machine, stations_m, dead_paths_m, targets_m, tool_m, *, noise_m, rng, name="tracker"):
    """Ranges from each station to the reflector at every commanded target.

    Parameters
    ----------
    machine : Machine
        The true machine (linear axes).
    stations_m : ndarray, shape (S, 3)
        True station positions, metres.
    dead_paths_m : ndarray, shape (S,)
        Each station's dead path (added to every range), metres.
    targets_m : ndarray, shape (T, 3)
        Commanded reflector positions, metres (each measured from every station).
    tool_m : ndarray, shape (3,)
    noise_m : float
        Standard deviation of each range, metres.
    rng : numpy.random.Generator
    name : str

    Returns
    -------
    Multilateration
    """
    noise_m = _checked(machine, noise_m, rng)
    tooled = _tooled(machine, tool_m)
    stations = check_array("stations_m", stations_m, ndim=2, last=3)
    dead_paths_m = check_array("dead_paths_m", dead_paths_m, ndim=1)
    if dead_paths_m.size != len(stations):
        raise AxiscalError(f"dead_paths_m must give one dead path per station ({len(stations)}), not {dead_paths_m.size}")
    targets = check_array("targets_m", targets_m, ndim=2, last=3)
    actual = targets + tooled.volumetric_error(axis_positions(tooled, targets, np.array(tooled.tool_m)), workers=1)
    station = np.repeat(np.arange(len(stations)), len(targets))
    rows = np.tile(np.arange(len(targets)), len(stations))
    ranges = np.linalg.norm(actual[rows] - stations[station], axis=1) + np.asarray(dead_paths_m)[station]
    ranges = ranges + noise_m * rng.standard_normal(len(ranges))
    return Multilateration(name, np.asarray(tool_m, dtype=float), station=station, targets_m=targets[rows], ranges_m=ranges)


def simulate_r_test(machine, positions_m, directions, *, noise_m, rng, zeros_m=None, name="rtest"):
    """R-test readings of sensors on the table against the ball on the tool.

    Parameters
    ----------
    machine : Machine
        The true machine; its tool point is the ball.
    positions_m : dict of str to ndarray, shape (N,)
        Every axis (e.g. from :func:`axiscal.identification.r_test_positions`).
    directions : ndarray, shape (K, 3)
        Unit sensing directions in the workpiece frame.
    noise_m : float
        Standard deviation of each reading, metres.
    rng : numpy.random.Generator
    zeros_m : ndarray, shape (K,), optional
        The sensors' zero offsets (default zero).
    name : str

    Returns
    -------
    RTest
    """
    noise_m = _checked(machine, noise_m, rng)
    directions = check_array("directions", directions, ndim=2, last=3)
    error = machine.volumetric_error(positions_m, workers=1)
    zeros = np.zeros(len(directions)) if zeros_m is None else np.asarray(zeros_m, dtype=float)
    readings = error @ directions.T + zeros + noise_m * rng.standard_normal((len(error), len(directions)))
    return RTest(name, np.array(machine.tool_m), axis_positions_m={k: np.asarray(v, dtype=float) for k, v in positions_m.items()},
                 directions=directions, readings_m=readings)
