"""fleet.html in headless Chromium: self-contained, and a click on a column header sorts the machines."""

from __future__ import annotations

import json
import time

import pytest

from axiscal.fleet import fleet_report, generated_fleet

pytestmark = pytest.mark.filterwarnings("ignore::UserWarning")

ROWS = "JSON.stringify(Array.from(document.querySelectorAll('#fleet tbody tr')).map(r => r.children[0].textContent.trim()))"


def test_the_fleet_page_sorts_by_a_clicked_column(chromium_page, tmp_path):
    generated_fleet(tmp_path / "plant", machines=3, campaigns=1, seed=5)
    fleet = fleet_report(tmp_path / "plant", tmp_path / "out", scheduler="threads")
    tools = chromium_page
    tools.call("Network.enable")
    tools.call("Runtime.enable")
    tools.call("Page.navigate", url=fleet.html.as_uri())
    deadline = time.monotonic() + 20.0
    while time.monotonic() < deadline and tools.evaluate("document.readyState") != "complete":
        time.sleep(0.1)
    machines = sorted(row.machine for row in fleet.machines)
    tools.evaluate("document.querySelectorAll('#fleet th')[0].click(); 'ok'")
    assert json.loads(tools.evaluate(ROWS)) == machines
    tools.evaluate("document.querySelectorAll('#fleet th')[0].click(); 'ok'")
    assert json.loads(tools.evaluate(ROWS)) == machines[::-1]
    tools.evaluate("document.querySelectorAll('#fleet th')[5].click(); 'ok'")
    nearest = sorted(fleet.machines, key=lambda r: r.worst_ratio)
    assert json.loads(tools.evaluate(ROWS)) == [r.machine for r in nearest]
    requested = [e["params"]["request"]["url"] for e in tools.events if e.get("method") == "Network.requestWillBeSent"]
    assert requested == [fleet.html.as_uri()]
    assert not [e for e in tools.events if e.get("method") == "Runtime.exceptionThrown"]
