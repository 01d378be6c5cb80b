"""The calibration certificate (ISO/IEC 17025:2017 7.8) and its Digital Calibration Certificate (PTB DCC 3.2.0)."""

from __future__ import annotations

import datetime as dt
import json
import math
import re
import shutil
import socket
import warnings
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from axiscal.errors import AxiscalError
from axiscal.report import report_campaign
from axiscal.report.dcc import SCHEMA_VERSION, dsi_unit, read_dcc

CERTIFICATE_TABLES = """
[laboratory]
name = "Example Calibration Ltd"
address = "1 Metrology Way, 12345 Sample Town"
country = "DE"
accreditation = "D-K-00000-01-00"

[certificate]
number = "AX-2026-0042"
issue_date = 2026-11-28
location = "customer"
languages = [{languages}]
replaces = "AX-2026-0017"
tolerance_source = "the customer's order 4711"

[[signatory]]
name = "J. Example"
role = "Head of calibration"
"""

CAMPAIGN = """uncertainty = "uncertainty_budget.toml"

[campaign]
title = "X axis of a test machine"
date = 2026-11-20
operator = "A. Technician"
customer = "Example Customer GmbH"
customer_address = "2 Spindle Road, 54321 Machine Town"

[machine]
name = "VMC 850"
serial = "SN 4711"
manufacturer = "Example Machines"
condition = "in use, no visible damage"

[instrument]
name = "Laser interferometer"
serial = "L-123"
certificate = "NMI-2026-77"
calibrated = 2026-03-02
calibrated_by = "an accredited laboratory"
vacuum_wavelength_nm = 632.99137

[tolerances]
positioning = {{ E_um = 40.0, R_um = 8.0 }}
straightness_um = 5.0

[[tests]]
kind = "positioning"
axis = "X"
file = "positioning_run.csv"
standard = "iso230-2:2014"

[[tests]]
kind = "straightness"
axis = "X"
direction = "Y"
file = "straightness_profile.csv"
""" + CERTIFICATE_TABLES


def make_campaign(folder: Path, examples: Path, *, languages: str = '"en", "de"', certificate: bool = True) -> Path:
    folder.mkdir(parents=True)
    for name in ("positioning_run.csv", "straightness_profile.csv", "uncertainty_budget.toml"):
        shutil.copy(examples / name, folder / name)
    text = CAMPAIGN.format(languages=languages)
    if not certificate:
        text = text[: text.index("[laboratory]")]
    (folder / "campaign.toml").write_text(text)
    return folder


@pytest.fixture(scope="module")
def written(tmp_path_factory):
    root = tmp_path_factory.mktemp("certificate")
    folder = make_campaign(root / "campaign", Path(__file__).resolve().parents[2] / "examples")
    return report_campaign(folder, root / "report", certificate=True)


def _leaves(value, path=()):
    if isinstance(value, dict):
        for key, inner in value.items():
            yield from _leaves(inner, (*path, key))
    else:
        yield path, value


def test_a_campaign_without_the_certificate_s_fields_is_refused_in_one_line_listing_them_all(run_cli, examples, tmp_path):
    folder = make_campaign(tmp_path / "c", examples, certificate=False)
    for flag in ("--certificate", "--dcc"):
        status, out, err = run_cli("report", folder, "-o", tmp_path / "out", flag)
        assert status == 2 and out == ""
        assert len(err.strip().splitlines()) == 1 and "Traceback" not in err
        assert "campaign.toml" in err and "a calibration certificate needs" in err
        for field in ("[laboratory] name", "[laboratory] address", "[laboratory] country", "[certificate] number",
                      "[certificate] issue_date", "[certificate] location", "[[signatory]]",
                      "[certificate] tolerance_source"):
            assert field in err, field
        assert not (tmp_path / "out").exists()  # nothing written
    # a plain report of the same campaign stays as it was
    status, out, err = run_cli("report", folder, "-o", tmp_path / "plain")
    assert status == 0, err
    assert not (tmp_path / "plain" / "dcc.xml").exists()
    assert "Geometric calibration report" in (tmp_path / "plain" / "report.html").read_text()


@pytest.mark.parametrize(("good", "bad"), [
    ('location = "customer"', 'location = "garage"'),
    ('country = "DE"', 'country = "Germany"'),
    ('languages = ["en", "de"]', 'languages = ["en", "fr"]'),
    ('languages = ["en", "de"]', 'languages = ["en", "en"]'),
    ('issue_date = 2026-11-28', 'issue_date = "soon"'),
])
def test_the_certificate_tables_are_checked_at_their_line(run_cli, examples, tmp_path, good, bad):
    folder = make_campaign(tmp_path / "c", examples)
    toml = folder / "campaign.toml"
    toml.write_text(toml.read_text().replace(good, bad))
    status, _, err = run_cli("report", folder, "-o", tmp_path / "out", "--certificate")
    assert status == 2 and "campaign.toml:" in err and len(err.strip().splitlines()) == 1, err
    assert not (tmp_path / "out").exists()


def test_the_html_certificate_carries_every_item_of_17025_7_8(written):
    html = written.certificate[0].read_text()
    assert written.certificate[0].name == "certificate.html"
    # main language English (the first of the campaign's languages)
    for words in ("Calibration certificate", "AX-2026-0042", "Example Calibration Ltd", "1 Metrology Way",
                  "D-K-00000-01-00", "Example Customer GmbH", "2 Spindle Road", "at the customer&#39;s site",
                  "VMC 850", "SN 4711", "Example Machines", "in use, no visible damage", "November 20, 2026",
                  "November 28, 2026", "iso230-2:2014", "Deviations from the methods",
                  "This certificate replaces certificate AX-2026-0017.",
                  "U is the expanded uncertainty for k = 2, a coverage probability of about 95 %.",
                  "traceable to the International System of Units (SI)", "NMI-2026-77", "an accredited laboratory",
                  "ILAC-G8", "the customer&#39;s order 4711", "The results relate only to the item calibrated",
                  "shall not be reproduced except in full", "J. Example", "Head of calibration",
                  "End of certificate AX-2026-0042", "Conditions of the tests"):
        assert words in html, words
    # calibration intervals stay off the certificate (ILAC-G24); its date is the issue date, not the run's
    assert "Next calibration" not in html and "Interval" not in html
    assert "UTC" not in html


def test_every_figure_has_its_u_or_the_words_why(written):
    from axiscal.report.certificate import figure_rows

    rows = figure_rows(written.results_data)
    assert rows
    for row in rows:
        assert (row["U"] is not None) != (row["why"] is not None), row
    by_label = {(r["test_id"], r["label"]): r for r in rows}
    assert by_label[("positioning-X-1", "E")]["U"] > 0
    # straightness has its U from the budget's straightness optics; its slope is not budgeted, and says so
    assert by_label[("straightness-X-1", "straightness EYX")]["U"] > 0
    assert by_label[("straightness-X-1", "slope")]["why"] == "not covered by the campaign's uncertainty budget"


def test_the_german_certificate_writes_german_words_numbers_and_dates(written):
    from axiscal.report.certificate import render_certificate_html

    html = render_certificate_html(written.results_data, language="de")
    assert '<html lang="de">' in html
    for words in ("Kalibrierschein", "Kalibrierscheinnummer", "Auftraggeber", "Kalibriergegenstand",
                  "20. November 2026", "28. November 2026", "erweiterte Messunsicherheit", "Ende des Kalibrierscheins",
                  "Entscheidungsregel", "Metrologische Rückführung"):
        assert words in html, words
    E = next(c for c in written.results_data.tests[0].checks if c.figure == "E")
    assert f"{E.value:.3f}".replace(".", ",") in html  # the decimal comma
    assert "Calibration certificate" not in html


def test_every_message_of_the_certificate_has_its_german_translation():
    """A missing translation fails here, rather than showing English in a German certificate."""
    from babel.messages.extract import extract_from_file
    from babel.messages.pofile import read_po

    from axiscal.report.i18n import catalog_path

    root = Path(__file__).resolve().parents[2]
    sources = [(root / "src/axiscal/report/certificate.py", "python"), (root / "src/axiscal/report/dcc.py", "python")]
    sources += [(p, "jinja2") for p in sorted((root / "src/axiscal/templates/report").glob("*.j2"))]
    messages = set()
    for path, method in sources:
        options = {"extensions": "jinja2.ext.i18n"} if method == "jinja2" else {}
        if method == "jinja2":
            from jinja2.ext import babel_extract as method
        for _, message, _, _ in extract_from_file(method, str(path), keywords={"_": None, "tr": None, "gettext": None},
                                                  options=options):
            messages.add(message)
    assert len(messages) > 60
    with catalog_path("de").open("rb") as handle:
        catalog = read_po(handle)
    missing = sorted(m for m in messages if not catalog.get(m) or not catalog.get(m).string or catalog.get(m).fuzzy)
    assert missing == []


def test_a_language_without_a_catalog_is_refused():
    from axiscal.report.i18n import translations

    with pytest.raises(AxiscalError, match="no translation"):
        translations("fr")


@pytest.fixture
def no_network(monkeypatch):
    """Validation must not fetch anything: every socket connection is refused."""
    def refuse(*args, **kwargs):
        raise OSError("network refused in the test")

    monkeypatch.setattr(socket.socket, "connect", refuse)
    monkeypatch.setattr(socket, "create_connection", refuse)


def test_the_dcc_validates_against_ptb_s_schema_offline(written, dcc_schema, no_network):
    root_text = written.dcc.read_text()
    assert f'schemaVersion="{SCHEMA_VERSION}"' in root_text
    errors = list(dcc_schema.iter_errors(str(written.dcc)))
    assert errors == [], [e.reason for e in errors[:5]]


def test_every_figure_of_results_json_is_in_the_dcc_with_the_same_value(written):
    results = json.loads(written.results.read_text())
    back = {t["id"]: t for t in read_dcc(written.dcc)["tests"]}
    assert set(back) == {t["id"] for t in results["tests"]}
    count = 0
    for test in results["tests"]:
        read = dict(_leaves(back[test["id"]]["figures"]))
        for path, value in _leaves(test["figures"]):
            assert path in read, (test["id"], path)
            assert read[path] == value, (test["id"], path)  # the same number, read back exactly
            count += 1
        for key, U in test.get("uncertainty", {}).items():
            assert back[test["id"]]["uncertainty"][key] == U
    assert count > 30


def test_the_dcc_writes_d_si_units_and_the_expanded_uncertainty(written):
    from lxml import etree
    from dsi_unit import DsiUnit

    root = etree.parse(str(written.dcc)).getroot()
    si = "{https://ptb.de/si}"
    units = {u.text for u in root.iter(f"{si}unit")} | {u.text for u in root.iter(f"{si}unitXMLList")}
    assert r"\micro\metre" in units and r"\milli\metre" in units
    assert not any(r"\per" in unit for unit in units)  # D-SI 2: a denominator is \tothe{-N}
    with warnings.catch_warnings():  # dsi_unit's own parser warns of '\per' on strings that hold none
        warnings.simplefilter("ignore")
        for unit in units:
            assert unit.startswith("\\") and DsiUnit(unit).valid, unit
    assert "um" not in units and "mm" not in units
    reals = [r for r in root.iter(f"{si}real") if r.findtext(f"{si}label") == "E"]
    assert len(reals) == 1
    unc = reals[0].find(f"{si}expandedUnc")
    assert float(unc.findtext(f"{si}coverageFactor")) == 2 and float(unc.findtext(f"{si}coverageProbability")) == 0.95
    conformity = [c.text for c in root.iter("{https://ptb.de/dcc}conformity")]
    assert set(conformity) <= {"pass", "fail", "conditionalPass"} and conformity
    # the texts in every language of the certificate
    names = {c.get("lang") for c in root.iter("{https://ptb.de/dcc}content") if c.get("lang")}
    assert names == {"en", "de"}


@pytest.mark.parametrize(("key", "unit", "dsi"), [
    ("straightness_um", None, r"\micro\metre"), ("E", "um", r"\micro\metre"), ("E", "arcsec", r"\arcsecond"),
    ("slope_urad", None, r"\micro\radian"), ("included_angle_deg", None, r"\degree"), ("target_mm", None, r"\milli\metre"),
    ("runs", None, r"\one"), ("x_psd_y_um_gain", None, r"\one"), ("feed_mm_min", None, r"\milli\metre\minute\tothe{-1}"),
])
def test_figure_keys_name_their_d_si_units(key, unit, dsi):
    assert dsi_unit(key, unit) == dsi


def test_the_pdf_is_pdf_a_3b_with_the_number_on_every_page_and_the_dcc_attached(written):
    import pypdf

    pdf = written.certificate[1]
    reader = pypdf.PdfReader(pdf)
    assert len(reader.pages) >= 2
    for index, page in enumerate(reader.pages, start=1):
        text = page.extract_text()
        assert "AX-2026-0042" in text, index
        assert f"page {index} of {len(reader.pages)}" in text, index
    assert "End of certificate AX-2026-0042" in reader.pages[-1].extract_text()
    assert reader.attachments["dcc.xml"] == [written.dcc.read_bytes()]
    xmp = reader.xmp_metadata.stream.get_data().decode()
    assert re.search(r"<pdfaid:part>3</pdfaid:part>|pdfaid:part=\"3\"", xmp)
    assert re.search(r"<pdfaid:conformance>B</pdfaid:conformance>|pdfaid:conformance=\"B\"", xmp)
    assert reader.metadata["/Title"] == "Calibration certificate AX-2026-0042"
    assert reader.metadata["/CreationDate"].startswith("D:20261128")  # the issue date, the same on every re-run


def test_signing_and_a_changed_value_after_signing(run_cli, written, tmp_path, dcc_schema, no_network):
    from cryptography import x509
    from cryptography.hazmat.primitives import hashes, serialization
    from cryptography.hazmat.primitives.asymmetric import ec
    from cryptography.x509.oid import NameOID

    key = ec.generate_private_key(ec.SECP256R1())
    name = x509.Name([x509.NameAttribute(NameOID.COMMON_NAME, "Example Calibration Ltd")])
    start = dt.datetime(2026, 1, 1, tzinfo=dt.timezone.utc)
    cert = (x509.CertificateBuilder().subject_name(name).issuer_name(name).public_key(key.public_key())
            .serial_number(1).not_valid_before(start).not_valid_after(start + dt.timedelta(days=3650))
            .sign(key, hashes.SHA256()))
    (tmp_path / "key.pem").write_bytes(key.private_bytes(serialization.Encoding.PEM, serialization.PrivateFormat.PKCS8,
                                                         serialization.NoEncryption()))
    (tmp_path / "cert.pem").write_bytes(cert.public_bytes(serialization.Encoding.PEM))
    signed = tmp_path / "signed.xml"
    status, out, err = run_cli("dcc", "sign", written.dcc, "--key", tmp_path / "key.pem", "--cert", tmp_path / "cert.pem",
                               "-o", signed)
    assert status == 0, err
    assert list(dcc_schema.iter_errors(str(signed))) == []  # still a valid DCC, signature and all
    status, out, err = run_cli("dcc", "verify", signed, "--cert", tmp_path / "cert.pem")
    assert status == 0 and "signature valid" in out and "Example Calibration Ltd" in out
    # one figure changed after signing: verify fails, naming the test it is in
    text = signed.read_text()
    E = json.loads(written.results.read_text())["tests"][0]["figures"]["E"]
    changed = tmp_path / "changed.xml"
    changed.write_text(text.replace(f"<si:value>{E!r}</si:value>", f"<si:value>{E * 0.5!r}</si:value>", 1))
    assert changed.read_text() != text
    status, out, err = run_cli("dcc", "verify", changed)
    assert status == 1 and len(err.strip().splitlines()) == 1
    assert "changed after signing: measurementResult 'positioning-X-1'" in err
    # the signatory's name changed: the administrative data
    forged = tmp_path / "forged.xml"
    forged.write_text(text.replace("J. Example", "J. Forger"))
    status, _, err = run_cli("dcc", "verify", forged)
    assert status == 1 and "the administrative data" in err
    # a key that is not the certificate's
    other = ec.generate_private_key(ec.SECP256R1())
    (tmp_path / "other.pem").write_bytes(other.private_bytes(serialization.Encoding.PEM, serialization.PrivateFormat.PKCS8,
                                                             serialization.NoEncryption()))
    status, _, err = run_cli("dcc", "sign", written.dcc, "--key", tmp_path / "other.pem", "--cert", tmp_path / "cert.pem",
                             "-o", tmp_path / "x.xml")
    assert status == 2 and "not the private key's" in err and not (tmp_path / "x.xml").exists()
    status, _, err = run_cli("dcc", "verify", written.dcc)
    assert status == 2 and "no signature" in err


def test_dcc_show_prints_the_figures(run_cli, written):
    status, out, err = run_cli("dcc", "show", written.dcc)
    assert status == 0, err
    assert out.startswith("certificate AX-2026-0042 · VMC 850 · calibrated 2026-11-20")
    assert re.search(r"^  E +\d+\.\d{6}  U \(k = 2\) \d+\.\d{6}$", out, re.M)
    status, out, _ = run_cli("dcc", "show", written.dcc, "--json")
    assert json.loads(out)["tests"][0]["id"] == "positioning-X-1"


def test_report_compare_takes_an_earlier_certificate_s_dcc_as_its_results_json(run_cli, written, tmp_path):
    folder = written.folder.parent / "campaign"
    status, _, err = run_cli("report", folder, "-o", tmp_path / "by-json", "--compare", written.results)
    assert status == 0, err
    status, _, err = run_cli("report", folder, "-o", tmp_path / "by-dcc", "--compare", written.dcc)
    assert status == 0, err
    by_json = json.loads((tmp_path / "by-json" / "results.json").read_text())
    by_dcc = json.loads((tmp_path / "by-dcc" / "results.json").read_text())
    assert by_json["tests"] == by_dcc["tests"]
    assert "certificate AX-2026-0042" in (tmp_path / "by-dcc" / "report.html").read_text()


@pytest.mark.parametrize("content", [b"", b"<a/>", b"not xml", b"<dcc:digitalCalibrationCertificate xmlns:dcc='https://ptb.de/dcc'/>"])
def test_a_file_that_is_no_dcc_of_ours_is_refused_in_one_line(run_cli, tmp_path, content):
    path = tmp_path / "x.xml"
    path.write_bytes(content)
    status, out, err = run_cli("dcc", "show", path)
    assert status == 2 and len(err.strip().splitlines()) == 1 and "x.xml" in err


def test_numbers_read_back_are_the_numbers_written():
    from axiscal.report.dcc import _number

    for value in (0.1, -2.89e-7, 1e300, 5e-324, 123456789012345678, 0.0, 39.00172289624386):
        text = _number(value)
        assert re.fullmatch(r"[-+]?((\d*\.\d+)|(\d+\.\d*)|(\d+\.?))([Ee][-+]?\d+)?", text)  # D-SI's decimalType
        assert (int(text) if isinstance(value, int) else float(text)) == value
    assert math.isclose(float(_number(1 / 3)), 1 / 3, rel_tol=0)


def test_a_dcc_declaring_an_encoding_python_does_not_know_is_refused_in_one_line(written, tmp_path):
    """A flipped byte in the declaration (``encoding="u-f-8"``, found by the mutation test below) is refused, not a LookupError."""
    text = written.dcc.read_text(encoding="utf-8")
    assert re.match(r"<\?xml [^>]*encoding=['\"]utf-8['\"]", text, flags=re.I)
    path = tmp_path / "dcc.xml"
    path.write_text(re.sub(r"encoding=['\"][^'\"]*['\"]", 'encoding="u-f-8"', text, count=1), encoding="utf-8")
    with pytest.raises(AxiscalError, match=r"not a readable XML file: unknown encoding") as caught:
        read_dcc(path)
    assert "\n" not in str(caught.value)


@settings(max_examples=80, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(data=st.data())
def test_a_damaged_dcc_reads_cleanly_or_is_refused_in_one_line(written, tmp_path_factory, data):
    """Every damage to a DCC: a clean refusal (AxiscalError) or a correct parse, never another exception."""
    blob = bytearray(written.dcc.read_bytes())
    kind = data.draw(st.sampled_from(["cut", "flip", "value", "key", "rows"]))
    if kind == "cut":
        blob = blob[: data.draw(st.integers(0, len(blob)))]
    elif kind == "flip":
        for _ in range(data.draw(st.integers(1, 8))):
            blob[data.draw(st.integers(0, len(blob) - 1))] = data.draw(st.integers(0, 255))
    elif kind == "value":
        text = blob.decode()
        junk = data.draw(st.sampled_from(["nan", "1e999", "", "x", "1,5", "--1", "0x10", "1e-99999"]))
        text = re.sub(r"<si:value>[^<]*</si:value>", f"<si:value>{junk}</si:value>", text,
                      count=data.draw(st.integers(1, 3)))
        blob = bytearray(text.encode())
    elif kind == "key":
        text = blob.decode()
        blob = bytearray(text.replace('axiscal_figure:E"', data.draw(st.sampled_from(
            ['axiscal_figure:E/x"', 'axiscal_figure:"', 'axiscal_figure:targets"', 'axiscal_figure:#3"']))).encode())
    else:
        blob = bytearray(blob.decode().replace("/#0", "/#7").encode())
    path = tmp_path_factory.mktemp("damaged") / "dcc.xml"
    path.write_bytes(bytes(blob))
    try:
        read = read_dcc(path)
    except AxiscalError as exc:
        assert "\n" not in str(exc) and len(str(exc)) < 600
    else:
        assert read["schema"] == "axiscal-results/1" and isinstance(read["tests"], list)
