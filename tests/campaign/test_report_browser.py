"""report.html in headless Chromium: every section and plot is there, and the page requests nothing
outside itself (no style sheet, script, font or image from anywhere)."""

from __future__ import annotations

import base64
import json
import shutil
import time
from pathlib import Path

READ = """JSON.stringify({
  title: document.querySelector("h1").textContent,
  verdict: document.getElementById("verdict").textContent.trim(),
  verdictRows: document.querySelectorAll("#verdict-table tbody tr").length,
  sections: Array.from(document.querySelectorAll("section")).map(s => s.id),
  tests: Array.from(document.querySelectorAll("article.test")).map(a => a.id),
  plots: Array.from(document.querySelectorAll("figure.plot svg")).map(s => s.getBoundingClientRect().width),
  external: Array.from(document.querySelectorAll("[src],[href]")).map(e => e.getAttribute("src") || e.getAttribute("href"))
    .filter(u => !u.startsWith("#")),
  resources: performance.getEntriesByType("resource").map(r => r.name),
})"""

#: a campaign of a 3-axis machining centre with every kind of file but the model's (test data)
VMC850 = Path(__file__).parent / "data" / "vmc850"


def test_report_page_in_chromium(chromium_page, run_cli, tmp_path):
    campaign = tmp_path / "campaign"
    shutil.copytree(VMC850, campaign)
    assert run_cli("report", campaign)[0] == 0
    page = campaign / "report" / "report.html"
    tools = chromium_page
    tools.call("Network.enable")
    tools.call("Runtime.enable")
    tools.call("Emulation.setDeviceMetricsOverride", width=1200, height=1500, deviceScaleFactor=1, mobile=False)
    tools.call("Page.navigate", url=page.as_uri())
    deadline = time.monotonic() + 20.0
    shown = None
    while time.monotonic() < deadline:
        if tools.evaluate("document.readyState") == "complete":
            shown = json.loads(tools.evaluate(READ))
            break
        time.sleep(0.1)
    assert shown is not None, "the page did not load"
    assert shown["title"] == "Acceptance test after rebuild"
    assert shown["verdict"] == "FAIL"
    assert shown["verdictRows"] == 12  # 4 figures for each of 2 positioning tests, then one each
    assert {"axis-X", "axis-Y", "squareness", "ballbar", "methods"} <= set(shown["sections"])
    assert shown["tests"] == ["positioning-X-1", "straightness-X-1", "separation-X-1", "positioning-Y-1", "squareness-XY-1", "ballbar-XY-1"]
    assert len(shown["plots"]) == 6 and min(shown["plots"]) > 300  # the plots are drawn, not empty boxes
    assert shown["external"] == [] and shown["resources"] == []
    requested = [e["params"]["request"]["url"] for e in tools.events if e.get("method") == "Network.requestWillBeSent"]
    assert requested == [page.as_uri()], requested
    errors = [e for e in tools.events if e.get("method") == "Runtime.exceptionThrown"]
    assert not errors
    shot = tools.call("Page.captureScreenshot", format="png", clip={"x": 0, "y": 0, "width": 1200, "height": 900, "scale": 1})
    (tmp_path / "summary.png").write_bytes(base64.b64decode(shot["data"]))
    assert Path(tmp_path / "summary.png").stat().st_size > 10_000
