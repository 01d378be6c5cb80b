"""Every declared TOML format, and JSON, read nested far too deep: one line naming the file and the line, never a RecursionError.

Arrays 100,000 deep and inline tables 3,000 deep make the TOML and JSON parsers recurse past Python's
limit; a 5,000-deep dotted key parses, but every reader after it (validation, error messages) recurses
as deep. The readers refuse nesting deeper than ``MAX_NESTING`` levels; the deepest format nests a few.
"""

from __future__ import annotations

import pytest

from axiscal.campaign import load_campaign
from axiscal.errors import AxiscalError
from axiscal.flatness.files import read_flatness_lines
from axiscal.identification.files import read_artefact
from axiscal.io.importers.columnmap import read_column_map
from axiscal.io.jsonio import read_json
from axiscal.io.schema import MAX_NESTING
from axiscal.io.text_files import parse_toml
from axiscal.model.machine_file import load_machine
from axiscal.uncertainty.budget import read_budget
from axiscal.uncertainty.volumetric import load_machine_uncertainty

DEEP = {
    "arrays": "name = \"m\"\nx = " + "[" * 100_000 + "]" * 100_000 + "\n",
    "inline tables": "name = \"m\"\nx = " + "{a = " * 3_000 + "1" + "}" * 3_000 + "\n",
    "dotted key": "name = \"m\"\nx" + ".a" * 5_000 + " = 1\n",
    "table header": "name = \"m\"\n[x" + ".a" * 5_000 + "]\nb = 1\n",
}
READERS = {
    "machine": load_machine,
    "machine uncertainty": load_machine_uncertainty,
    "campaign": lambda path: load_campaign(path.parent),
    "budget": read_budget,
    "artefact": read_artefact,
    "flatness": read_flatness_lines,
    "import-map": read_column_map,
}


@pytest.mark.parametrize("reader", sorted(READERS))
@pytest.mark.parametrize("deep", sorted(DEEP))
def test_a_file_nested_too_deep_is_refused_in_one_line(tmp_path, reader, deep):
    path = tmp_path / "campaign.toml"
    path.write_text(DEEP[deep])
    with pytest.raises(AxiscalError) as caught:
        READERS[reader](path)
    assert str(caught.value) == f"{path}:2: nested more than {MAX_NESTING} levels deep (arrays, tables or dotted keys inside each other)"


@pytest.mark.parametrize("text, line", [("[" * 100_000 + "]" * 100_000, 1), ('{"a": ' * 3_000 + "1" + "}" * 3_000, 1),
                                        ("[\n" * 60 + "1" + "]" * 60, MAX_NESTING + 1)])
def test_json_nested_too_deep_is_refused(tmp_path, text, line):
    path = tmp_path / "results.json"
    path.write_text(text)
    with pytest.raises(AxiscalError, match=rf"^{path}:{line}: nested more than {MAX_NESTING} levels deep"):
        read_json(path)


def test_nesting_up_to_the_bound_reads():
    text = "x = " + "[" * MAX_NESTING + "1" + "]" * MAX_NESTING + "\ny" + ".a" * (MAX_NESTING - 1) + " = 2\n"
    data = parse_toml(text)
    assert data["y"]["a"]["a"] and data["x"][0][0]
    with pytest.raises(AxiscalError, match=r"^line 1: nested more than"):
        parse_toml("x = " + "[" * (MAX_NESTING + 1) + "1" + "]" * (MAX_NESTING + 1) + "\n")


def test_the_command_line_says_it_in_one_line(run_cli, tmp_path):
    path = tmp_path / "machine.toml"
    path.write_text(DEEP["dotted key"])
    status, stdout, err = run_cli("volumetric", "--machine", path, "--grid", "X=0")
    assert status == 2 and stdout == "" and err.count("\n") == 1 and "nested more than" in err, err


def test_dots_in_strings_and_prose_are_not_keys():
    leaders = "." * 200
    text = f'note = """\nTable of contents {leaders} 3\n{".".join(["a"] * 80)}\n"""\nother = "{".".join(["b"] * 80)}"\n'
    text += f'"{".".join(["c"] * 80)}" = 1\n'
    data = parse_toml(text)
    assert data["other"].count(".") == 79 and data[".".join(["c"] * 80)] == 1
