"""The campaign folder: ``campaign.toml`` and the data files it names, read and checked once.

A campaign is what a calibration engineer does on one machine on one day: several tests (laser
positioning runs, straightness, separation, squareness, diagonal checks, 6-DOF recordings), the
instrument used, the tolerances agreed with the customer. :func:`load_campaign` turns the folder
into a :class:`Campaign`; every mistake (an unknown key, a wrong type, a missing file, a path that
leaves the folder, a kind with no data) is an :class:`~axiscal.errors.AxiscalError` naming
``campaign.toml`` and the line. The format is documented in docs/campaign.md.
"""

from __future__ import annotations

import datetime as _dt
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_choice, check_count, check_mapping, check_path
from axiscal.io.arguments import check_instance
from axiscal.io.schema import TomlLines
from axiscal.io.tabular import parse_toml, read_text

__all__ = [
    "CAMPAIGN_FILE",
    "KINDS",
    "CONTROLLERS",
    "POSITIONING_TOLERANCE_KEYS",
    "TestSpec",
    "Campaign",
    "load_campaign",
    "TABLE_KEYS",
]

CAMPAIGN_FILE = "campaign.toml"

#: the keys the [campaign], [machine] and [instrument] tables take: key -> (type, required); the
#: report prints every one of them that a campaign states
TABLE_KEYS: dict[str, dict[str, tuple[type, bool]]] = {
    "campaign": {"title": (str, True), "date": (_dt.date, True), "operator": (str, True), "customer": (str, False),
                 "notes": (str, False)},
    "machine": {"name": (str, True), "serial": (str, False), "model": (str, False), "controller": (str, False),
                "compensation": (dict, False)},
    "instrument": {"name": (str, False), "serial": (str, False), "certificate": (str, False),
                   "calibrated": (_dt.date, False), "vacuum_wavelength_nm": (float, False)},
}
CONTROLLERS = ("linuxcnc", "fanuc", "siemens", "heidenhain")
_FIGURES = ("A", "A_up", "A_down", "B", "B_mean", "E", "E_up", "E_down", "M", "R", "R_up", "R_down")
#: figure keys a positioning tolerance may name: um for a linear axis, arcsec for a rotary one
POSITIONING_TOLERANCE_KEYS = tuple(f"{k}_um" for k in _FIGURES) + tuple(f"{k}_arcsec" for k in _FIGURES)
_TOLERANCE_KEYS = {
    "positioning": dict,
    "straightness_um": float,
    "squareness_arcsec": float,
    "diagonal_um": float,
    "circular_deviation_um": float,
    "flatness_um": float,
    "etve_um": float,
    "thermal_drift_um": float,
    "calibration_um": float,
    "calibration_arcsec": float,
    # ISO 10360-2: E0,MPE = min(A + L/K, B), E150,MPE likewise, R0,MPL; ISO 10360-5: the probing MPEs
    "cmm_e0_a_um": float, "cmm_e0_k": float, "cmm_e0_b_um": float,
    "cmm_e150_a_um": float, "cmm_e150_k": float, "cmm_e150_b_um": float, "cmm_r0_um": float,
    "pform_um": float, "psize_um": float, "pform_ms_um": float, "psize_ms_um": float, "ploc_um": float,
    "settling_s": float,
    "overshoot_um": float,
    "periodic_um": float,
}

# option types: "str", "float", "int", "bool", "file", "floats2", ("choice", values)
_COMMON = {"kind": "str", "id": "str", "notes": "str", "tolerances": "table"}
#: per kind: the keys a test may carry, spelled as the options of the command of the same name
KINDS: dict[str, dict[str, Any]] = {
    "positioning": {
        "axis": "axis", "file": "file",
        "standard": ("choice", ("iso230-2:2014", "iso230-2:2006", "iso230-2:1997", "iso230-2:1988", "jis-b6192", "vdi3441")),
        "wavelength_nm": "float", "expansion_per_k": "float",
    },
    "straightness": {
        "axis": "axis", "direction": "axis", "file": "file",
        "reference": ("choice", ("least-squares", "end-points", "minimum-zone")),
    },
    "separation": {
        "axis": "axis", "direction": "axis", "file": "file",
        "method": ("choice", ("stp", "strp", "fstrp", "gtp", "frequency", "combined", "reversal")),
        "spacing_mm": "float", "spacing_bc_mm": "float", "reversed": "file", "two_probe": "bool",
        "min_gain": "float", "periodic": "bool", "calibration_mm": "floats2",
        "reference": ("choice", ("least-squares", "end-points", "minimum-zone")),
    },
    "squareness": {
        "axes": "plane", "plane": "plane", "first": "file", "second": "file",
        "prism_deviation_arcsec": "float",
        "reference": ("choice", ("least-squares", "end-points")),
        "convention": ("choice", ("included-angle", "iso")),
    },
    "diagonal": {
        "from": "str", "to": "str", "steps": "int", "interferometer": "file", "file": "file",
        "measure": ("choice", ("projection", "length")),
    },
    "sixdof": {"file": "file", "machine": "file", "axis": "axis"},
    "ballbar": {"file": "file", "radius_mm": "float", "plane": "plane", "axes": "plane", "feed_mm_min": "float"},
    "levels": {
        "axis": "axis", "direction": "axis", "file": "file", "foot_mm": "float",
        "reference": ("choice", ("least-squares", "end-points", "minimum-zone")),
    },
    "flatness": {"file": "file", "evaluation": ("choice", ("least-squares", "moody"))},
    "thermal_etve": {"file": "file", "max_lag_h": "float"},
    "thermal_drift": {"file": "file"},
    "sensor_calibration": {"file": "file", "machine": "file"},
    "sixdof_diagonal": {"file": "file", "frames": "file", "machine": "file", "from": "str", "to": "str"},
    "cmm_acceptance": {"file": "file", "uncertainty_um": "float", "uncertainty_um_per_m": "float"},
    "cmm_probing": {"file": "file", "diameter_mm": "float", "uncertainty_um": "float"},
    "dynamics": {"axis": "axis", "file": "file", "plan": "file", "channel": "str", "window_ms": "float", "band_um": "float"},
    "periodic": {"axis": "axis", "file": "file", "period_mm": "float"},
    "on_the_fly": {
        "axis": "axis", "file": "file", "plan": "file", "channel": "str", "delay_ms": "float",
        "standard": ("choice", ("iso230-2:2014", "iso230-2:2006", "iso230-2:1997", "iso230-2:1988", "jis-b6192")),
    },
}
#: the kinds held against one tolerance of the campaign's (or their own)
_OWN_TOLERANCE = {"levels": "straightness_um", "flatness": "flatness_um", "thermal_etve": "etve_um",
                  "thermal_drift": "thermal_drift_um", "periodic": "periodic_um"}
#: the data file(s) each kind cannot do without
_REQUIRED = {
    "positioning": ("axis", "file"),
    "straightness": ("axis", "file"),
    "separation": ("file",),
    "squareness": ("first", "second"),
    "diagonal": ("from", "to"),
    "sixdof": ("file",),
    "ballbar": ("file", "radius_mm"),
    "levels": ("axis", "file", "foot_mm"),
    "flatness": ("file",),
    "thermal_etve": ("file",),
    "thermal_drift": ("file",),
    "sensor_calibration": ("file",),
    "sixdof_diagonal": ("file", "frames", "from", "to"),
    "cmm_acceptance": ("file",),
    "cmm_probing": ("file", "diameter_mm"),
    "dynamics": ("file",),
    "periodic": ("axis", "file"),
    "on_the_fly": ("axis", "file", "plan"),
}
#: the tolerances of the CMM kinds (the MPE as the maker states it)
_CMM_TOLERANCES = {
    "cmm_acceptance": ("cmm_e0_a_um", "cmm_e0_k", "cmm_e0_b_um", "cmm_e150_a_um", "cmm_e150_k", "cmm_e150_b_um",
                       "cmm_r0_um"),
    "cmm_probing": ("pform_um", "psize_um", "pform_ms_um", "psize_ms_um", "ploc_um"),
}


@dataclass(frozen=True)
class TestSpec:
    """One ``[[tests]]`` entry, checked: its kind, axis or axes, files (absolute paths) and options.

    Attributes
    ----------
    id : str
        The test's name in the report and in results.json (``id`` key, else ``kind-axis-n``).
    kind : str
        One of :data:`KINDS`.
    axis : str or None
        The moving axis (``"X"``), or for squareness the plane (``"XY"``).
    options : dict
        Every other key, spelled as the command's option (``method``, ``spacing_mm`` ...);
        file options hold absolute paths.
    tolerances : dict
        Limits for this test (merged over the campaign's ``[tolerances]``), figure key -> limit.
    line : int
        The line of ``[[tests]]`` in campaign.toml.

    Raises
    ------
    AxiscalError
        For an empty ``id``, an unknown ``kind``, ``options`` or ``tolerances`` that are not
        mappings, a negative ``line``.
    """

    id: str
    kind: str
    axis: str | None
    options: dict[str, Any]
    tolerances: dict[str, float]
    line: int

    __test__ = False  # not a pytest test class

    def __post_init__(self) -> None:
        if not isinstance(self.id, str) or not self.id:
            raise AxiscalError(f"id must be the test's name (a str), not {self.id!r}")
        check_choice("test kind", self.kind, KINDS)
        if self.axis is not None and not isinstance(self.axis, str):
            raise AxiscalError(f"axis must be an axis letter, a plane or None, not {self.axis!r}")
        check_mapping("options", self.options)
        check_mapping("tolerances", self.tolerances)
        check_count("line", self.line, minimum=0)


@dataclass(frozen=True)
class Campaign:
    """A checked campaign folder.

    Attributes
    ----------
    folder : Path
        The campaign folder (absolute).
    campaign, machine, instrument : dict
        The ``[campaign]``, ``[machine]`` and ``[instrument]`` tables as written (dates as ISO strings).
    tolerances : dict
        The ``[tolerances]`` table.
    tests : tuple of TestSpec
    model : Path or None
        The machine description (``[machine] model``), absolute.
    controller : str or None
        ``[machine] controller``.
    compensation : dict of str to Path, or None
        ``[machine] compensation``: the compensation files the controller had loaded while the
        campaign was measured (axis letter -> file, absolute); the volumetric section draws the
        model of the compensated machine.
    budget : axiscal.uncertainty.Budget or None
        The uncertainty budget (``uncertainty = "budget.toml"`` or an ``[uncertainty]`` table).
    decision_rule : str
        ``"simple"`` (default) or ``"guard-band"`` (ISO 14253-1), from ``[uncertainty] decision_rule``.

    Raises
    ------
    AxiscalError
        For a ``folder`` or ``model`` that is not a Path, tables that are not mappings,
        ``tests`` that are not TestSpecs, an unknown controller or decision rule, a
        ``budget`` that is not a Budget.
    """

    folder: Path
    campaign: dict[str, Any]
    machine: dict[str, Any]
    instrument: dict[str, Any]
    tolerances: dict[str, Any]
    tests: tuple[TestSpec, ...]
    model: Path | None = None
    controller: str | None = None
    budget: Any = None
    decision_rule: str = "simple"
    compensation: dict[str, Path] | None = None

    def __post_init__(self) -> None:
        from axiscal.uncertainty.budget import Budget
        from axiscal.uncertainty.decision import DECISION_RULES

        check_instance("folder", self.folder, Path)
        for name in ("campaign", "machine", "instrument", "tolerances"):
            check_mapping(name, getattr(self, name))
        if not isinstance(self.tests, tuple) or not all(isinstance(t, TestSpec) for t in self.tests):
            raise AxiscalError(f"tests must be a tuple of TestSpec, not {self.tests!r}"[:120])
        if self.model is not None:
            check_instance("model", self.model, Path)
        if self.controller is not None:
            check_choice("controller", self.controller, CONTROLLERS)
        if self.compensation is not None:
            check_mapping("compensation", self.compensation, what="a mapping of axis letters to files")
            for letter, path in self.compensation.items():
                check_instance(f"compensation[{letter!r}]", path, Path)
            if self.controller is None:
                raise AxiscalError("compensation files need the controller that loaded them")
        if self.budget is not None:
            check_instance("budget", self.budget, Budget)
        check_choice("decision rule", self.decision_rule, DECISION_RULES)


def load_campaign(folder: str | Path) -> Campaign:
    """Read and check a campaign folder.

    Parameters
    ----------
    folder : str or Path
        A folder holding ``campaign.toml`` (or the path of that file).

    Returns
    -------
    Campaign

    Raises
    ------
    AxiscalError
        For a missing or malformed campaign.toml, an unknown key, a value of the wrong type, a data
        file that is missing or outside the folder, a kind that has no data; it names
        ``campaign.toml`` and the line.

    Examples
    --------
    >>> campaign = load_campaign("examples/campaign")  # doctest: +SKIP
    >>> [t.id for t in campaign.tests]  # doctest: +SKIP
    ['positioning-X-1', ...]
    """
    folder = check_path("folder", folder)
    path = folder if folder.name == CAMPAIGN_FILE and folder.is_file() else folder / CAMPAIGN_FILE
    folder = path.parent.resolve()
    if not path.parent.is_dir():
        raise AxiscalError("no such campaign folder", path=path.parent)
    text = read_text(path)
    data = parse_toml(text, path=path)
    lines = TomlLines(text)

    def fail(message: str, table: str = "", index: int = 0, key: str | None = None) -> AxiscalError:
        return AxiscalError(message, path=path, line=lines.of(table, index, key))

    known = {"campaign", "machine", "instrument", "tolerances", "tests", "uncertainty"}
    for name in data:
        if name not in known:
            raise AxiscalError(f"unknown table or key '{name}' (known: {', '.join(sorted(known))})", path=path,
                               line=lines.of("", 0, name) or lines.of(name))

    def table(name: str, spec: Mapping[str, tuple[type, bool]]) -> dict[str, Any]:
        value = data.get(name, {})
        if not isinstance(value, dict):
            raise fail(f"'{name}' must be a table [{name}]", "", 0, name)
        for key, item in value.items():
            if key not in spec:
                raise fail(f"unknown key '{key}' in [{name}] (known: {', '.join(spec)})", name, 0, key)
            kind, _ = spec[key]
            if not _is_type(item, kind):
                raise fail(f"[{name}] {key} must be {_type_name(kind)}, not {_show(item)}", name, 0, key)
        for key, (_, required) in spec.items():
            if required and key not in value:
                raise fail(f"[{name}] needs '{key}'", name, 0)
        return {k: (v.isoformat() if isinstance(v, (_dt.date, _dt.datetime)) else v) for k, v in value.items()}

    if "campaign" not in data:
        raise fail("campaign.toml needs a [campaign] table (title, date, operator)")
    campaign = table("campaign", TABLE_KEYS["campaign"])
    if "machine" not in data:
        raise fail("campaign.toml needs a [machine] table (name)")
    machine = table("machine", TABLE_KEYS["machine"])
    instrument = table("instrument", TABLE_KEYS["instrument"])
    tolerances = _tolerances(data.get("tolerances", {}), lambda m, k=None: fail(m, "tolerances", 0, k), "[tolerances]")

    def budget_line(section: str, key: str | None = None) -> int | None:
        if key is not None:
            return lines.of(f"uncertainty.{section}", 0, key) or lines.of("uncertainty", 0, section)
        return lines.of("uncertainty", 0, section) or lines.of(f"uncertainty.{section}") or lines.of("uncertainty")

    budget, rule = _uncertainty(data.get("uncertainty"), folder, path, budget_line,
                                lambda m, k=None: fail(m, "uncertainty", 0, k), lambda m: fail(m, "", 0, "uncertainty"))

    controller = machine.get("controller")
    if controller is not None and controller not in CONTROLLERS:
        raise fail(f"[machine] controller '{controller}' is not one of {', '.join(CONTROLLERS)}", "machine", 0, "controller")
    model = None
    if "model" in machine:
        model = _inside(folder, machine["model"], lambda m: fail(m, "machine", 0, "model"))
    compensation = None
    if "compensation" in machine:
        compensation = _compensation(machine["compensation"], folder, model, controller,
                                     lambda m: fail(m, "machine", 0, "compensation"))

    raw_tests = data.get("tests", [])
    if not isinstance(raw_tests, list) or not all(isinstance(t, dict) for t in raw_tests):
        raise fail("'tests' must be an array of tables [[tests]]", "", 0, "tests")
    if not raw_tests:
        raise fail("the campaign has no [[tests]]")
    tests: list[TestSpec] = []
    counters: dict[str, int] = {}
    for index, raw in enumerate(raw_tests):
        tests.append(_test(raw, index, folder, tolerances, model, counters, fail))
    ids = [t.id for t in tests]
    for index, test_id in enumerate(ids):
        if ids.index(test_id) != index:
            raise fail(f"two tests have the id '{test_id}'", "tests", index, "id")
    return Campaign(folder, campaign, machine, instrument, tolerances, tuple(tests), model, controller,
                    budget=budget, decision_rule=rule, compensation=compensation)


def _compensation(value: dict, folder: Path, model: Path | None, controller: str | None, fail) -> dict[str, Path]:
    """``[machine] compensation`` checked: linear axis letters to files inside the folder, read as the
    controller reads them (a file it would refuse is refused here, naming it)."""
    from axiscal.campaign.volumetric import read_loaded_compensation

    if model is None:
        raise fail("[machine] compensation needs [machine] model: the compensated machine is that model with the"
                   " files loaded")
    if controller is None:
        raise fail("[machine] compensation needs [machine] controller: whose files they are")
    if not value:
        raise fail("[machine] compensation names no file: give { X = \"X.comp\", ... } or leave it out")
    files = {}
    for letter, name in value.items():
        if letter not in ("X", "Y", "Z"):
            raise fail(f"[machine] compensation: '{letter}' is not a linear axis (X, Y or Z)")
        files[letter] = _inside(folder, name, lambda m, k=letter: fail(f"[machine] compensation {k}: {m}"))
    read_loaded_compensation(files, controller)
    return files


def _test(raw, index, folder, campaign_tolerances, model, counters, fail) -> TestSpec:
    def bad(message: str, key: str | None = None) -> AxiscalError:
        return fail(message, "tests", index, key)

    kind = raw.get("kind")
    if kind is None:
        raise bad(f"[[tests]] number {index + 1} needs 'kind' ({' | '.join(KINDS)})")
    if not isinstance(kind, str) or kind not in KINDS:
        raise bad(f"unknown kind {_show(kind)} (kinds: {', '.join(KINDS)})", "kind")
    spec = {**_COMMON, **KINDS[kind]}
    options: dict[str, Any] = {}
    for key, value in raw.items():
        name = key.replace("-", "_")
        if name not in spec:
            allowed = sorted(k for k in spec if k != "kind")
            raise bad(f"unknown key '{key}' for a {kind} test (known: {', '.join(allowed)})", key)
        options[name] = _check_option(name, spec[name], value, folder, lambda m, k=key: bad(m, k))
    for name in _REQUIRED[kind]:
        if name not in options:
            raise bad(f"a {kind} test needs '{name}'")
    if kind == "diagonal":
        if model is None:
            raise bad("a diagonal test needs the machine model: set [machine] model", "kind")
        if "interferometer" in options and "file" in options:
            raise bad("give the laser readings as 'interferometer' or 'file', not both", "file")
        if "file" in options:
            options["interferometer"] = options.pop("file")
    if kind == "sixdof_diagonal":
        from axiscal.model.inputs import parse_point

        for end in ("from", "to"):
            try:
                point = parse_point(options[end], end)
            except AxiscalError as exc:
                raise bad(exc.message, end) from None
            if set(point) - {"X", "Z"}:
                raise bad(f"{end} '{options[end]}': the diagonal of the 6-DOF sensors lies in the XZ plane", end)
    if kind in ("squareness", "ballbar"):
        plane = options.pop("axes", None) or options.pop("plane", None) or "XY"
        options.pop("plane", None)
        options["plane"] = plane
    own = _tolerances(options.pop("tolerances", {}), lambda m, k=None: bad(m, k or "tolerances"), "tolerances of this test")
    merged = _merged_tolerances(kind, campaign_tolerances, own, options.get("axis"))
    axis = options.pop("axis", None) if kind not in ("squareness", "ballbar") else options["plane"]
    options.pop("kind")
    test_id = options.pop("id", None)
    notes = options.pop("notes", None)
    if notes is not None:
        options["notes"] = notes
    if test_id is None:
        stem = f"{kind}-{axis}" if axis else kind
        counters[stem] = counters.get(stem, 0) + 1
        test_id = f"{stem}-{counters[stem]}"
    return TestSpec(test_id, kind, axis, options, merged, fail("", "tests", index).line or 0)


def _uncertainty(value: Any, folder: Path, path: Path, locate, fail, fail_top) -> tuple[Any, str]:
    """The budget and the decision rule: ``uncertainty = "budget.toml"`` or an ``[uncertainty]`` table
    holding the budget's tables and, optionally, ``decision_rule`` and ``budget = "file.toml"``."""
    from axiscal.uncertainty.budget import budget_from_dict, read_budget
    from axiscal.uncertainty.decision import DECISION_RULES

    if value is None:
        return None, "simple"
    if isinstance(value, str):
        return read_budget(_inside(folder, value, fail_top)), "simple"
    if not isinstance(value, dict):
        raise fail_top("uncertainty must be a budget file name or an [uncertainty] table")
    table = dict(value)
    rule = table.pop("decision_rule", "simple")
    if rule not in DECISION_RULES:
        raise fail(f"decision_rule must be one of {', '.join(DECISION_RULES)}, not {_show(rule)}", "decision_rule")
    if "budget" in table:
        name = table.pop("budget")
        if table:
            raise fail("give the budget as budget = \"file.toml\" or as tables here, not both", "budget")
        return read_budget(_inside(folder, name, lambda m: fail(m, "budget"))), rule
    return budget_from_dict(table, source=str(path), locate=locate), rule


def _merged_tolerances(
    kind: str, campaign: Mapping[str, Any], own: Mapping[str, Any], axis: str | None = None
) -> dict[str, float]:
    """The limits that apply to a test of ``kind``: the campaign's, overridden by the test's own.

    Positioning limits are in um for a linear axis (X, Y, Z) and in arcsec for a rotary one (A, B,
    C); the campaign's limits of the other kind do not apply to the axis.
    """
    out: dict[str, float] = {}
    if kind in ("positioning", "on_the_fly"):
        unit = "_arcsec" if axis in ("A", "B", "C") else "_um"
        out.update({k: v for k, v in campaign.get("positioning", {}).items() if k.endswith(unit)})
        out.update(own.get("positioning", {}))
        out.update({k: v for k, v in own.items() if k in POSITIONING_TOLERANCE_KEYS})
    elif kind in ("straightness", "separation"):
        for source in (campaign, own):
            if "straightness_um" in source:
                out["straightness_um"] = source["straightness_um"]
    elif kind == "squareness":
        for source in (campaign, own):
            if "squareness_arcsec" in source:
                out["squareness_arcsec"] = source["squareness_arcsec"]
    elif kind == "diagonal":
        for source in (campaign, own):
            if "diagonal_um" in source:
                out["diagonal_um"] = source["diagonal_um"]
    elif kind == "ballbar":
        for source in (campaign, own):
            if "circular_deviation_um" in source:
                out["circular_deviation_um"] = source["circular_deviation_um"]
    elif kind in _OWN_TOLERANCE:
        for source in (campaign, own):
            if _OWN_TOLERANCE[kind] in source:
                out[_OWN_TOLERANCE[kind]] = source[_OWN_TOLERANCE[kind]]
    elif kind == "sensor_calibration":
        for source in (campaign, own):
            out.update({k: source[k] for k in ("calibration_um", "calibration_arcsec") if k in source})
    elif kind in _CMM_TOLERANCES:
        for source in (campaign, own):
            out.update({k: source[k] for k in _CMM_TOLERANCES[kind] if k in source})
    elif kind == "dynamics":
        for source in (campaign, own):
            out.update({k: source[k] for k in ("settling_s", "overshoot_um") if k in source})
    return {k: float(v) for k, v in out.items()}


def _tolerances(value: Any, fail, where: str) -> dict[str, Any]:
    if not isinstance(value, dict):
        raise fail(f"{where} must be a table", None)
    out: dict[str, Any] = {}
    for key, item in value.items():
        if key in POSITIONING_TOLERANCE_KEYS:
            out[key] = _limit(item, key, fail)
            continue
        if key not in _TOLERANCE_KEYS:
            known = [*_TOLERANCE_KEYS, *POSITIONING_TOLERANCE_KEYS]
            raise fail(f"unknown tolerance '{key}' in {where} (known: {', '.join(known)})", key)
        if key == "positioning":
            if not isinstance(item, dict):
                raise fail(f"{where} positioning must be a table such as {{ A_um = 12.0 }}", key)
            for name, limit in item.items():
                if name not in POSITIONING_TOLERANCE_KEYS:
                    raise fail(
                        f"unknown positioning tolerance '{name}' (known: {', '.join(POSITIONING_TOLERANCE_KEYS)})", key
                    )
            out[key] = {name: _limit(limit, name, fail, key) for name, limit in item.items()}
        else:
            out[key] = _limit(item, key, fail)
    return out


def _limit(value: Any, name: str, fail, key: str | None = None) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not (value > 0) or value == float("inf"):
        raise fail(f"tolerance {name} must be a positive number, not {_show(value)}", key or name)
    return float(value)


def _check_option(name: str, kind: Any, value: Any, folder: Path, fail) -> Any:
    if kind == "table":
        return value
    if isinstance(kind, tuple):
        if not isinstance(value, str) or value not in kind[1]:
            raise fail(f"{name} must be one of {', '.join(kind[1])}, not {_show(value)}")
        return value
    if kind in ("str", "axis", "plane"):
        if not isinstance(value, str) or not value.strip():
            raise fail(f"{name} must be a text, not {_show(value)}")
        if kind == "axis" and value.upper() not in ("X", "Y", "Z", "A", "B", "C"):
            raise fail(f"{name} must be an axis letter (X, Y, Z, A, B, C), not {_show(value)}")
        if kind == "plane" and value.upper() not in ("XY", "XZ", "YZ"):
            raise fail(f"{name} must be a plane XY, XZ or YZ, not {_show(value)}")
        return value.upper() if kind in ("axis", "plane") else value
    if kind == "float":
        if isinstance(value, bool) or not isinstance(value, (int, float)) or value != value or abs(value) == float("inf"):
            raise fail(f"{name} must be a finite number, not {_show(value)}")
        return float(value)
    if kind == "int":
        if isinstance(value, bool) or not isinstance(value, int) or value < 1:
            raise fail(f"{name} must be a positive whole number, not {_show(value)}")
        return value
    if kind == "bool":
        if not isinstance(value, bool):
            raise fail(f"{name} must be true or false, not {_show(value)}")
        return value
    if kind == "floats2":
        if (not isinstance(value, list) or len(value) != 2
                or not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in value)):
            raise fail(f"{name} must be two numbers [START, END], not {_show(value)}")
        return [float(v) for v in value]
    if kind == "file":
        if not isinstance(value, str):
            raise fail(f"{name} must be a file name, not {_show(value)}")
        return _inside(folder, value, fail)
    raise AssertionError(kind)


def _inside(folder: Path, name: str, fail) -> Path:
    """The file ``name`` relative to the campaign folder; it must exist and stay inside the folder."""
    if not isinstance(name, str) or not name.strip():
        raise fail(f"a file name is needed, not {_show(name)}")
    candidate = Path(name)
    if candidate.is_absolute():
        raise fail(f"'{name}' is an absolute path: data files are named relative to the campaign folder")
    resolved = (folder / candidate).resolve()
    if not resolved.is_relative_to(folder):
        raise fail(f"'{name}' leaves the campaign folder")
    if not resolved.is_file():
        raise fail(f"data file '{name}' not found in the campaign folder")
    return resolved


def _is_type(value: Any, kind: type) -> bool:
    if kind is float:
        return isinstance(value, (int, float)) and not isinstance(value, bool)
    if kind is _dt.date:
        return isinstance(value, _dt.date)
    return isinstance(value, kind)


def _type_name(kind: type) -> str:
    return {str: "a text", float: "a number", _dt.date: "a date (2026-11-20)", dict: "a table"}.get(kind, kind.__name__)


def _show(value: Any) -> str:
    text = repr(value)
    return text if len(text) <= 40 else text[:37] + "..."
