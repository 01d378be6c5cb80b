"""Shared fixtures: the shipped examples folder, a CLI runner that returns (status, stdout, stderr), and a browser page."""

from __future__ import annotations

import math
import os
import re
import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import pytest
from hypothesis import settings

# CI runs the property tests on a fixed sequence of examples, so a submission is judged the same way
# every time; developers' runs keep drawing new examples (set HYPOTHESIS_PROFILE=ci to repeat CI's).
settings.register_profile("ci", derandomize=True, deadline=None)
settings.register_profile("dev", deadline=None)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci" if os.environ.get("CI") else "dev"))

# The suite starts a few hundred Python interpreters (the docs' command lines, the CLI in subprocesses,
# killed writers): where the environment asks for no bytecode files (PYTHONDONTWRITEBYTECODE), each one
# compiled axiscal's modules again, about a quarter of a second apiece. The caches go to __pycache__
# folders, which git ignores.
os.environ.pop("PYTHONDONTWRITEBYTECODE", None)
sys.dont_write_bytecode = False

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"

# Test files whose tests must not run beside each other: under pytest-xdist (`make test` runs `-n 2`;
# pyproject's addopts give `--dist loadgroup`) each group's tests go to one worker and run there one
# after another, while the other worker takes the rest. The groups are named here, by file, and not
# with xdist's `xdist_group` mark: from pytest 9.2 on that mark silently stops reaching xdist's
# scheduler (xdist 3.8 writes the group into a field of the test's id that pytest no longer reads),
# and the tests it should keep apart would run at once.
ONE_AT_A_TIME = {
    "tests/devices/test_linuxcnc.py": "linuxcnc",  # one LinuxCNC per machine: rtapi_app, HAL's shared memory, TCP 5007
}
# Test files whose module-scoped fixtures are costly (a campaign reported, a server started): all their
# tests go to one worker, so the fixture is built once and not once on each worker.
ONE_WORKER = {
    "tests/campaign/test_compare.py": "compare",  # two campaigns reported against their scaled copies: ~40 s
    "tests/campaign/test_report.py": "report",  # the vmc850 campaign reported and run once
    "tests/report/test_demo.py": "demo",  # the demo job (two campaigns, their reports): ~40 s under load
}


@pytest.hookimpl(optionalhook=True)
def pytest_xdist_make_scheduler(config, log):
    """xdist's loadgroup scheduling, each group of :data:`ONE_AT_A_TIME` and :data:`ONE_WORKER` one unit of work."""
    if config.getvalue("dist") != "loadgroup":
        return None
    from xdist.scheduler import LoadGroupScheduling

    class Scheduling(LoadGroupScheduling):
        def _split_scope(self, nodeid: str) -> str:
            path = nodeid.split("::", 1)[0]
            group = ONE_AT_A_TIME.get(path) or ONE_WORKER.get(path)
            return f"@{group}" if group else super()._split_scope(nodeid)

    return Scheduling(config, log)


@pytest.fixture
def examples() -> Path:
    return EXAMPLES


# A number as files print it: sign, digits with or without a point, an exponent.
_NUMBER = re.compile(r"[-+]?(?:\d+\.\d*|\.\d+|\d+)(?:[eE][-+]?\d+)?")


def _printed_unit(token: str) -> float:
    """One unit in the last digit printed: 0.01 for ``1.23``, 1e-7 for ``1.5e-6``; 0 for a whole number."""
    mantissa, _, exponent = token.lower().partition("e")
    if "." not in mantissa and not exponent:
        return 0.0  # counts, indices, line numbers, dates: exact
    decimals = len(mantissa.partition(".")[2])
    return 10.0 ** (int(exponent or 0) - decimals)


def assert_same_text_to_precision(expected: str, actual: str, *, rel: float = 1e-9, name: str = "") -> None:
    """Assert two texts agree but for their numbers, which agree to `rel` or to one unit of the last digit printed.

    Regenerated files are compared with this, never byte for byte: another CPU (another BLAS kernel, another
    order of a sum) changes the 16th significant digit of a float, and the rounding of a printed figure may
    then flip its last digit. Whole numbers (counts, indices, dates) must be equal.
    """
    lines_a, lines_b = expected.splitlines(), actual.splitlines()
    assert len(lines_a) == len(lines_b), f"{name}: {len(lines_a)} lines expected, {len(lines_b)} written"
    for number, (line_a, line_b) in enumerate(zip(lines_a, lines_b), start=1):
        if line_a == line_b:
            continue
        text_a, text_b = _NUMBER.split(line_a), _NUMBER.split(line_b)
        values_a, values_b = _NUMBER.findall(line_a), _NUMBER.findall(line_b)
        where = f"{name} line {number}:\n  expected {line_a[:300]}\n  written  {line_b[:300]}"
        assert text_a == text_b and len(values_a) == len(values_b), where
        for a, b in zip(values_a, values_b):
            x, y = float(a), float(b)
            bound = max(rel * max(abs(x), abs(y)), _printed_unit(a), _printed_unit(b))
            assert math.isclose(x, y, rel_tol=0.0, abs_tol=bound * (1 + 1e-9)), f"{where}\n  {a} != {b}"


@pytest.fixture
def same_text_to_precision():
    """:func:`assert_same_text_to_precision`, for tests that compare regenerated files with shipped ones."""
    return assert_same_text_to_precision


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


CHROMIUM = "/usr/bin/chromium"
"""Debian's chromium, which Playwright drives (no browser is downloaded)."""


@dataclass
class BrowserPage:
    """A Playwright page and what it did: the URLs it requested and the errors its scripts threw."""

    page: Any
    requests: list[str] = field(default_factory=list)
    errors: list[str] = field(default_factory=list)


@pytest.fixture(scope="module")
def chromium():
    """Headless Chromium (Debian's, ``--no-sandbox``) launched by Playwright once for a test module.

    Closed with its module: no browser (nor Playwright's driver and its event loop) stays behind
    while the rest of the suite runs.

    Without Chromium this fails: ``make chromium`` (and ``.ci/run``) install it.
    """
    from playwright.sync_api import sync_playwright

    assert Path(CHROMIUM).exists(), "headless Chromium is needed for browser tests: apt-get install chromium"
    with sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path=CHROMIUM, args=["--no-sandbox", "--disable-gpu"])
        try:
            yield browser
        finally:
            browser.close()


@pytest.fixture
def browser_page(chromium):
    """A fresh page (its own context, 1366x768) in :func:`chromium`, as a :class:`BrowserPage`."""
    context = chromium.new_context(viewport={"width": 1366, "height": 768})
    page = context.new_page()
    page.set_default_timeout(20_000)
    shown = BrowserPage(page)
    page.on("request", lambda request: shown.requests.append(request.url))
    page.on("pageerror", lambda error: shown.errors.append(str(error)))
    try:
        yield shown
    finally:
        context.close()


#: the published DCC schemas (PTB's dcc.xsd 3.2.0 and D-SI 2.1.0), beside the project, never copied into it
DCC_SCHEMAS = Path(__file__).resolve().parents[2] / "shared" / "dcc" / "schema"


@pytest.fixture(scope="session")
def dcc_schema():
    """PTB's DCC schema 3.2.0 built offline (xmlschema), to validate every DCC the suite writes.

    The schema imports D-SI and the W3C xmldsig schema by URL: both are mapped to local files (D-SI from
    ../shared/dcc, xmldsig from the copy xmlschema ships) and nothing is fetched (``allow="local"``). Skipped,
    saying why, where ../shared/dcc is absent (a user's clone has no ../shared).
    """
    if not (DCC_SCHEMAS / "dcc-3.2.0" / "dcc.xsd").is_file():
        pytest.skip(f"the published DCC schema is not at {DCC_SCHEMAS} (../shared/dcc, beside the project)")
    import xmlschema

    xmldsig = Path(xmlschema.__file__).parent / "schemas" / "DSIG" / "xmldsig-core-schema.xsd"
    local = {
        "https://ptb.de/si/v2.1.0/SI_Format.xsd": str(DCC_SCHEMAS / "d-si-2.1.0" / "SI_Format.xsd"),
        "https://www.w3.org/TR/xmldsig-core/xmldsig-core-schema.xsd": str(xmldsig),
        "http://www.w3.org/TR/xmldsig-core/xmldsig-core-schema.xsd": str(xmldsig),
    }
    return xmlschema.XMLSchema10(str(DCC_SCHEMAS / "dcc-3.2.0" / "dcc.xsd"), uri_mapper=lambda url: local.get(url, url),
                                 allow="local")
