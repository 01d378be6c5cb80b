"""Column-map importer: wide (one column per run) and long (one row per reading) exports, units, signs, errors."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.errors import AxiscalError
from axiscal.io.importers import (
    INCH,
    POSITIONING_COLUMNS,
    column_map,
    import_readings,
    positioning_csv,
    read_column_map,
    write_positioning_csv,
)
from axiscal.positioning import read_positioning_run
from axiscal.units import MM, UM

TARGETS = [0.0, 100.0, 200.0, 300.0, 400.0]


def wide_export(path, deviations_um, *, delimiter=";", decimal=","):
    """A laser software export: one row per target, forward pass then reverse pass, one column per run."""
    rows = [delimiter.join(["Target (mm)"] + [f"Run {r + 1}" for r in range(deviations_um.shape[0])])]
    sequence = [(t, 0, i) for i, t in enumerate(TARGETS)] + [(t, 1, i) for i, t in reversed(list(enumerate(TARGETS)))]
    for t, d, i in sequence:
        cells = [f"{t:.3f}"] + [f"{deviations_um[r, d, i]:.3f}" for r in range(deviations_um.shape[0])]
        rows.append(delimiter.join(c.replace(".", decimal) for c in cells))
    path.write_text("Laser export v1\nAxis: X\n" + "\n".join(rows) + "\n", encoding="utf-8")
    return path


WIDE_MAP = {
    "layout": "runs",
    "delimiter": ";",
    "decimal": ",",
    "skip_lines": 2,
    "columns": {"target": "Target (mm)", "readings": ["Run 1", "Run 2", "Run 3"], "direction": "infer"},
    "units": {"target": "mm", "reading": "um"},
}


def test_wide_export_round_trip(tmp_path):
    rng = np.random.default_rng(1)
    dev = np.round(rng.normal(0, 3, size=(3, 2, len(TARGETS))), 3)
    export = wide_export(tmp_path / "laser.csv", dev)
    readings = import_readings(column_map(WIDE_MAP), export)
    assert len(readings) == 3 * 2 * len(TARGETS)
    out = write_positioning_csv(readings, tmp_path / "run.csv")
    frame = pd.read_csv(out)
    assert tuple(frame.columns) == POSITIONING_COLUMNS
    run = read_positioning_run(out).run
    np.testing.assert_allclose(run.targets / MM, TARGETS)
    np.testing.assert_allclose(run.deviations_up / UM, dev[:, 0, :].T, atol=1e-9)
    np.testing.assert_allclose(run.deviations_down / UM, dev[:, 1, :].T, atol=1e-9)
    assert (tmp_path / "run.json").exists()


def test_long_export_position_inch_and_sign(tmp_path):
    # one row per reading, positions in inches, the laser counts down as the axis moves up
    lines = ["target_in\treading_in\tcycle\tdir"]
    truth = {}
    for run in ("A", "B"):
        for d, targets in (("F", [0.0, 1.0, 2.0]), ("R", [2.0, 1.0, 0.0])):
            for t in targets:
                dev_in = 0.0001 * (t + 1) * (1 if d == "F" else -1) + (0.00005 if run == "B" else 0.0)
                truth[(t, run, "+" if d == "F" else "-")] = dev_in * INCH
                lines.append(f"{t}\t{-(t + dev_in):.7f}\t{run}\t{d}")
    export = tmp_path / "inch.txt"
    export.write_text("\n".join(lines) + "\n")
    cmap = column_map({
        "layout": "rows", "delimiter": "tab", "reading": "position", "sign": -1,
        "columns": {"target": "target_in", "reading": "reading_in", "run": "cycle", "direction": "dir"},
        "units": {"target": "in", "reading": "in"},
    })
    r = import_readings(cmap, export)
    for k in range(len(r)):
        assert r.deviations_m[k] == pytest.approx(truth[(round(r.targets_m[k] / INCH, 6), r.runs[k], r.directions[k])], abs=1e-12)
    assert set(r.runs) == {"A", "B"}


def test_headerless_whitespace_infers_runs_and_directions(tmp_path):
    seq = [0, 10, 20, 20, 10, 0] * 2
    export = tmp_path / "plain.txt"
    export.write_text("".join(f"{t}   {0.5 * k:.1f}\n" for k, t in enumerate(seq)))
    cmap = column_map({"delimiter": "whitespace", "header": False, "columns": {"target": 1, "reading": 2}})
    r = import_readings(cmap, export)
    assert r.directions == ("+", "+", "+", "-", "-", "-") * 2
    assert r.runs == ("1",) * 6 + ("2",) * 6
    text = positioning_csv(r)
    assert text.splitlines()[0] == "target_mm,run,direction,deviation_um"


def test_unidirectional_fixed_direction(tmp_path):
    export = tmp_path / "uni.csv"
    export.write_text("pos,err\n0,1\n10,2\n20,3\n0,1.5\n10,2.5\n20,3.5\n")
    cmap = column_map({"columns": {"target": "pos", "reading": "err", "direction": "+"}})
    r = import_readings(cmap, export)
    assert set(r.directions) == {"+"} and r.runs == ("1",) * 3 + ("2",) * 3


def test_map_file_read(tmp_path):
    path = tmp_path / "map.toml"
    path.write_text('layout = "rows"\n[columns]\ntarget = "T"\nreading = "E"\n[units]\nreading = "nm"\n')
    cmap = read_column_map(path)
    assert cmap.reading_unit == "nm" and cmap.target_unit == "mm"


@settings(max_examples=30, deadline=None)
@given(st.lists(st.floats(-50, 50, allow_nan=False), min_size=10, max_size=10))
def test_round_trip_property(tmp_path_factory, values):
    dev = np.round(np.array(values).reshape(1, 2, 5), 3)
    folder = tmp_path_factory.mktemp("p")
    export = wide_export(folder / "e.csv", dev, delimiter=",", decimal=".")
    cmap = column_map({**WIDE_MAP, "delimiter": ",", "decimal": ".", "columns": {"target": "Target (mm)", "readings": ["Run 1"]}})
    out = write_positioning_csv(import_readings(cmap, export), folder / "r.csv")
    run = read_positioning_run(out).run
    np.testing.assert_allclose(run.deviations_up[:, 0] / UM, dev[0, 0], atol=1e-9)
    np.testing.assert_allclose(run.deviations_down[:, 0] / UM, dev[0, 1], atol=1e-9)


@pytest.mark.parametrize(
    "settings_, text, message, line",
    [
        ({"columns": {"target": "T", "reading": "X"}}, "T,E\n0,1\n", "reading column 'X'", 1),
        ({"columns": {"target": "T", "reading": "E"}}, "T,E\n0,1\n5,abc\n", "'abc' is not a number", 3),
        ({"columns": {"target": "T", "reading": "E", "direction": "D"}}, "T,E,D\n0,1,sideways\n", "not a direction", 2),
        ({"columns": {"target": "T", "reading": "E", "run": "R", "direction": "D"}}, "T,E,R,D\n0,1,1,+\n0,2,1,+\n",
         "read twice", 3),
        ({"columns": {"target": "T", "reading": "E"}}, "T,E\n", "no readings", 1),
        ({"columns": {"target": "T", "reading": "E"}}, "T,E\n0\n", "column 2 is missing", 2),
        ({"decimal": ",", "delimiter": ";", "columns": {"target": "T", "reading": "E"}}, "T;E\n0;1.5\n", "decimal comma", 2),
    ],
)
def test_bad_files_one_line_error(tmp_path, settings_, text, message, line):
    export = tmp_path / "bad.csv"
    export.write_text(text)
    with pytest.raises(AxiscalError, match=message) as info:
        import_readings(column_map(settings_), export)
    assert info.value.path == str(export) and info.value.line == line
    assert "\n" not in str(info.value)


@pytest.mark.parametrize(
    "settings_, message",
    [
        ({"columns": {"reading": "E"}}, r"\[columns\] needs 'target'"),
        ({"columns": {"target": "T", "reading": "E"}, "units": {"target": "ft"}}, r"\[units\] target must be one of 'nm', 'um', 'mm', 'm' or 'in', not 'ft'"),
        ({"columns": {"target": "T", "reading": "E"}, "colums": {}}, "unknown key 'colums'"),
        ({"layout": "runs", "columns": {"target": "T"}}, "columns.readings"),
        ({"columns": {"target": "T", "reading": "E"}, "sign": 2}, "sign must be 1 or -1"),
        ({"columns": {"target": "T", "reading": "E"}, "decimal": ","}, "decimal comma needs another delimiter"),
        ({"header": False, "columns": {"target": "T", "reading": 2}}, "no header"),
    ],
)
def test_bad_maps(settings_, message):
    with pytest.raises(AxiscalError, match=message):
        column_map(settings_, source="m.toml")


def test_malformed_map_names_its_line(tmp_path):
    path = tmp_path / "map.toml"
    path.write_text('layout = "rows"\n[columns\n')
    with pytest.raises(AxiscalError) as info:
        read_column_map(path)
    assert info.value.line == 2
