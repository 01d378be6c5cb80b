"""Reading positioning runs of linear and rotary axes from CSV, with errors that name the file and the line.

The data of an ISO 230-2 test: target P_i, run j, direction and the deviation x_ij = P_ij - P_i.

Columns (see docs/positioning.md): ``target_<unit>``, ``run`` (a whole number), ``direction``
(``+``/``-`` or ``up``/``down``) and exactly one of ``deviation_<unit>`` (actual - target) or
``actual_<unit>`` (position reached). Length units are nm, um, mm or in (a linear axis); a target
in deg with the deviation in deg, arcmin or arcsec is a rotary axis (ISO 230-2, rotary axes), whose
targets are taken round the circle: 0 and 360 deg are the same target. Rows may come in any order
(runs interleaved); a test may go in both directions or in one. A row whose target and value cells are both empty is
a move without a reading (the overrun moves of a plan written by :func:`axiscal.positioning.plan.write_plan`)
and is passed over, so a plan with its readings typed in is a run file as it is. When the environment columns ``air_temperature_c``,
``pressure_pa`` and ``humidity_pct`` (and optionally ``material_temperature_c``) are present,
``actual_<unit>`` is a raw laser reading computed with the vacuum wavelength (``deviation_<unit>``
is then the raw reading less the target, as ``axiscal capture`` writes it); it is compensated
with :func:`axiscal.instruments.interferometer.compensated_length` (paper 003 eq 1, ISO 1 normalisation to
20 degC) before the deviations are formed. Several material sensors (``material_temperature_1_c``,
``material_temperature_2_c``, ...: every column named ``material_temperature*_c``) are averaged.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_choice, check_number, check_optional_number
from axiscal.io.tabular import CsvTable, read_csv
from axiscal.instruments.air import METHODS
from axiscal.materials import STEEL_EXPANSION_PER_K
from axiscal.positioning.evaluation import PositioningRun, covers_circle
from axiscal.units import ANGLE_UNITS, DEG, INCH, LENGTH_UNITS

__all__ = [
    "DIRECTIONS",
    "ENVIRONMENT_REQUIRED",
    "ALLOWED_UNITS",
    "ANGLE_TARGET_UNITS",
    "ANGLE_DEVIATION_UNITS",
    "RunFile",
    "read_positioning_run",
]

DIRECTIONS = {"+": "+", "up": "+", "-": "-", "down": "-"}
_RUN_NUMBER = re.compile(r"\+?[0-9]+(?:\.0*)?")
ENVIRONMENT_REQUIRED = ("air_temperature_c", "pressure_pa", "humidity_pct")
#: length units of the columns of a linear axis, and metres per unit
ALLOWED_UNITS = ("nm", "um", "mm", "in")
#: angle unit of the targets of a rotary axis
ANGLE_TARGET_UNITS = ("deg",)
#: angle units of the deviations (or positions reached) of a rotary axis
ANGLE_DEVIATION_UNITS = ("deg", "arcmin", "arcsec")
_FACTORS = {**{u: LENGTH_UNITS[u] for u in ("nm", "um", "mm")}, "in": INCH,
            **{u: ANGLE_UNITS[u] for u in ANGLE_DEVIATION_UNITS}}
_ALL_UNITS = ALLOWED_UNITS + ANGLE_DEVIATION_UNITS
#: one revolution, degrees (the unit of rotary targets in files)
_TURN_DEG = 360.0


@dataclass(frozen=True)
class RunFile:
    """A positioning run read from a file.

    Attributes
    ----------
    run : PositioningRun
        Deviations per target, metres (radians for a rotary axis).
    compensated : bool
        True when the file held raw laser readings that were compensated for the air (and the
        material temperature, if given).
    run_labels : tuple of str
        The ``run`` numbers in column order of the deviation arrays.
    warnings : tuple of str
        What the reader should know about the file (a rotary test that does not cover the
        circle, readings at 360 deg taken as those at 0 deg).
    compensation : str
        What was applied to raw laser readings, in words ("" when nothing was): the air index
        always, the normalisation to 20 degC only when the file gave a material temperature.

    Examples
    --------
    >>> data = read_positioning_run("examples/positioning_run.csv")  # doctest: +SKIP
    >>> data.run.targets.shape, data.compensated, data.run_labels  # doctest: +SKIP
    ((17,), False, ('1', '2', '3', '4', '5'))
    """

    run: PositioningRun
    compensated: bool
    run_labels: tuple[str, ...]
    warnings: tuple[str, ...] = ()
    compensation: str = ""


def _compensation_text(material_sensors: int, *, method: str = "ciddor") -> str:
    """What the compensation of raw laser readings applied, as reports and plots say it.

    Parameters
    ----------
    material_sensors : int
        How many material temperature columns the file gave (0: none).
    method : str, keyword-only
        The refractive-index equation (:func:`axiscal.instruments.air.refractive_index`).

    Returns
    -------
    str

    Examples
    --------
    >>> _compensation_text(0)
    'raw laser readings compensated for the air index (ciddor); no material temperature: not normalised to 20 degC'
    >>> _compensation_text(2)
    'raw laser readings compensated for the air index (ciddor) and normalised to 20 degC (material temperature, 2 sensors)'
    """
    air = f"raw laser readings compensated for the air index ({method})"
    if material_sensors <= 0:
        return f"{air}; no material temperature: not normalised to 20 degC"
    sensors = "1 sensor" if material_sensors == 1 else f"{material_sensors} sensors"
    return f"{air} and normalised to 20 degC (material temperature, {sensors})"


def _unit_column(table: CsvTable, stem: str) -> list[tuple[str, float]]:
    found = []
    for name in table.header:
        head, sep, unit = name.rpartition("_")
        if sep and head == stem:
            if unit not in _ALL_UNITS:
                raise AxiscalError(
                    f"column '{name}': unknown unit '{unit}'; use a length ({', '.join(ALLOWED_UNITS)}) or, for a"
                    f" rotary axis, an angle ({', '.join(ANGLE_DEVIATION_UNITS)})",
                    path=table.path,
                    line=table.header_line,
                )
            found.append((name, _FACTORS[unit]))
    return found


def _one_column(table: CsvTable, stems: tuple[str, ...], what: str) -> tuple[str, str, float]:
    found = [(stem, name, factor) for stem in stems for name, factor in _unit_column(table, stem)]
    if not found:
        wanted = " or ".join(f"{stem}_<unit>" for stem in stems)
        raise AxiscalError(
            f"no {what} column: expected {wanted} with unit {', '.join(ALLOWED_UNITS)} or, for a rotary axis,"
            f" {', '.join(ANGLE_DEVIATION_UNITS)} (columns are: {', '.join(table.header)})",
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
    """Read a positioning test (linear or rotary axis, one direction or both) from CSV.

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
        The deviations in metres (radians for a rotary axis), whether they were compensated,
        the run numbers and the warnings about the file.

    Raises
    ------
    AxiscalError
        Naming the file and line: a missing or ambiguous column (two deviation columns in
        different units, deviation and actual both given, a length target with an angle
        deviation), a missing or unknown direction, a run number that is not a whole number, a
        repeated (target, run, direction) however the target is spelled (for a rotary axis: two
        targets at the same place of the circle other than 0 and 360 deg), a target measured in
        one direction only where others have both, a run missing at some target, a non-numeric
        or non-finite cell, environment columns given only in part, or a row with a target but
        no reading (or a reading but no target).

    Examples
    --------
    >>> data = read_positioning_run("examples/laser_raw_run.csv")  # doctest: +SKIP
    >>> data.compensated, data.run.runs  # doctest: +SKIP
    (True, 5)
    """
    check_optional_number("wavelength_nm", wavelength_nm, positive=True)
    check_number("co2_ppm", co2_ppm, nonnegative=True)
    check_number("expansion_per_k", expansion_per_k)
    check_choice("method", method, METHODS)
    table = read_csv(path, min_rows=2)
    table.require("run", "direction")
    target_name, target_factor = _one_column(table, ("target",), "target position")[1:]
    stem, value_name, value_factor = _one_column(table, ("deviation", "actual"), "deviation or actual position")
    target_unit, value_unit = target_name.rpartition("_")[2], value_name.rpartition("_")[2]
    rotary = target_unit in ANGLE_TARGET_UNITS
    if rotary != (value_unit in ANGLE_DEVIATION_UNITS) or (target_unit in ANGLE_DEVIATION_UNITS and not rotary):
        raise AxiscalError(
            f"columns {target_name} and {value_name}: a linear axis gives both in lengths ({', '.join(ALLOWED_UNITS)}),"
            f" a rotary axis its targets in {', '.join(ANGLE_TARGET_UNITS)} and its deviations in"
            f" {', '.join(ANGLE_DEVIATION_UNITS)}",
            path=table.path,
            line=table.header_line,
        )
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
        if rotary:
            raise AxiscalError(
                f"environment columns compensate raw laser readings of a length: give actual_<unit> or"
                f" deviation_<unit> in {', '.join(ALLOWED_UNITS)} (of the raw reading), not '{value_name}'",
                path=table.path,
                line=table.header_line,
            )

    header_line = table.header_line
    table = _readings_only(table, target_name, value_name)
    targets_m = table.numeric(target_name) * target_factor
    values_m = table.numeric(value_name) * value_factor
    if compensate:
        from axiscal.instruments.interferometer import compensated_length

        if stem == "deviation":  # the deviation of the raw reading: the raw reading is target + deviation
            values_m = targets_m + values_m
            stem = "actual"
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

    runs = [_run_number(text, table, k) for k, text in enumerate(table.text("run"))]
    directions = [_direction(text, table, k) for k, text in enumerate(table.text("direction"))]
    notes: list[str] = []
    if rotary:
        targets_m, closure = _fold_circle(table, target_name, targets_m, runs, directions, deviations_m)
        keep = [k for k in range(len(table)) if k not in closure]
        if closure:
            worst = max(abs(deviations_m[k] - deviations_m[j]) for k, j in closure.items()) / ANGLE_UNITS["arcsec"]
            notes.append(
                f"0 and 360 deg are the same target: the readings at 360 deg are taken as those at 0 deg and left"
                f" out (they differ from the readings at 0 deg by up to {worst:.2f} arcsec)"
            )
    else:
        keep = list(range(len(table)))

    cells: dict[tuple[float, str, str], float] = {}
    first_line: dict[tuple[float, str, str], int] = {}
    first_text: dict[tuple[float, str, str], str] = {}
    target_line: dict[float, int] = {}
    target_texts = table.text(target_name)
    for k in keep:
        key = (float(targets_m[k]), runs[k], directions[k])
        if key in cells:
            spelled = (
                f" (written '{target_texts[k]}' here and '{first_text[key]}' there)"
                if target_texts[k] != first_text[key] else ""
            )
            raise AxiscalError(
                f"target {target_texts[k]}, run {runs[k]}, direction {directions[k]} appears twice"
                f" (first on line {first_line[key]}){spelled}",
                path=table.path,
                line=table.lines[k],
            )
        cells[key] = float(deviations_m[k])
        first_line[key] = table.lines[k]
        first_text[key] = target_texts[k]
        target_line.setdefault(key[0], table.lines[k])

    targets = sorted(target_line)
    run_labels = sorted(set(runs), key=int)
    expected = set(run_labels)
    tested = sorted({d for _, _, d in cells}, reverse=True)  # "+" before "-"
    runs_at: dict[tuple[float, str], set[str]] = {}
    for t, r, d in cells:
        runs_at.setdefault((t, d), set()).add(r)
    for target in targets:
        label = f"target {target / target_factor:g} {target_unit}"
        for d in tested:
            present = runs_at.get((target, d), set())
            if not present:
                other = "-" if d == "+" else "+"
                raise AxiscalError(
                    f"{label} is measured in the {other} direction only, other targets in both; ISO 230-2 needs both"
                    " directions at every target (or, for a one-direction test, the same direction at every target)",
                    path=table.path,
                    line=target_line[target],
                )
            if present != expected:
                missing = ", ".join(sorted(expected - present, key=int))
                raise AxiscalError(
                    f"unequal run counts: {label}, direction {d} has {len(present)} of {len(expected)} runs"
                    f" (missing run {missing})",
                    path=table.path,
                    line=target_line[target],
                )

    if len(targets) < 2:
        raise AxiscalError("at least 2 target positions are needed", path=table.path, line=header_line)
    arrays = {d: np.array([[cells[(t, r, d)] for r in run_labels] for t in targets]) for d in tested}
    if rotary:
        notes.extend(_coverage_warnings(np.array(targets) / DEG))
    run = PositioningRun(np.array(targets), arrays.get("+"), arrays.get("-"), source=str(path), rotary=rotary)
    applied = _compensation_text(len(material_columns), method=method) if compensate else ""
    return RunFile(run=run, compensated=compensate, run_labels=tuple(run_labels), warnings=tuple(notes),
                   compensation=applied)


def _run_number(text: str, table: CsvTable, k: int) -> str:
    """The run number of row ``k`` as a whole number's digits ("2.0" -> "2"); anything else raises."""
    if not text:
        raise AxiscalError("column 'run': empty run number", path=table.path, line=table.lines[k])
    # ASCII digits only, as a spreadsheet writes them (Python's float() would take "1_0" or full-width digits)
    whole = _RUN_NUMBER.fullmatch(text)
    value = float(text) if whole else math.nan
    if not (math.isfinite(value) and value == int(value) and value >= 0):
        raise AxiscalError(
            f"column 'run': '{text}' is not a run number (a whole number such as 1, 2, 3)",
            path=table.path,
            line=table.lines[k],
        )
    return str(int(value))


def _direction(text: str, table: CsvTable, k: int) -> str:
    """The direction of row ``k``, "+" or "-"; an empty cell or an unknown word raises."""
    if not text:
        raise AxiscalError(
            "column 'direction': missing direction; write +, -, up or down", path=table.path, line=table.lines[k]
        )
    d = DIRECTIONS.get(text.lower())
    if d is None:
        raise AxiscalError(
            f"column 'direction': '{text}' is not a direction; use +, -, up or down", path=table.path, line=table.lines[k]
        )
    return d


def _fold_circle(
    table: CsvTable, target_name: str, targets: np.ndarray, runs: list[str], directions: list[str], deviations: np.ndarray
) -> tuple[np.ndarray, dict[int, int]]:
    """Rotary targets taken round the circle into [0, 360) deg, radians; rows at 360 deg that repeat 0 deg.

    Returns the folded targets and, for every row whose target is a whole turn away from a
    reading of the same run and direction at the start of the circle, that row -> the row it
    repeats. Any other two readings that fall on the same place of the circle raise.
    """
    degrees = np.round(targets / DEG, 9)  # to 1e-9 deg, so that 390 and 30 meet however they were converted
    folded = np.round(np.mod(degrees, _TURN_DEG), 9)
    folded[folded == _TURN_DEG] = 0.0
    texts = table.text(target_name)
    seen: dict[tuple[float, str, str], int] = {}
    closure: dict[int, int] = {}
    order = sorted(range(len(table)), key=lambda k: degrees[k])
    for k in order:
        key = (float(folded[k]), runs[k], directions[k])
        j = seen.get(key)
        if j is None:
            seen[key] = k
        elif folded[k] == 0.0 and not np.isclose(degrees[k], degrees[j], rtol=0.0, atol=1e-9):
            closure[k] = j
        elif not np.isclose(degrees[k], degrees[j], rtol=0.0, atol=1e-9):
            raise AxiscalError(
                f"target {texts[k]} deg is {folded[k]:g} deg on the circle, which run {runs[k]}, direction"
                f" {directions[k]} already measured on line {table.lines[j]}",
                path=table.path,
                line=table.lines[k],
            )
    return folded * DEG, closure


def _coverage_warnings(targets_deg: np.ndarray) -> list[str]:
    """A warning when the targets (degrees, in [0, 360), increasing) leave part of the circle untested (:func:`covers_circle`)."""
    if covers_circle(targets_deg * DEG):
        return []
    return [
        f"the targets cover {targets_deg[0]:g}..{targets_deg[-1]:g} deg, not the full circle: ISO 230-2 tests a"
        " rotary axis over 360 deg, so the figures hold for the arc tested only"
    ]
