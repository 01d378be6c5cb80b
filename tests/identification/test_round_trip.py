"""Round trips on virtual machines with known polynomial errors: every identifiable coefficient within its stated uncertainty."""

from __future__ import annotations

import numpy as np
import pytest

from axiscal.identification import identify
from axiscal.identification.simulate import (
    plate_grid,
    simulate_ball_plate,
    simulate_ballbar,
    simulate_multilateration,
    simulate_step_gauge,
)

TRAVEL_XY = {"X": (-0.05, 0.35), "Y": (-0.05, 0.35)}
TRAVEL_XYZ = {"X": (-0.05, 0.35), "Y": (-0.05, 0.35), "Z": (-0.05, 0.35)}
PROBES = ((0.0, 0.0, 0.0), (0.03, 0.0, 0.0), (0.0, 0.03, 0.05))


def plate_case(virtual, seed):
    rng = np.random.default_rng(seed)
    ideal, true, theta = virtual.polynomial_machine("FXY", "poly:2", TRAVEL_XY, rng)
    artefacts = [
        simulate_ball_plate(true, plate_grid(3, 0.15), np.eye(3), np.zeros(3), np.array(tool), noise_m=0.2e-6, rng=rng, name=f"plate{k}")
        for k, tool in enumerate(PROBES)
    ]
    return identify(ideal, artefacts, model="poly:2", travel=TRAVEL_XY), theta


def test_ball_plate_recovers_every_coefficient_within_k2_in_95_percent_over_50_seeds(virtual):
    z = np.concatenate([virtual.coverage(*plate_case(virtual, seed)) for seed in range(50)])
    assert z.size == 50 * 21
    assert 0.92 <= np.mean(z < 2.0) <= 0.98


def test_ball_plate_without_noise_is_exact(virtual):
    rng = np.random.default_rng(3)
    ideal, true, theta = virtual.polynomial_machine("FXY", "poly:2", TRAVEL_XY, rng)
    artefacts = [
        simulate_ball_plate(true, plate_grid(3, 0.15), np.eye(3), np.zeros(3), np.array(tool), noise_m=0.0, rng=rng, name=f"p{k}")
        for k, tool in enumerate(PROBES)
    ]
    result = identify(ideal, artefacts, model="poly:2", travel=TRAVEL_XY)
    assert np.allclose(result.values[: len(theta)], theta, atol=1e-11)
    assert result.residual_std < 1e-9


def test_one_plate_with_one_probe_names_what_it_cannot_see(virtual):
    rng = np.random.default_rng(4)
    ideal, true, _ = virtual.polynomial_machine("FXY", "poly:2", TRAVEL_XY, rng)
    plate = simulate_ball_plate(true, plate_grid(3, 0.15), np.eye(3), np.zeros(3), np.zeros(3), noise_m=0.1e-6, rng=rng)
    result = identify(ideal, [plate], model="poly:2", travel=TRAVEL_XY)
    hidden = {name for group in result.undetermined for name in group.names}
    # with the stylus on the reference point of the Y carriage its rotations are invisible, and so is
    # the pitch of X (it turns the Y axis about itself)
    assert {"EBX:1", "EAY:1", "EBY:1"} <= hidden
    assert all(np.isnan(result.value(name)[1]) for name in hidden if ":" in name and name[:3] in ("EAX", "EAY"))
    # what is seen is named too: its value and uncertainty are finite
    for group in result.undetermined:
        assert group.hidden
        for combination in group.determined:
            assert np.isfinite(combination.value) and np.isfinite(combination.u)


def line_case(virtual, seed, noise_m=0.1e-6):
    """Step gauges along X, Y, Z and the diagonals of a 3-axis machine with errors only in positioning and squareness."""
    rng = np.random.default_rng(seed)
    fix = [k for k in ("EYX", "EZX", "EAX", "EBX", "ECX", "EXY", "EZY", "EAY", "EBY", "ECY", "EXZ", "EYZ", "EAZ", "EBZ", "ECZ")]
    ideal, true, theta = virtual.polynomial_machine("FYXZ", "poly:2", TRAVEL_XYZ, rng, fix=fix)
    gauges = []
    for k, d in enumerate([(1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 1, 0), (1, 0, 1), (0, 1, 1), (1, 1, 1)]):
        direction = np.array(d, float) / np.linalg.norm(d)
        faces = np.linspace(0.0, 0.3 * np.linalg.norm(d), 7)
        gauges.append(simulate_step_gauge(true, np.zeros(3), direction, faces, np.zeros(3), noise_m=noise_m, rng=rng, name=f"g{k}"))
    return identify(ideal, gauges, model="poly:2", travel=TRAVEL_XYZ, fix=fix), theta


def test_step_gauges_recover_positioning_and_squareness(virtual):
    z = np.concatenate([virtual.coverage(*line_case(virtual, seed)) for seed in range(20)])
    assert z.size == 20 * 9
    assert 0.9 <= np.mean(z < 2.0) <= 1.0


def test_ballbar_network_round_trip(virtual):
    zs = []
    for seed in range(10):
        rng = np.random.default_rng(seed)
        ideal, true, theta = virtual.polynomial_machine("FYXZ", "poly:1", TRAVEL_XYZ, rng)
        centres = np.array([[0.15, 0.15, 0.15], [0.1, 0.1, 0.12], [0.2, 0.2, 0.18]])
        directions = rng.standard_normal((20, 3))
        directions /= np.linalg.norm(directions, axis=1)[:, None]
        ends = np.concatenate([c + 0.08 * directions for c in centres])
        setup = np.repeat(np.arange(3), 20)
        bars = [simulate_ballbar(true, centres, ends, setup, 0.08, np.array(t), noise_m=0.1e-6, rng=rng, name=f"bar{k}")
                for k, t in enumerate(((0, 0, 0), (0.03, 0, 0), (0, 0.03, -0.03)))]
        result = identify(ideal, bars, model="poly:1", travel=TRAVEL_XYZ)
        zs.append(virtual.coverage(result, theta))
    z = np.concatenate(zs)
    assert z.size == 10 * 15
    assert 0.9 <= np.mean(z < 2.0) <= 1.0


def test_multilateration_round_trip(virtual):
    zs = []
    grid = np.linspace(0.0, 0.3, 3)
    targets = np.array(np.meshgrid(grid, grid, grid)).reshape(3, -1).T
    stations = np.array([[-0.5, -0.5, 0.0], [0.8, -0.5, 0.1], [0.8, 0.8, 0.0], [-0.5, 0.8, 0.2], [0.15, 0.15, 0.9]])
    for seed in range(10):
        rng = np.random.default_rng(seed)
        ideal, true, theta = virtual.polynomial_machine("FYXZ", "poly:1", TRAVEL_XYZ, rng)
        trackers = [simulate_multilateration(true, stations, np.full(5, 0.2), targets, np.array(t), noise_m=0.1e-6, rng=rng, name=f"t{k}")
                    for k, t in enumerate(((0, 0, 0), (0.05, 0, 0), (0, 0.05, -0.05)))]
        result = identify(ideal, trackers, model="poly:1", travel=TRAVEL_XYZ)
        assert not result.undetermined
        zs.append(virtual.coverage(result, theta))
    z = np.concatenate(zs)
    assert 0.9 <= np.mean(z < 2.0) <= 1.0


@pytest.mark.parametrize("model", ["spline:3"])
def test_spline_model_round_trip_without_noise(virtual, model):
    rng = np.random.default_rng(5)
    ideal, true, theta = virtual.polynomial_machine("FXY", model, TRAVEL_XY, rng)
    artefacts = [
        simulate_ball_plate(true, plate_grid(4, 0.1), np.eye(3), np.zeros(3), np.array(tool), noise_m=0.0, rng=rng, name=f"p{k}")
        for k, tool in enumerate(PROBES)
    ]
    result = identify(ideal, artefacts, model=model, travel=TRAVEL_XY)
    determined = result.determined[: len(theta)]
    assert determined.any()
    assert np.allclose(result.values[: len(theta)][determined], theta[determined], atol=1e-10)


def test_artefacts_of_different_noise_are_weighted_by_their_own_variance(virtual):
    zs, spread = [], []
    for seed in range(15):
        rng = np.random.default_rng(seed)
        ideal, true, theta = virtual.polynomial_machine("FXY", "poly:2", TRAVEL_XY, rng)
        artefacts = [
            simulate_ball_plate(true, plate_grid(3, 0.15), np.eye(3), np.zeros(3), np.array(tool), noise_m=0.5e-6, rng=rng, name=f"plate{k}")
            for k, tool in enumerate(PROBES)
        ] + [
            simulate_step_gauge(true, np.zeros(3), np.array(d) / np.linalg.norm(d), np.linspace(0.0, 0.3, 7), np.zeros(3),
                                noise_m=0.02e-6, rng=rng, name=f"gauge{k}")
            for k, d in enumerate(((1, 0, 0), (0, 1, 0), (1, 1, 0)))
        ]
        result = identify(ideal, artefacts, model="poly:2", travel=TRAVEL_XY)
        zs.append(virtual.coverage(result, theta))
        spread.append([result.kind_std["ball_plate"], result.kind_std["step_gauge"]])
    assert np.allclose(np.median(spread, axis=0), [0.5e-6, 0.02e-6], rtol=0.2)
    assert 0.9 <= np.mean(np.concatenate(zs) < 2.0) <= 0.99
