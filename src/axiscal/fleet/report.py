"""``axiscal fleet report`` in one call: every campaign reported on Dask, then fleet.html and fleet.json.

No standard clause: :mod:`axiscal.fleet.runner` runs the campaigns, :mod:`axiscal.fleet.page`
ranks the machines. The output folder is built beside its destination and swapped into place whole
(:func:`axiscal.io.folders.atomic_folder`): a run killed at any moment leaves the earlier output as
it was, never campaign folders of one run beside a fleet page of another.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace
from pathlib import Path

from axiscal.fleet.page import MachineRow, fleet_payload, machine_rows, render_fleet_html
from axiscal.fleet.runner import SCHEDULER_TIMEOUT_S, FleetRun, find_campaigns, run_fleet
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_count, check_path
from axiscal.io.atomic import write_text
from axiscal.io.folders import atomic_folder
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

    @property
    def failed_machines(self) -> int:
        """How many machines' drift and next due date could not be worked out."""
        return sum(1 for r in self.machines if r.error)


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
        ``fleet.json`` to ``OUT``. ``OUT`` is replaced as a whole, in one step once everything is
        written; an existing folder must be empty or an earlier fleet report (holding fleet.json).
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
        For a folder without campaigns, a scheduler that does not answer, an output folder that
        holds something else, or a page that cannot be written; a campaign that fails, or a machine
        whose drift cannot be worked out, is listed on the page instead.

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
    if history:
        from axiscal.history.database import resolve_url

        db = resolve_url(db)

    def fill(staging: Path) -> tuple[FleetRun, list[MachineRow]]:
        run = run_fleet(campaigns, staging, scheduler=scheduler, workers=workers, processes=processes,
                        history=history, db=db, timeout_s=timeout_s, progress=progress, recorded_dir=out_dir)
        run = _moved(run, staging, out_dir)
        rows = machine_rows(run, history=history, db=db)
        write_text(staging / "fleet.html", render_fleet_html(run, rows, out_dir=out_dir))
        write_text(staging / "fleet.json", dumps(fleet_payload(run, rows)))
        return run, rows

    run, rows = atomic_folder(out_dir, fill, marker="fleet.json")
    return FleetReport(out_dir / "fleet.html", out_dir / "fleet.json", run, tuple(rows))


def _moved(run: FleetRun, staging: Path, out_dir: Path) -> FleetRun:
    """``run`` with its report folders named where they will be once the staging folder is in place."""
    outcomes = tuple(replace(o, report=str(out_dir / Path(o.report).relative_to(staging))) if o.report else o
                     for o in run.outcomes)
    return replace(run, outcomes=outcomes)
