"""Running a fleet of campaigns on Dask: every campaign's report, then the fleet's page.

No standard clause. The campaigns (folders holding campaign.toml) are reported in parallel by
:func:`axiscal.report.report_campaign`, one task per campaign, on a ``dask.distributed``
LocalCluster (default), Dask's threads in this process, or any distributed scheduler by address.
A campaign that fails is listed with its one-line error and the others finish. Each machine's
drift and next due date come from its trends (:mod:`axiscal.history`): over the history database
with ``history=True`` (the campaigns are stored first), else over the campaigns of the run.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from axiscal.campaign.config import CAMPAIGN_FILE
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_instance, check_number, check_path

__all__ = ["SCHEDULER_TIMEOUT_S", "CampaignOutcome", "FleetRun", "find_campaigns", "report_one", "run_fleet"]

#: seconds to wait for a scheduler given by address
SCHEDULER_TIMEOUT_S = 10.0
# seconds a LocalCluster's worker process is given to exit on its own once the fleet is done (Dask's
# own 5 s is short on a loaded machine: the nanny then kills the worker and logs a warning)
_WORKER_EXIT_S = 60.0
# pyplot is not thread-safe: reports made by threads of one process take turns
_PLOT_LOCK = threading.Lock()


@dataclass(frozen=True)
class CampaignOutcome:
    """What reporting one campaign of the fleet gave.

    Attributes
    ----------
    folder : str
        The campaign folder.
    report : str
        Its report folder ("" when it failed).
    error : str
        The one-line error ("" when it was reported).
    payload : dict
        Its results.json object (empty when it failed).
    seconds : float
        How long its report took.
    """

    folder: str
    report: str
    error: str
    payload: dict[str, Any] = field(default_factory=dict)
    seconds: float = 0.0


@dataclass(frozen=True)
class FleetRun:
    """Every campaign of a fleet, reported.

    Attributes
    ----------
    outcomes : tuple of CampaignOutcome
        In the order of the campaign folders.
    scheduler : str
        ``"local"``, ``"threads"`` or the address used.
    seconds : float
        Wall time of the reports (the cluster's start included).
    """

    outcomes: tuple[CampaignOutcome, ...]
    scheduler: str
    seconds: float


def find_campaigns(folder: str | Path, *, exclude: str | Path | None = None) -> list[Path]:
    """The campaign folders under ``folder``: every folder holding a campaign.toml, sorted.

    Parameters
    ----------
    folder : str or Path
    exclude : str or Path, keyword-only
        A folder left out with everything below it (the fleet's output).

    Returns
    -------
    list of Path

    Raises
    ------
    AxiscalError
        For a folder that does not exist or holds no campaign.
    """
    folder = check_path("folder", folder)
    if not folder.is_dir():
        raise AxiscalError("no such folder of campaigns", path=folder)
    skip = None if exclude is None else check_path("exclude", exclude).resolve()
    found = []
    for toml in sorted(folder.rglob(CAMPAIGN_FILE)):
        campaign = toml.parent.resolve()
        if skip is not None and (campaign == skip or skip in campaign.parents):
            continue
        found.append(toml.parent)
    if not found:
        raise AxiscalError(f"no campaign (a folder with {CAMPAIGN_FILE}) under the folder", path=folder)
    return found


def report_one(campaign: str, out_dir: str, history: bool, db: str | None, lock: bool = False,
               recorded_as: str | None = None) -> CampaignOutcome:
    """Report one campaign; any failure becomes the outcome's one-line error.

    Parameters
    ----------
    campaign, out_dir : str
        The campaign folder and its report folder.
    history : bool
        Store it in the history database and give the report its history section.
    db : str or None
        The history database.
    lock : bool
        Take turns with other threads of this process (pyplot is not thread-safe).
    recorded_as : str, optional
        The report folder the history records (default ``out_dir``): where it will be once moved.

    Returns
    -------
    CampaignOutcome
    """
    from axiscal.campaign.results import results_payload
    from axiscal.report.writer import report_campaign

    start = time.perf_counter()
    try:
        if lock:
            with _PLOT_LOCK:
                files = report_campaign(campaign, out_dir, history=history, db=db,
                                        recorded_as=recorded_as if history else None)
        else:
            files = report_campaign(campaign, out_dir, history=history, db=db,
                                        recorded_as=recorded_as if history else None)
    except AxiscalError as exc:
        return CampaignOutcome(campaign, "", " ".join(str(exc).split()), {}, time.perf_counter() - start)
    except Exception as exc:  # a campaign's failure must not stop the fleet: it is listed
        return CampaignOutcome(campaign, "", f"{type(exc).__name__}: {' '.join(str(exc).split())}"[:500], {},
                               time.perf_counter() - start)
    return CampaignOutcome(campaign, str(files.folder), "", results_payload(files.results_data),
                           time.perf_counter() - start)


def run_fleet(
    campaigns: list[Path],
    out_dir: str | Path,
    *,
    scheduler: str = "local",
    workers: int = 2,
    processes: bool = True,
    history: bool = False,
    db: str | None = None,
    timeout_s: float = SCHEDULER_TIMEOUT_S,
    progress: Callable[[int, int], None] | None = None,
    recorded_dir: str | Path | None = None,
) -> FleetRun:
    """Report every campaign on Dask, each into ``out_dir/<campaign folder name>``.

    Parameters
    ----------
    campaigns : list of Path
        Campaign folders (see :func:`find_campaigns`); their names must differ.
    out_dir : str or Path
        Where the reports go.
    scheduler : str, keyword-only
        ``"local"``: a LocalCluster of ``workers`` workers; ``"threads"``: Dask's threads here;
        else a distributed scheduler's address (``tcp://host:8786``).
    workers : int, keyword-only
        Workers of the LocalCluster.
    processes : bool, keyword-only
        LocalCluster workers as processes (default) or threads of this process.
    history : bool, keyword-only
        Store each campaign in the history database (reports get their history section).
    db : str, keyword-only
        The history database, resolved here so that every worker writes to the same one.
    timeout_s : float, keyword-only
        Seconds to wait for a scheduler given by address.
    progress : callable, keyword-only
        Called with (done, total) as campaigns finish.
    recorded_dir : str or Path, keyword-only
        Where the reports will be once ``out_dir`` is moved into place (the history records the
        campaigns' report folders there); default ``out_dir``.

    Returns
    -------
    FleetRun

    Raises
    ------
    AxiscalError
        When Dask is not installed, no scheduler answers at the address, or two campaign folders
        share a name.
    """
    out_dir = check_path("out_dir", out_dir)
    recorded_dir = out_dir if recorded_dir is None else check_path("recorded_dir", recorded_dir)
    check_instance("scheduler", scheduler, str, what='"local", "threads" or a scheduler address')
    check_instance("processes", processes, bool)
    check_instance("history", history, bool)
    timeout_s = check_number("timeout_s", timeout_s, positive=True)
    names = [Path(c).name for c in campaigns]
    for name in names:
        if names.count(name) > 1:
            raise AxiscalError(f"two campaign folders are named '{name}': their reports would share a folder")
    if history:
        from axiscal.history.database import open_engine, resolve_url

        db = resolve_url(db)
        open_engine(db).dispose()  # made (and migrated) once, before the workers write to it
    tasks = [(str(c), str(out_dir / Path(c).name), str(recorded_dir / Path(c).name)) for c in campaigns]
    start = time.perf_counter()
    if scheduler == "threads":
        import dask

        delayed = [dask.delayed(report_one)(c, o, history, db, True, r) for c, o, r in tasks]
        outcomes = list(dask.compute(*delayed, scheduler="threads", num_workers=workers))
        if progress is not None:
            progress(len(tasks), len(tasks))
    else:
        outcomes = _on_cluster(tasks, scheduler, workers, processes, history, db, timeout_s, progress)
    return FleetRun(tuple(outcomes), scheduler, time.perf_counter() - start)


def _on_cluster(tasks, scheduler, workers, processes, history, db, timeout_s, progress) -> list[CampaignOutcome]:
    try:
        from dask.distributed import Client, LocalCluster, as_completed
    except ImportError:
        raise AxiscalError("a fleet on Dask needs dask[distributed]: pip install 'axiscal[dask]'") from None
    own = None
    if scheduler == "local":
        own = LocalCluster(n_workers=workers, threads_per_worker=1, processes=processes, dashboard_address=None)
        client = Client(own)
    else:
        try:
            client = Client(scheduler, timeout=float(timeout_s))
        except (OSError, TimeoutError) as exc:
            raise AxiscalError(f"no dask scheduler answered at '{scheduler}' within {timeout_s:g} s"
                               f" ({' '.join(str(exc).split()) or type(exc).__name__})") from None
        except Exception as exc:  # not an address, or something else listening there
            raise AxiscalError(f"cannot use '{scheduler}' as a dask scheduler: {type(exc).__name__}"
                               f" {' '.join(str(exc).split())[:200]}".rstrip()) from None
    try:
        lock = own is not None and not processes
        futures = [client.submit(report_one, c, o, history, db, lock, r, pure=False) for c, o, r in tasks]
        order = {future.key: i for i, future in enumerate(futures)}
        outcomes: list = [None] * len(futures)
        for done, future in enumerate(as_completed(futures), start=1):
            outcomes[order[future.key]] = future.result()
            if progress is not None:
                progress(done, len(futures))
        return outcomes
    finally:
        client.close()
        if own is not None:
            _close_cluster(own)


def _close_cluster(cluster: Any) -> None:
    """Close a LocalCluster cleanly: every worker asked to stop and given time to exit on its own."""
    import asyncio

    async def close_workers() -> None:
        await asyncio.gather(*(worker.close(timeout=_WORKER_EXIT_S) for worker in list(cluster.workers.values())),
                             return_exceptions=True)

    try:
        cluster.sync(close_workers)
    finally:
        cluster.close(timeout=_WORKER_EXIT_S)
