"""Every public name of axiscal.compensation has a numpydoc docstring, and every Examples section runs."""

from __future__ import annotations

import doctest
import importlib
import inspect
import pkgutil

import pytest

import axiscal.compensation as room

MODULES = [importlib.import_module(f"{room.__name__}.{info.name}") for info in pkgutil.iter_modules(room.__path__)]


@pytest.mark.parametrize("module", MODULES, ids=lambda m: m.__name__)
def test_examples_in_docstrings_run(module, monkeypatch, examples):
    monkeypatch.chdir(examples.parent)
    failed, _ = doctest.testmod(module, optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    assert failed == 0


@pytest.mark.parametrize("name", [n for n in room.__all__ if callable(getattr(room, n))])
def test_public_names_have_numpydoc_sections(name):
    obj = getattr(room, name)
    doc = inspect.getdoc(obj) or ""
    summary = doc.splitlines()[0] if doc else ""
    assert summary.endswith(".") or summary.endswith(":"), f"{name}: one-line summary"
    sections = ("Attributes", "Parameters") if inspect.isclass(obj) else ("Parameters",)
    assert any(f"\n{s}\n---" in doc for s in sections), f"{name}: no {' or '.join(sections)} section"
    if inspect.isfunction(obj):
        assert "\nReturns\n---" in doc, f"{name}: no Returns section"


@pytest.mark.parametrize("module", MODULES, ids=lambda m: m.__name__)
def test_the_package_re_exports_every_public_name_of_its_modules(module):
    assert set(module.__all__) <= set(room.__all__)
    assert all(getattr(room, name) is getattr(module, name) for name in module.__all__)
