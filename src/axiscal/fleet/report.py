"""``axiscal fleet report`` in one call: every campaign reported on Dask, then fleet.html and fleet.json.

No standard clause: :mod:`axiscal.fleet.runner` runs the campaigns, :mod:`axiscal.fleet.page`
ranks the machines.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from axiscal.fleet.page import MachineRow, fleet_payload, machine_rows, render_fleet_html
from axiscal.fleet.runner import SCHEDULER_TIMEOUT_S, FleetRun, find_campaigns, run_fleet
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_count, check_path
from axiscal.io.atomic import write_text
from axiscal.io.jsonio import dumps

__all__ = ["FleetReport", "fleet_report"]


@dataclass(frozen=True)
class FleetReport:
    """What ``axiscal fleet report`` wrote.

    Attributes
    ----------
    html, json : Path
        ``OUT/fleet.html`` and ``OUT/fleet.json``.
    run : FleetRun
        Every campaign's outcome.
    machines : tuple of MachineRow
        The page's rows, most urgent first.
    """

    html: Path
    json: Path
    run: FleetRun
    machines: tuple[MachineRow, ...]

    @property
    def failed(self) -> int:
        """How many campaigns could not be reported."""
        return sum(1 for o in self.run.outcomes if o.error)


def fleet_report(
    campaigns_dir: str | Path,
    out_dir: str | Path,
    *,
    scheduler: str = "local",
    workers: int = 2,
    processes: bool = True,
    history: bool = False,
    db: str | None = None,
    timeout_s: float = SCHEDULER_TIMEOUT_S,
    progress: Callable[[int, int], None] | None = None,
) -> FleetReport:
    """Report every campaign under ``campaigns_dir`` in parallel and write the fleet's page.

    Parameters
    ----------
    campaigns_dir : str or Path
        A folder of campaign folders (each with campaign.toml), at any depth.
    out_dir : str or Path
        Each campaign's report goes to ``OUT/<campaign folder name>``; ``fleet.html`` and
        ``fleet.json`` to ``OUT``.
    scheduler : str, keyword-only
        ``"local"`` (a LocalCluster, default), ``"threads"`` or a scheduler's address.
    workers : int, keyword-only
        Workers of the LocalCluster or threads.
    processes : bool, keyword-only
        LocalCluster workers as processes (default) or threads.
    history : bool, keyword-only
        Store every campaign in the history database; drift and next due dates then use every
        stored campaign of each machine.
    db : str, keyword-only
        The history database (default ``$AXISCAL_DB``, else the user's SQLite file).
    timeout_s : float, keyword-only
        Seconds to wait for a scheduler given by address.
    progress : callable, keyword-only
        Called with (done, total) as campaigns finish.

    Returns
    -------
    FleetReport

    Raises
    ------
    AxiscalError
        For a folder without campaigns, a scheduler that does not answer, or a page that cannot
        be written; a campaign that fails is listed on the page instead.

    Examples
    --------
    >>> fleet = fleet_report("plant/", "plant-report/", scheduler="threads")  # doctest: +SKIP
    >>> fleet.machines[0].next_due  # doctest: +SKIP
    """
    out_dir = check_path("out_dir", out_dir)
    workers = check_count("workers", workers)
    if db is not None and not history:
        raise AxiscalError("db applies only with history=True")
    campaigns = find_campaigns(campaigns_dir, exclude=out_dir)
    run = run_fleet(campaigns, out_dir, scheduler=scheduler, workers=workers, processes=processes, history=history,
                    db=db, timeout_s=timeout_s, progress=progress)
    if history:
        from axiscal.history.database import resolve_url

        db = resolve_url(db)
    rows = machine_rows(run, history=history, db=db)
    html = write_text(out_dir / "fleet.html", render_fleet_html(run, rows, out_dir=out_dir))
    data = write_text(out_dir / "fleet.json", dumps(fleet_payload(run, rows)))
    return FleetReport(html, data, run, tuple(rows))
