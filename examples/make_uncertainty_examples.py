"""Write examples/xfyz_machine_u: the XFYZ example machine with the standard uncertainty of every error.

The tables are those of examples/xfyz_machine with a ``<column>_u`` column beside each error column
(docs/uncertainty.md), as a laser calibration would state them: positioning errors 0.3 um plus
1.5 um per metre of travel (in quadrature), straightness 0.5 um, angles 1.5 urad; the squareness
terms 1.0 arcsec each. Run: python examples/make_uncertainty_examples.py
"""

from __future__ import annotations

import csv
import math
from pathlib import Path

HERE = Path(__file__).resolve().parent
SOURCE = HERE / "xfyz_machine"
TARGET = HERE / "xfyz_machine_u"


def u_of(column: str, letter: str, position_mm: float) -> float:
    """Standard uncertainty of one error value, in the column's unit."""
    stem = column.rsplit("_", 1)[0]
    if stem == f"E{letter}{letter}":
        return math.hypot(0.3, 1.5e-3 * position_mm)
    return 0.5 if column.endswith("_um") else 1.5


def main() -> None:
    TARGET.mkdir(exist_ok=True)
    for letter in "XYZ":
        name = f"{letter.lower()}_errors.csv"
        with open(SOURCE / name, newline="") as f:
            rows = list(csv.reader(f))
        header, body = rows[0], rows[1:]
        errors = header[1:]
        lines = [",".join(header + [f"{c}_u" for c in errors])]
        for row in body:
            position = float(row[0])
            lines.append(",".join(row + [f"{u_of(c, letter, position):.4f}" for c in errors]))
        (TARGET / name).write_text("\n".join(lines) + "\n")
    toml = (SOURCE / "machine.toml").read_text().replace("3-axis machine tool XFYZ", "3-axis machine tool XFYZ, with uncertainties")
    for term in ("EC0Y", "EB0Z", "EA0Z"):
        line = next(x for x in toml.splitlines() if x.startswith(f"{term}_arcsec"))
        toml = toml.replace(line, f"{line}\n{term}_arcsec_u = 1.0")
    (TARGET / "machine.toml").write_text(toml)


if __name__ == "__main__":
    main()
