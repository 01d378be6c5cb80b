"""campaign.toml declared: its tables, the keys of every kind of test, the tolerances.

The kinds of test and their keys are the table :data:`KINDS` (spelled as the options of the
command of the same name); the pydantic models are made from it, so the reader, the JSON Schema
and the key tables of docs/campaign.md come from one declaration.
"""

from __future__ import annotations

import datetime as _dt
from typing import Annotated, Any, Literal, Union

from pydantic import Discriminator, Field, Strict, StringConstraints, Tag, create_model, model_validator

from axiscal.io.formats.base import Bool, Count, FileName, FormatModel, Name, Number, Pair, Positive, Text
from axiscal.io.formats.budget import BudgetTables

__all__ = [
    "CAMPAIGN_FILE",
    "KINDS",
    "REQUIRED",
    "CONTROLLERS",
    "DECISION_RULES",
    "POSITIONING_TOLERANCE_KEYS",
    "TOLERANCE_KEYS",
    "CampaignTable",
    "MachineTable",
    "InstrumentTable",
    "LOCATIONS",
    "LANGUAGES",
    "LaboratoryTable",
    "CertificateTable",
    "SignatoryTable",
    "PositioningTolerances",
    "Tolerances",
    "UncertaintyTable",
    "TestEntryBase",
    "TEST_MODELS",
    "CampaignFile",
]

CAMPAIGN_FILE = "campaign.toml"
CONTROLLERS = ("linuxcnc", "fanuc", "siemens", "heidenhain")
#: ISO 14253-1 decision rules a campaign may name
DECISION_RULES = ("simple", "guard-band")
_FIGURES = ("A", "A_up", "A_down", "B", "B_mean", "E", "E_up", "E_down", "M", "R", "R_up", "R_down")
#: figure keys a positioning tolerance may name: um for a linear axis, arcsec for a rotary one
POSITIONING_TOLERANCE_KEYS = tuple(f"{k}_um" for k in _FIGURES) + tuple(f"{k}_arcsec" for k in _FIGURES)
#: the other tolerances (a positive number each), with what they limit
TOLERANCE_KEYS = {
    "straightness_um": "straightness of a straightness, separation or levels test",
    "squareness_arcsec": "squareness error",
    "diagonal_um": "error along a diagonal",
    "circular_deviation_um": "circular deviation G of a ballbar test",
    "flatness_um": "flatness",
    "etve_um": "ETVE of a thermal test (ISO 230-3)",
    "thermal_drift_um": "thermal drift",
    "calibration_um": "residual of a sensor calibration (um channels)",
    "calibration_arcsec": "residual of a sensor calibration (angle channels)",
    "cmm_e0_a_um": "E0,MPE = min(A + L/K, B): A", "cmm_e0_k": "E0,MPE: K", "cmm_e0_b_um": "E0,MPE: B",
    "cmm_e150_a_um": "E150,MPE: A", "cmm_e150_k": "E150,MPE: K", "cmm_e150_b_um": "E150,MPE: B",
    "cmm_r0_um": "R0,MPL",
    "pform_um": "probing form PForm,Sph,1x25,Tj,MPE", "psize_um": "probing size PSize,Sph,1x25,Tj,MPE",
    "pform_ms_um": "multi-stylus form", "psize_ms_um": "multi-stylus size", "ploc_um": "multi-stylus location",
    "settling_s": "settling time of a dynamics test (to its band)",
    "overshoot_um": "overshoot of a dynamics test",
    "periodic_um": "amplitude of a periodic error (step cycle)",
}

_AXIS = r"^[XYZABCxyzabc]$"
_PLANE = r"^([Xx][Yy]|[Xx][Zz]|[Yy][Zz])$"
_REFERENCES = ("least-squares", "end-points", "minimum-zone")
# option types: "str", "float", "int", "bool", "file", "floats2", "axis", "plane", ("choice", values)
#: per kind: the keys a test may carry, spelled as the options of the command of the same name
KINDS: dict[str, dict[str, Any]] = {
    "positioning": {
        "axis": "axis", "file": "file",
        "standard": ("choice", ("iso230-2:2014", "iso230-2:2006", "iso230-2:1997", "iso230-2:1988", "jis-b6192", "vdi3441")),
        "wavelength_nm": "float", "expansion_per_k": "float",
    },
    "straightness": {
        "axis": "axis", "direction": "axis", "file": "file", "reference": ("choice", _REFERENCES),
    },
    "separation": {
        "axis": "axis", "direction": "axis", "file": "file",
        "method": ("choice", ("stp", "strp", "fstrp", "gtp", "frequency", "combined", "reversal")),
        "spacing_mm": "float", "spacing_bc_mm": "float", "reversed": "file", "two_probe": "bool",
        "min_gain": "float", "periodic": "bool", "calibration_mm": "floats2",
        "reference": ("choice", _REFERENCES),
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
        "axis": "axis", "direction": "axis", "file": "file", "foot_mm": "float", "reference": ("choice", _REFERENCES),
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
#: the keys each kind cannot do without
REQUIRED: dict[str, tuple[str, ...]] = {
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

Date = Annotated[_dt.date, Strict(), Field(json_schema_extra={"format": "date"})]


class CampaignTable(FormatModel):
    """``[campaign]``: who measured, when, for whom.

    Attributes
    ----------
    title, operator : str
        What the campaign is and who measured.
    date : datetime.date
        The day of the measurement (a TOML date, ``2026-11-20``).
    customer, notes : str or None
    """

    title: Text = Field(description="the report's title")
    date: Date = Field(description="the day of the measurement, a TOML date (2026-11-20)")
    operator: Text = Field(description="who measured")
    customer: Text | None = Field(None, description="for whom")
    customer_address: Text | None = Field(None, description="the customer's address, as the certificate prints it")
    notes: Text | None = Field(None, description="anything else, printed in the report")


class MachineTable(FormatModel):
    """``[machine]``: the machine measured.

    Attributes
    ----------
    name : str
    serial, model, controller : str or None
        ``model`` names the machine description (TOML) in the folder.
    compensation : dict of str to str, or None
        Axis letter -> compensation file the controller had loaded.
    """

    name: Text = Field(description="the machine's name")
    serial: Text | None = Field(None, description="serial number")
    manufacturer: Text | None = Field(None, description="who made the machine")
    condition: Text | None = Field(None, description="the machine's condition as received, in a few words")
    model: FileName | None = Field(None, description="machine description (TOML) in the campaign folder")
    controller: Literal[CONTROLLERS] | None = Field(None, description="the controller whose files `compensation` names")  # type: ignore[valid-type]
    compensation: dict[str, FileName] | None = Field(
        None, description="files the controller had loaded, { X = \"X.comp\" } (needs model and controller)")


class InstrumentTable(FormatModel):
    """``[instrument]``: the laser or other instrument used.

    Attributes
    ----------
    name, serial, certificate : str or None
    calibrated : datetime.date or None
    vacuum_wavelength_nm : float or None
    """

    name: Text | None = Field(None, description="instrument")
    serial: Text | None = Field(None, description="serial number")
    certificate: Text | None = Field(None, description="calibration certificate")
    calibrated: Date | None = Field(None, description="date of its calibration")
    calibrated_by: Text | None = Field(None, description="the laboratory or institute that calibrated it")
    vacuum_wavelength_nm: Number | None = Field(None, description="laser vacuum wavelength, nm")


#: where the calibration was performed, as the DCC names it (``performanceLocation``)
LOCATIONS = ("laboratory", "customer", "laboratoryBranch", "customerBranch", "other")
#: the languages a certificate can be written in (ISO 639-1), each with a full translation
LANGUAGES = ("en", "de")


class LaboratoryTable(FormatModel):
    """``[laboratory]``: the laboratory that issues the certificate.

    Attributes
    ----------
    name, address : str
    country : str
        ISO 3166-1 alpha-2 code (``DE``).
    accreditation : str or None
        The accreditation body and number as printed (``D-K-00000-01-00``).
    """

    name: Text = Field(description="the laboratory's name")
    address: Text = Field(description="its address, one line")
    country: Annotated[str, Strict(), StringConstraints(pattern=r"^[A-Z]{2}$")] = Field(
        description="ISO 3166-1 alpha-2 country code (DE)")
    accreditation: Text | None = Field(None, description="accreditation body and number, as printed")


class CertificateTable(FormatModel):
    """``[certificate]``: the certificate's number, dates, place and languages.

    Attributes
    ----------
    number : str
        Identifies every page and the DCC (``uniqueIdentifier``).
    issue_date : datetime.date
        Fixed, so every re-run makes the same certificate.
    location : str
        One of :data:`LOCATIONS`: where the work was done.
    languages : list of str
        ISO 639-1 codes of :data:`LANGUAGES`, the first the certificate's main language.
    replaces : str or None
        The number of an earlier certificate this one replaces.
    tolerance_source : str or None
        Where the limits of ``[tolerances]`` come from (the customer's order, the maker's acceptance
        specification ...), printed with the conformity statement.
    deviations : str or None
        Any deviation from the stated methods (default: none).
    """

    number: Text = Field(description="the certificate number, on every page")
    issue_date: Date = Field(description="the day of issue, a TOML date (fixed: the same certificate on every re-run)")
    location: Literal[LOCATIONS] = Field(description="where the calibration was performed")  # type: ignore[valid-type]
    languages: Annotated[list[Literal[LANGUAGES]], Field(min_length=1, max_length=len(LANGUAGES))] = Field(  # type: ignore[valid-type]
        ["en"], description="languages of the certificate, the first its main language")
    replaces: Text | None = Field(None, description="the number of the certificate this one replaces")
    tolerance_source: Text | None = Field(None, description="where the tolerances come from")
    deviations: Text | None = Field(None, description="any deviation from the methods, as the certificate states it")

    @model_validator(mode="after")
    def _languages_once(self) -> "CertificateTable":
        if len(set(self.languages)) != len(self.languages):
            raise ValueError("languages: each language once")
        return self


class SignatoryTable(FormatModel):
    """``[[signatory]]``: a person who authorises the certificate (the first is the main signer).

    Attributes
    ----------
    name, role : str
    """

    name: Text = Field(description="the person's name")
    role: Text = Field(description="the person's function")


PositioningTolerances = create_model(
    "PositioningTolerances",
    __base__=FormatModel,
    __doc__="""``positioning = { A_um = 12.0, ... }``: limits of the ISO 230-2 figures.

    Attributes
    ----------
    A_um, ..., R_down_arcsec : float or None
        um for a linear axis, arcsec for a rotary one.
    """,
    **{k: (Positive | None, Field(None, description=f"limit of {k.rsplit('_', 1)[0]}")) for k in POSITIONING_TOLERANCE_KEYS},
)

Tolerances = create_model(
    "Tolerances",
    __base__=FormatModel,
    __doc__="""``[tolerances]`` (or a test's ``tolerances``): limits, each a positive number.

    Attributes
    ----------
    positioning : PositioningTolerances or None
    straightness_um, ... : float or None
        See :data:`TOLERANCE_KEYS`; the positioning figure keys may also stand here.
    """,
    positioning=(PositioningTolerances | None, Field(None, description="positioning figures { A_um = 12.0 }")),
    **{k: (Positive | None, Field(None, description=words)) for k, words in TOLERANCE_KEYS.items()},
    **{k: (Positive | None, Field(None, description=f"limit of {k.rsplit('_', 1)[0]}")) for k in POSITIONING_TOLERANCE_KEYS},
)


def _option_type(spec: Any) -> Any:
    if isinstance(spec, tuple):
        return Literal[spec[1]]  # type: ignore[valid-type]
    return {
        "str": Name, "float": Number, "int": Count, "bool": Bool, "file": FileName, "floats2": Pair,
        "axis": Annotated[str, Strict(), StringConstraints(pattern=_AXIS)],
        "plane": Annotated[str, Strict(), StringConstraints(pattern=_PLANE)],
    }[spec]


_WORDS = {"str": "text", "float": "number", "int": "whole number", "bool": "true or false", "file": "data file",
          "floats2": "[START, END]", "axis": "axis letter", "plane": "plane XY, XZ or YZ"}


class TestEntryBase(FormatModel):
    """A ``[[tests]]`` entry: its keys may be spelled as the command's options (``two-probe``) or
    with underscores (``two_probe``).

    Attributes
    ----------
    kind : str
    """

    __test__ = False  # not a pytest test class

    @model_validator(mode="before")
    @classmethod
    def _underscores(cls, data: Any) -> Any:
        if isinstance(data, dict):
            return {(k.replace("-", "_") if isinstance(k, str) else k): v for k, v in data.items()}
        return data


def _test_model(kind: str) -> type[FormatModel]:
    fields: dict[str, Any] = {
        "kind": (Literal[kind], Field(description="the kind of test")),  # type: ignore[valid-type]
        "id": (Name | None, Field(None, description="the test's name in the report (default kind-axis-n)")),
        "notes": (Text | None, Field(None, description="printed with the test")),
        "tolerances": (Tolerances | None, Field(None, description="limits of this test, over [tolerances]")),
    }
    for key, spec in KINDS[kind].items():
        words = "one of " + ", ".join(spec[1]) if isinstance(spec, tuple) else _WORDS[spec]
        required = key in REQUIRED[kind]
        fields[key] = (_option_type(spec) if required else _option_type(spec) | None,
                       Field(... if required else None, description=words))
    name = "".join(part.title() for part in kind.split("_")) + "Test"
    return create_model(name, __base__=TestEntryBase, __doc__=f"A ``[[tests]]`` entry of kind ``{kind}``.", **fields)


#: kind -> the model of a ``[[tests]]`` entry of that kind
TEST_MODELS: dict[str, type[FormatModel]] = {kind: _test_model(kind) for kind in KINDS}
TestEntry = Annotated[Union[tuple(TEST_MODELS.values())], Field(discriminator="kind")]  # type: ignore[valid-type]


class UncertaintyTable(BudgetTables):
    """``[uncertainty]``: the budget's tables here, or ``budget = "file.toml"``; the decision rule.

    Attributes
    ----------
    decision_rule : str
        ``"simple"`` or ``"guard-band"`` (ISO 14253-1).
    budget : str or None
        A budget file in the folder (then no budget tables here).
    """

    decision_rule: Literal[DECISION_RULES] = Field("simple", description="simple or guard-band (ISO 14253-1)")  # type: ignore[valid-type]
    budget: FileName | None = Field(None, description="a budget file in the campaign folder")


def _file_or_table(value: Any) -> str:
    return "=table" if isinstance(value, dict) else "=file"


class CampaignFile(FormatModel):
    """campaign.toml: the campaign, the machine, the instrument, tolerances, uncertainty, tests.

    Attributes
    ----------
    campaign : CampaignTable
    machine : MachineTable
    instrument : InstrumentTable or None
    tolerances : Tolerances or None
    uncertainty : str or UncertaintyTable or None
        A budget file name, or the ``[uncertainty]`` table.
    tests : list of test entries
        One model per kind (:data:`TEST_MODELS`), told apart by ``kind``.
    """

    campaign: CampaignTable = Field(description="title, date, operator")
    machine: MachineTable = Field(description="the machine measured")
    instrument: InstrumentTable | None = Field(None, description="the instrument used")
    tolerances: Tolerances | None = Field(None, description="limits agreed with the customer")
    uncertainty: Annotated[
        Union[Annotated[FileName, Tag("=file")], Annotated[UncertaintyTable, Tag("=table")]],
        Discriminator(_file_or_table),
    ] | None = Field(None, description="a budget file name or an [uncertainty] table")
    tests: Annotated[list[TestEntry], Field(min_length=1)] = Field(description="the tests, [[tests]]")
    laboratory: LaboratoryTable | None = Field(None, description="the issuing laboratory (for a certificate)")
    certificate: CertificateTable | None = Field(None, description="the certificate's number and dates")
    signatory: Annotated[list[SignatoryTable], Field(min_length=1)] | None = Field(
        None, description="who authorises the certificate, [[signatory]]")
