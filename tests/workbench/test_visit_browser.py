"""A whole visit clicked through in headless Chromium on the virtual machine (``sim`` instrument and controller).

Machines and their history, a new visit (with a mistake shown beside its field), the plan and its program, connect,
the run (paused, resumed, its connection cut and the run resumed), the results, the compensation and the as-left run
with the before/after table, the reports stored in the history. The page must show every sample the laser gave.
"""

from __future__ import annotations

import pytest

from axiscal.history import Drift, add_results, drifting_results, write_results
from axiscal.workbench import serial_ports, serve_workbench

SPEED = 40.0  # the virtual machine runs 40 times faster than real time


@pytest.fixture
def workbench(tmp_path):
    db = str(tmp_path / "history.sqlite")
    payloads = drifting_results({"positioning.X.E": Drift(12.0, 4.0, 0.5, 40.0)}, machine="Lathe 7", serial="L7", campaigns=3)
    add_results(write_results(tmp_path / "lathe", payloads), url=db)
    server = serve_workbench(tmp_path / "data", db=db, port=0, speed=SPEED)
    try:
        yield server
    finally:
        server.stop()


def count(page, selector: str) -> int:
    return page.locator(selector).count()


def test_a_page_load_logs_no_console_error(browser_page, workbench):
    page = browser_page.page
    logged = []
    page.on("console", lambda message: logged.append(f"{message.type}: {message.text}"))
    failed = []
    page.on("response", lambda response: failed.append(f"{response.status} {response.url}") if response.status >= 400 else None)
    page.goto(workbench.url)
    page.wait_for_selector("#machines tbody tr")
    page.wait_for_load_state("networkidle")  # the icon is asked for after the page has loaded
    page.reload()
    page.wait_for_selector("#machines tbody tr")
    page.wait_for_load_state("networkidle")
    assert [m for m in logged if m.startswith("error")] == [] and failed == [], (logged, failed)
    assert not browser_page.errors, browser_page.errors


def test_a_whole_visit_on_the_virtual_machine(browser_page, workbench):
    page = browser_page.page
    bench = workbench.bench
    page.goto(workbench.url)

    # 1. machines: the one in the history, its sparkline; opened, its visits and the trend plot
    page.wait_for_selector("#machines tbody tr")
    assert page.locator("#machines tbody tr td").first.text_content() == "Lathe 7 (L7)"
    assert count(page, "#machines tbody svg.spark polyline") == 1
    page.get_by_role("button", name="Open").click()
    page.wait_for_selector("#trend-plot svg")
    assert count(page, "#visits tbody tr") == 3

    # 2. new visit: a wrong tolerance is named beside its field, then the campaign is written
    page.get_by_role("button", name="2 New visit").click()
    page.fill("#visit-form [name=title]", "Acceptance after rebuild")
    page.fill("#visit-form [name=operator]", "J. Doe")
    page.fill("#visit-form [name=machine]", "VMC 1")
    page.fill("#visit-form [name=serial]", "S1")
    page.fill("#visit-form [name=date]", "2026-11-26")
    page.fill("#visit-form [name=A_um]", "-3")
    page.click("#visit-form button[type=submit]")
    page.wait_for_selector(".field-error[data-for=A_um]:not(:empty)")
    assert page.locator(".field-error[data-for=A_um]").text_content() == "Input should be greater than 0"
    assert page.get_attribute("#visit-form [name=A_um]", "aria-invalid") == "true"
    page.fill("#visit-form [name=A_um]", "45")
    page.fill("#visit-form [name=length_U_ppm]", "0.5")  # the uncertainty budget: U beside every figure in Results
    page.fill("#visit-form [name=eve_um]", "1")
    page.click("#visit-form button[type=submit]")
    page.wait_for_selector("#visit-saved:not([hidden])")
    assert page.locator(".field-error[data-for=A_um]").text_content() == ""
    assert (bench.data / "vmc-1-2026-11-26" / "campaign.toml").is_file()

    # 3. plan: the table and the program, downloadable
    page.get_by_role("button", name="3 Plan").click()
    page.fill("#plan-form [name=runs]", "2")
    page.click("#plan-form button[type=submit]")
    page.wait_for_selector("#plan-table tbody tr")
    assert page.locator("#plan-readings").text_content() == "20"
    assert "G1" in page.locator("#program").text_content()
    href = page.get_attribute("#program-download", "href")
    download = page.request.get(workbench.server.url.rstrip("/") + href)
    assert download.ok and "attachment" in download.headers["content-disposition"] and "G4" in download.text()

    # 4. connect: the computer's ports listed; a spec that cannot be used named beside its field before anything
    # is opened; then both lights on, the reading and the position shown, and what each device told
    page.get_by_role("button", name="4 Connect").click()
    page.wait_for_function("document.querySelector('#ports-count').textContent === String("
                           f"{len(serial_ports())})")
    page.fill("#connect-form [name=instrument]", "umd:/dev/no-such-port")
    page.fill("#connect-form [name=ini]", "/no/such/mill.ini")  # LinuxCNC's INI file: checked at once
    page.click("#connect-form button[type=submit]")
    page.wait_for_selector("#connect-form .field-error[data-for=instrument]:not(:empty)")
    assert "this computer has no serial port /dev/no-such-port" in page.locator("#connect-form .field-error[data-for=instrument]").text_content()
    assert page.locator("#connect-form .field-error[data-for=ini]").text_content() == "no INI file at /no/such/mill.ini"
    page.fill("#connect-form [name=instrument]", "sim")
    page.fill("#connect-form [name=ini]", "")
    page.click("#connect-form button[type=submit]")
    page.wait_for_selector("#light-instrument[data-state=ok]")
    assert page.locator("#connect-form .field-error[data-for=instrument]").text_content() == ""
    assert "virtual laser" in page.locator("#told-instrument").text_content()
    assert "ready" in page.locator("#told-controller").text_content() and page.locator("#refused").is_hidden()
    assert "none: the virtual machine runs a plan's overrun" in page.locator("#told-controller").text_content()
    assert page.get_attribute("#light-controller", "data-state") == "ok"
    assert page.locator("#live-position").text_content() == "0.0000"

    # 5. run: start, pause, resume; the connection cut, the stops kept, the run resumed to its end
    page.get_by_role("button", name="5 Run").click()
    bench.speed = 10.0  # slow enough (about 4 s) for a loaded machine to pause and cut the run before it ends
    page.click("#start")
    page.wait_for_function("document.querySelectorAll('#stops tbody tr').length >= 2")
    page.click("#pause")
    page.wait_for_selector("#run-state[data-state=paused]")
    page.click("#resume")
    page.wait_for_selector("#run-state[data-state=running]")
    page.wait_for_function("document.querySelectorAll('#stops tbody tr').length >= 5")
    bench.run.cut_connection()
    page.wait_for_selector("#run-state[data-state=broken]")
    assert "connection to the instrument was lost" in page.locator("#run-message").text_content()
    assert page.get_attribute("#light-instrument", "data-state") == "lost"
    kept = count(page, "#stops tbody tr")
    assert kept >= 5
    bench.speed = SPEED
    page.click("#resume-broken")
    page.wait_for_selector("#run-state[data-state=done]", timeout=60_000)
    page.wait_for_function(f"Number(document.body.dataset.samples) === {bench.run.samples_since(0)[2]}")
    assert count(page, "#stops tbody tr") == 20
    assert page.locator("#progress").text_content() == "20 of 20 stops"
    assert count(page, "#trace circle.stop") == 20 and count(page, "#trace line, #trace polyline.target") >= 5
    assert count(page, "#deviation circle") == 20

    # 6. results: the figures with U against the tolerance, the verdict, the plot
    page.wait_for_selector("#results article.test", state="attached")  # evaluated as soon as the run ended
    page.get_by_role("button", name="6 Results").click()
    page.click("#show-results")
    page.wait_for_selector("#results article.test")
    rows = page.locator("#results table.checks tbody tr")
    assert rows.count() == 4 and rows.first.locator("td").first.text_content() == "A"
    assert "µm" in rows.first.locator("td").nth(1).text_content()
    assert all(row.locator("td").nth(2).text_content().endswith(" µm") for row in rows.all())  # U (k=2), stated
    assert page.locator("#results-decision").text_content().startswith("Decision rule: simple acceptance")
    assert count(page, "#results .plot svg") == 1

    # 7. compensate: the table, its plot and file; the as-left run with it loaded; before and after
    page.get_by_role("button", name="7 Compensate").click()
    page.click("#compensate")
    page.wait_for_selector("#comp-download:not([hidden])")
    assert count(page, "#comp-plot polyline") == 4
    assert page.locator("#comp-text").text_content().strip()
    bench.speed = 4.0  # slow enough (about 9 s) to ask for Before / after while the as-left run goes on
    page.click("#run-as-left")
    page.wait_for_selector("#run-phase:has-text('as-left')")
    page.wait_for_selector("#run-state[data-state=running]")
    page.get_by_role("button", name="7 Compensate").click()
    page.click("#before-after")
    page.wait_for_selector("#ba-status[data-state=waiting]")
    assert "waits for the as-left run to end" in page.locator("#ba-status").text_content()
    assert count(page, "#changes tbody tr") == 0
    bench.speed = SPEED
    # as soon as the run has ended the table is filled, not asked for again
    page.wait_for_selector("#ba-status[data-state=done]", timeout=60_000)
    assert bench.run.state == "done" and bench.phase == "as-left"
    changes = page.locator("#changes tbody tr")
    assert changes.count() == 4
    before, after = (float(changes.first.locator("td").nth(i).text_content().split()[0]) for i in (2, 3))
    assert after < before / 3  # the table takes most of the error away

    # 8. finish: both reports made (HTML, PDF, results) and stored; the machine is now in the history
    page.get_by_role("button", name="8 Finish").click()
    page.click("#finish")
    page.wait_for_selector("#report-links li", timeout=60_000)
    links = page.locator("#report-links a")
    assert links.count() == 6
    report = page.request.get(workbench.server.url.rstrip("/") + links.first.get_attribute("href"))
    assert report.ok and "<html" in report.text().lower()
    page.get_by_role("button", name="1 Machines").click()
    page.wait_for_function("document.querySelectorAll('#machines tbody tr').length === 2")
    page.locator("#machines tbody tr", has_text="VMC 1 (S1)").get_by_role("button", name="Open").click()
    page.wait_for_selector("#machine-title:has-text('VMC 1 (S1)')")
    assert count(page, "#visits tbody tr") == 2
    reports = [a.get_attribute("href") for a in page.locator("#visits tbody a").all()]
    assert sorted(reports) == ["/files/vmc-1-2026-11-26/as-left/report/report.html", "/files/vmc-1-2026-11-26/report/report.html"]
    assert not browser_page.errors, browser_page.errors
    external = [u for u in browser_page.requests if not u.startswith(workbench.server.url.rstrip("/"))]
    assert external == []


def test_the_visit_survives_a_reload_a_restart_and_a_second_tab(browser_page, chromium, tmp_path):
    db = str(tmp_path / "history.sqlite")
    server = serve_workbench(tmp_path / "data", db=db, port=0, speed=SPEED)
    try:
        page = browser_page.page
        page.goto(server.url)
        page.get_by_role("button", name="2 New visit").click()
        for name, value in {"title": "Acceptance", "operator": "J. Doe", "machine": "VMC 1", "serial": "S1",
                            "date": "2026-11-26"}.items():
            page.fill(f"#visit-form [name={name}]", value)
        page.uncheck("#test-boxes input[value=positioning-Z]")  # X and Y only
        page.click("#visit-form button[type=submit]")
        page.wait_for_selector("#visit-saved:not([hidden])")
        page.get_by_role("button", name="3 Plan").click()
        page.fill("#plan-form [name=runs]", "2")
        page.click("#plan-form button[type=submit]")
        page.wait_for_selector("#plan-table tbody tr")
        steps = count(page, "#plan-table tbody tr")
        with page.expect_response("**/api/step"):  # the step the page is at, kept
            page.get_by_role("button", name="4 Connect").click()

        # a reload: the visit, its plan and the step it was at
        page.reload()
        page.wait_for_selector("#step-connect:not([hidden])")
        assert page.locator("#visit-name").text_content() == "vmc-1-2026-11-26"
        assert count(page, "#plan-table tbody tr") == steps and page.input_value("#plan-form [name=runs]") == "2"
        assert count(page, ".tests-list[data-mode=plan] tbody tr") == 2  # the visit's tests, and its form as written
        assert [b.is_checked() for b in page.locator("#test-boxes input").all()] == [True, True, False]

        # a second tab on the same visit follows it read-only: its changes are refused, the visit is not touched
        other = chromium.new_context(viewport={"width": 1366, "height": 768}).new_page()
        try:
            other.goto(server.url)
            other.wait_for_selector("#readonly:not([hidden])")
            assert other.locator("#visit-name").text_content() == "vmc-1-2026-11-26"
            other.get_by_role("button", name="3 Plan").click()
            other.fill("#plan-form [name=runs]", "3")
            other.click("#plan-form button[type=submit]")
            other.wait_for_selector("#error:not([hidden])")
            assert "open in another tab" in other.locator("#error").text_content()
        finally:
            other.context.close()
        assert server.bench.plan.runs == 2 and server.bench.saved.step == "connect"
    finally:
        server.stop()

    # a server restart: the page, reloaded, is at the same step of the same visit; connect and run go on
    server = serve_workbench(tmp_path / "data", db=db, port=0, speed=SPEED)
    try:
        page.goto(server.url)
        page.wait_for_selector("#step-connect:not([hidden])")
        assert page.locator("#visit-name").text_content() == "vmc-1-2026-11-26"
        assert count(page, "#plan-table tbody tr") == steps
        page.click("#connect-form button[type=submit]")
        page.wait_for_selector("#light-instrument[data-state=ok]")
        page.get_by_role("button", name="5 Run").click()
        page.click("#start")
        page.wait_for_selector("#run-state[data-state=done]", timeout=60_000)
        assert page.locator("#progress").text_content() == "20 of 20 stops"
        assert not browser_page.errors, browser_page.errors
    finally:
        server.stop()


def no_sideways_scroll(page) -> None:
    """The step shown fits the 1366 px wide screen: nothing to scroll horizontally."""
    assert page.evaluate("document.documentElement.scrollWidth") <= 1366


def test_a_three_axis_visit_with_tests_from_files(browser_page, tmp_path):
    """The example machine's X, Y and Z planned, run (Y run again) and evaluated, with tests from files beside them."""
    from pathlib import Path

    examples = Path(__file__).resolve().parents[2] / "examples"
    data = tmp_path / "data"
    (data / "instrument").mkdir(parents=True)
    for name in ("straightness_profile.csv", "ballbar/ballbar_run.csv", "squareness_x.csv"):
        (data / "instrument" / Path(name).name).write_bytes((examples / name).read_bytes())
    (tmp_path / "bad.csv").write_text("position_mm,deviation_um\n0,1\n10,abc\n20,2\n")
    server = serve_workbench(data, db=str(tmp_path / "history.sqlite"), port=0, speed=SPEED)
    try:
        page = browser_page.page
        page.goto(server.url)

        # 2. the visit: the example machine's three axes offered as tests, all three kept
        page.get_by_role("button", name="2 New visit").click()
        page.wait_for_selector("#test-boxes input[value=positioning-Z]")
        assert page.locator("#test-boxes input:checked").count() == 3
        for name, value in {"title": "Three axes", "operator": "J. Doe", "machine": "VMC 3", "date": "2026-11-26"}.items():
            page.fill(f"#visit-form [name={name}]", value)
        page.click("#visit-form button[type=submit]")
        page.wait_for_selector("#file-block:not([hidden])")
        no_sideways_scroll(page)
        # tests from files: from the data folder, by upload, and a bad file refused in one line
        page.select_option("#file-kind", "straightness")
        page.fill("#file-form [name=file]", "instrument/straightness_profile.csv")
        page.fill("#file-form [name=axis]", "X")
        page.fill("#file-form [name=direction]", "Y")
        page.click("#file-form button[type=submit]")
        page.wait_for_selector("#file-added:has-text('Added and checked')")
        page.select_option("#file-kind", "ballbar")
        page.fill("#file-form [name=file]", "instrument/ballbar_run.csv")
        page.fill("#file-form [name=radius_mm]", "100")
        page.select_option("#file-form [name=plane]", "XY")
        assert page.locator("#file-form [name=tolerance_arcsec]").is_hidden()  # a ballbar's G is in µm
        page.fill("#file-form [name=tolerance_um]", "1000")  # its tolerance: the test is assessed (Results: PASS)
        page.click("#file-form button[type=submit]")
        page.wait_for_selector(".tests-list[data-mode=visit] tr[data-test=ballbar-XY]")
        page.select_option("#file-kind", "straightness")
        page.set_input_files("#file-form input[data-upload=file]", str(tmp_path / "bad.csv"))
        page.wait_for_function("document.querySelector('#file-form [name=file]').value.endsWith('files/bad.csv')")
        page.fill("#file-form [name=direction]", "Z")
        page.click("#file-form button[type=submit]")
        page.wait_for_selector("#file-added.warn-line")
        assert page.locator("#file-added").text_content() == "vmc-3-2026-11-26/files/bad.csv:3: column 'deviation_um': 'abc' is not a number"
        assert page.locator(".tests-list[data-mode=visit] tbody tr").count() == 5

        # 3. plan: each axis chosen in the list and planned; a travel beyond the axis named beside its field
        page.get_by_role("button", name="3 Plan").click()
        assert page.locator(".tests-list[data-mode=plan] tbody tr").count() == 3
        for axis in "XYZ":
            page.locator(f".tests-list[data-mode=plan] tr[data-test=positioning-{axis}] button").click()
            page.fill("#plan-form [name=start_mm]", "20")
            page.fill("#plan-form [name=end_mm]", "900" if axis == "Z" else "120")
            page.fill("#plan-form [name=runs]", "1")
            page.click("#plan-form button[type=submit]")
            if axis == "Z":
                page.wait_for_selector(".field-error[data-for=end_mm]:not(:empty)")
                assert page.locator(".field-error[data-for=end_mm]").text_content() == "beyond the travel of Z (0 to 400 mm)"
                page.fill("#plan-form [name=end_mm]", "120")
                page.click("#plan-form button[type=submit]")
            page.wait_for_selector(f"#program:has-text('G1 {axis}')")
        no_sideways_scroll(page)

        # 4, 5: the virtual machine is every axis of the visit's machine; each axis run from the list, Y again
        page.get_by_role("button", name="4 Connect").click()
        page.click("#connect-form button[type=submit]")
        page.wait_for_selector("#light-instrument[data-state=ok]")
        assert "Y 0 to 500 mm" in page.locator("#connect-description").text_content()
        no_sideways_scroll(page)
        page.get_by_role("button", name="5 Run").click()
        for axis in "XYZ":
            row = f".tests-list[data-mode=run] tr[data-test=positioning-{axis}]"
            page.locator(f"{row} button").click()
            page.wait_for_selector(f"{row} td.state[data-state=done]:has-text('done')", timeout=60_000)
            page.wait_for_selector("#run-state[data-state=done]")
            assert page.locator("#progress").text_content() == "10 of 10 stops"
        # Y again, aborted: Y failed, X and Z done; resumed from its row to its end
        server.bench.speed = 5.0
        row = ".tests-list[data-mode=run] tr[data-test=positioning-Y]"
        page.locator(row).get_by_role("button", name="Repeat").click()
        page.wait_for_function("document.querySelector('#run-state').dataset.state === 'running'"
                               " && parseInt(document.querySelector('#progress').textContent) >= 2")
        page.click("#abort")
        page.wait_for_selector(f"{row} td.state[data-state=failed]")
        assert page.locator(".tests-list[data-mode=run] td.state[data-state=done]").count() == 2
        server.bench.speed = SPEED
        page.locator(row).get_by_role("button", name="Resume").click()
        page.wait_for_selector(f"{row} td.state[data-state=done]", timeout=60_000)
        assert page.locator(".tests-list[data-mode=run] td.state[data-state=done]").count() == 3
        no_sideways_scroll(page)

        # 6. results: every test evaluated by the campaign, those from files with their figures
        page.get_by_role("button", name="6 Results").click()
        page.click("#show-results")
        page.wait_for_function("document.querySelectorAll('#results article.test').length === 5")
        assert page.locator("#result-positioning-Z h3").text_content().startswith("Positioning of Z")
        assert page.locator("#result-straightness-X table.figures tr").count() > 0  # no tolerance: its figures
        assert page.locator("#result-ballbar-XY table.checks tbody tr").count() > 0  # held against its tolerance
        assert page.locator("#result-ballbar-XY h3").text_content().endswith(": PASS")
        no_sideways_scroll(page)

        # 7. the table of the axis chosen
        page.get_by_role("button", name="7 Compensate").click()
        assert page.locator("#comp-axis option").all_text_contents() == ["X", "Y", "Z"]
        page.select_option("#comp-axis", "Y")
        page.click("#compensate")
        page.wait_for_selector("#comp-download:has-text('Y.comp')")
        no_sideways_scroll(page)

        # 8. finish: one report of every test
        page.get_by_role("button", name="8 Finish").click()
        page.click("#finish")
        page.wait_for_selector("#report-links li", timeout=60_000)
        assert "over 5 tests" in page.locator("#finish-verdict").text_content()
        no_sideways_scroll(page)
        assert not browser_page.errors, browser_page.errors
    finally:
        server.stop()
