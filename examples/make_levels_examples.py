"""Write the electronic-level example (run from the repository root: python examples/make_levels_examples.py).

examples/levels/levels_run.csv: a 1000 mm axis measured with a level of 100 mm foot spacing in
steps of one foot (the classic method), readings in arcsec rounded to 0.01 arcsec, with a second
level on the machine bed (reference_arcsec) that sees the whole machine tilt by up to 1.5 arcsec
while the run is taken. The guideway's profile is a bow of 3 um with a 0.4 um wave of 250 mm.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
ARCSEC = np.pi / 648000
FOOT_MM = 100.0


def guideway_um(x_mm: np.ndarray) -> np.ndarray:
    """The true profile of the guideway, um, over 0..1000 mm."""
    u = x_mm / 1000.0
    return 12.0 * u * (1.0 - u) + 0.4 * np.sin(2 * np.pi * x_mm / 250.0)


def main() -> None:
    stations = np.arange(0.0, 1000.0 + FOOT_MM / 2, FOOT_MM)
    rise_um = np.diff(guideway_um(stations))
    slope_arcsec = rise_um * 1e-6 / (FOOT_MM * 1e-3) / ARCSEC
    tilt_arcsec = 1.5 * np.sin(np.linspace(0.0, np.pi / 2, slope_arcsec.size)) + 0.8
    rows = ["position_mm,angle_arcsec,reference_arcsec"]
    for x, a, t in zip(stations[:-1], slope_arcsec + tilt_arcsec, tilt_arcsec):
        rows.append(f"{x:.1f},{a:.2f},{t:.2f}")
    folder = HERE / "levels"
    folder.mkdir(exist_ok=True)
    (folder / "levels_run.csv").write_text("\n".join(rows) + "\n", encoding="utf-8")


if __name__ == "__main__":
    main()
