"""The declared file formats: one model per format is the reader's check, the docs' key tables and
the editors' JSON Schema; the committed docs/schemas/ and tables equal what the models give, and
every shipped file of these formats passes the schema under an independent validator (jsonschema)."""

from __future__ import annotations

import datetime as dt
import json
import re
import tomllib
from pathlib import Path

import jsonschema
import pytest

from axiscal.errors import AxiscalError
from axiscal.io.formats import FORMATS, json_schema, key_path, line_of, validate_data
from axiscal.io.formats.catalogue import json_schema_text, key_tables
from axiscal.io.schema import TomlLines

ROOT = Path(__file__).resolve().parents[2]
DOCS = ROOT / "docs"
EXAMPLES = ROOT / "examples"

#: every file of these formats shipped in examples/ and the tests' data
FILES = {
    "campaign": [EXAMPLES / "campaign/campaign.toml", EXAMPLES / "cmm/campaign.toml",
                 ROOT / "tests/campaign/data/vmc850/campaign.toml"],
    "machine": sorted(p for p in EXAMPLES.glob("**/*.toml") if "machine" in p.name),
    "budget": [EXAMPLES / "uncertainty_budget.toml"],
    "artefact": sorted((EXAMPLES / "identification").glob("*.toml")),
    "flatness": sorted((EXAMPLES / "flatness").glob("*.toml")),
    "import-map": sorted((EXAMPLES / "imports").glob("*.toml")),
}
CASES = [(name, path) for name, paths in FILES.items() for path in paths]


def _plain(value):
    """TOML data as a TOML editor hands it to a JSON Schema: dates as their ISO text."""
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, list):
        return [_plain(v) for v in value]
    if isinstance(value, (dt.date, dt.datetime, dt.time)):
        return value.isoformat()
    return value


def _validator(name: str) -> jsonschema.Draft7Validator:
    schema = json.loads((DOCS / "schemas" / f"{name}.json").read_text(encoding="utf-8"))
    jsonschema.Draft7Validator.check_schema(schema)
    return jsonschema.Draft7Validator(schema)


def test_every_format_has_its_files():
    assert set(FILES) == set(FORMATS) and all(FILES.values())


@pytest.mark.parametrize("name", sorted(FORMATS))
def test_committed_schema_is_what_the_model_gives(name):
    committed = (DOCS / "schemas" / f"{name}.json").read_text(encoding="utf-8")
    assert committed == json_schema_text(name), "run: python docs/schema_files.py"


def test_committed_key_tables_are_what_the_models_give():
    page = (DOCS / "formats.md").read_text(encoding="utf-8")
    blocks = dict(re.findall(r"<!-- keys: ([\w-]+) -->\n(.*?)<!-- end of keys -->", page, re.S))
    assert set(blocks) == set(FORMATS)
    for name, block in blocks.items():
        assert block == "\n" + key_tables(name) + "\n", f"{name}: run python docs/schema_files.py"


@pytest.mark.parametrize(("name", "path"), CASES, ids=[f"{n}:{p.relative_to(ROOT)}" for n, p in CASES])
def test_every_shipped_file_passes_its_schema(name, path):
    data = _plain(tomllib.loads(path.read_text(encoding="utf-8")))
    errors = [f"{'/'.join(map(str, e.absolute_path))}: {e.message}" for e in _validator(name).iter_errors(data)]
    assert errors == []


# (format, a valid file, the change, the path jsonschema names): the reader refuses it too
MISTAKES = [
    ("campaign", "campaign/campaign.toml", ('operator = ', 'operater = '), "campaign"),
    ("campaign", "campaign/campaign.toml", ('kind = "positioning"', 'kind = "positioning"\nspacing = 3'), "tests"),
    ("campaign", "campaign/campaign.toml", ('axis = "X"', 'axis = "Q"'), "tests"),
    ("machine", "xz_module/machine.toml", ('tool_mm = [0.0, -40.0, 0.0]', 'tool_mm = [0.0, -40.0]'), "tool_mm"),
    ("machine", "xz_module/machine.toml", ('errors = "x_errors.csv"', 'errors = "x_errors.csv"\nhold_ends = "false"'),
     "axes/X/hold_ends"),
    ("budget", "uncertainty_budget.toml", ("eve_um = 1.0", "eve_um = 1e300"), "setup/eve_um"),
    ("budget", "uncertainty_budget.toml", ("eve_um = 1.0", "eve_um = -1.0"), "setup/eve_um"),
    ("artefact", "identification/plate_xz.toml", ('pose = "fit"', 'pose = "guess"'), "pose"),
    ("flatness", "flatness/grid.toml", ("[[lines]]", "[[lines]]\ncolour = 1"), "lines/0"),
    ("import-map", "imports/reading_per_row.toml", ("sign = -1", "sign = 2"), "sign"),
]


@pytest.mark.parametrize(("name", "example", "change", "where"), MISTAKES, ids=[f"{m[0]}:{m[3]}" for m in MISTAKES])
def test_the_schema_and_the_model_refuse_the_same_mistakes(tmp_path, name, example, change, where):
    from axiscal.io.formats.artefact import ARTEFACT_MODELS

    text = (EXAMPLES / example).read_text(encoding="utf-8")
    assert change[0] in text
    text = text.replace(change[0], change[1], 1)
    data = tomllib.loads(text)
    errors = list(_validator(name).iter_errors(_plain(data)))
    paths = ["/".join(map(str, e.absolute_path)) for e in errors]
    assert errors and any(p.startswith(where) or where.startswith(p) for p in paths), paths
    model = ARTEFACT_MODELS[data["kind"]] if name == "artefact" else FORMATS[name]
    with pytest.raises(AxiscalError) as caught:
        validate_data(model, data, path="f.toml", lines=TomlLines(text))
    changed = change[1].splitlines()[-1].split("=")[0].strip()
    assert caught.value.line == text.splitlines().index(next(l for l in text.splitlines() if l.startswith(changed))) + 1


@pytest.mark.parametrize(("data", "message", "line"), [
    ({"setup": {"eve_um": "one"}}, "[setup] eve_um must be a finite number, not 'one'", 2),
    ({"setup": {"eve_um": -1.0}}, "[setup] eve_um must not be negative, not -1.0", 2),
    ({"setup": {"eve_um": 2e4}}, "[setup] eve_um must be 0 to 10000, not 20000", 2),
    ({"air": {"temprature_u_K": 0.1}}, "unknown key 'temprature_u_K' in [air]; did you mean 'temperature_u_K'?", 2),
    ({"setup": 3}, "setup must be a table, not 3", 1),
])
def test_one_line_naming_key_path_and_what_was_expected(data, message, line):
    from axiscal.io.formats import BudgetFile

    section, table = next(iter(data.items()))
    key = next(iter(table)) if isinstance(table, dict) else None
    text = f"[{section}]\n{key} = 0\n" if key else f"{section} = 3\n"
    with pytest.raises(AxiscalError) as caught:
        validate_data(BudgetFile, data, path="b.toml", lines=TomlLines(text))
    assert caught.value.message.startswith(message) and caught.value.line == line
    assert "\n" not in str(caught.value)


def test_key_paths_and_their_lines():
    lines = TomlLines('[[tests]]\nkind = "a"\n[[tests]]\nkind = "b"\ntolerances = { A_um = 1 }\n[machine.compensation]\nX = "x"\n')
    assert key_path(("tests", 1, "kind")) == "tests[2].kind"
    assert line_of(lines, ("tests", 1, "kind")) == 4
    assert line_of(lines, ("tests", 1, "tolerances", "A_um")) == 5
    assert line_of(lines, ("tests", 1, "missing")) == 3  # the table, for a key that is not there
    assert line_of(lines, ("machine", "compensation", "X")) == 7


def test_unknown_kind_of_test_suggests_the_nearest(tmp_path, examples):
    import shutil

    from axiscal.campaign import load_campaign

    folder = tmp_path / "campaign"
    shutil.copytree(examples / "campaign", folder)
    path = folder / "campaign.toml"
    text = path.read_text()
    path.write_text(text.replace('kind = "positioning"', 'kind = "positoning"', 1))
    with pytest.raises(AxiscalError) as caught:
        load_campaign(folder)
    assert "unknown kind 'positoning'; did you mean 'positioning'?" in caught.value.message
    assert path.read_text().splitlines()[caught.value.line - 1] == 'kind = "positoning"'


def test_the_declared_constants_are_the_rooms_constants():
    from axiscal.identification import ARTEFACT_KINDS
    from axiscal.instruments.air import METHODS
    from axiscal.io.formats.artefact import ARTEFACT_MODELS
    from axiscal.io.formats.budget import BUDGET_WORDS
    from axiscal.io.formats.flatness import ANGLE_KEYS
    from axiscal.io.formats.importmap import IMPORT_UNIT_NAMES
    from axiscal.io.formats.machine import INTERPOLATIONS
    from axiscal.io.importers.columnmap import IMPORT_UNITS
    from axiscal.levels.files import ANGLE_COLUMNS
    from axiscal.model.tables import INTERPOLATIONS as TABLE_INTERPOLATIONS
    from axiscal.uncertainty.decision import DECISION_RULES
    from axiscal.io.formats.campaign import DECISION_RULES as FILE_RULES

    assert tuple(ARTEFACT_MODELS) == tuple(ARTEFACT_KINDS)
    assert ANGLE_KEYS == tuple(ANGLE_COLUMNS)
    assert IMPORT_UNIT_NAMES == tuple(IMPORT_UNITS)
    assert INTERPOLATIONS == TABLE_INTERPOLATIONS
    assert tuple(FILE_RULES) == tuple(DECISION_RULES)
    assert all(method in BUDGET_WORDS["instrument"]["method"] for method in METHODS)


def test_schema_command_prints_the_committed_schema(run_cli):
    for name in FORMATS:
        status, out, err = run_cli("schema", name)
        assert status == 0 and err == "" and out == (DOCS / "schemas" / f"{name}.json").read_text(encoding="utf-8")
    status, out, err = run_cli("schema", "laser")
    assert status == 2 and out == "" and "laser" in err and "Traceback" not in err


def test_a_schema_comment_line_reads_the_same(tmp_path, examples):
    from axiscal.uncertainty import read_budget

    text = (examples / "uncertainty_budget.toml").read_text()
    (tmp_path / "b.toml").write_text("#:schema ./budget.schema.json\n" + text)
    assert read_budget(tmp_path / "b.toml") == read_budget(examples / "uncertainty_budget.toml").__class__(
        **{**read_budget(examples / "uncertainty_budget.toml").__dict__, "source": str(tmp_path / "b.toml")})


def test_a_test_key_spelled_as_the_option_reads_the_same(tmp_path, examples):
    import shutil

    from axiscal.campaign import load_campaign

    folder = tmp_path / "campaign"
    shutil.copytree(examples / "campaign", folder)
    before = load_campaign(folder)
    path = folder / "campaign.toml"
    path.write_text(path.read_text().replace("spacing_mm = ", "spacing-mm = "))
    assert load_campaign(folder).tests == before.tests
