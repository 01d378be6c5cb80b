"""The command line's choices (axiscal.cli.choices) are the library's own values."""

from __future__ import annotations

import importlib
from collections.abc import Mapping

import pytest

from axiscal.cli import choices


@pytest.mark.parametrize("name", sorted(choices.MIRRORED))
def test_each_choice_equals_the_library_constant(name):
    module, _, attribute = choices.MIRRORED[name].partition(":")
    library = getattr(importlib.import_module(module), attribute)
    if isinstance(library, Mapping):
        library = tuple(library)
    assert getattr(choices, name) == library


def test_every_value_of_the_module_is_mirrored():
    values = {n for n in choices.__all__ if n != "MIRRORED"}
    assert values == set(choices.MIRRORED)
