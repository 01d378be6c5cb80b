"""Take the screenshots of docs/workbench.md: each step of a visit on the virtual machine, in headless Chromium.

Run from the repository root: ``.venv/bin/python docs/workbench_screenshots.py``. It needs Debian's
chromium (``make chromium``) and Playwright (``make`` installs it). A history with one machine
(three visits of a lathe, made by ``axiscal.history.drifting_results``) and a data folder holding the
example instrument files are made in a temporary folder; the page is 1366x768, the laptop screen the
workbench is made for. The visit is the example three-axis machine's: X, Y and Z planned and run,
a straightness, a squareness and a ballbar test added from files.
Writes docs/workbench_1_machines.png ... docs/workbench_8_finish.png and docs/workbench_2_files.png.
"""

from __future__ import annotations

import shutil
import tempfile
from pathlib import Path

from playwright.sync_api import sync_playwright

from axiscal.history import Drift, add_results, drifting_results, write_results
from axiscal.workbench import serve_workbench

DOCS = Path(__file__).resolve().parent
EXAMPLES = DOCS.parent / "examples"
#: the instrument files of the data folder the visit takes its tests from
FILES = ("straightness_profile.csv", "squareness_x.csv", "squareness_y.csv", "ballbar/ballbar_run.csv")


def main() -> None:
    with tempfile.TemporaryDirectory(prefix="axiscal-shots-") as folder:
        tmp = Path(folder)
        db = str(tmp / "history.sqlite")
        payloads = drifting_results({"positioning.X.E": Drift(12.0, 4.0, 0.5, 40.0)}, machine="Lathe 7", serial="L7",
                                    campaigns=5)
        add_results(write_results(tmp / "lathe", payloads), url=db)
        (tmp / "data" / "instrument").mkdir(parents=True)
        for name in FILES:
            shutil.copyfile(EXAMPLES / name, tmp / "data" / "instrument" / Path(name).name)
        server = serve_workbench(tmp / "data", db=db, port=0, speed=8.0)
        try:
            with sync_playwright() as playwright:
                browser = playwright.chromium.launch(executable_path="/usr/bin/chromium", args=["--no-sandbox"])
                page = browser.new_page(viewport={"width": 1366, "height": 768})
                page.set_default_timeout(120_000)
                visit(page, server)
                browser.close()
        finally:
            server.stop()


def shot(page, name: str) -> None:
    path = DOCS / f"workbench_{name}.png"
    page.screenshot(path=path)
    wide = page.evaluate("document.documentElement.scrollWidth")
    print(path.relative_to(DOCS.parent), "" if wide <= 1366 else f"(scrolls sideways: {wide} px wide)")


def add_file_test(page, fields: dict[str, str]) -> None:
    """Add a test from a file of the data folder on the New visit step, and wait for it to be checked."""
    page.select_option("#file-form [name=kind]", fields.pop("kind"))
    for name, value in fields.items():
        if name == "plane":
            page.select_option(f"#file-form [name={name}]", value)
        else:
            page.fill(f"#file-form [name={name}]", value)
    page.click("#file-form button[type=submit]")
    page.wait_for_function("!document.querySelector('#file-added').textContent.startsWith('Checking')")


def run_test(page, axis: str) -> None:
    page.locator(f".tests-list[data-mode=run] tr[data-test=positioning-{axis}] button").click()
    page.wait_for_selector(f".tests-list[data-mode=run] tr[data-test=positioning-{axis}] td.state[data-state=running]")


def visit(page, server) -> None:
    page.goto(server.url)
    page.get_by_role("button", name="Open").click()
    page.wait_for_selector("#trend-plot svg")
    shot(page, "1_machines")

    page.get_by_role("button", name="2 New visit").click()
    for name, value in (("title", "Acceptance after the ball screw was changed"), ("operator", "J. Doe"),
                        ("customer", "Works 2"), ("machine", "VMC 1"), ("serial", "S1"), ("instrument_serial", "L-1204"),
                        ("certificate", "CAL-2026-118"), ("A_um", "-3")):
        page.fill(f"#visit-form [name={name}]", value)
    # a new machine described by its chain and travels, one travel forgotten: named beside its field
    page.select_option("#machine-choice", "new")
    page.fill("#visit-form [name=machine_chain]", "XFYZ")
    page.fill("#visit-form [name=machine_travels]", "X=0:800, Y=0:500")
    page.click("#visit-form button[type=submit]")
    page.wait_for_selector(".field-error[data-for=machine_travels]:not(:empty)")
    page.evaluate("document.querySelectorAll('#visit-form fieldset')[1].scrollIntoView(); window.scrollBy(0, -60)")
    shot(page, "2_visit")
    page.select_option("#machine-choice", "example")  # the example machine after all: its axes have their errors
    page.fill("#visit-form [name=A_um]", "45")
    # the laser's budget: U (k = 2) beside every figure on Results
    for name, value in (("length_U_ppm", "0.5"), ("air_temperature_u_K", "0.1"), ("air_pressure_u_Pa", "50"),
                        ("air_humidity_u_percent", "2"), ("machine_temperature_C", "20.3"), ("machine_temperature_u_K", "0.1"),
                        ("expansion_per_K", "11.5e-6"), ("expansion_u_per_K", "1e-6"), ("misalignment_urad", "50"),
                        ("eve_um", "1")):
        page.fill(f"#visit-form [name={name}]", value)
    page.click("#visit-form button[type=submit]")
    page.wait_for_selector("#visit-saved:not([hidden])")
    add_file_test(page, {"kind": "straightness", "file": "instrument/straightness_profile.csv", "axis": "X", "direction": "Y"})
    add_file_test(page, {"kind": "squareness", "file": "instrument/squareness_x.csv", "second": "instrument/squareness_y.csv",
                         "plane": "XY"})
    add_file_test(page, {"kind": "ballbar", "file": "instrument/ballbar_run.csv", "radius_mm": "100", "plane": "XY"})
    add_file_test(page, {"kind": "straightness", "file": "instrument/squareness_x.csv", "axis": "Y", "direction": "X"})
    page.locator("#file-block").scroll_into_view_if_needed()
    shot(page, "2_files")

    page.get_by_role("button", name="3 Plan").click()
    for axis, end in (("X", "150"), ("Y", "120"), ("Z", "100")):
        page.locator(f".tests-list[data-mode=plan] tr[data-test=positioning-{axis}] button").click()
        page.fill("#plan-form [name=end_mm]", end)
        page.fill("#plan-form [name=runs]", "2")
        page.click("#plan-form button[type=submit]")
        page.wait_for_selector(f".tests-list[data-mode=plan] tr[data-test=positioning-{axis}]:has-text('planned')")
    page.locator(".tests-list[data-mode=plan] tr[data-test=positioning-Y] button").click()
    shot(page, "3_plan")

    page.get_by_role("button", name="4 Connect").click()
    page.click("#connect-form button[type=submit]")
    page.wait_for_selector("#light-instrument[data-state=ok]")
    shot(page, "4_connect")

    page.get_by_role("button", name="5 Run").click()
    for axis in ("X", "Y"):
        run_test(page, axis)
        page.wait_for_selector(f".tests-list[data-mode=run] tr[data-test=positioning-{axis}] td.state[data-state=done]")
    run_test(page, "Z")
    page.wait_for_function("document.querySelectorAll('#stops tbody tr').length >= 7")
    shot(page, "5_run")
    page.wait_for_selector("#run-state[data-state=done]")

    page.get_by_role("button", name="6 Results").click()
    page.click("#show-results")
    page.wait_for_selector("#results article.test")
    shot(page, "6_results")

    page.get_by_role("button", name="7 Compensate").click()
    page.click("#compensate")
    page.wait_for_selector("#comp-download:not([hidden])")
    page.click("#run-as-left")
    page.wait_for_selector("#run-phase:has-text('as-left')")
    page.wait_for_selector("#run-state[data-state=done]")
    page.get_by_role("button", name="7 Compensate").click()
    page.click("#before-after")
    page.wait_for_selector("#changes tbody tr")
    shot(page, "7_compensate")

    page.get_by_role("button", name="8 Finish").click()
    page.click("#finish")
    page.wait_for_selector("#report-links li")
    shot(page, "8_finish")


if __name__ == "__main__":
    main()
