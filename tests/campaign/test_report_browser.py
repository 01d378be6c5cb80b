"""report.html in headless Chromium: every section and plot is there, and the page requests nothing
outside itself (no style sheet, script, font or image from anywhere)."""

from __future__ import annotations

import shutil
from pathlib import Path

READ = """() => ({
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


def test_report_page_in_chromium(browser_page, run_cli, tmp_path):
    campaign = tmp_path / "campaign"
    shutil.copytree(VMC850, campaign)
    assert run_cli("report", campaign)[0] == 0
    page = campaign / "report" / "report.html"
    browser = browser_page.page
    browser.set_viewport_size({"width": 1200, "height": 1500})
    browser.goto(page.as_uri(), wait_until="load")
    shown = browser.evaluate(READ)
    assert shown["title"] == "Acceptance test after rebuild"
    assert shown["verdict"] == "FAIL"
    assert shown["verdictRows"] == 12  # 4 figures for each of 2 positioning tests, then one each
    assert {"axis-X", "axis-Y", "squareness", "ballbar", "methods"} <= set(shown["sections"])
    assert shown["tests"] == ["positioning-X-1", "straightness-X-1", "separation-X-1", "positioning-Y-1", "squareness-XY-1", "ballbar-XY-1"]
    assert len(shown["plots"]) == 6 and min(shown["plots"]) > 300  # the plots are drawn, not empty boxes
    assert shown["external"] == [] and shown["resources"] == []
    assert browser_page.requests == [page.as_uri()], browser_page.requests
    assert not browser_page.errors
    browser.screenshot(path=tmp_path / "summary.png", clip={"x": 0, "y": 0, "width": 1200, "height": 900})
    assert Path(tmp_path / "summary.png").stat().st_size > 10_000
