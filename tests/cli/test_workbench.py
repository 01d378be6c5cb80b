"""``axiscal workbench``: serves the page until SIGTERM; a port in use is one line."""

from __future__ import annotations

import os
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import httpx

SRC = Path(__file__).resolve().parents[2] / "src"


def test_the_workbench_serves_until_sigterm(tmp_path):
    env = os.environ | {"PYTHONPATH": str(SRC)}
    process = subprocess.Popen([sys.executable, "-m", "axiscal.cli.main", "workbench", "--port", "0", "--data",
                                str(tmp_path / "data"), "--db", str(tmp_path / "h.sqlite")],
                               stderr=subprocess.PIPE, text=True, env=env, cwd=tmp_path)
    try:
        line = process.stderr.readline()
        assert line.startswith("workbench: http://127.0.0.1:"), line
        url = line.split(" ", 1)[1].strip()
        assert "axiscal workbench" in httpx.get(url, timeout=10).text
        assert httpx.get(url + "api/machines", timeout=10).json() == []
        process.send_signal(signal.SIGTERM)
        assert process.wait(timeout=15) == 0
    finally:
        if process.poll() is None:
            process.kill()
            process.wait()
    assert (tmp_path / "data").is_dir()


def test_a_port_in_use_is_one_line(run_cli, tmp_path):
    with socket.socket() as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen()
        port = taken.getsockname()[1]
        status, out, err = run_cli("workbench", "--port", port, "--data", tmp_path / "data")
    assert status == 2 and out == ""
    assert err.startswith(f"axiscal: error: the dashboard cannot listen on 127.0.0.1:{port}") and err.count("\n") == 1
    assert "choose another --port or --host" in err


def test_a_bad_port_is_refused_by_the_command_line(run_cli):
    status, _, err = run_cli("workbench", "--port", "70000")
    assert status == 2 and "--port" in err and err.count("\n") == 1
