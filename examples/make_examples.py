"""Write the example error tables in examples/ (run from the repository root: python examples/make_examples.py).

The XZ module is paper 000's 2-axis linear module: 190 mm strokes, squareness EB0Z = -42.4 arcsec,
functional point 40 mm below the Z carriage. Its error tables are the true error motions of the
virtual module (axiscal.measurement.virtual), plausible smooth curves, not measurements. The XFYZ machine is a
small 3-axis machine tool used by the benchmark and tests.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from axiscal.units import ANGLE_UNITS, MM, UM

URAD = ANGLE_UNITS["urad"]
HERE = Path(__file__).resolve().parent
#: the XZ module is the built-in example of `axiscal demo`, shipped inside the package
DATA = HERE.parent / "src" / "axiscal" / "data"


def smooth(position_mm: np.ndarray, stroke_mm: float, terms: list[tuple[float, float, float]]) -> np.ndarray:
    """Sum of amplitude * sin(2 pi * cycles * s + phase) over the normalised stroke s in [0, 1]."""
    s = position_mm / stroke_mm
    return sum(a * np.sin(2 * np.pi * c * s + p) for a, c, p in terms)


def write_table(path: Path, position_mm: np.ndarray, columns: dict[str, np.ndarray]) -> None:
    header = ["position_mm", *columns]
    lines = [",".join(header)]
    for k, q in enumerate(position_mm):
        lines.append(",".join([f"{q:.3f}", *(f"{v[k]:.4f}" for v in columns.values())]))
    path.write_text("\n".join(lines) + "\n")


def xz_module() -> None:
    """Error tables of the XZ module: the true error motions of the virtual module of
    :mod:`axiscal.measurement.virtual` (seed 0, no load) sampled every 10 mm, so that the demo's offline model
    and its simulated live measurement describe one and the same module."""
    from axiscal.conventions import component_names
    from axiscal.measurement.virtual import VirtualModule

    module = VirtualModule(seed=0, noise=False)
    q = np.arange(0.0, 191.0, 10.0)
    for letter in ("X", "Z"):
        values = module.true_errors(letter, q * MM)
        names = component_names(letter)
        columns = {f"{n}_um": values[k] / UM for k, n in enumerate(names[:3])}
        columns |= {f"{n}_urad": values[3 + k] / URAD for k, n in enumerate(names[3:])}
        write_table(DATA / "xz_module" / f"{letter.lower()}_errors.csv", q, columns)


def xfyz_machine() -> None:
    rng = np.random.default_rng(7)
    for letter, stroke in (("X", 800.0), ("Y", 500.0), ("Z", 400.0)):
        q = np.linspace(0.0, stroke, 100)
        directions = ["X", "Y", "Z"]
        columns: dict[str, np.ndarray] = {}
        for d in directions:
            size = 6.0 if d == letter else 3.0
            terms = [(size * rng.uniform(0.5, 1.0), c, rng.uniform(0, np.pi)) for c in (0.5, 1.5)]
            columns[f"E{d}{letter}_um"] = smooth(q, stroke, terms)
        for d in ("A", "B", "C"):
            terms = [(25.0 * rng.uniform(0.5, 1.0), c, rng.uniform(0, np.pi)) for c in (0.5, 2.0)]
            columns[f"E{d}{letter}_urad"] = smooth(q, stroke, terms)
        write_table(HERE / "xfyz_machine" / f"{letter.lower()}_errors.csv", q, columns)


def xz_diagonal_readings() -> None:
    """Laser interferometer readings on the XZ diagonal (19 steps of 10 mm per axis) of the same
    virtual module carrying 2 kg on its Z slide, with the interferometer's noise. The error tables
    were taken without the load, so the offline model misses what the load does to the angular
    errors: the gap that paper 000's live measurement closes."""
    from axiscal.measurement.virtual import VirtualModule

    module = VirtualModule(seed=0, load_kg=2.0)
    q = np.arange(20) * 10.0 * MM
    measured = module.laser_diagonal({"X": q, "Z": q})
    nominal = np.hypot(q, q)
    # a plain data CSV: the header is the first line (docs/formats.md); this docstring says what it is
    lines = ["nominal_mm,measured_mm"]
    lines += [f"{n / MM:.6f},{m / MM:.6f}" for n, m in zip(nominal, measured)]
    (DATA / "xz_module" / "diagonal_laser.csv").write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    xz_module()
    xfyz_machine()
    xz_diagonal_readings()
