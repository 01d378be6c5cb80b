"""fleet.html says why a machine has no drift or next due date, and names figures as people read them."""

from __future__ import annotations

import datetime as _dt

from axiscal.fleet import CampaignOutcome, FleetRun, figure_title, machine_rows, render_fleet_html
from axiscal.history import Drift, drifting_results


def _run(*machines: tuple[str, int, float]) -> FleetRun:
    outcomes = []
    for name, campaigns, slope in machines:
        for n, payload in enumerate(drifting_results({"positioning.X.E": Drift(10.0, slope, 0.5, 20.0)}, machine=name,
                                                     campaigns=campaigns, start=_dt.date(2025, 1, 6), seed=1)):
            outcomes.append(CampaignOutcome(f"{name}-{n}", "", "", payload))
    return FleetRun(tuple(outcomes), "threads", 0.0)


def test_a_machine_with_two_visits_says_three_are_needed():
    run = _run(("new mill", 2, 3.0), ("old lathe", 4, 3.0), ("steady", 4, 0.0))
    rows = {r.machine: r for r in machine_rows(run)}
    assert rows["new mill"].trend_note == "2 visits; 3 needed" and rows["new mill"].next_due is None
    assert rows["old lathe"].trend_note == "" and rows["old lathe"].next_due is not None
    page = render_fleet_html(run, list(rows.values()), generated="now")
    row = page[page.index(">new mill<"):]
    row = row[:row.index("</tr>")]
    assert row.count("2 visits; 3 needed") == 2 and "not predicted" not in page
    assert "no drift" in page[page.index(">steady<"):]
    # figures by name, not by key
    assert "X: positioning E" in page and "positioning.X.E" not in page


def test_figure_titles():
    assert figure_title("diagonal.diagonal-0kg.diagonal_error_um") == "diagonal-0kg: diagonal error"
    assert figure_title("squareness.XZ.squareness_arcsec") == "XZ: squareness"
    assert figure_title("odd") == "odd"
