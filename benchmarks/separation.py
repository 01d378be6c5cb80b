"""Paper 001's simulation, every separation method, with and without noise, offsets and yaw; 10^6-point timing.

Run from the repository root::

    .venv/bin/python benchmarks/separation.py [PLOT.png]

Prints a Markdown table of each method's separation error (P-V and RMS of the separated profile
minus the true one, after removing their least-squares line), then the time each method takes on
10^6 readings and how much probe noise each method lets through, and writes a plot of truth vs
separated profiles and motions (default ``separation.png``). Errors with noise are means over 20
noise draws.

Set-up (paper 001, Fig. 4 and section 4): R and S as printed under Fig. 4 with n the position in
mm, N = 300 (a 300 mm workpiece), the step G = 0.4 um on N/2.7 <= n <= N/1.5; three probes 15 mm
apart, carriage steps of 1 mm, probe A over 0..269 mm. FSTRP uses spacings 7 and 4 mm, the
unequal three-point frequency method 15 and 2 mm. Scenarios: clean; zero offsets xi_b = 0.05 um,
xi_c = 0.02 um; probe noise 0.01 um (seed 0); yaw 2 arcsec + 1 arcsec sin(2 pi x / 50 mm); all
three together.
"""

from __future__ import annotations

import sys
from collections.abc import Callable

import numpy as np
from timing import best_time

from axiscal.cli.common import pyplot
from axiscal.straightness.reference import reference_line
from axiscal.straightness.separation import (
    ProbeReadings,
    Separation,
    combined,
    fine_sequential_three_point,
    frequency_domain,
    generalized_two_point,
    noise_propagation,
    reversal,
    sequential_three_point,
    sequential_two_point,
    simulate_readings,
)
from axiscal.units import ARCSEC, MM, UM

N = 300
STEP = 1 * MM
SPACING = 15 * MM
OFFSETS = (0.0, 0.05 * UM, 0.02 * UM)
NOISE = 0.01 * UM


def profile(x: np.ndarray) -> np.ndarray:
    n = x / MM
    return UM * (np.sin(np.pi * n / (2.5 * N)) + 0.02 * np.sin(2 * np.pi * n / 54) + 0.02 * np.sin(2 * np.pi * n / 34))


def motion(x: np.ndarray) -> np.ndarray:
    n = x / MM
    return UM * (np.sin(0.75 * np.pi * n / (2.5 * N)) + 0.4 * ((n >= N / 2.7) & (n <= N / 1.5)))


def yaw(x: np.ndarray) -> np.ndarray:
    return ARCSEC * (2.0 + np.sin(2 * np.pi * x / (50 * MM)))


SCENARIOS: dict[str, dict] = {
    "clean": {},
    "offsets": {"offsets_m": OFFSETS},
    "noise": {"noise_m": NOISE},
    "yaw": {"yaw": yaw},
    "all": {"offsets_m": OFFSETS, "noise_m": NOISE, "yaw": yaw},
}


def readings(spacing_bc: float, scenario: dict, spacing_ab: float = SPACING, seed: int = 0) -> ProbeReadings:
    x = np.arange(0.0, N * MM - 2 * SPACING + 1e-12, STEP)
    options = dict(scenario)
    g = options.pop("yaw", None)
    return simulate_readings(
        x, profile, motion, g, spacing_ab_m=spacing_ab, spacing_bc_m=spacing_bc, rng=np.random.default_rng(seed), **options
    )


def reversal_run(scenario: dict, seed: int = 0) -> Separation:
    x = np.arange(0.0, N * MM + 1e-12, STEP)
    rng = np.random.default_rng(seed)
    noise = scenario.get("noise_m", 0.0)
    offset = scenario.get("offsets_m", (0.0, 0.0, 0.0))
    normal = profile(x) - motion(x) - offset[0] + noise * rng.standard_normal(x.size)
    turned = profile(x) + motion(x) - offset[1] + noise * rng.standard_normal(x.size)
    return reversal(x, normal, turned)


METHODS: dict[str, Callable[[dict, int], Separation]] = {
    "reversal (1 probe, 2 runs)": reversal_run,
    "STP (eq 3-4)": lambda sc, seed: sequential_two_point(readings(SPACING, sc, seed=seed)),
    "STRP (eq 1-2)": lambda sc, seed: sequential_three_point(readings(SPACING, sc, seed=seed)),
    "FSTRP 7+4 mm (eq 5-6)": lambda sc, seed: fine_sequential_three_point(readings(4 * MM, sc, 7 * MM, seed)),
    "GTP (eq 7)": lambda sc, seed: generalized_two_point(readings(SPACING, sc, seed=seed)),
    "frequency 2-point": lambda sc, seed: frequency_domain(readings(SPACING, sc, seed=seed), probes=2),
    "frequency 3-point 15+15 mm": lambda sc, seed: frequency_domain(readings(SPACING, sc, seed=seed), probes=3),
    "frequency 3-point 15+2 mm": lambda sc, seed: frequency_domain(readings(2 * MM, sc, seed=seed), probes=3),
    "combined (section 4)": lambda sc, seed: combined(readings(SPACING, sc, seed=seed)),
}
SEEDS = 20


def separation_error(result: Separation) -> tuple[float, float]:
    """P-V and RMS (um) of separated minus true profile after removing their least-squares line."""
    diff = result.profile_m - profile(result.position_m)
    residual = reference_line(result.position_m, diff).residuals(result.position_m, diff)
    return float(np.ptp(residual) / UM), float(np.sqrt(np.mean(residual**2)) / UM)


def mean_error(method: Callable[[dict, int], Separation], scenario: str) -> tuple[float, float]:
    """Separation error; with noise, the mean P-V and RMS over SEEDS noise draws."""
    seeds = range(SEEDS) if "noise_m" in SCENARIOS[scenario] else range(1)
    errors = np.array([separation_error(method(SCENARIOS[scenario], seed)) for seed in seeds])
    return float(errors[:, 0].mean()), float(errors[:, 1].mean())


def error_table() -> dict[str, dict[str, Separation]]:
    results = {name: {sc: method(SCENARIOS[sc], 0) for sc in SCENARIOS} for name, method in METHODS.items()}
    head = "| method | points | " + " | ".join(f"{sc} P-V / RMS" for sc in SCENARIOS) + " |"
    print(head)
    print("|" + "---|" * (len(SCENARIOS) + 2))
    for name, per in results.items():
        cells = []
        for sc in SCENARIOS:
            pv, rms = mean_error(METHODS[name], sc)
            cells.append(f"{pv:.4f} / {rms:.4f}")
        print(f"| {name} | {per['clean'].position_m.size} | " + " | ".join(cells) + " |")
    print()
    x = np.arange(0.0, N * MM + 1e-12, STEP)
    truth = reference_line(x, profile(x))
    print(f"with noise: mean over {SEEDS} noise draws (seeds 0..{SEEDS - 1}); the plot shows seed 0")
    print(
        f"errors in um; the true profile spans {np.ptp(profile(x)) / UM:.2f} um "
        f"({truth.straightness_m / UM:.2f} um about its least-squares line)"
    )
    lost = results["frequency 3-point 15+15 mm"]["clean"].lost_wavelength_m
    print("frequency 3-point 15+15 mm leaves out wavelengths (mm): " + ", ".join(f"{w / MM:.3g}" for w in np.sort(lost)[::-1]))
    lost2 = results["frequency 3-point 15+2 mm"]["clean"].lost_wavelength_m
    print(f"frequency 3-point 15+2 mm leaves out {lost2.size} harmonics")
    return results


def noise_table() -> None:
    """Mean P-V about the least-squares line of separated pure noise, per unit of probe noise."""
    x = np.arange(0.0, N * MM - 2 * SPACING + 1e-12, STEP)
    equal = ProbeReadings(x, x, x, x, SPACING, SPACING)
    setups = {
        "reversal": (equal, "reversal"),
        "STP": (equal, "stp"),
        "STRP": (equal, "strp"),
        "FSTRP 7+4 mm": (ProbeReadings(x, x, x, x, 7 * MM, 4 * MM), "fstrp"),
        "GTP": (equal, "gtp"),
        "frequency 2-point": (ProbeReadings(x, x, x, None, SPACING), "frequency"),
        "frequency 3-point 15+15 mm": (equal, "frequency"),
        "frequency 3-point 15+2 mm": (ProbeReadings(x, x, x, x, SPACING, 2 * MM), "frequency"),
        "combined": (equal, "combined"),
    }
    print()
    print("| method | noise P-V / sigma (mean over 500 runs, about the least-squares line) |")
    print("|---|---|")
    for name, (template, method) in setups.items():
        figure = noise_propagation(template, method=method, noise_m=1.0, trials=500)
        print(f"| {name} | {figure.mean_pv_m:.2f} |")


def timing() -> None:
    """Best of 3 runs on 10^6 readings per method, and the minimum-zone line on 10^6 points."""
    n = 10**6
    rng = np.random.default_rng(0)
    x = np.arange(n) * 1e-6
    a, b, c = 1e-8 * rng.standard_normal((3, n))
    cases = {
        "STP": lambda: sequential_two_point(ProbeReadings(x, a, b, c, 15e-6, 15e-6)),
        "STRP": lambda: sequential_three_point(ProbeReadings(x, a, b, c, 1e-6, 1e-6)),
        "FSTRP": lambda: fine_sequential_three_point(ProbeReadings(x, a, b, c, 7e-6, 4e-6)),
        "GTP": lambda: generalized_two_point(ProbeReadings(x, a, b, c, 15e-6, 15e-6)),
        "frequency 3-point": lambda: frequency_domain(ProbeReadings(x, a, b, c, 15e-6, 2e-6), probes=3),
        "combined": lambda: combined(ProbeReadings(x, a, b, c, 15e-6, 15e-6)),
        "minimum-zone line, noisy profile": lambda: reference_line(x, np.cumsum(a), reference="minimum-zone"),
        "minimum-zone line, convex profile (every point on the hull)": lambda: reference_line(
            x, (x - 0.5) ** 2, reference="minimum-zone"
        ),
    }
    print()
    print("| 10^6 readings or points (best of 3) | seconds |")
    print("|---|---|")
    for name, run in cases.items():
        print(f"| {name} | {best_time(run, 3):.3f} |")
    print("(STRP at a step equal to the spacing, so it uses all 10^6 readings)")


def plot(path: str, results: dict[str, dict[str, Separation]]) -> None:
    """Top row: true R and separated profiles; bottom row: true S (with the step G) and separated motions.

    Separated curves are brought onto the truth by the straight line they are undetermined by
    (fitted to their difference from the truth); the y range is the truth's +- 0.3 um, and the
    methods that fail by more than that are named in the panel with their error.
    """
    plt = pyplot()
    scenarios = ("clean", "noise", "all")
    shown = ("STP (eq 3-4)", "STRP (eq 1-2)", "GTP (eq 7)", "frequency 3-point 15+2 mm", "combined (section 4)")
    fig, axes = plt.subplots(2, len(scenarios), figsize=(15, 8), sharex=True)
    x = np.arange(0.0, N * MM + 1e-12, STEP)
    for column, scenario in enumerate(scenarios):
        for row, (truth, field) in enumerate(((profile, "profile_m"), (motion, "motion_m"))):
            ax = axes[row, column]
            low, high = truth(x).min() / UM - 0.3, truth(x).max() / UM + 0.3
            ax.plot(x / MM, truth(x) / UM, "k-", lw=3, alpha=0.5, label="truth")
            off_scale = []
            for name in shown:
                r = results[name][scenario]
                pos = r.position_m[np.isfinite(getattr(r, field))]
                values = getattr(r, field)[np.isfinite(getattr(r, field))]
                line = reference_line(pos, values - truth(pos))
                placed = (values - line.slope * pos - line.intercept_m) / UM
                ax.plot(pos / MM, placed, lw=1, label=name)
                if placed.min() < low or placed.max() > high:
                    off_scale.append(f"{name}: off scale, error {line.straightness_m / UM:.2f} um P-V")
            if off_scale:
                ax.text(0.98, 0.03, "\n".join(off_scale), transform=ax.transAxes, ha="right", va="bottom", fontsize=8,
                        bbox={"facecolor": "white", "alpha": 0.85, "edgecolor": "none"})
            ax.set_ylim(low, high)
            ax.set_title(f"{'profile R' if row == 0 else 'motion S'}, scenario: {scenario}")
            if row == 1:
                ax.set_xlabel("position / mm")
            if column == 0:
                ax.set_ylabel("deviation / um")
    axes[0, 0].legend(fontsize=8)
    fig.suptitle("paper 001 Fig. 4 simulation: truth and separated curves (each less the line it is undetermined by)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    print(f"\nplot written to {path}")


def main(argv: list[str]) -> int:
    path = argv[0] if argv else "separation.png"
    results = error_table()
    noise_table()
    timing()
    plot(path, results)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
