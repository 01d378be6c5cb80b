"""The Examples sections of the straightness and squareness rooms run as written."""

from __future__ import annotations

import doctest
import importlib

import pytest

MODULES = [
    "axiscal.straightness.files",
    "axiscal.straightness.reference",
    "axiscal.straightness.report",
    "axiscal.straightness.separation",
    "axiscal.squareness.cmm",
    "axiscal.squareness.evaluation",
    "axiscal.squareness.pentaprism",
]


@pytest.mark.parametrize("name", MODULES)
def test_examples_run(name):
    result = doctest.testmod(importlib.import_module(name), optionflags=doctest.ELLIPSIS)
    assert result.failed == 0
