"""The stated public API: every name in ``axiscal.__all__`` resolves, has a numpydoc docstring,
and every module of the package states ``__all__``."""

from __future__ import annotations

import importlib
import inspect
import pkgutil
import subprocess
import sys

import pytest

import axiscal


@pytest.mark.parametrize("name", axiscal.__all__)
def test_every_public_name_resolves(name):
    assert getattr(axiscal, name) is not None


@pytest.mark.parametrize("name", [n for n in axiscal.__all__ if n != "__version__"])
def test_every_public_name_has_a_numpydoc_docstring(name):
    doc = inspect.getdoc(getattr(axiscal, name)) or ""
    assert doc.strip(), f"{name} has no docstring"
    first = doc.strip().splitlines()[0]
    assert first.endswith((".", ")")), f"{name}: the first line is one sentence: {first!r}"
    if inspect.isfunction(getattr(axiscal, name)):
        assert "Parameters\n----------" in doc, f"{name} has no Parameters section"
        assert "Returns\n-------" in doc, f"{name} has no Returns section"


def test_an_unknown_name_is_an_attribute_error():
    with pytest.raises(AttributeError):
        axiscal.no_such_name  # noqa: B018


def _modules():
    for info in pkgutil.walk_packages(axiscal.__path__, prefix="axiscal."):
        yield info.name


@pytest.mark.parametrize("module_name", sorted(_modules()))
def test_every_module_states_all(module_name):
    module = importlib.import_module(module_name)
    assert hasattr(module, "__all__"), f"{module_name} has no __all__"
    for name in module.__all__:
        assert hasattr(module, name), f"{module_name}.__all__ names '{name}', which it does not define"


def test_import_axiscal_is_cheap():
    """``import axiscal`` imports neither NumPy nor any plotting or web library."""
    code = "import sys, axiscal; print(' '.join(m for m in ('numpy', 'matplotlib', 'starlette', 'click') if m in sys.modules))"
    loaded = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.split()
    assert loaded == []
