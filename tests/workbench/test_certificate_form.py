"""The visit's certificate from the workbench: the New visit form carries the certificate's fields, the
laboratory and the signatory are remembered between visits with the next number proposed, and Finish
writes the certificate and its DCC."""

from __future__ import annotations

import json
import warnings

import pytest

from axiscal.campaign import load_campaign
from axiscal.workbench import FormErrors, Workbench, checked, create_workbench_app, next_number

with warnings.catch_warnings():  # Starlette's notice that its test client will move to httpx2
    warnings.simplefilter("ignore")
    from starlette.testclient import TestClient

VISIT = {"title": "Visit", "date": "2026-11-26", "operator": "J. Doe", "machine": "VMC 1", "serial": "S1",
         "instrument": "Laser", "A_um": 45, "E_um": 40, "R_um": 5, "B_um": 6}
TESTS = {"tests": ["positioning-X"]}  # the New visit form's boxes
CERTIFICATE = {"customer": "Example Customer GmbH", "customer_address": "2 Spindle Road, Machine Town",
               "manufacturer": "Example Machines", "condition": "in use", "instrument_serial": "L-1",
               "certificate": "NMI-77", "instrument_calibrated": "2026-03-02", "instrument_calibrated_by": "an NMI",
               "lab_name": "Example Calibration Ltd", "lab_address": "1 Metrology Way", "lab_country": "DE",
               "certificate_number": "AX-2026-0042", "issue_date": "2026-11-28", "location": "customer",
               "language": "de", "signatory_name": "J. Example", "signatory_role": "Head of calibration",
               "tolerance_source": "the customer's order"}
PLAN = {"start_mm": 20, "end_mm": 170, "targets": 5, "runs": 1, "overrun_mm": 5, "dwell_s": 1}
SIM = {"instrument": "sim", "controller": "sim"}


def _bench(tmp_path, speed=80.0):
    return Workbench(tmp_path / "data", db=str(tmp_path / "h.sqlite"), speed=speed)


def test_a_certificate_number_asks_for_every_field_a_certificate_needs():
    with pytest.raises(FormErrors) as caught:
        checked("visit", VISIT | {"certificate_number": "AX-1"})
    assert set(caught.value.fields) == {"certificate_number"}
    for field in ("lab_name", "signatory_name", "issue_date", "tolerance_source", "manufacturer"):
        assert field in caught.value.fields["certificate_number"]
    with pytest.raises(FormErrors) as caught:
        checked("visit", VISIT | CERTIFICATE | {"lab_country": "Germany", "language": "fr"})
    assert {"lab_country", "language"} <= set(caught.value.fields)
    assert checked("visit", VISIT).certificate_number == ""  # a visit without a certificate, as before


@pytest.mark.parametrize(("number", "after"), [("AX-2026-0042", "AX-2026-0043"), ("K-0999", "K-1000"),
                                                ("7", "8"), ("AX-12a", "AX-13a"), ("lab", "lab-2")])
def test_the_next_number(number, after):
    assert next_number(number) == after


def test_the_laboratory_is_remembered_and_the_next_number_proposed(tmp_path):
    bench = _bench(tmp_path)
    assert bench.certificate_defaults() == {}
    bench.new_visit(TESTS | VISIT | CERTIFICATE)
    (bench.folder / "positioning_x.csv").write_text("target_mm,run,direction,deviation_um\n")  # the run to come
    campaign = load_campaign(bench.folder)
    assert campaign.laboratory["name"] == "Example Calibration Ltd" and campaign.certificate["languages"] == ["de"]
    assert campaign.signatories[0]["role"] == "Head of calibration"
    assert campaign.instrument["calibrated_by"] == "an NMI" and campaign.machine["condition"] == "in use"
    with TestClient(create_workbench_app(_bench(tmp_path)), base_url="http://127.0.0.1:8770") as client:
        defaults = client.get("/api/certificate").json()
    assert defaults["certificate_number"] == "AX-2026-0043" and defaults["lab_name"] == "Example Calibration Ltd"
    assert defaults["signatory_name"] == "J. Example" and defaults["language"] == "de"
    assert "customer" not in defaults and "machine" not in defaults  # the visit's own fields are not carried over
    (tmp_path / "data" / "laboratory.json").write_text("{ damaged")
    assert bench.certificate_defaults() == {}


def test_finish_writes_the_certificate_and_its_dcc(tmp_path):
    bench = _bench(tmp_path)
    bench.new_visit(TESTS | VISIT | CERTIFICATE)
    bench.make_plan(PLAN)
    bench.connect(SIM)
    bench.start_run("as-found")
    assert bench.run.wait(60) == "done"
    answer = bench.finish(pdf=False)
    kinds = {link["kind"]: link["path"] for link in answer["files"]}
    assert {"certificate html", "certificate pdf", "dcc"} <= set(kinds)
    html = (bench.data / kinds["certificate html"]).read_text()
    assert "Kalibrierschein" in html and "AX-2026-0042" in html  # in the form's language
    dcc = (bench.data / kinds["dcc"]).read_text()
    assert "<dcc:uniqueIdentifier>AX-2026-0042</dcc:uniqueIdentifier>" in dcc
    assert json.loads((bench.data / kinds["results"]).read_text())["campaign"]["certificate"]["number"] == "AX-2026-0042"
