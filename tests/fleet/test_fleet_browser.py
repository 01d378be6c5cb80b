"""fleet.html in headless Chromium: self-contained, and a click on a column header sorts the machines."""

from __future__ import annotations

import pytest

from axiscal.fleet import fleet_report, generated_fleet

pytestmark = pytest.mark.filterwarnings("ignore::UserWarning")

ROWS = "() => Array.from(document.querySelectorAll('#fleet tbody tr')).map(r => r.children[0].textContent.trim())"


def test_the_fleet_page_sorts_by_a_clicked_column(browser_page, tmp_path):
    generated_fleet(tmp_path / "plant", machines=3, campaigns=1, seed=5)
    fleet = fleet_report(tmp_path / "plant", tmp_path / "out", scheduler="threads")
    page = browser_page.page
    page.goto(fleet.html.as_uri(), wait_until="load")
    machines = sorted(row.machine for row in fleet.machines)
    headers = page.locator("#fleet th")
    headers.nth(0).click()
    assert page.evaluate(ROWS) == machines
    headers.nth(0).click()
    assert page.evaluate(ROWS) == machines[::-1]
    headers.nth(5).click()
    nearest = sorted(fleet.machines, key=lambda r: r.worst_ratio)
    assert page.evaluate(ROWS) == [r.machine for r in nearest]
    assert browser_page.requests == [fleet.html.as_uri()]
    assert not browser_page.errors
