"""The history side of the workbench's page: the machines, their visits, the trend of a figure.

:class:`HistoryViews` is a part of :class:`~axiscal.workbench.visit.Workbench`: what the page's first
step (Machines) asks of the calibration history (:mod:`axiscal.history`), computed there, turned
into JSON-able answers here. It uses the workbench's ``db``, ``data``, ``_history_lock`` and
``_plot_lock``.
"""

from __future__ import annotations

import tempfile
from pathlib import Path
from typing import Any

__all__ = ["HistoryViews"]


class HistoryViews:
    """The history's machines, one machine's visits and a figure's trend, as the page shows them.

    Attributes
    ----------
    (none of its own)
        It reads the history named by the :class:`~axiscal.workbench.visit.Workbench`'s ``db``.
    """

    def check_history(self) -> None:
        """Open the history database as the page's first reading will: one line if it cannot be used.

        A database that does not exist yet is made (an SQLite file: the history's own tables), one of an
        older schema brought up to date, as :func:`axiscal.history.machine_histories` does.

        Raises
        ------
        AxiscalError
            As the ``axiscal history`` commands: for a file that is not a database, one cut short or
            damaged, of a newer schema, another application's tables, a folder, a URL SQLAlchemy does
            not read or whose driver is missing, a server that cannot be reached.
        """
        from axiscal.history import open_engine

        with self._history_lock:
            open_engine(self.db).dispose()

    # -- 1. machines -------------------------------------------------------------------------------
    def machines(self) -> list[dict[str, Any]]:
        """The machines of the history: last visit, verdict, next due date, trend of the first figure."""
        from axiscal.history import machine_histories, machine_trends

        out = []
        with self._history_lock:
            histories = machine_histories(url=self.db)
        for history in histories:
            trends = machine_trends(history)
            due = min((t.next_date for t in trends), default=None)
            first = trends[0] if trends else None
            last = history.campaigns[-1]
            out.append({
                "machine": history.label, "visits": len(history.campaigns), "last_date": last.date.isoformat(),
                "verdict": last.verdict, "next_due": None if due is None else due.isoformat(),
                "spark_figure": None if first is None else first.figure,
                "spark": [] if first is None else [float(v / first.tolerance) for v in first.values],
            })
        return out

    def machine(self, label: str) -> dict[str, Any]:
        """One machine's visits and the figures whose trend can be drawn."""
        from axiscal.history import machine_history, machine_trends

        history = machine_history(label, url=self.db)
        trends = machine_trends(history)
        reports = self._reports()
        return {
            "machine": history.label,
            "visits": [{"id": c.id, "date": c.date.isoformat(), "title": c.title, "verdict": c.verdict,
                        "figures": len(c.figures), "report": reports.get(c.results_sha256)}
                       for c in reversed(history.campaigns)],
            "trends": [{"figure": t.figure, "unit": t.unit, "next_due": t.next_date.isoformat(),
                        "latest": float(t.values[-1]), "tolerance": t.tolerance} for t in trends],
        }

    def _reports(self) -> dict[str, str]:
        """The reports of the data folder's visits by their results.json's SHA-256 (as the history keys them)."""
        import hashlib

        found = {}
        for results in [*self.data.glob("*/report/results.json"), *self.data.glob("*/as-left/report/results.json")]:
            html = results.with_name("report.html")
            if html.is_file():
                found[hashlib.sha256(results.read_bytes()).hexdigest()] = self._rel(html)
        return found

    def trend_svg(self, label: str, figure: str) -> str:
        """The history's trend plot of one figure of a machine, as SVG text."""
        from axiscal.history import figure_trend

        with tempfile.TemporaryDirectory(prefix="axiscal-trend-") as folder:
            path = Path(folder) / "trend.svg"
            with self._plot_lock:
                figure_trend(label, figure, url=self.db, plot=path)
            return path.read_text(encoding="utf-8")
