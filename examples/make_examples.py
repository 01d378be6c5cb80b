"""Write the example error tables in examples/ (run from the repository root: python examples/make_examples.py).

The XZ module is paper 000's 2-axis linear module: 190 mm strokes, squareness EB0Z = -42.4 arcsec,
functional point 40 mm below the Z carriage. Its error motions are plausible smooth curves of the
sizes such modules show (positioning and straightness a few um, angles some tens of urad), not
measurements. The XFYZ machine is a small 3-axis machine tool used by the benchmark and tests.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

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
    q = np.arange(0.0, 191.0, 10.0)
    stroke = 190.0
    x = {
        "EXX_um": 0.021 * q + smooth(q, stroke, [(0.8, 3.0, 0.4)]),
        "EYX_um": smooth(q, stroke, [(1.6, 0.5, 0.0), (0.4, 2.0, 1.0)]),
        "EZX_um": smooth(q, stroke, [(-2.2, 0.5, 0.0), (0.3, 1.5, 0.7)]),
        "EAX_urad": smooth(q, stroke, [(12.0, 0.5, 0.3), (3.0, 2.0, 0.0)]),
        "EBX_urad": 18.0 + smooth(q, stroke, [(25.0, 0.5, 0.0), (5.0, 1.5, 1.2)]),
        "ECX_urad": smooth(q, stroke, [(-20.0, 0.5, 0.6), (4.0, 2.5, 0.0)]),
    }
    z = {
        "EXZ_um": smooth(q, stroke, [(2.8, 0.5, 0.0), (0.5, 2.0, 0.3)]),
        "EYZ_um": smooth(q, stroke, [(-1.3, 0.5, 0.2), (0.3, 1.5, 0.0)]),
        "EZZ_um": -0.015 * q + smooth(q, stroke, [(0.6, 2.5, 1.0)]),
        "EAZ_urad": smooth(q, stroke, [(15.0, 0.5, 0.0), (4.0, 1.5, 0.5)]),
        "EBZ_urad": smooth(q, stroke, [(-22.0, 0.5, 0.4), (3.0, 2.0, 0.0)]),
        "ECZ_urad": smooth(q, stroke, [(9.0, 0.5, 1.0), (2.0, 3.0, 0.0)]),
    }
    write_table(DATA / "xz_module" / "x_errors.csv", q, x)
    write_table(DATA / "xz_module" / "z_errors.csv", q, z)


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
    """Simulated interferometer readings on the XZ diagonal (19 steps of 10 mm per axis).

    The 'true' machine differs from the model by a smooth unmodelled error along the diagonal
    (about 3 um) plus 0.2 um of reading noise, so the model removes most but not all of the error,
    as in paper 000 section 5.
    """
    import axiscal
    from axiscal.diagonal import diagonal_check

    machine = axiscal.load_machine(DATA / "xz_module" / "machine.toml")
    result = diagonal_check(machine, {"X": 0.0, "Z": 0.0}, {"X": 0.19, "Z": 0.19}, 19)
    rng = np.random.default_rng(3)
    s = result.nominal_m / result.nominal_m[-1]
    unmodelled = 1.5e-6 * np.sin(2 * np.pi * 1.2 * s) + 1.0e-6 * s
    measured = result.predicted_m + unmodelled + rng.normal(0.0, 0.2e-6, s.size)
    measured[0] = 0.0
    lines = ["# Simulated laser interferometer on the XZ diagonal of examples/xz_module (see make_examples.py)"]
    lines.append("nominal_mm,measured_mm")
    lines += [f"{n * 1e3:.6f},{m * 1e3:.6f}" for n, m in zip(result.nominal_m, measured)]
    (DATA / "xz_module" / "diagonal_laser.csv").write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    xz_module()
    xfyz_machine()
    xz_diagonal_readings()
