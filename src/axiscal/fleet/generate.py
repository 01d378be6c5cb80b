"""Generated fleets: campaign folders of machines whose positioning error grows linearly with time.

No standard clause: a test bench for :mod:`axiscal.fleet` and its benchmark. Each campaign holds one
bidirectional ISO 230-2 positioning run of an X axis (11 targets over 800 mm, 5 runs): a linear
scale error that grows by ``drift_um_per_year`` over the axis length each year, a reversal of
2 um and normal noise, so that E rises about linearly over the campaigns.
"""

from __future__ import annotations

import datetime as _dt
from pathlib import Path

import numpy as np

from axiscal.io.arguments import check_count, check_instance, check_number, check_path
from axiscal.io.atomic import write_text
from axiscal.io.jsonio import write_sidecar
from axiscal.io.tabular import write_csv

__all__ = ["generated_fleet"]

_TOML = """[campaign]
title = "{machine}: periodic calibration {n}"
date = {date}
operator = "generated fleet"

[machine]
name = "{machine}"
serial = "{serial}"

[instrument]
name = "Laser interferometer (generated)"

[tolerances]
positioning = {{ A_um = {tolerance_a:.1f}, E_um = {tolerance:.1f}, R_um = 6.0, B_um = 5.0 }}

[[tests]]
kind = "positioning"
axis = "X"
file = "positioning_x.csv"
"""


def generated_fleet(
    folder: str | Path,
    *,
    machines: int = 4,
    campaigns: int = 3,
    interval_days: int = 120,
    start: _dt.date = _dt.date(2024, 1, 8),
    drift_um_per_year: float = 4.0,
    tolerance_um: float = 25.0,
    seed: int = 0,
) -> list[Path]:
    """Write ``machines x campaigns`` campaign folders under ``folder``.

    Parameters
    ----------
    folder : str or Path
        Made when missing; campaign ``k`` of machine ``m`` is ``folder/mMMM-cKK``.
    machines, campaigns : int, keyword-only
        How many machines and campaigns of each.
    interval_days : int, keyword-only
        Days between a machine's campaigns.
    start : datetime.date, keyword-only
        The first campaign's date.
    drift_um_per_year : float, keyword-only
        How fast the scale error grows (machine ``m`` drifts ``(1 + m % 3) / 2`` times this).
    tolerance_um : float, keyword-only
        The E tolerance (A's is 1.2 times it).
    seed : int, keyword-only
        Seed of the noise.

    Returns
    -------
    list of Path
        The campaign folders, machine by machine.

    Raises
    ------
    AxiscalError
        For counts that are not positive, a drift that is not a number, or a folder that cannot
        be written.
    """
    folder = check_path("folder", folder)
    machines = check_count("machines", machines)
    campaigns = check_count("campaigns", campaigns)
    interval_days = check_count("interval_days", interval_days)
    check_instance("start", start, _dt.date)
    drift = check_number("drift_um_per_year", drift_um_per_year)
    tolerance = check_number("tolerance_um", tolerance_um, positive=True)
    rng = np.random.default_rng(seed)
    targets = np.linspace(0.0, 800.0, 11) + np.r_[0.0, rng.uniform(-5, 5, 9), 0.0]
    out = []
    for m in range(machines):
        rate = drift * (1 + m % 3) / 2
        for k in range(campaigns):
            date = start + _dt.timedelta(days=k * interval_days)
            years = k * interval_days / 365.25
            scale = (4.0 + rate * years) / 800.0  # um per mm
            rows = {"target_mm": [], "run": [], "direction": [], "deviation_um": []}
            for run in range(1, 6):
                for direction, order, shift in (("+", targets, 1.0), ("-", targets[::-1], -1.0)):
                    for x in order:
                        rows["target_mm"].append(float(x))
                        rows["run"].append(str(run))
                        rows["direction"].append(direction)
                        rows["deviation_um"].append(scale * x + shift + rng.normal(0.0, 0.3))
            campaign = folder / f"m{m:03d}-c{k:02d}"
            csv = campaign / "positioning_x.csv"
            write_csv(csv, rows, fmt={"target_mm": "{:.3f}", "deviation_um": "{:.3f}"})
            write_sidecar(csv, kind="positioning run", description="generated fleet", synthetic=True)
            write_text(campaign / "campaign.toml", _TOML.format(machine=f"Machine {m:03d}", serial=f"G-{m:03d}",
                                                                n=k + 1, date=date.isoformat(), tolerance=tolerance,
                                                                tolerance_a=1.2 * tolerance))
            out.append(campaign)
    return out
