"""The workbench's routes and guards, through Starlette's test client (no server, no browser)."""

from __future__ import annotations

import warnings

import pytest

with warnings.catch_warnings():  # Starlette's notice that its test client will move to httpx2
    warnings.simplefilter("ignore")
    from starlette.testclient import TestClient

from axiscal.workbench import MAX_BODY, TOKEN_COOKIE, Workbench, create_workbench_app, new_token

VISIT = {"title": "Acceptance", "date": "2026-11-26", "operator": "J. Doe", "machine": "VMC 1", "serial": "S1",
         "instrument": "Laser", "A_um": 45, "E_um": 40, "R_um": 5, "B_um": 6, "tests": ["positioning-X"]}


@pytest.fixture
def bench(tmp_path):
    return Workbench(tmp_path / "data", db=str(tmp_path / "history.sqlite"), speed=40.0)


@pytest.fixture
def client(bench):
    with TestClient(create_workbench_app(bench), base_url="http://127.0.0.1:8770") as c:
        yield c


def test_the_page_and_its_files_are_served_from_the_package(client):
    page = client.get("/")
    assert page.status_code == 200 and "axiscal workbench" in page.text
    assert "http" not in page.text.replace("http://www.w3.org", "")  # nothing from elsewhere
    for name in ("app.js", "tests.js", "style.css"):
        assert client.get(f"/static/{name}").status_code == 200


def test_another_host_or_origin_is_refused(client):
    assert client.get("/api/machines", headers={"host": "evil.example:8770"}).status_code == 403
    assert client.get("/api/machines", headers={"origin": "http://evil.example"}).status_code == 403
    assert client.get("/api/machines", headers={"origin": "http://127.0.0.1:8770"}).status_code == 200


def test_beyond_loopback_every_request_brings_the_token(bench):
    token = new_token()
    app = create_workbench_app(bench, allowed_hosts=None, token=token)
    with TestClient(app, base_url="http://192.0.2.10:8770") as c:
        assert c.get("/").status_code == 403
        assert c.get("/api/machines").status_code == 403
        assert c.get("/", params={"token": "x" * 24}).status_code == 403
        page = c.get("/", params={"token": token})
        assert page.status_code == 200 and TOKEN_COOKIE in page.cookies
        assert c.get("/api/machines").status_code == 200  # the cookie from now on


def test_a_large_body_is_refused(client):
    status = client.post("/api/visit", content=b"{" + b" " * (MAX_BODY + 1) + b"}",
                         headers={"content-type": "application/json"}).status_code
    assert status == 413


def test_files_only_from_the_data_folder(client, bench, tmp_path):
    (tmp_path / "secret.txt").write_text("no")
    assert client.get("/files/../secret.txt").status_code == 404
    assert client.get("/files/%2e%2e/secret.txt").status_code == 404
    assert client.get("/files//etc/passwd").status_code == 404
    assert client.post("/api/visit", json=VISIT).status_code == 200
    answer = client.get("/files/vmc-1-2026-11-26/campaign.toml", params={"download": "1"})
    assert answer.status_code == 200 and "attachment" in answer.headers["content-disposition"]
    assert 'name = "VMC 1"' in answer.text


def test_a_form_names_each_field_that_is_wrong(client):
    answer = client.post("/api/visit", json=VISIT | {"title": "", "A_um": -1, "date": "yesterday", "colour": "red"})
    assert answer.status_code == 422
    fields = answer.json()["fields"]
    assert set(fields) == {"title", "A_um", "date", "colour"}
    answer = client.post("/api/visit", json=VISIT | {"E_um": "nan"})
    assert answer.status_code == 422 and "finite" in answer.json()["fields"]["E_um"]
    assert client.post("/api/visit", content=b"not json", headers={"content-type": "application/json"}).status_code == 422


def test_steps_out_of_order_say_what_comes_first(client):
    assert client.post("/api/plan", json={"start_mm": 0, "end_mm": 150, "targets": 5, "runs": 1, "overrun_mm": 5,
                                          "dwell_s": 1}).json() == {"error": "start a visit first (New visit)"}
    assert client.post("/api/run", json={"phase": "as-found"}).status_code == 400
    assert client.post("/api/run/pause").json()["error"] == "no run is going on"
    assert client.post("/api/connect", json={"instrument": "umd:/dev/no-such-port"}).status_code == 422
    plan = client.post("/api/plan", json={"start_mm": 10, "end_mm": 5, "targets": 5, "runs": 1, "overrun_mm": 5, "dwell_s": 1})
    assert plan.status_code == 422 and "end_mm" in plan.json()["fields"]


def test_the_stream_sends_the_run_state(client):
    with client.websocket_connect("ws://127.0.0.1:8770/ws") as socket:
        message = socket.receive_json()
    assert message["run"] == {"state": "idle", "phase": "as-found", "resumable": False} and message["trace"]["t_s"] == []


def test_two_first_readings_of_a_new_history_at_once_both_list_its_machines(tmp_path):
    """The server's warm-up and the page's first request read a history that is not made yet, together."""
    import threading

    for k in range(6):
        bench = Workbench(tmp_path / f"data{k}", db=str(tmp_path / f"history{k}.sqlite"))
        answers, start = [], threading.Barrier(2)

        def read(bench=bench, start=start, answers=answers):
            start.wait()
            try:
                answers.append(bench.machines())
            except Exception as exc:  # noqa: BLE001 - the test names what went wrong
                answers.append(str(exc))

        threads = [threading.Thread(target=read) for _ in range(2)]
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join(60)
        assert answers == [[], []]


def test_the_page_names_its_icon_and_both_addresses_serve_it(client):
    assert '<link rel="icon" href="/favicon.svg"' in client.get("/").text
    for address in ("/favicon.svg", "/favicon.ico"):  # a browser asks for /favicon.ico whatever the page names
        icon = client.get(address)
        assert icon.status_code == 200 and icon.headers["content-type"].startswith("image/svg+xml")
        assert icon.text.startswith("<svg") and "http" not in icon.text.replace("http://www.w3.org", "")
