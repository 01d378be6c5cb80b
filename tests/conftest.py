"""Shared fixtures: the shipped examples folder and a CLI runner that returns (status, stdout, stderr)."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from hypothesis import settings

# CI runs the property tests on a fixed sequence of examples, so a submission is judged the same way
# every time; developers' runs keep drawing new examples (set HYPOTHESIS_PROFILE=ci to repeat CI's).
settings.register_profile("ci", derandomize=True, deadline=None)
settings.register_profile("dev", deadline=None)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci" if os.environ.get("CI") else "dev"))

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


@pytest.fixture
def examples() -> Path:
    return EXAMPLES


@pytest.fixture
def run_cli(capsys):
    """Run ``axiscal`` in-process: ``status, out, err = run_cli("volumetric", "--machine", ...)``."""
    from axiscal.cli.main import main

    def run(*argv: str) -> tuple[int, str, str]:
        status = main([str(a) for a in argv])
        captured = capsys.readouterr()
        return status, captured.out, captured.err

    return run


@pytest.fixture(scope="module")
def module():
    """The virtual XZ module of paper 000 (seed 0); test files may define their own ``module``."""
    from axiscal.measurement.virtual import VirtualModule

    return VirtualModule(seed=0)


@pytest.fixture(scope="module")
def system(module):
    """The calibrated measurement system of :func:`module`."""
    return module.measurement_system()


CHROMIUM_FLAGS = (
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--remote-debugging-address=127.0.0.1",
    "--remote-debugging-port=0",
)


class DevTools:
    """A minimal DevTools-protocol client for one page: commands with ids, events kept."""

    def __init__(self, socket):
        self.socket = socket
        self.next_id = 0
        self.events: list[dict] = []

    def call(self, method: str, **params) -> dict:
        import json
        import time

        self.next_id += 1
        self.socket.send(json.dumps({"id": self.next_id, "method": method, "params": params}))
        deadline = time.monotonic() + 15.0
        while time.monotonic() < deadline:
            message = json.loads(self.socket.recv(timeout=15.0))
            if message.get("id") == self.next_id:
                assert "error" not in message, message
                return message["result"]
            self.events.append(message)
        raise TimeoutError(method)

    def evaluate(self, expression: str):
        result = self.call("Runtime.evaluate", expression=expression, returnByValue=True)
        assert "exceptionDetails" not in result, result
        return result["result"].get("value")


@pytest.fixture
def chromium_page(tmp_path):
    """Headless Chromium (Debian's, ``--no-sandbox``) with one page, driven over DevTools.

    Yields a :class:`DevTools` bound to the page. Without Chromium this fails: ``.ci/run`` installs
    it.
    """
    import os
    import shutil
    import signal
    import subprocess
    import time

    import httpx
    from websockets.sync.client import connect

    binary = shutil.which("chromium") or "/usr/bin/chromium"
    assert Path(binary).exists(), "headless Chromium is needed for browser tests: apt-get install chromium"
    profile = tmp_path / "chromium-profile"
    process = subprocess.Popen(
        [binary, *CHROMIUM_FLAGS, f"--user-data-dir={profile}", "about:blank"],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        start_new_session=True,
    )
    try:
        port_file = profile / "DevToolsActivePort"
        deadline = time.monotonic() + 20.0
        while not (port_file.exists() and port_file.read_text().count("\n") >= 1):
            assert process.poll() is None and time.monotonic() < deadline, "Chromium did not open its DevTools port"
            time.sleep(0.05)
        port = int(port_file.read_text().split("\n")[0])
        targets = httpx.get(f"http://127.0.0.1:{port}/json/list", timeout=10).json()
        page = next(t for t in targets if t["type"] == "page")
        with connect(page["webSocketDebuggerUrl"], max_size=None, open_timeout=10) as socket:
            yield DevTools(socket)
    finally:
        if process.poll() is None:
            os.killpg(process.pid, signal.SIGTERM)
            try:
                process.wait(timeout=5)
            except subprocess.TimeoutExpired:
                os.killpg(process.pid, signal.SIGKILL)
                process.wait(timeout=5)
