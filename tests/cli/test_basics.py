"""The command line's own behaviour: help, version, and the one-line error contract."""

from __future__ import annotations


def test_help_and_version(run_cli):
    status, out, _ = run_cli("--help")
    assert status == 0 and "Usage" in out
    status, out, _ = run_cli("--version")
    assert status == 0 and "axiscal" in out


def test_unknown_command_is_a_usage_error(run_cli):
    status, _, err = run_cli("no-such-command")
    assert status == 2
    assert "Traceback" not in err


def test_usage_errors_are_one_line_naming_the_help(run_cli, examples):
    status, _, err = run_cli("volumetric", "--machine")
    assert status == 2 and len(err.strip().splitlines()) == 1
    status, _, err = run_cli("air", "--temperature-c", "warm", "--pressure-pa", "101325", "--humidity-pct", "50")
    assert status == 2 and len(err.strip().splitlines()) == 1
    assert err.startswith("axiscal: error: ") and "'axiscal air --help'" in err and "warm" in err
