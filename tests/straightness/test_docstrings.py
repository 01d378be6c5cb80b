"""The Examples sections of the straightness and squareness rooms run as written."""

from __future__ import annotations

import doctest
import importlib

import pytest

MODULES = [
    "axiscal.straightness.files",
    "axiscal.straightness.readers",
    "axiscal.straightness.probes",
    "axiscal.straightness.sequential",
    "axiscal.straightness.frequency",
    "axiscal.straightness.error_analysis",
    "axiscal.straightness.reference",
    "axiscal.straightness.report",
    "axiscal.straightness.separation",
    "axiscal.squareness.cmm",
    "axiscal.squareness.cmm_squareness",
    "axiscal.squareness.gauge_blocks",
    "axiscal.squareness.evaluation",
    "axiscal.squareness.signs",
    "axiscal.squareness.prism",
    "axiscal.squareness.pentaprism",
]


@pytest.mark.parametrize("name", MODULES)
def test_examples_run(name):
    result = doctest.testmod(importlib.import_module(name), optionflags=doctest.ELLIPSIS)
    assert result.failed == 0
