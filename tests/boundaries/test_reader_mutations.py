"""Readers fed mutated valid files: an AxiscalError naming the file and a line, or a correct parse.

Covers the positioning run reader (linear, rotary and raw laser files), the probe readings reader
of error separation and the campaign.toml reader. Each starts from a shipped example, applies one
to three mutations (a cell replaced, dropped or added, a line dropped, duplicated or inserted, a
header name changed, or raw bytes flipped, truncated or inserted) and asserts the outcome.
Where a file is read, the result is compared with a plain reference parse of the same text.
"""

from __future__ import annotations

import csv
import io
import math
import os
import shutil
import tomllib
import warnings

import numpy as np
import pytest
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st

from axiscal.campaign import load_campaign
from axiscal.campaign.config import KINDS
from axiscal.errors import AxiscalError
from axiscal.positioning import read_positioning_run
from axiscal.straightness import read_probe_readings
from axiscal.units import DEG, MM, UM

EXAMPLES = int(os.environ.get("FUZZ_EXAMPLES", "200"))
SETTINGS = settings(max_examples=EXAMPLES, deadline=None,
                    suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])

CELLS = st.sampled_from([
    "", " ", "abc", "nan", "inf", "-inf", "1e999", "1_000", "\uff11", "0x10", "1,5", "+", "-", "--1", "1e", ".",
    "0", "-0", "1.5", "-2.25", "1e-3", "1E3", "+7", "800.000", "0.000", "3", "7", "+", "-", "up", "down", "?",
    "#", "\"", "\"1\"", "1;2", "\t", "\u00b5m", "\x00", "1e12", "1e13", "   2  ",
])
MUTATIONS = st.sampled_from(["cell", "drop_cell", "add_cell", "drop_line", "duplicate_line", "insert_line", "header",
                             "flip", "truncate", "insert_bytes"])
BYTES = [b",", b";", b"\t", b'"', b"\0", b"\xef\xbb\xbf", b"\r", b"\n", b"\r\n", b"#", b" ", b"\x0c",
         "\u2028".encode(), b"\xff", b"_", b"nan", b"e", b".", b"-", "\uff11".encode()]


@st.composite
def mutations(draw, line_count: int, width: int):
    """A list of 1..3 (kind, row, column, cell, bytes, offset) mutations."""
    out = []
    for _ in range(draw(st.integers(1, 3))):
        out.append((draw(MUTATIONS), draw(st.integers(0, line_count)), draw(st.integers(0, width - 1)),
                    draw(CELLS), draw(st.sampled_from(BYTES)), draw(st.floats(0.0, 1.0)), draw(st.integers(1, 255))))
    return out


def mutate(text: str, steps) -> bytes:
    """Apply the mutations to the text of a CSV or TOML file; returns the bytes written."""
    lines = text.splitlines()
    data = None
    for kind, row, col, cell, chunk, where, mask in steps:
        if data is not None or kind in ("flip", "truncate", "insert_bytes"):
            if data is None:
                data = bytearray(("\n".join(lines) + "\n").encode("utf-8"))
            at = int(where * len(data))
            if kind == "flip" and at < len(data):
                data[at] ^= mask
            elif kind == "truncate":
                del data[at:]
            else:
                data[at:at] = chunk
            continue
        k = row % max(len(lines), 1)
        if not lines:
            lines = [cell]
            continue
        cells = lines[k].split(",")
        c = col % len(cells)
        if kind == "cell":
            cells[c] = cell
            lines[k] = ",".join(cells)
        elif kind == "drop_cell":
            del cells[c]
            lines[k] = ",".join(cells)
        elif kind == "add_cell":
            cells.insert(c, cell)
            lines[k] = ",".join(cells)
        elif kind == "drop_line":
            del lines[k]
        elif kind == "duplicate_line":
            lines.insert(k, lines[k])
        elif kind == "insert_line":
            lines.insert(k, cell)
        else:  # header
            head = lines[0].split(",")
            head[col % len(head)] = cell
            lines[0] = ",".join(head)
    if data is None:
        data = bytearray(("\n".join(lines) + "\n").encode("utf-8"))
    return bytes(data)


def located(exc: AxiscalError, path, physical_lines: int) -> None:
    """The error names the file and a line inside it (one past the end for a file cut short)."""
    assert exc.path == str(path), str(exc)
    assert isinstance(exc.line, int) and 1 <= exc.line <= physical_lines + 1, str(exc)
    assert "\n" not in exc.message


def physical_line_count(data: bytes) -> int:
    return max(1, data.count(b"\n") + data.count(b"\r") - data.count(b"\r\n") + 1)


def plain_rows(data: bytes) -> tuple[list[str], list[list[str]]]:
    """Header and data rows of a comma CSV as a spreadsheet would see them (comment and blank lines skipped)."""
    text = data.decode("utf-8-sig")
    rows = [r for r in csv.reader(io.StringIO(text, newline="")) if r and "".join(r).strip() and not r[0].lstrip().startswith("#")]
    return [h.strip(" \t\v\f").lstrip("\ufeff") for h in rows[0]], rows[1:]


def run(reader, path):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        return reader(path)


REFUSED = object()


def read_or_refused(reader, path, raw: bytes):
    """The reader's result, or REFUSED after checking the error names the file and a line in it."""
    try:
        result = run(reader, path)
    except AxiscalError as exc:
        located(exc, path, physical_line_count(raw))
        event("refused")
        return REFUSED
    event("read")
    return result


# ---- positioning runs


POSITIONING_FILES = ["positioning_run.csv", "rotary_run.csv", "laser_raw_run.csv"]


def reference_deviations(header, rows):
    """{(target, run, direction): deviation} in the file's units, for files with a deviation column."""
    names = {n.rpartition("_")[0] or n: (i, n) for i, n in enumerate(header)}
    ti, target_name = names["target"]
    di, deviation_name = names["deviation"]
    ri, _ = names["run"]
    si, _ = names["direction"]
    table = {}
    for row in rows:
        sign = {"up": "+", "down": "-"}.get(row[si].strip().lower(), row[si].strip())
        table[(float(row[ti]), int(float(row[ri])), sign)] = float(row[di])
    return table, target_name, deviation_name


@SETTINGS
@pytest.mark.parametrize("name", POSITIONING_FILES)
@given(data=st.data())
def test_mutated_positioning_runs(tmp_path, examples, name, data):
    text = (examples / name).read_text(encoding="utf-8")
    lines = text.splitlines()
    steps = data.draw(mutations(len(lines), len(lines[0].split(","))))
    raw = mutate(text, steps)
    path = tmp_path / name
    path.write_bytes(raw)
    result = read_or_refused(read_positioning_run, path, raw)
    if result is REFUSED:
        return
    r = result.run
    arrays = [a for a in (r.deviations_up, r.deviations_down) if a is not None]
    assert arrays and all(np.isfinite(a).all() and a.shape == (r.targets.size, r.runs) for a in arrays)
    assert np.all(np.diff(r.targets) > 0)
    if result.compensated or r.rotary:
        return  # raw readings go through the air compensation; rotary targets fold round the circle
    header, rows = plain_rows(raw)
    expected, target_name, deviation_name = reference_deviations(header, rows)
    t_scale = {"mm": MM, "in": 25.4 * MM}[target_name.rpartition("_")[2]]
    d_scale = {"um": UM, "mm": MM, "nm": 1e-9}[deviation_name.rpartition("_")[2]]
    targets = sorted({t for t, _, _ in expected})
    np.testing.assert_allclose(r.targets, np.array(targets) * t_scale, rtol=0, atol=1e-15)
    labels = [int(label) for label in result.run_labels]
    for sign, array in (("+", r.deviations_up), ("-", r.deviations_down)):
        if array is None:
            continue
        for i, t in enumerate(targets):
            for j, label in enumerate(labels):
                assert array[i, j] == pytest.approx(expected[(t, label, sign)] * d_scale, abs=1e-18)


# ---- probe readings


@SETTINGS
@given(data=st.data())
def test_mutated_probe_readings(tmp_path, examples, data):
    text = (examples / "probe_readings.csv").read_text(encoding="utf-8")
    lines = text.splitlines()[:60]
    text = "\n".join(lines) + "\n"
    steps = data.draw(mutations(len(lines), 4))
    raw = mutate(text, steps)
    path = tmp_path / "probes.csv"
    path.write_bytes(raw)
    result = read_or_refused(lambda p: read_probe_readings(p, spacing_ab_m=15 * MM), path, raw)
    if result is REFUSED:
        return
    header, rows = plain_rows(raw)
    column = {name: [float(row[header.index(name)]) for row in rows] for name in header if name}
    np.testing.assert_array_equal(result.position_m, np.array(column["position_mm"]) * MM)
    np.testing.assert_array_equal(result.a_m, np.array(column["a_um"]) * UM)
    np.testing.assert_array_equal(result.b_m, np.array(column["b_um"]) * UM)
    if "c_um" in column:
        np.testing.assert_array_equal(result.c_m, np.array(column["c_um"]) * UM)
    steps_mm = np.diff(column["position_mm"])
    assert np.all(steps_mm > 0)


# ---- campaign.toml


TOML_VALUES = st.sampled_from([
    '""', '"x"', "true", "false", "0", "-1", "1e400", "nan", "inf", "[]", "[1, 2]", "{}", "{ A_um = -1 }",
    '"../outside.csv"', '"/etc/passwd"', '"positioning_x.csv"', '"missing.csv"', '"XYZ"', '"Q"', '"positioning"',
    '"ballbar"', "2026-11-20", '"iso230-2:2014"', '"vdi3441"', "5.0", "1e9",
])
TOML_LINES = st.sampled_from(["[[tests]]", "[tests]", "[campaign]", "kind = \"positioning\"", "axis = \"X\"", "x = 1",
                              "= 3", "[", "\"", "file = ", "[uncertainty]", "decision_rule = \"guard-band\"", ""])


@st.composite
def toml_mutations(draw, line_count: int):
    out = []
    for _ in range(draw(st.integers(1, 3))):
        out.append((draw(st.sampled_from(["value", "drop_line", "duplicate_line", "insert_line", "key", "bytes"])),
                    draw(st.integers(0, line_count)), draw(TOML_VALUES), draw(TOML_LINES),
                    draw(st.sampled_from(BYTES)), draw(st.floats(0.0, 1.0))))
    return out


def mutate_toml(text: str, steps) -> bytes:
    lines = text.splitlines()
    data = None
    for kind, row, value, line, chunk, where in steps:
        if data is not None or kind == "bytes":
            if data is None:
                data = bytearray(("\n".join(lines) + "\n").encode("utf-8"))
            at = int(where * len(data))
            data[at:at] = chunk
            continue
        k = row % len(lines)
        if kind == "value" and "=" in lines[k]:
            lines[k] = lines[k].split("=", 1)[0] + "= " + value
        elif kind == "key" and "=" in lines[k]:
            lines[k] = line.split("=", 1)[0].strip() + " =" + lines[k].split("=", 1)[1]
        elif kind == "drop_line":
            del lines[k]
        elif kind == "duplicate_line":
            lines.insert(k, lines[k])
        else:
            lines.insert(k, line)
    if data is None:
        data = bytearray(("\n".join(lines) + "\n").encode("utf-8"))
    return bytes(data)


@SETTINGS
@given(data=st.data())
def test_mutated_campaign_files(tmp_path, examples, data):
    campaign_copy = tmp_path / "campaign"
    if not campaign_copy.exists():  # one copy for all examples; only campaign.toml changes
        shutil.copytree(examples / "campaign", campaign_copy)
    path = campaign_copy / "campaign.toml"
    original = (examples / "campaign" / "campaign.toml").read_text(encoding="utf-8")
    lines = original.splitlines()
    raw = mutate_toml(original, data.draw(toml_mutations(len(lines))))
    path.write_bytes(raw)
    try:
        campaign = run(load_campaign, campaign_copy)
    except AxiscalError as exc:
        located(exc, path, physical_line_count(raw))
        event("refused")
        return
    event("read")
    parsed = tomllib.loads(raw.decode("utf-8-sig"))
    assert len(campaign.tests) == len(parsed["tests"])
    for spec, entry in zip(campaign.tests, parsed["tests"]):
        assert spec.kind == entry["kind"]
        for name, value in spec.options.items():
            if KINDS[spec.kind].get(name) == "file":  # data files resolve inside the campaign folder
                assert os.path.commonpath([os.path.realpath(value), os.path.realpath(campaign_copy)]) == os.path.realpath(campaign_copy)
    for figure, limit in campaign.tolerances.items():
        if isinstance(limit, float):
            assert math.isfinite(limit)
    assert campaign.tests and DEG > 0


# ---- what the mutation tests found, kept as plain cases


def test_bad_utf8_in_a_toml_file_names_its_line(tmp_path):
    from axiscal.io import read_toml

    path = tmp_path / "m.toml"
    path.write_bytes(b'a = 1\r\nb = 2\rc = "\xff"\n')
    with pytest.raises(AxiscalError) as info:
        read_toml(path)
    assert info.value.line == 3 and "not UTF-8" in info.value.message


def test_toml_cut_short_names_the_last_line(tmp_path):
    from axiscal.io import read_toml

    path = tmp_path / "m.toml"
    path.write_text("[machine]\nname = \"x\"\nserial_\n")
    with pytest.raises(AxiscalError) as info:
        read_toml(path)
    assert info.value.line == 3 and "malformed TOML" in info.value.message


def test_a_table_made_only_by_its_sub_tables_has_the_line_of_the_first():
    from axiscal.io.schema import TomlLines

    assert TomlLines('x = 1\n[instrumen.t]\nname = "y"\n').of("instrumen") == 2


@pytest.mark.parametrize("cell", ["1_0", "\uff11", "0x1", "1e0", "2.5"])
def test_run_numbers_are_ascii_whole_numbers(tmp_path, examples, cell):
    lines = (examples / "positioning_run.csv").read_text().splitlines()
    lines[1] = lines[1].replace(",1,", f",{cell},", 1)
    path = tmp_path / "run.csv"
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    with pytest.raises(AxiscalError) as info:
        read_positioning_run(path)
    assert info.value.line == 2 and "run number" in info.value.message


@pytest.mark.parametrize("edit, words", [
    (('kind = "positioning"', "kind = []"), "unknown kind '[]'"),
    (("[machine]", "[uncertainty]\nserial = 3\n[machine]"), "unknown key 'serial' in [uncertainty]"),
    (("[campaign]", "kind = 1\n[campaign]"), "unknown key 'kind' (known: campaign"),
])
def test_campaign_refusals_found_by_mutation(tmp_path, examples, edit, words):
    folder = tmp_path / "campaign"
    shutil.copytree(examples / "campaign", folder)
    path = folder / "campaign.toml"
    text = path.read_text()
    assert edit[0] in text
    path.write_text(text.replace(edit[0], edit[1], 1))
    with pytest.raises(AxiscalError) as info:
        load_campaign(folder)
    assert words in info.value.message and info.value.path == str(path)
    changed = path.read_text().splitlines()
    assert isinstance(info.value.line, int)
    named = changed[info.value.line - 1]
    assert named.split("=")[0].strip() in edit[1] or named.strip("[] ") in edit[1]


# ---- the other readers: instrument imports, sensor frames and calibration, error tables, laser readings


def pandas_columns(raw: bytes, names) -> dict[str, np.ndarray]:
    """Numeric columns of a comma CSV as pandas reads it (comment and blank lines, blanks included, skipped)."""
    import pandas as pd

    header, rows = plain_rows(raw)
    frame = pd.read_csv(io.StringIO("\n".join([",".join(header)] + [",".join(r) for r in rows])), dtype=str)
    # cells are stripped of what Python calls white space (the file grammar does the same)
    return {n: np.array([float(v.strip()) for v in frame[n]]) for n in names}


def _frames(path):
    from axiscal.measurement.offline import read_frames

    return read_frames(path, ("x_cmd_mm", "x_scale_mm", "x_psd_y_um"))


def _error_table(path):
    from axiscal.model.tables import read_error_table

    return read_error_table(path, "X")


def _laser(path):
    from axiscal.model.inputs import read_interferometer

    return read_interferometer(path)


def frames_reference(raw: bytes) -> dict[str, np.ndarray]:
    """Raw frames as their rule says: a cell that is not a number (by the file grammar) is a missing reading."""
    from axiscal.io.tabular import parse_number

    header, rows = plain_rows(raw)
    out = {}
    for name in ("t_s", "x_cmd_mm", "x_scale_mm", "x_psd_y_um"):
        k = header.index(name)
        values = [parse_number(row[k]) if k < len(row) else None for row in rows]
        out[name] = np.array([np.nan if v is None else v for v in values])
    return out


CSV_READERS = {  # name: (example, reader, lines kept, check of a parse against a reference)
    "frames": ("xz_module/sensors_frames.csv", _frames, 40,
               lambda got, raw: [np.testing.assert_array_equal(got[k], want) for k, want in frames_reference(raw).items()]),
    "error table": ("xfyz_machine/x_errors.csv", _error_table, 30,
                    lambda got, raw: np.testing.assert_allclose(
                        got.position_m / MM, pandas_columns(raw, ["position_mm"])["position_mm"], rtol=1e-15)),
    "laser readings": ("xz_module/diagonal_laser.csv", _laser, 30,
                       lambda got, raw: np.testing.assert_allclose(
                           np.asarray(got) / MM, pandas_columns(raw, ["measured_mm"])["measured_mm"], rtol=1e-15, atol=1e-15)),
}


@SETTINGS
@pytest.mark.parametrize("name", sorted(CSV_READERS))
@given(data=st.data())
def test_mutated_files_of_the_other_csv_readers(tmp_path, examples, name, data):
    example, reader, keep, check = CSV_READERS[name]
    lines = (examples / example).read_text(encoding="utf-8").splitlines()[:keep]
    text = "\n".join(lines) + "\n"
    raw = mutate(text, data.draw(mutations(len(lines), len(lines[0].split(",")))))
    path = tmp_path / "f.csv"
    path.write_bytes(raw)
    result = read_or_refused(reader, path, raw)
    if result is REFUSED:
        return
    check(result, raw)


@SETTINGS
@given(data=st.data())
def test_mutated_rtx_captures(tmp_path, examples, data):
    from axiscal.io.importers.rtx import read_rtx

    blob = bytearray((examples / "imports" / "capture.rtx").read_bytes())
    for _ in range(data.draw(st.integers(1, 3))):
        at = data.draw(st.integers(0, len(blob)))
        kind = data.draw(st.sampled_from(["flip", "truncate", "insert"]))
        if kind == "flip" and at < len(blob):
            blob[at] ^= data.draw(st.integers(1, 255))
        elif kind == "truncate":
            del blob[at:]
        else:
            blob[at:at] = data.draw(st.sampled_from(BYTES + [b"Sample no: 1_0\r\n", b"Sample rate: inf\r\n", b"::\r\n"]))
    path = tmp_path / "c.rtx"
    path.write_bytes(bytes(blob))
    try:
        capture = run(lambda p: read_rtx(p, unit="um"), path)
    except AxiscalError as exc:
        assert exc.path == str(path) and isinstance(exc.line, int) and exc.line >= 1, str(exc)
        event("refused")
        return
    event("read")
    assert np.isfinite(capture.samples_m).all() and capture.sample_rate_hz > 0


@SETTINGS
@pytest.mark.parametrize("which", ["map", "data"])
@given(data=st.data())
def test_mutated_column_maps_and_exports(tmp_path, examples, which, data):
    from axiscal.io.importers.readings import import_readings

    folder = examples / "imports"
    map_text = (folder / "reading_per_row.toml").read_text(encoding="utf-8")
    data_text = (folder / "reading_per_row.txt").read_text(encoding="utf-8")
    if which == "map":
        map_bytes = mutate_toml(map_text, data.draw(toml_mutations(len(map_text.splitlines()))))
        data_bytes = data_text.encode()
    else:
        map_bytes = map_text.encode()
        tabbed = data_text.replace("\t", ",")  # mutate cells, then restore the tab delimiter
        steps = data.draw(mutations(len(tabbed.splitlines()), 4))
        data_bytes = mutate(tabbed, steps).replace(b",", b"\t")
    map_path, data_path = tmp_path / "map.toml", tmp_path / "export.txt"
    map_path.write_bytes(map_bytes)
    data_path.write_bytes(data_bytes)
    try:
        readings = run(lambda p: import_readings(map_path, p), data_path)
    except AxiscalError as exc:
        named = map_path if exc.path == str(map_path) else data_path
        located(exc, named, physical_line_count(map_bytes if named == map_path else data_bytes))
        event("refused")
        return
    event("read")
    assert np.isfinite(readings.deviations_m).all() and np.isfinite(readings.targets_m).all()


@SETTINGS
@given(data=st.data())
def test_mutated_sensor_calibrations(tmp_path, examples, data):
    from axiscal.instruments.calibration import load_calibration

    text = (examples / "xz_module" / "sensors_calibration.json").read_text(encoding="utf-8")
    lines = text.splitlines()
    steps = data.draw(st.lists(st.tuples(st.sampled_from(["value", "drop_line", "duplicate_line", "bytes"]),
                                         st.integers(0, len(lines)),
                                         st.sampled_from(['"x"', "true", "null", "[]", "{}", "-1", "1e999", "NaN",
                                                          "0", "1e12", '"1_0"', "[1, 2]"]),
                                         st.sampled_from(BYTES), st.floats(0.0, 1.0)), min_size=1, max_size=3))
    for kind, row, value, chunk, where in steps:
        k = row % len(lines)
        if kind == "value" and ":" in lines[k]:
            key, _, rest = lines[k].partition(":")
            lines[k] = key + ": " + value + ("," if rest.rstrip().endswith(",") else "")
        elif kind == "drop_line":
            del lines[k]
        elif kind == "duplicate_line":
            lines.insert(k, lines[k])
        elif kind == "bytes":
            joined = "\n".join(lines)
            at = int(where * len(joined))
            lines = (joined[:at] + chunk.decode("utf-8", "replace") + joined[at:]).split("\n")
    raw = ("\n".join(lines) + "\n").encode("utf-8")
    path = tmp_path / "cal.json"
    path.write_bytes(raw)
    calibration = read_or_refused(load_calibration, path, raw)
    if calibration is REFUSED:
        return
    assert calibration is not None


@pytest.mark.parametrize("entry, words", [(b"Sample no: inf", "not a whole number"), (b"Sample no: 1_0", "not a whole number"),
                                          (b"Actual sample rate: 1_000", "not a positive number")])
def test_rtx_header_numbers_follow_the_file_grammar_and_name_their_line(tmp_path, examples, entry, words):
    from axiscal.io.importers.rtx import read_rtx

    blob = (examples / "imports" / "capture.rtx").read_bytes()
    key = entry.split(b":")[0]
    lines = blob.split(b"\r\n")
    k = next(i for i, line in enumerate(lines) if line.startswith(key + b":"))
    lines[k] = entry
    path = tmp_path / "c.rtx"
    path.write_bytes(b"\r\n".join(lines))
    with pytest.raises(AxiscalError) as info:
        read_rtx(path, unit="um")
    assert words in info.value.message and info.value.line == k + 1


def test_column_map_errors_name_the_key_line(tmp_path, examples):
    from axiscal.io.importers.columnmap import read_column_map

    text = (examples / "imports" / "reading_per_row.toml").read_text()
    for old, new, words in [('target = "in"', 'target = "furlong"', "[units] target must be one of"), ("sign = -1", "sign = 2", "sign"),
                            ('layout = "rows"', 'layout = "rows"\nspeed = 3', "unknown key 'speed'")]:
        path = tmp_path / "map.toml"
        changed = text.replace(old, new, 1)
        path.write_text(changed)
        with pytest.raises(AxiscalError) as info:
            read_column_map(path)
        assert words in info.value.message
        named = changed.splitlines()[info.value.line - 1]
        assert new.splitlines()[-1] == named.split("#")[0].strip() or new.splitlines()[-1] in named


def test_sensor_calibration_errors_name_the_key_line(tmp_path, examples):
    from axiscal.instruments.calibration import load_calibration

    text = (examples / "xz_module" / "sensors_calibration.json").read_text()
    path = tmp_path / "cal.json"
    first_gain = text.index('"gain"')
    changed = text[:first_gain] + '"gain": "x",' + text[text.index("\n", first_gain):]
    path.write_text(changed)
    with pytest.raises(AxiscalError) as info:
        load_calibration(path)
    assert "'gain' must be a finite number" in info.value.message
    assert '"gain": "x"' in changed.splitlines()[info.value.line - 1]
