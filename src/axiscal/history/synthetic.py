"""Generated results files of machines whose figures drift linearly: known answers for the history.

No standard clause: a test bench for :mod:`axiscal.history.trend`. Each figure of each campaign is
``value0 + slope * years + noise``, the noise normal with the standard deviation ``U / 2`` that the
file states as its expanded uncertainty (k = 2), so a drift fit's coverage can be checked against
the slope that made the data.
"""

from __future__ import annotations

import datetime as _dt
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.campaign.results import SCHEMA, Check, overall_verdict
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_count, check_instance, check_mapping, check_number, check_path
from axiscal.io.atomic import write_text
from axiscal.io.jsonio import dumps
from axiscal.version import __version__

__all__ = ["Drift", "drifting_results", "write_results"]

_YEAR_DAYS = 365.25


@dataclass(frozen=True)
class Drift:
    """How one figure of a generated machine moves.

    Attributes
    ----------
    value0 : float
        The figure at the first campaign, in its unit (micrometres for ``E``).
    slope : float
        Its drift, unit per year.
    U : float
        The expanded uncertainty (k = 2) each campaign states; the noise is normal with ``U / 2``.
    tolerance : float
        The tolerance held against its magnitude.
    """

    value0: float
    slope: float
    U: float
    tolerance: float


def drifting_results(
    figures: Mapping[str, Drift],
    *,
    machine: str = "machine",
    serial: str = "",
    start: _dt.date = _dt.date(2020, 1, 6),
    campaigns: int = 6,
    interval_days: int = 91,
    seed: int = 0,
) -> list[dict[str, Any]]:
    """The results.json objects of one machine's campaigns.

    Parameters
    ----------
    figures : mapping of str to Drift
        ``KIND.AXIS.FIGURE`` (``positioning.X.E``) -> how it drifts; the tolerance key is the
        figure's name with ``_um``.
    machine, serial : str, keyword-only
        The machine's identity.
    start : datetime.date, keyword-only
        The first campaign's date.
    campaigns : int, keyword-only
        How many, at least 1.
    interval_days : int, keyword-only
        Days between campaigns.
    seed : int, keyword-only
        Seed of the noise.

    Returns
    -------
    list of dict
        Schema ``axiscal-results/1``, oldest first.

    Raises
    ------
    AxiscalError
        For a figure key that is not ``KIND.AXIS.FIGURE``, a drift that is not a Drift, or
        counts that are not positive.
    """
    check_mapping("figures", figures, what="a mapping of figure keys to Drift")
    check_instance("start", start, _dt.date)
    campaigns = check_count("campaigns", campaigns)
    interval_days = check_count("interval_days", interval_days)
    for key, drift in figures.items():
        check_instance(f"figures['{key}']", drift, Drift)
        if not isinstance(key, str) or len(key.split(".")) != 3 or not all(key.split(".")):
            raise AxiscalError(f"figures: {key!r} must be KIND.AXIS.FIGURE, e.g. 'positioning.X.E'")
        check_number(f"figures['{key}'].U", drift.U, positive=True)
        check_number(f"figures['{key}'].tolerance", drift.tolerance, positive=True)
    rng = np.random.default_rng(seed)
    out = []
    for n in range(campaigns):
        date = start + _dt.timedelta(days=n * interval_days)
        years = (date - start).days / _YEAR_DAYS
        tests: dict[tuple[str, str], dict[str, Any]] = {}
        for key, drift in figures.items():
            kind, axis, name = key.split(".")
            test = tests.setdefault((kind, axis), {"id": f"{kind}-{axis}-1", "kind": kind, "axis": axis, "file": "",
                                                    "figures": {}, "tolerances": {}, "uncertainty": {"k": 2},
                                                    "checks": []})
            value = drift.value0 + drift.slope * years + rng.normal(0.0, drift.U / 2)
            test["figures"][name] = value
            test["tolerances"][f"{name}_um"] = drift.tolerance
            test["uncertainty"][name] = drift.U
            test["checks"].append(Check(name, f"{name}_um", value, drift.tolerance, "um", drift.U).result)
        entries = []
        for test in tests.values():
            results = test.pop("checks")
            test["verdict"] = "fail" if "fail" in results else "pass"
            entries.append(test)
        out.append({
            "schema": SCHEMA,
            "software": {"name": "axiscal", "version": __version__},
            "campaign": {"campaign": {"title": f"{machine}: campaign {n + 1} (generated)", "date": date.isoformat()},
                         "machine": {"name": machine, "serial": serial}, "instrument": {}},
            "verdict": overall_verdict([t["verdict"] for t in entries]),
            "decision_rule": "simple",
            "tests": entries,
            "compensation": [],
            "warnings": [],
        })
    return out


def write_results(folder: str | Path, payloads: list[dict[str, Any]], *, prefix: str = "results") -> list[Path]:
    """Write results objects as ``FOLDER/PREFIX-NNN.json``, atomically.

    Parameters
    ----------
    folder : str or Path
        Made when missing.
    payloads : list of dict
        From :func:`drifting_results`.
    prefix : str, keyword-only
        The files' name before the number.

    Returns
    -------
    list of Path

    Raises
    ------
    AxiscalError
        When a file cannot be written.
    """
    folder = check_path("folder", folder)
    check_instance("payloads", payloads, list)
    return [write_text(folder / f"{prefix}-{n:03d}.json", dumps(p)) for n, p in enumerate(payloads)]
