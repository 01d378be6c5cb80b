"""Artefact files in, the identified machine folder out: the TOML and CSV formats of docs/identification.md.

An artefact file (TOML) names its ``kind`` and its data CSV (``measured``) beside it; lengths are in
mm, readings in um, directions unit vectors. What is written is a machine folder that
:func:`axiscal.load_machine` (and so ``axiscal volumetric``, ``compensate`` and a campaign) reads
unchanged, plus ``identify.json`` and ``identify.html``.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from axiscal.conventions import AXIS_INDEX, ROTARY_LETTERS
from axiscal.errors import AxiscalError
from axiscal.identification.artefacts import (
    ARTEFACT_KINDS,
    Artefact,
    BallbarNetwork,
    BallPlate,
    Multilateration,
    RTest,
    StepGauge,
)
from axiscal.io.arguments import check_path
from axiscal.io.atomic import write_text
from axiscal.io.formats.artefact import ARTEFACT_MODELS
from axiscal.io.formats.base import validate_data
from axiscal.io.schema import TomlLines, confined_path
from axiscal.io.tabular import CsvTable, parse_toml, read_csv, read_checked_text, write_csv
from axiscal.units import ANGLE_UNITS, MM, UM

__all__ = ["read_artefact", "write_artefact", "ARTEFACT_KEYS"]

_URAD = ANGLE_UNITS["urad"]
_DEG = ANGLE_UNITS["deg"]
#: the keys of each kind of artefact file (from the declared formats, axiscal.io.formats.artefact)
ARTEFACT_KEYS = {kind: {*model.model_fields} for kind, model in ARTEFACT_MODELS.items()}


class _File:
    """An artefact file being read: its keys, and errors naming its lines."""

    def __init__(self, path: Path):
        self.path = path
        text = read_checked_text(path)  # read once: parsed, validated, its lines kept
        raw = parse_toml(text, path=path)
        self.lines = TomlLines(text)
        kind = raw.get("kind")
        if kind not in ARTEFACT_KINDS:
            raise self.error(f"kind must be one of {', '.join(ARTEFACT_KINDS)}, not {kind!r}", "", "kind")
        checked = validate_data(ARTEFACT_MODELS[kind], raw, path=str(path), lines=self.lines)
        self.data = checked.model_dump(exclude_unset=True)

    def error(self, message: str, section: str = "", key: str | None = None) -> AxiscalError:
        return AxiscalError(message, path=str(self.path), line=self.lines.of(section, key=key))

    def vector(self, value, what: str, section: str = "", key: str | None = None, *, unit: float = MM) -> np.ndarray:
        return np.array(value, dtype=float) * unit

    def direction(self, value, what: str, section: str = "", key: str | None = None) -> np.ndarray:
        v = self.vector(value, what, section, key, unit=1.0)
        norm = float(np.linalg.norm(v))
        if abs(norm - 1.0) > 1e-3:
            raise self.error(f"{what} must be a unit vector (its length is {norm:.6g})", section, key or what)
        return v / norm

    def csv(self, key: str) -> CsvTable:
        name = self.data[key]
        try:
            path = confined_path(self.path.parent, name)
        except AxiscalError as exc:
            raise self.error(exc.message, "", key) from None
        if not path.is_file():
            raise self.error(f"{key}: no file '{name}' beside the artefact file", "", key)
        return read_csv(path)


def _labels(table: CsvTable, column: str) -> list[str]:
    table.require(column)
    return table.text(column)


def _points(table: CsvTable, prefix: str = "") -> np.ndarray:
    names = [f"{prefix}{c}_mm" for c in "xyz"]
    table.require(*names)
    return np.column_stack([table.numeric(n) for n in names]) * MM


def _index(table: CsvTable, column: str, known: list[str], what: str) -> np.ndarray:
    """Row labels of ``column`` as indices into ``known``; an unknown label names its line."""
    where = {label: k for k, label in enumerate(known)}
    out = np.empty(len(table), dtype=int)
    for row, label in enumerate(_labels(table, column)):
        if label not in where:
            raise AxiscalError(f"unknown {what} '{label}' (not in the certificate)", path=table.path, line=table.line_of(row))
        out[row] = where[label]
    return out


def _certificate(table: CsvTable, column: str) -> tuple[list[str], np.ndarray]:
    labels = _labels(table, column)
    seen: dict[str, int] = {}
    for row, label in enumerate(labels):
        if label in seen:
            raise AxiscalError(f"{column} '{label}' given twice", path=table.path, line=table.line_of(row))
        seen[label] = row
    u = table.numeric("U_um") * UM / 2.0 if table.has("U_um") else np.zeros(len(table))
    if np.any(u < 0):
        row = int(np.argmax(u < 0))
        raise AxiscalError("U_um must not be negative", path=table.path, line=table.line_of(row))
    return labels, u


def _ball_plate(f: _File, name: str, tool: np.ndarray) -> BallPlate:
    certificate = f.csv("balls")
    labels, u = _certificate(certificate, "ball")
    certificate.require("x_mm", "y_mm")
    z = certificate.numeric("z_mm") if certificate.has("z_mm") else np.zeros(len(certificate))
    centres = np.column_stack([certificate.numeric("x_mm"), certificate.numeric("y_mm"), z]) * MM
    measured = f.csv("measured")
    ball = _index(measured, "ball", labels, "ball")
    pose = f.data.get("pose", "fit")
    rotation = origin = None
    if pose != "fit":
        origin = f.vector(pose["origin_mm"], "origin_mm", "pose")
        x = f.direction(pose["x_direction"], "x_direction", "pose")
        y = f.direction(pose["y_direction"], "y_direction", "pose")
        if abs(float(x @ y)) > 1e-3:
            raise f.error(f"the pose is not orthonormal: x_direction . y_direction = {float(x @ y):.4g}", "pose", "y_direction")
        y = y - (x @ y) * x
        y /= np.linalg.norm(y)
        rotation = np.column_stack([x, y, np.cross(x, y)])
    return BallPlate(
        name, tool, centres_m=centres, centre_u_m=u, ball=ball, measured_m=_points(measured), rotation=rotation,
        origin_m=origin, data_path=measured.path, lines=tuple(measured.lines), balls=tuple(labels),
    )


def _step_gauge(f: _File, name: str, tool: np.ndarray) -> StepGauge:
    certificate = f.csv("faces")
    labels, u = _certificate(certificate, "face")
    certificate.require("position_mm")
    measured = f.csv("measured")
    line = f.data["line"]
    return StepGauge(
        name, tool, start_m=f.vector(line["start_mm"], "start_mm", "line"), direction=f.direction(line["direction"], "direction", "line"),
        faces_m=certificate.numeric("position_mm") * MM, face_u_m=u, face=_index(measured, "face", labels, "face"),
        measured_m=_points(measured), data_path=measured.path, lines=tuple(measured.lines), face_names=tuple(labels),
    )


def _groups(table: CsvTable, column: str) -> tuple[list[str], np.ndarray]:
    labels = _labels(table, column)
    names = list(dict.fromkeys(labels))
    where = {label: k for k, label in enumerate(names)}
    return names, np.array([where[label] for label in labels], dtype=int)


def _ballbar(f: _File, name: str, tool: np.ndarray) -> BallbarNetwork:
    length = f.data["length_mm"]
    u = f.data.get("length_U_um") or 0.0
    measured = f.csv("measured")
    setups, setup = _groups(measured, "setup")
    centres = _points(measured, "centre_")
    first = np.array([int(np.argmax(setup == s)) for s in range(len(setups))])
    moved = np.flatnonzero(np.linalg.norm(centres - centres[first][setup], axis=1) > 1e-9)
    if moved.size:
        raise AxiscalError("the centre of a setup must be the same on each of its rows", path=measured.path, line=measured.line_of(int(moved[0])))
    if measured.has("length_mm"):
        lengths = measured.numeric("length_mm") * MM
    else:
        measured.require("deviation_um")
        lengths = length * MM + measured.numeric("deviation_um") * UM
    return BallbarNetwork(
        name, tool, setup=setup, centres_m=centres[first], ends_m=_points(measured, "end_"),
        lengths_m=lengths, length_u_m=float(u) * UM / 2.0,
        data_path=measured.path, lines=tuple(measured.lines), setups=tuple(setups),
    )


def _multilateration(f: _File, name: str, tool: np.ndarray) -> Multilateration:
    measured = f.csv("measured")
    stations, station = _groups(measured, "station")
    measured.require("range_mm")
    given = f.data.get("stations")
    positions = None
    if given is not None:
        if set(given) != set(stations):
            raise f.error(f"[stations] must give the approximate position_mm of every station ({', '.join(stations)})", "stations")
        positions = np.array([f.vector(given[s], s, "stations", s) for s in stations])
    return Multilateration(
        name, tool, station=station, targets_m=_points(measured), ranges_m=measured.numeric("range_mm") * MM,
        stations_m=positions, data_path=measured.path, lines=tuple(measured.lines), stations=tuple(stations),
    )


def _r_test(f: _File, name: str, tool: np.ndarray) -> RTest:
    sensors = f.data["sensors"]
    directions = np.array([f.direction(v, "sensors", "", "sensors") for v in sensors])
    measured = f.csv("measured")
    columns = [f"sensor_{k + 1}_um" for k in range(len(directions))]
    measured.require(*columns)
    positions = {}
    for column in measured.header:
        letter, _, unit = column.partition("_")
        if letter in AXIS_INDEX and unit == "mm":
            positions[letter] = measured.numeric(column) * MM
        elif letter in ROTARY_LETTERS and unit == "deg":
            positions[letter] = measured.numeric(column) * _DEG
    ball = f.vector(f.data["ball_on_table_mm"], "ball_on_table_mm") if "ball_on_table_mm" in f.data else None
    return RTest(
        name, tool, axis_positions_m=positions, directions=directions, ball_table_m=ball,
        readings_m=np.column_stack([measured.numeric(c) for c in columns]) * UM, data_path=measured.path, lines=tuple(measured.lines),
    )


_READERS = {"ball_plate": _ball_plate, "step_gauge": _step_gauge, "ballbar_network": _ballbar, "multilateration": _multilateration, "r_test": _r_test}


def read_artefact(path: str | Path) -> Artefact:
    """Read an artefact file (TOML) and its CSVs (docs/identification.md).

    Parameters
    ----------
    path : str or Path
        The artefact file; the CSVs it names are beside it.

    Returns
    -------
    Artefact
        A BallPlate, StepGauge, BallbarNetwork, Multilateration or RTest, in SI units.

    Raises
    ------
    AxiscalError
        An unknown kind or key, a missing file or column, an unknown ball or face, a pose that
        is not orthonormal, a direction that is not a unit vector; naming the file and line.
    """
    path = check_path("path", path)
    f = _File(path)
    kind = f.data["kind"]
    name = f.data.get("name") or path.stem
    tool = f.vector(f.data.get("tool_mm", [0.0, 0.0, 0.0]), "tool_mm")
    return _READERS[kind](f, name.strip(), tool)


def _toml_vector(v: np.ndarray, unit: float = MM) -> str:
    return "[" + ", ".join(f"{x / unit:.9g}" for x in v) + "]"


def write_artefact(artefact: Artefact, path: str | Path) -> Path:
    """Write an artefact as its TOML file and CSVs beside it (the formats :func:`read_artefact` reads).

    Parameters
    ----------
    artefact : Artefact
        Any artefact (e.g. one simulated on a virtual machine).
    path : str or Path
        The TOML file; the CSVs are named after its stem.

    Returns
    -------
    Path
        The TOML file.
    """
    path = check_path("path", path)
    path.parent.mkdir(parents=True, exist_ok=True)
    stem = path.stem
    head = [f'kind = "{artefact.kind}"', f'name = "{artefact.name}"', f"tool_mm = {_toml_vector(artefact.tool_m)}"]
    fmt = "{:.6f}"
    if isinstance(artefact, (BallPlate, StepGauge)):
        plate = isinstance(artefact, BallPlate)
        labels = list(artefact.balls or [str(k + 1) for k in range(len(artefact.centres_m))]) if plate else list(
            artefact.face_names or [str(k + 1) for k in range(len(artefact.faces_m))])
        column = "ball" if plate else "face"
        certificate = {column: labels}
        if plate:
            for c, name in enumerate(("x_mm", "y_mm", "z_mm")):
                certificate[name] = artefact.centres_m[:, c] / MM
            certificate["U_um"] = 2.0 * artefact.centre_u_m / UM
        else:
            certificate["position_mm"] = artefact.faces_m / MM
            certificate["U_um"] = 2.0 * artefact.face_u_m / UM
        index = artefact.ball if plate else artefact.face
        measured = {column: [labels[k] for k in index]}
        for c, name in enumerate(("x_mm", "y_mm", "z_mm")):
            measured[name] = artefact.measured_m[:, c] / MM
        write_csv(path.with_name(f"{stem}_certificate.csv"), certificate, fmt=fmt)
        head.append(f'{"balls" if plate else "faces"} = "{stem}_certificate.csv"')
        if plate:
            if artefact.rotation is None:
                head.append('pose = "fit"')
            else:
                head += ["", "[pose]", f"origin_mm = {_toml_vector(artefact.origin_m)}",
                         f"x_direction = {_toml_vector(artefact.rotation[:, 0], 1.0)}", f"y_direction = {_toml_vector(artefact.rotation[:, 1], 1.0)}"]
        else:
            head += ["", "[line]", f"start_mm = {_toml_vector(artefact.start_m)}", f"direction = {_toml_vector(artefact.direction, 1.0)}"]
    elif isinstance(artefact, BallbarNetwork):
        names = list(artefact.setups or [str(k + 1) for k in range(len(artefact.centres_m))])
        length = float(np.median(artefact.lengths_m))
        measured = {"setup": [names[k] for k in artefact.setup]}
        for c, axis in enumerate("xyz"):
            measured[f"centre_{axis}_mm"] = artefact.centres_m[artefact.setup, c] / MM
        for c, axis in enumerate("xyz"):
            measured[f"end_{axis}_mm"] = artefact.ends_m[:, c] / MM
        measured["deviation_um"] = (artefact.lengths_m - length) / UM
        head += [f"length_mm = {length / MM:.9f}", f"length_U_um = {2.0 * artefact.length_u_m / UM:.6g}"]
    elif isinstance(artefact, Multilateration):
        names = list(artefact.stations or [str(k + 1) for k in range(artefact.size)])
        measured = {"station": [names[k] for k in artefact.station]}
        for c, axis in enumerate("xyz"):
            measured[f"{axis}_mm"] = artefact.targets_m[:, c] / MM
        measured["range_mm"] = artefact.ranges_m / MM
        if artefact.stations_m is not None:
            head += ["", "[stations]"] + [f'"{n}" = {_toml_vector(v)}' for n, v in zip(names, artefact.stations_m)]
    elif isinstance(artefact, RTest):
        measured = {}
        for letter, q in artefact.axis_positions_m.items():
            measured[f"{letter}_{'deg' if letter in ROTARY_LETTERS else 'mm'}"] = q / (_DEG if letter in ROTARY_LETTERS else MM)
        for k in range(artefact.directions.shape[0]):
            measured[f"sensor_{k + 1}_um"] = artefact.readings_m[:, k] / UM
        head.insert(3, "sensors = [" + ", ".join(_toml_vector(d, 1.0) for d in artefact.directions) + "]")
        if artefact.ball_table_m is not None:
            head.insert(3, f"ball_on_table_mm = {_toml_vector(artefact.ball_table_m)}")
    else:
        raise AxiscalError(f"cannot write an artefact of kind {type(artefact).__name__}")
    write_csv(path.with_name(f"{stem}_measured.csv"), measured, fmt=fmt)
    head.insert(3, f'measured = "{stem}_measured.csv"')
    return write_text(path, "\n".join(head) + "\n")
