"""The New visit form in headless Chromium prefills the budget of the instrument's last visit: on a fresh
form for the remembered instrument, and again when the technician names another instrument."""

from __future__ import annotations

from axiscal.workbench import remember_laboratory, serve_workbench
from axiscal.workbench.budget import remember_budget

VISIT = {"title": "Visit", "date": "2026-11-26", "operator": "J. Doe", "machine": "VMC 1", "instrument": "Laser",
         "instrument_serial": "L-1", "certificate_number": "AX-1", "lab_name": "Lab"}


def test_the_instruments_last_budget_fills_the_form(browser_page, tmp_path):
    data = tmp_path / "data"
    data.mkdir()
    remember_laboratory(data, VISIT)  # the laboratory's instrument L-1 comes back on the next form
    remember_budget(data, VISIT | {"length_U_ppm": 0.5, "eve_um": 1.0, "decision_rule": "guard-band"})
    remember_budget(data, VISIT | {"instrument_serial": "L-2", "date": "2026-10-01", "length_U_ppm": 0.2,
                                   "decision_rule": "simple"})
    server = serve_workbench(data, db=str(tmp_path / "h.sqlite"), port=0)
    try:
        page = browser_page.page
        page.goto(server.url)
        page.get_by_role("button", name="2 New visit").click()
        page.wait_for_selector("#budget-from:not([hidden])")
        assert page.input_value("#visit-form [name=instrument_serial]") == "L-1"
        assert page.input_value("#visit-form [name=length_U_ppm]") == "0.5"
        assert page.input_value("#visit-form [name=eve_um]") == "1"
        assert page.input_value("#visit-form [name=decision_rule]") == "guard-band"
        assert page.locator("#budget-from").text_content() == "Prefilled from this instrument's last visit (2026-11-26)."
        page.fill("#visit-form [name=instrument_serial]", "L-2")
        page.dispatch_event("#visit-form [name=instrument_serial]", "change")
        page.wait_for_selector("#budget-from:has-text('2026-10-01')")
        assert page.input_value("#visit-form [name=length_U_ppm]") == "0.2"
        assert page.input_value("#visit-form [name=eve_um]") == ""  # the other instrument's budget, whole
        assert page.input_value("#visit-form [name=decision_rule]") == "simple"
        assert not browser_page.errors, browser_page.errors
    finally:
        server.stop()
