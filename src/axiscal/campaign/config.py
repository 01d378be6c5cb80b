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
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_path
from axiscal.io.formats.base import read_format
from axiscal.io.formats.campaign import (
    CAMPAIGN_FILE,
    CONTROLLERS,
    KINDS,
    POSITIONING_TOLERANCE_KEYS,
    CampaignFile,
    CampaignTable,
    InstrumentTable,
    MachineTable,
)

__all__ = [
    "CAMPAIGN_FILE",
    "KINDS",
    "CONTROLLERS",
    "POSITIONING_TOLERANCE_KEYS",
    "TestSpec",
    "Campaign",
    "load_campaign",
    "read_campaign",
    "TABLE_KEYS",
]

#: the keys the [campaign], [machine] and [instrument] tables take: key -> (type, required); the
#: report prints every one of them that a campaign states (made from the declared format)
TABLE_KEYS: dict[str, dict[str, tuple[type, bool]]] = {
    name: {key: (_dt.date if key in ("date", "calibrated") else dict if key == "compensation" else float
                 if key.endswith("_nm") else str, field.is_required()) for key, field in model.model_fields.items()}
    for name, model in (("campaign", CampaignTable), ("machine", MachineTable), ("instrument", InstrumentTable))
}
#: the kinds held against one tolerance of the campaign's (or their own)
_OWN_TOLERANCE = {"levels": "straightness_um", "flatness": "flatness_um", "thermal_etve": "etve_um",
                  "thermal_drift": "thermal_drift_um", "periodic": "periodic_um"}
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

    Made by :func:`load_campaign` from the validated file; nothing here is checked again.
    """

    id: str
    kind: str
    axis: str | None
    options: dict[str, Any]
    tolerances: dict[str, float]
    line: int

    __test__ = False  # not a pytest test class


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
    laboratory, certificate : dict
        The ``[laboratory]`` and ``[certificate]`` tables as written (dates as ISO strings); empty
        when the campaign states none (a plain report).
    signatories : tuple of dict
        The ``[[signatory]]`` entries, ``{"name", "role"}``, the first the main signer.

    Made by :func:`load_campaign` (or :func:`read_campaign`) from the validated campaign.toml
    (:class:`axiscal.io.formats.CampaignFile`); nothing here is checked again.
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
    laboratory: dict[str, Any] = field(default_factory=dict)
    certificate: dict[str, Any] = field(default_factory=dict)
    signatories: tuple[dict[str, Any], ...] = ()


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
    return read_campaign(check_path("folder", folder))


def read_campaign(folder: Path) -> Campaign:
    """Read a campaign folder whose path a public entry has already checked.

    :func:`load_campaign` and ``axiscal.report.report_campaign`` check the path they are given
    once and pass it here; this reads campaign.toml once, validates it into
    :class:`axiscal.io.formats.CampaignFile` and resolves what only the folder can tell (data
    files present and inside it, the budget file, the compensation files).

    Parameters
    ----------
    folder : Path
        The campaign folder, or its campaign.toml.

    Returns
    -------
    Campaign

    Raises
    ------
    AxiscalError
        As :func:`load_campaign`.
    """
    path = folder if folder.name == CAMPAIGN_FILE and folder.is_file() else folder / CAMPAIGN_FILE
    folder = path.parent.resolve()
    if not path.parent.is_dir():
        raise AxiscalError("no such campaign folder", path=path.parent)
    checked, lines = read_format(CampaignFile, path)

    def fail(message: str, table: str = "", index: int = 0, key: str | None = None) -> AxiscalError:
        return AxiscalError(message, path=path, line=lines.of(table, index, key))

    campaign = _plain(checked.campaign.given())
    machine = _plain(checked.machine.given())
    instrument = _plain(checked.instrument.given()) if checked.instrument is not None else {}
    tolerances = _tolerance_dict(checked.tolerances)

    def budget_line(section: str, key: str | None = None) -> int | None:
        if key is not None:
            return lines.of(f"uncertainty.{section}", 0, key) or lines.of("uncertainty", 0, section)
        return lines.of("uncertainty", 0, section) or lines.of(f"uncertainty.{section}") or lines.of("uncertainty")

    budget, rule = _uncertainty(checked.uncertainty, folder, path, budget_line,
                                lambda m, k=None: fail(m, "uncertainty", 0, k), lambda m: fail(m, "", 0, "uncertainty"))
    controller = checked.machine.controller
    model = None
    if checked.machine.model is not None:
        model = _inside(folder, checked.machine.model, lambda m: fail(m, "machine", 0, "model"))
    compensation = None
    if checked.machine.compensation is not None:
        compensation = _compensation(checked.machine.compensation, folder, model, controller,
                                     lambda m: fail(m, "machine", 0, "compensation"))
    tests: list[TestSpec] = []
    counters: dict[str, int] = {}
    for index, entry in enumerate(checked.tests):
        tests.append(_test(entry, index, folder, tolerances, model, counters, fail))
    ids = [t.id for t in tests]
    for index, test_id in enumerate(ids):
        if ids.index(test_id) != index:
            raise fail(f"two tests have the id '{test_id}'", "tests", index, "id")
    return Campaign(folder, campaign, machine, instrument, tolerances, tuple(tests), model, controller,
                    budget=budget, decision_rule=rule, compensation=compensation,
                    laboratory=_plain(checked.laboratory.given()) if checked.laboratory is not None else {},
                    certificate=_plain(checked.certificate.given()) if checked.certificate is not None else {},
                    signatories=tuple(_plain(s.given()) for s in checked.signatory or ()))


def _plain(table: Mapping[str, Any]) -> dict[str, Any]:
    """A table as the report prints it: dates as ISO strings."""
    return {k: (v.isoformat() if isinstance(v, (_dt.date, _dt.datetime)) else v) for k, v in table.items()}


def _tolerance_dict(tolerances: Any) -> dict[str, Any]:
    """The validated tolerances as a dict in the file's order (``positioning`` a dict too)."""
    if tolerances is None:
        return {}
    out: dict[str, Any] = {}
    for key, value in tolerances.given().items():
        out[key] = {k: float(v) for k, v in value.given().items()} if key == "positioning" else float(value)
    return out


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


def _test(entry, index, folder, campaign_tolerances, model, counters, fail) -> TestSpec:
    def bad(message: str, key: str | None = None) -> AxiscalError:
        return fail(message, "tests", index, key)

    kind = entry.kind
    spec = KINDS[kind]
    options: dict[str, Any] = {}
    for key, value in entry.given().items():
        name = key.replace("-", "_")
        if name in ("kind", "tolerances"):
            continue
        kind_of = spec.get(name)
        if kind_of == "file":
            value = _inside(folder, value, lambda m, k=key: bad(m, k))
        elif kind_of == "float":
            value = float(value)
        elif kind_of in ("axis", "plane"):
            value = value.upper()
        elif kind_of == "floats2":
            value = [float(v) for v in value]
        options[name] = value
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
    own = _tolerance_dict(entry.tolerances)
    merged = _merged_tolerances(kind, campaign_tolerances, own, options.get("axis"))
    axis = options.pop("axis", None) if kind not in ("squareness", "ballbar") else options["plane"]
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
    from axiscal.uncertainty.budget import budget_from_tables, read_budget

    if value is None:
        return None, "simple"
    if isinstance(value, str):
        return read_budget(_inside(folder, value, fail_top)), "simple"
    rule = value.decision_rule
    if value.budget is not None:
        if set(value.given()) - {"budget", "decision_rule"}:
            raise fail("give the budget as budget = \"file.toml\" or as tables here, not both", "budget")
        return read_budget(_inside(folder, value.budget, lambda m: fail(m, "budget"))), rule
    return budget_from_tables(value, source=str(path), locate=locate), rule


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


def _inside(folder: Path, name: str, fail) -> Path:
    """The file ``name`` relative to the campaign folder; it must exist and stay inside the folder."""
    candidate = Path(name)
    if candidate.is_absolute():
        raise fail(f"'{name}' is an absolute path: data files are named relative to the campaign folder")
    resolved = (folder / candidate).resolve()
    if not resolved.is_relative_to(folder):
        raise fail(f"'{name}' leaves the campaign folder")
    if not resolved.is_file():
        raise fail(f"data file '{name}' not found in the campaign folder")
    return resolved
