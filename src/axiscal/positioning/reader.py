"""Reading bidirectional positioning runs from CSV, with errors that name the file and the line.

The data of an ISO 230-2 test: target P_i, run j, direction and the deviation x_ij = P_ij - P_i.

Columns (see docs/positioning.md): ``target_<unit>``, ``run``, ``direction`` (``+``/``-`` or
``up``/``down``) and exactly one of ``deviation_<unit>`` (actual - target) or ``actual_<unit>``
(position reached). Units are nm, um or mm. A row whose target and value cells are both empty is
a move without a reading (the overrun moves of a plan written by :func:`axiscal.positioning.plan.write_plan`)
and is passed over, so a plan with its readings typed in is a run file as it is. When the environment columns ``air_temperature_c``,
``pressure_pa`` and ``humidity_pct`` (and optionally ``material_temperature_c``) are present,
``actual_<unit>`` is a raw laser reading computed with the vacuum wavelength; it is compensated
with :func:`axiscal.instruments.interferometer.compensated_length` (paper 003 eq 1, ISO 1 normalisation to
20 degC) before the deviations are formed. Several material sensors (``material_temperature_1_c``,
``material_temperature_2_c``, ...: every column named ``material_temperature*_c``) are averaged.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.tabular import CsvTable, read_csv
from axiscal.materials import STEEL_EXPANSION_PER_K
from axiscal.positioning.evaluation import PositioningRun
from axiscal.units import LENGTH_UNITS

__all__ = ["DIRECTIONS", "ENVIRONMENT_REQUIRED", "ALLOWED_UNITS", "RunFile", "read_positioning_run"]

DIRECTIONS = {"+": "+", "up": "+", "-": "-", "down": "-"}
ENVIRONMENT_REQUIRED = ("air_temperature_c", "pressure_pa", "humidity_pct")
ALLOWED_UNITS = ("nm", "um", "mm")


@dataclass(frozen=True)
class RunFile:
    """A positioning run read from a file.

    Attributes
    ----------
    run : PositioningRun
        Deviations per target, metres.
    compensated : bool
        True when the file held raw laser readings that were compensated for the air (and the
        material temperature, if given).
    run_labels : tuple of str
        The ``run`` identifiers in column order of the deviation arrays.

    Examples
    --------
    >>> data = read_positioning_run("examples/positioning_run.csv")  # doctest: +SKIP
    >>> data.run.targets.shape, data.compensated, data.run_labels  # doctest: +SKIP
    ((17,), False, ('1', '2', '3', '4', '5'))
    """

    run: PositioningRun
    compensated: bool
    run_labels: tuple[str, ...]


def _unit_column(table: CsvTable, stem: str) -> list[tuple[str, float]]:
    found = []
    for name in table.header:
        head, sep, unit = name.rpartition("_")
        if sep and head == stem:
            if unit not in ALLOWED_UNITS:
                raise AxiscalError(
                    f"column '{name}': unknown length unit '{unit}'; use one of {', '.join(ALLOWED_UNITS)}",
                    path=table.path,
                    line=table.header_line,
                )
            found.append((name, LENGTH_UNITS[unit]))
    return found


def _one_column(table: CsvTable, stems: tuple[str, ...], what: str) -> tuple[str, str, float]:
    found = [(stem, name, factor) for stem in stems for name, factor in _unit_column(table, stem)]
    if not found:
        wanted = " or ".join(f"{stem}_<unit>" for stem in stems)
        raise AxiscalError(
            f"no {what} column: expected {wanted} with unit nm, um or mm (columns are: {', '.join(table.header)})",
            path=table.path,
            line=table.header_line,
        )
    if len(found) > 1:
        names = ", ".join(name for _, name, _ in found)
        raise AxiscalError(
            f"columns {names} all give the {what} (mixed units or sources); keep exactly one",
            path=table.path,
            line=table.header_line,
        )
    return found[0]


def _readings_only(table: CsvTable, target_name: str, value_name: str) -> CsvTable:
    """The rows that hold a reading: rows with an empty target and an empty value are moves without one.

    A row with only one of the two cells filled is a mistake and raises naming its line.
    """
    targets, values = table.text(target_name), table.text(value_name)
    keep = []
    for k, (target, value) in enumerate(zip(targets, values)):
        if target and value:
            keep.append(k)
        elif target:
            run, direction = table.text("run")[k], table.text("direction")[k]
            raise AxiscalError(
                f"no reading at target {target} (run {run}, direction {direction}): type the {value_name} value"
                f" in, or empty the {target_name} cell of a move without a reading",
                path=table.path,
                line=table.lines[k],
            )
        elif value:
            raise AxiscalError(
                f"a {value_name} value without a target: fill in {target_name}, or empty the value of a move"
                " without a reading",
                path=table.path,
                line=table.lines[k],
            )
    if len(keep) == len(table):
        return table
    return replace(table, rows=tuple(table.rows[k] for k in keep), lines=tuple(table.lines[k] for k in keep))


def _sort_key(label: str) -> tuple[int, float, str]:
    try:
        return (0, float(label), label)
    except ValueError:
        return (1, 0.0, label)


def _first_refused_line(table: CsvTable, readings_m: np.ndarray, environment: dict, settings: dict) -> int | None:
    """Line of the first row whose environment values the compensation refuses (None: not row-specific).

    Only called after the whole-column call failed, so the per-row loop costs nothing on good files.
    """
    from axiscal.instruments.interferometer import compensated_length

    try:  # a refused setting (wavelength, CO2, method) is no row's fault
        compensated_length(0.0, air_temperature_c=20.0, pressure_pa=101325.0, humidity_pct=50.0, **settings)
    except AxiscalError:
        return None
    for k in range(len(table)):
        row = {name: (None if values is None else values[k : k + 1]) for name, values in environment.items()}
        try:
            compensated_length(readings_m[k : k + 1], **row, **settings)
        except AxiscalError:
            return table.lines[k]
    return None


def read_positioning_run(
    path: str | Path,
    *,
    wavelength_nm: float | None = None,
    co2_ppm: float = 450.0,
    expansion_per_k: float = STEEL_EXPANSION_PER_K,
    method: str = "ciddor",
) -> RunFile:
    """Read a bidirectional positioning test from CSV.

    Parameters
    ----------
    path : str or Path
        The CSV file.
    wavelength_nm : float, optional, keyword-only
        Vacuum wavelength of the laser for raw readings, nm (default: that of
        :func:`axiscal.instruments.interferometer.compensated_length`, 632.991 nm).
    co2_ppm : float, keyword-only
        CO2 content of the air, ppm (default 450), for raw readings.
    expansion_per_k : float, keyword-only
        Expansion coefficient of the material, 1/K (default steel, 11.5e-6), for raw readings
        with a material temperature.
    method : str, keyword-only
        Refractive index equation of the air (default ``"ciddor"``), for raw readings.

    Returns
    -------
    RunFile
        The deviations in metres, whether they were compensated and the run labels.

    Raises
    ------
    AxiscalError
        Naming the file and line: a missing or ambiguous column (two deviation columns in
        different units, deviation and actual both given), an unknown direction, a repeated
        (target, run, direction), a target measured in one direction only, a run missing at
        some target, a non-numeric or non-finite cell, environment columns given only in part, or
        a row with a target but no reading (or a reading but no target).

    Examples
    --------
    >>> data = read_positioning_run("examples/laser_raw_run.csv")  # doctest: +SKIP
    >>> data.compensated, data.run.runs  # doctest: +SKIP
    (True, 5)
    """
    table = read_csv(path, min_rows=2)
    table.require("run", "direction")
    target_name, target_factor = _one_column(table, ("target",), "target position")[1:]
    stem, value_name, value_factor = _one_column(table, ("deviation", "actual"), "deviation or actual position")
    material_columns = [c for c in table.header if c.startswith("material_temperature") and c.endswith("_c")]
    env_present = [c for c in ENVIRONMENT_REQUIRED if table.has(c)] + material_columns
    compensate = bool(env_present)
    if compensate:
        missing = [c for c in ENVIRONMENT_REQUIRED if not table.has(c)]
        if missing:
            raise AxiscalError(
                f"environment columns given only in part: missing {', '.join(missing)}"
                f" (raw laser readings need {', '.join(ENVIRONMENT_REQUIRED)})",
                path=table.path,
                line=table.header_line,
            )
        if stem != "actual":
            raise AxiscalError(
                f"environment columns compensate raw laser readings: give actual_<unit> (the raw reading),"
                f" not '{value_name}'",
                path=table.path,
                line=table.header_line,
            )

    header_line = table.header_line
    table = _readings_only(table, target_name, value_name)
    targets_m = table.numeric(target_name) * target_factor
    values_m = table.numeric(value_name) * value_factor
    if compensate:
        from axiscal.instruments.interferometer import compensated_length

        options = {} if wavelength_nm is None else {"wavelength_nm": wavelength_nm}
        environment = {
            "air_temperature_c": table.numeric("air_temperature_c"),
            "pressure_pa": table.numeric("pressure_pa"),
            "humidity_pct": table.numeric("humidity_pct"),
            "material_temperature_c": (
                np.column_stack([table.numeric(c) for c in material_columns]) if material_columns else None
            ),
        }
        settings = {"expansion_per_k": expansion_per_k, "co2_ppm": co2_ppm, "method": method, **options}
        try:
            values_m = compensated_length(values_m, **environment, **settings)
        except AxiscalError as exc:
            raise exc.located(path=table.path, line=_first_refused_line(table, values_m, environment, settings)) from None
    deviations_m = values_m - targets_m if stem == "actual" else values_m

    runs = [r.strip() for r in table.text("run")]
    directions = []
    for k, text in enumerate(table.text("direction")):
        d = DIRECTIONS.get(text.lower())
        if d is None:
            raise AxiscalError(
                f"column 'direction': '{text}' is not a direction; use +, -, up or down", path=table.path, line=table.lines[k]
            )
        if not runs[k]:
            raise AxiscalError("column 'run': empty run identifier", path=table.path, line=table.lines[k])
        directions.append(d)

    cells: dict[tuple[float, str, str], float] = {}
    first_line: dict[tuple[float, str, str], int] = {}
    target_line: dict[float, int] = {}
    for k in range(len(table)):
        key = (float(targets_m[k]), runs[k], directions[k])
        if key in cells:
            raise AxiscalError(
                f"target {targets_m[k] / target_factor:g}, run {runs[k]}, direction {directions[k]} appears twice"
                f" (first on line {first_line[key]})",
                path=table.path,
                line=table.lines[k],
            )
        cells[key] = float(deviations_m[k])
        first_line[key] = table.lines[k]
        target_line.setdefault(key[0], table.lines[k])

    targets = sorted(target_line)
    run_labels = sorted(set(runs), key=_sort_key)
    expected = set(run_labels)
    runs_at: dict[tuple[float, str], set[str]] = {}
    for t, r, d in cells:
        runs_at.setdefault((t, d), set()).add(r)
    for target in targets:
        for d, other in (("+", "-"), ("-", "+")):
            present = runs_at.get((target, d), set())
            label = f"target {target / target_factor:g} {target_name.rpartition('_')[2]}"
            if not present:
                raise AxiscalError(
                    f"{label} is measured in the {other} direction only; ISO 230-2 needs both directions at every target",
                    path=table.path,
                    line=target_line[target],
                )
            if present != expected:
                missing = ", ".join(sorted(expected - present, key=_sort_key))
                raise AxiscalError(
                    f"unequal run counts: {label}, direction {d} has {len(present)} of {len(expected)} runs"
                    f" (missing run {missing})",
                    path=table.path,
                    line=target_line[target],
                )

    up = np.array([[cells[(t, r, "+")] for r in run_labels] for t in targets])
    down = np.array([[cells[(t, r, "-")] for r in run_labels] for t in targets])
    if len(targets) < 2:
        raise AxiscalError("at least 2 target positions are needed", path=table.path, line=header_line)
    run = PositioningRun(np.array(targets), up, down, source=str(path))
    return RunFile(run=run, compensated=compensate, run_labels=tuple(run_labels))
