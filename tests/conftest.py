"""Shared fixtures: the shipped examples folder and a CLI runner that returns (status, stdout, stderr)."""

from __future__ import annotations

from pathlib import Path

import pytest

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
