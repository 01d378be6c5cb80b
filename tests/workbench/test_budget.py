"""The uncertainty on every figure: the New visit form takes the budget, writes it as the campaign's budget
file, remembers it per instrument for the instrument's next visit, and Results states U (k = 2) beside
every figure with the decision against the tolerance under the campaign's decision rule."""

from __future__ import annotations

import json
import warnings
from pathlib import Path

import pytest

from axiscal.campaign import load_campaign
from axiscal.errors import AxiscalError
from axiscal.positioning import evaluate_positioning_file
from axiscal.report import decision_statement
from axiscal.uncertainty import figure_uncertainties, read_budget
from axiscal.workbench import FormErrors, Workbench, checked, create_workbench_app
from axiscal.workbench import BUDGET_FIELDS, BUDGETS_FILE, budget_defaults, budget_tables, remember_budget, write_budget

with warnings.catch_warnings():  # Starlette's notice that its test client will move to httpx2
    warnings.simplefilter("ignore")
    from starlette.testclient import TestClient

VISIT = {"title": "Visit", "date": "2026-11-26", "operator": "J. Doe", "machine": "VMC 1", "serial": "S1",
         "instrument": "Laser", "instrument_serial": "L-1", "A_um": 45, "E_um": 40, "R_um": 5, "B_um": 6}
TESTS = {"tests": ["positioning-X"]}  # the New visit form's boxes
BUDGET = {"length_U_ppm": 0.5, "air_temperature_u_K": 0.1, "air_pressure_u_Pa": 30.0, "air_humidity_u_percent": 5.0,
          "machine_temperature_C": 23.0, "machine_temperature_u_K": 0.2, "expansion_per_K": 11.5e-6,
          "expansion_u_per_K": 1.2e-6, "misalignment_urad": 100.0, "eve_um": 1.0}
PLAN = {"start_mm": 20, "end_mm": 170, "targets": 5, "runs": 2, "overrun_mm": 5, "dwell_s": 1}
SIM = {"instrument": "sim", "controller": "sim"}
DOC = Path(__file__).resolve().parents[2] / "docs" / "workbench.md"


def _bench(tmp_path, speed=80.0):
    return Workbench(tmp_path / "data", db=str(tmp_path / "h.sqlite"), speed=speed)


def _client(bench):
    return TestClient(create_workbench_app(bench), base_url="http://127.0.0.1:8770")


def test_the_form_takes_the_budget_in_the_budget_files_units_and_ranges():
    form = checked("visit", VISIT | BUDGET)
    assert {name: getattr(form, name) for name in BUDGET} == BUDGET
    assert form.decision_rule == "simple"  # a budget is held by simple acceptance unless the guard band is chosen
    assert checked("visit", VISIT | {"eve_um": 1.0, "decision_rule": "guard-band"}).decision_rule == "guard-band"
    assert checked("visit", VISIT | {"decision_rule": "simple"}).decision_rule is None  # no budget: no rule to state
    with pytest.raises(FormErrors) as caught:
        checked("visit", VISIT | {"length_U_ppm": -0.5, "air_pressure_u_Pa": 1e9, "misalignment_urad": "nan",
                                  "decision_rule": "strict"})
    assert set(caught.value.fields) == {"length_U_ppm", "air_pressure_u_Pa", "misalignment_urad", "decision_rule"}
    assert all("\n" not in text for text in caught.value.fields.values())
    with pytest.raises(FormErrors) as caught:
        checked("visit", VISIT | {"decision_rule": "guard-band"})
    assert caught.value.fields == {"decision_rule": "the guard band needs the uncertainty budget (U is what it guards by)"}


def test_the_budget_is_written_as_the_campaigns_budget_file_and_read_by_the_library(tmp_path):
    bench = _bench(tmp_path)
    answer = bench.new_visit(TESTS | VISIT | BUDGET | {"decision_rule": "guard-band"})
    assert '[uncertainty]\nbudget = "budget.toml"\ndecision_rule = "guard-band"' in answer["text"]
    budget = read_budget(bench.folder / "budget.toml")
    assert budget.length_U_rel == pytest.approx(0.5e-6) and budget.air_pressure_u_Pa == 30.0
    assert budget.machine_temperature_C == 23.0 and budget.expansion_u_per_K == pytest.approx(1.2e-6)
    assert budget.misalignment_rad == pytest.approx(100e-6) and budget.eve_m == pytest.approx(1e-6)
    assert budget.wavelength_nm == pytest.approx(632.99137)  # the form's wavelength, for the air's sensitivities
    assert (bench.folder / "as-left" / "budget.toml").read_text() == (bench.folder / "budget.toml").read_text()
    (bench.folder / "positioning_x.csv").write_text("target_mm,run,direction,deviation_um\n")  # the run to come
    campaign = load_campaign(bench.folder)
    assert campaign.budget == budget.__class__(**{**budget.__dict__, "source": campaign.budget.source})
    assert campaign.decision_rule == "guard-band"
    # the same visit written again without a budget: no budget file, no [uncertainty], no U
    answer = bench.new_visit(TESTS | VISIT)
    assert "[uncertainty]" not in answer["text"] and not (bench.folder / "budget.toml").exists()
    assert not (bench.folder / "as-left" / "budget.toml").exists()
    assert load_campaign(bench.folder).budget is None


def test_only_the_numbers_given_are_written(tmp_path):
    assert budget_tables(VISIT | {"wavelength_nm": 633.0}) == {}
    tables = budget_tables(VISIT | {"wavelength_nm": 633.0, "length_U_ppm": 0.4, "eve_um": None})
    assert tables == {"instrument": {"length_U_ppm": 0.4, "wavelength_nm": 633.0}}
    assert write_budget(tmp_path / "visit", VISIT) is None and not (tmp_path / "visit" / "budget.toml").exists()
    path = write_budget(tmp_path / "visit", VISIT | {"length_U_ppm": 0.4})
    assert read_budget(path).length_U_rel == pytest.approx(0.4e-6) and read_budget(path).eve_m == 0.0
    with pytest.raises(AxiscalError, match="form must be"):
        budget_tables(None)


def test_the_budget_is_remembered_per_instrument_and_prefills_its_next_visit(tmp_path):
    bench = _bench(tmp_path)
    with _client(bench) as client:
        assert client.get("/api/budget", params={"instrument": "Laser", "serial": "L-1"}).json() == {}
        assert client.post("/api/visit", json=TESTS | VISIT | BUDGET | {"decision_rule": "guard-band"}).status_code == 200
        assert client.post("/api/visit", json=TESTS | VISIT | {"instrument_serial": "L-2", "machine": "VMC 2",
                                                        "length_U_ppm": 0.2}).status_code == 200
        first = client.get("/api/budget", params={"instrument": "Laser", "serial": "L-1"}).json()
        second = client.get("/api/budget", params={"instrument": "Laser", "serial": "l-2 "}).json()
        assert first == {"fields": BUDGET | {"decision_rule": "guard-band"}, "date": "2026-11-26"}
        assert second["fields"] == {"length_U_ppm": 0.2, "decision_rule": "simple"}
        assert client.get("/api/budget", params={"instrument": "Laser", "serial": "L-3"}).json() == {}
        # a visit without a budget leaves the instrument's remembered one as it was
        assert client.post("/api/visit", json=TESTS | VISIT | {"machine": "VMC 3"}).status_code == 200
        assert client.get("/api/budget", params={"instrument": "Laser", "serial": "L-1"}).json() == first
    # an instrument without a serial is remembered by its name
    remember_budget(bench.data, VISIT | {"instrument": "Old laser", "instrument_serial": "", "eve_um": 2.0})
    assert budget_defaults(bench.data, "old LASER")["fields"] == {"eve_um": 2.0}
    assert budget_defaults(bench.data, "Old laser", "L-1") == first  # the serial decides when there is one
    (bench.data / BUDGETS_FILE).write_text("{ damaged")
    assert budget_defaults(bench.data, "Laser", "L-1") == {}
    (bench.data / BUDGETS_FILE).write_text(json.dumps({"serial:l-1": {"budget": {"eve_um": "much", "decision_rule": "?"}}}))
    assert budget_defaults(bench.data, "Laser", "L-1") == {}
    with pytest.raises(AxiscalError, match="instrument must be the instrument's instrument"):
        budget_defaults(bench.data, None)


def test_results_state_u_beside_every_figure_and_the_decision_under_the_campaigns_rule(tmp_path):
    bench = _bench(tmp_path)
    bench.new_visit(TESTS | VISIT | BUDGET | {"decision_rule": "guard-band"})
    bench.make_plan(PLAN)
    bench.connect(SIM)
    bench.start_run("as-found")
    assert bench.run.wait(60) == "done"
    with _client(bench) as client:
        results = client.get("/api/results", params={"phase": "as-found"}).json()
    assert results["budget"] is True and results["decision_rule"] == "guard-band"
    assert results["decision"] == decision_statement("guard-band")
    checks = {c["figure"]: c for c in results["tests"][0]["checks"]}
    assert set(checks) == {"A", "E", "R", "B"} and all(c["U"] is not None and c["U"] > 0 for c in checks.values())
    # U is the library's, from the budget file the campaign names
    expected = figure_uncertainties("positioning", evaluate_positioning_file(bench.folder / "positioning_x.csv"),
                                    bench.folder / "budget.toml")
    assert {name: c["U"] for name, c in checks.items()} == pytest.approx({name: expected[name] for name in checks})
    for c in checks.values():  # the guard band of ISO 14253-1 with that U
        value, U, limit = c["value"], c["U"], c["limit"]
        assert c["result"] == ("pass" if value + U <= limit else "fail" if value - U > limit else "inconclusive")

    # as left: the as-left campaign names its own copy of the budget
    bench.compensate()
    bench.start_run("as-left")
    assert bench.run.wait(60) == "done"
    left = bench.results("as-left")
    assert left["budget"] is True and all(c["U"] is not None for c in left["tests"][0]["checks"])


def test_without_a_budget_results_say_u_is_not_stated_and_hold_by_simple_acceptance(tmp_path):
    bench = _bench(tmp_path)
    bench.new_visit(TESTS | VISIT)
    bench.make_plan(PLAN | {"runs": 1})
    bench.connect(SIM)
    bench.start_run("as-found")
    assert bench.run.wait(60) == "done"
    results = bench.results("as-found")
    assert (results["budget"], results["decision_rule"]) == (False, "simple")
    assert all(c["U"] is None for c in results["tests"][0]["checks"])


def test_the_page_and_its_documentation_name_every_budget_field():
    page = (Path(__file__).resolve().parents[2] / "src" / "axiscal" / "workbench" / "web" / "index.html").read_text()
    text = DOC.read_text(encoding="utf-8")
    for name in (*BUDGET_FIELDS, "decision_rule"):
        assert f'name="{name}"' in page, name
        assert f"`{name}`" in text, name
    assert "budget.toml" in text and "budgets.json" in text
