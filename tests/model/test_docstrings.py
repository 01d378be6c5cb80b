"""The examples in the model room's docstrings run as written."""

from __future__ import annotations

import doctest
import importlib

import pytest


@pytest.mark.parametrize("name", ["machine", "tables", "inputs", "kinematics", "diagonal", "volumetric", "inverse"])
def test_docstring_examples(name):
    module = importlib.import_module(f"axiscal.model.{name}")
    failures, _ = doctest.testmod(module, optionflags=doctest.ELLIPSIS)
    assert failures == 0
