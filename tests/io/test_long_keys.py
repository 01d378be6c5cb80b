"""A key of megabytes in a declared format: refused in one short line, its start quoted and its length said."""

from __future__ import annotations

import pytest

from axiscal.errors import AxiscalError
from axiscal.model.machine_file import load_machine

BIG = "k" * 10_000_000


@pytest.mark.parametrize("text, line, where", [
    (f"{BIG} = 1\n", 1, ""),
    (f'chain = "FX"\n[axes.X]\nerrors = "x.csv"\n{BIG} = 1\n', 4, " in [axes.X]"),
])
def test_a_ten_megabyte_unknown_key_is_cut_in_the_message(tmp_path, text, line, where):
    path = tmp_path / "machine.toml"
    path.write_text(text)
    with pytest.raises(AxiscalError) as caught:
        load_machine(path)
    shown = "k" * 37 + "... (10000000 characters)"
    assert str(caught.value).startswith(f"{path}:{line}: unknown key '{shown}'{where} (known: ")
    assert len(str(caught.value)) < 400


def test_a_short_unknown_key_is_quoted_whole_with_its_nearest_name(tmp_path):
    path = tmp_path / "machine.toml"
    path.write_text('chian = "FX"\n')
    with pytest.raises(AxiscalError, match=r":1: unknown key 'chian'; did you mean 'chain'\?"):
        load_machine(path)
