"""Every public function and class of the importers and of the firmware/controller writers has a numpydoc docstring."""

from __future__ import annotations

import importlib
import inspect

import pytest

MODULES = [
    "axiscal.io.importers.columnmap",
    "axiscal.io.importers.rtx",
    "axiscal.compensation.skew",
    "axiscal.compensation.backlash",
    "axiscal.compensation.screwmaps",
    "axiscal.compensation.sag",
]


def _public():
    for name in MODULES:
        module = importlib.import_module(name)
        assert (module.__doc__ or "").strip(), f"{name} has no module docstring"
        for public in module.__all__:
            value = getattr(module, public)
            if inspect.isfunction(value) or inspect.isclass(value):
                yield f"{name}.{public}", value


@pytest.mark.parametrize("name, value", list(_public()), ids=lambda v: v if isinstance(v, str) else "")
def test_numpydoc(name, value):
    doc = inspect.getdoc(value) or ""
    first = doc.strip().splitlines()[0] if doc.strip() else ""
    assert first.endswith("."), f"{name}: the first line is one sentence: {first!r}"
    if inspect.isfunction(value):
        assert "Parameters\n----------" in doc, f"{name} has no Parameters section"
        assert "Returns\n-------" in doc, f"{name} has no Returns section"
    else:
        assert "Attributes\n----------" in doc or "Parameters\n----------" in doc, f"{name} documents no fields"


@pytest.mark.parametrize("name", MODULES)
def test_examples_run(name):
    import doctest

    result = doctest.testmod(importlib.import_module(name), optionflags=doctest.ELLIPSIS)
    assert result.failed == 0 and result.attempted > 0


@pytest.mark.parametrize("name", MODULES)
def test_the_package_re_exports_every_public_name(name):
    module = importlib.import_module(name)
    package = importlib.import_module(name.rsplit(".", 1)[0])
    for public in module.__all__:
        assert public in package.__all__ and getattr(package, public) is getattr(module, public), public
