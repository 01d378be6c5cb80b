"""Write the error tables of the five-axis trunnion example (run from the repository root:
python examples/trunnion_machine/make_tables.py).

Plausible smooth curves with the sizes a calibrated machining centre shows, not measurements:
linear axes a few um and tens of urad; the C table a few um of radial and axial error motion,
a few urad of tilt and a few arcsec of angular positioning error; the A cradle likewise.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent


def harmonics(s: np.ndarray, rng: np.random.Generator, size: float, cycles: tuple[float, ...]) -> np.ndarray:
    """Sum of size * U(0.5, 1) * sin(2 pi * cycles * s + random phase) over the normalised position s."""
    return sum(size * rng.uniform(0.5, 1.0) * np.sin(2 * np.pi * c * s + rng.uniform(0, np.pi)) for c in cycles)


def write(path: Path, first: str, position: np.ndarray, columns: dict[str, np.ndarray]) -> None:
    lines = [",".join([first, *columns])]
    lines += [",".join([f"{q:.3f}", *(f"{v[k]:.4f}" for v in columns.values())]) for k, q in enumerate(position)]
    path.write_text("\n".join(lines) + "\n")


def main() -> None:
    rng = np.random.default_rng(11)
    for letter, start, end in (("X", -300.0, 300.0), ("Y", -250.0, 250.0), ("Z", -500.0, 0.0)):
        q = np.linspace(start, end, 61)
        s = (q - start) / (end - start)
        columns = {f"E{d}{letter}_um": harmonics(s, rng, 5.0 if d == letter else 2.5, (0.5, 1.5)) for d in "XYZ"}
        columns |= {f"E{d}{letter}_urad": harmonics(s, rng, 20.0, (0.5, 2.0)) for d in "ABC"}
        write(HERE / f"{letter.lower()}_errors.csv", "position_mm", q, columns)
    # C: a full turn every 10 deg, periodic (the table closes the circle back to 0 deg)
    q = np.arange(0.0, 360.0, 10.0)
    s = q / 360.0
    columns = {
        "EXC_um": harmonics(s, rng, 1.5, (2.0, 3.0)),
        "EYC_um": harmonics(s, rng, 1.5, (2.0, 3.0)),
        "EZC_um": harmonics(s, rng, 1.0, (1.0, 4.0)),
        "EAC_urad": harmonics(s, rng, 4.0, (1.0, 2.0)),
        "EBC_urad": harmonics(s, rng, 4.0, (1.0, 2.0)),
        "ECC_arcsec": harmonics(s, rng, 3.0, (1.0, 2.0, 4.0)),
    }
    write(HERE / "c_errors.csv", "position_deg", q, columns)
    # A: the cradle tilts from -120 to +30 deg, every 5 deg
    q = np.arange(-120.0, 30.1, 5.0)
    s = (q + 120.0) / 150.0
    columns = {
        "EXA_um": harmonics(s, rng, 1.0, (0.5, 1.0)),
        "EYA_um": harmonics(s, rng, 2.0, (0.5, 1.0)),
        "EZA_um": harmonics(s, rng, 2.0, (0.5, 1.0)),
        "EAA_arcsec": harmonics(s, rng, 4.0, (0.5, 1.5)),
        "EBA_urad": harmonics(s, rng, 6.0, (0.5, 1.0)),
        "ECA_urad": harmonics(s, rng, 6.0, (0.5, 1.0)),
    }
    write(HERE / "a_errors.csv", "position_deg", q, columns)


if __name__ == "__main__":
    main()
