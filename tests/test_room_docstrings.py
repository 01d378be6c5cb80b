"""Every public name of a room has a numpydoc docstring, every Examples section runs, and the package re-exports its modules' names.

Rooms checked so far: add a room's package to ROOMS once its docstrings are in order.
"""

from __future__ import annotations

import doctest
import importlib
import inspect
import pkgutil

import pytest

ROOMS = (
    "axiscal.positioning",
    "axiscal.compensation",
    "axiscal.model",
    "axiscal.straightness",
    "axiscal.squareness",
    "axiscal.circular",
    "axiscal.uncertainty",
    "axiscal.campaign",
    "axiscal.report",
    "axiscal.instruments",
    "axiscal.measurement",
    "axiscal.live",
    "axiscal.capture",
    "axiscal.dynamics",
    "axiscal.levels",
    "axiscal.flatness",
    "axiscal.thermal",
    "axiscal.identification",
    "axiscal.history",
    "axiscal.fleet",
    "axiscal.cmm",
    "axiscal.devices",
    "axiscal.workbench",
)

PACKAGES = [importlib.import_module(name) for name in ROOMS]
MODULES = [
    (package, importlib.import_module(f"{package.__name__}.{info.name}"))
    for package in PACKAGES
    for info in pkgutil.iter_modules(package.__path__)
]
PUBLIC = [(package, name) for package in PACKAGES for name in package.__all__ if callable(getattr(package, name))]


@pytest.mark.parametrize("package,module", MODULES, ids=lambda m: m.__name__)
def test_examples_in_docstrings_run(package, module, monkeypatch, examples):
    monkeypatch.chdir(examples.parent)
    failed, _ = doctest.testmod(module, optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    assert failed == 0


@pytest.mark.parametrize("package,module", MODULES, ids=lambda m: m.__name__)
def test_the_package_re_exports_every_public_name_of_its_modules(package, module):
    assert set(module.__all__) <= set(package.__all__)
    assert all(getattr(package, name) is getattr(module, name) for name in module.__all__)


@pytest.mark.parametrize("package,name", PUBLIC, ids=lambda x: x if isinstance(x, str) else x.__name__)
def test_public_names_have_numpydoc_sections(package, name):
    obj = getattr(package, name)
    doc = inspect.getdoc(obj) or ""
    summary = doc.splitlines()[0] if doc else ""
    assert summary.endswith((".", ":")), f"{name}: one-line summary"
    sections = ("Attributes", "Parameters") if inspect.isclass(obj) else ("Parameters",)
    if inspect.isclass(obj) or inspect.signature(obj).parameters:
        assert any(f"\n{s}\n---" in doc for s in sections), f"{name}: no {' or '.join(sections)} section"
    if inspect.isfunction(obj):
        assert "\nReturns\n---" in doc, f"{name}: no Returns section"
