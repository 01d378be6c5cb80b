"""The workbench's forms, checked once where the page sends them: each mistake named with its field.

A form arrives as JSON from the page (numbers in the units the labels say: mm, um, nm, s). Each is
a pydantic model; :func:`checked` turns a refusal into :class:`FormErrors`, whose ``fields`` maps
each field to one sentence that the page prints next to it.
"""

from __future__ import annotations

import datetime as _dt
from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field, ValidationError, ValidationInfo, field_validator, model_validator

from axiscal.capture.run import CaptureSettings
from axiscal.capture.stops import SETTLE_S, least_dwell_s
from axiscal.errors import AxiscalError
from axiscal.io.formats.budget import BUDGET_RANGES
from axiscal.uncertainty.decision import DECISION_RULES
from axiscal.workbench.budget import BUDGET_FIELDS
from axiscal.workbench.connection import check_ini, check_spec

__all__ = ["FORMS", "FormErrors", "checked"]

_TEXT = dict(max_length=200)


class FormErrors(AxiscalError):
    """A form the page sent that cannot be used: ``fields`` maps each field to what is wrong with it.

    Parameters
    ----------
    fields : dict of str to str
        Field name -> one sentence.
    """

    def __init__(self, fields: dict[str, str]):
        self.fields = dict(fields)
        super().__init__("; ".join(f"{name}: {text}" for name, text in self.fields.items()) or "the form is empty")


class _Form(BaseModel):
    model_config = ConfigDict(extra="forbid", str_strip_whitespace=True, allow_inf_nan=False)


def _budget(field: str) -> Any:
    """A budget number of the New visit form: optional, within the budget file's range for its key."""
    low, high = BUDGET_RANGES.get(BUDGET_FIELDS[field], (None, None))
    return Field(default=None, ge=low, le=high)


class VisitForm(_Form):
    """The campaign of a visit: what ``campaign.toml`` holds (tolerances in um, wavelength in nm)."""

    title: str = Field(min_length=1, **_TEXT)
    date: _dt.date
    operator: str = Field(min_length=1, **_TEXT)
    customer: str = Field(default="", **_TEXT)
    notes: str = Field(default="", max_length=2000)
    machine: str = Field(min_length=1, **_TEXT)
    serial: str = Field(default="", **_TEXT)
    controller: Literal["linuxcnc", "fanuc", "siemens", "heidenhain"] = "linuxcnc"
    instrument: str = Field(min_length=1, **_TEXT)
    instrument_serial: str = Field(default="", **_TEXT)
    certificate: str = Field(default="", **_TEXT)
    wavelength_nm: float = Field(default=632.99137, ge=400.0, le=1700.0)
    A_um: float = Field(gt=0, le=10000)
    E_um: float = Field(gt=0, le=10000)
    R_um: float = Field(gt=0, le=10000)
    B_um: float = Field(gt=0, le=10000)
    # what makes the visit's report a calibration certificate (all optional; all of them, or none)
    customer_address: str = Field(default="", **_TEXT)
    manufacturer: str = Field(default="", **_TEXT)
    condition: str = Field(default="", **_TEXT)
    instrument_calibrated: _dt.date | None = None
    instrument_calibrated_by: str = Field(default="", **_TEXT)
    lab_name: str = Field(default="", **_TEXT)
    lab_address: str = Field(default="", **_TEXT)
    lab_country: str = Field(default="", pattern=r"^([A-Z]{2})?$")
    lab_accreditation: str = Field(default="", **_TEXT)
    certificate_number: str = Field(default="", **_TEXT)
    issue_date: _dt.date | None = None
    location: Literal["laboratory", "customer", "laboratoryBranch", "customerBranch", "other"] = "customer"
    language: Literal["en", "de"] = "en"
    signatory_name: str = Field(default="", **_TEXT)
    signatory_role: str = Field(default="", **_TEXT)
    tolerance_source: str = Field(default="", **_TEXT)
    # the uncertainty budget (workbench.budget), in the budget file's units; none given: no budget, no U
    length_U_ppm: float | None = _budget("length_U_ppm")
    air_temperature_u_K: float | None = _budget("air_temperature_u_K")
    air_pressure_u_Pa: float | None = _budget("air_pressure_u_Pa")
    air_humidity_u_percent: float | None = _budget("air_humidity_u_percent")
    machine_temperature_C: float | None = _budget("machine_temperature_C")
    machine_temperature_u_K: float | None = _budget("machine_temperature_u_K")
    expansion_per_K: float | None = _budget("expansion_per_K")
    expansion_u_per_K: float | None = _budget("expansion_u_per_K")
    misalignment_urad: float | None = _budget("misalignment_urad")
    eve_um: float | None = _budget("eve_um")
    decision_rule: Literal[tuple(DECISION_RULES)] | None = None  # type: ignore[valid-type]

    @model_validator(mode="after")
    def _budget_and_rule(self) -> "VisitForm":
        """A budget's decision rule is simple acceptance unless chosen; without a budget there is none to choose."""
        if any(getattr(self, name) is not None for name in BUDGET_FIELDS):
            self.decision_rule = self.decision_rule or "simple"
        elif self.decision_rule == "guard-band":
            raise ValueError("decision_rule: the guard band needs the uncertainty budget (U is what it guards by)")
        else:
            self.decision_rule = None
        return self

    @model_validator(mode="after")
    def _certificate_whole(self) -> "VisitForm":
        """A certificate number asks for every field a certificate needs, each named where it is missing."""
        if not self.certificate_number:
            return self
        needed = ("customer", "customer_address", "manufacturer", "condition", "instrument_serial", "certificate",
                  "instrument_calibrated", "instrument_calibrated_by", "lab_name", "lab_address", "lab_country",
                  "issue_date", "signatory_name", "signatory_role", "tolerance_source")
        missing = [name for name in needed if getattr(self, name) in ("", None)]
        if missing:
            raise ValueError("certificate_number: a certificate also needs " + ", ".join(missing))
        return self


class PlanForm(_Form):
    """A positioning test's plan: travel in mm, dwell in s, the program's dialect.

    The dwell is at least what the stop detector can use (:func:`~axiscal.capture.stops.least_dwell_s`
    of the capture's window): a shorter one would run the whole program and find no stop.
    """

    axis: Literal["X"] = "X"
    start_mm: float = Field(ge=0.0, le=200.0)
    end_mm: float = Field(ge=0.0, le=200.0)
    targets: int = Field(ge=2, le=100)
    runs: int = Field(ge=1, le=10)
    overrun_mm: float = Field(gt=0.0, le=50.0)
    dwell_s: float = Field(gt=0.0, le=60.0)
    dialect: Literal["linuxcnc", "fanuc", "sinumerik", "heidenhain", "grbl", "marlin"] = "linuxcnc"
    seed: int = Field(default=1, ge=0, le=2**31)

    @model_validator(mode="after")
    def _travel(self) -> "PlanForm":
        if self.end_mm <= self.start_mm:
            raise ValueError("end_mm: the end must lie beyond the start")
        window_s = CaptureSettings().window_s
        least = least_dwell_s(window_s)
        if self.dwell_s < least:
            raise ValueError(f"dwell_s: the least dwell is {least:g} s: the stop detector needs the axis still for a"
                             f" whole {window_s:g} s window after it settles ({SETTLE_S:g} s allowed)")
        return self


class ConnectForm(_Form):
    """The instrument and the controller, as ``axiscal run`` names them, and LinuxCNC's INI file: each checked before connecting.

    ``ini`` is a path on the computer running the workbench (empty: none); the file is read at once.
    """

    instrument: str = Field(default="sim", min_length=1, max_length=200)
    controller: str = Field(default="sim", min_length=1, max_length=200)
    ini: str = Field(default="", max_length=1000)

    @field_validator("instrument", "controller")
    @classmethod
    def _spec(cls, value: str, info: ValidationInfo) -> str:
        try:
            return check_spec(info.field_name, value)
        except AxiscalError as exc:
            raise ValueError(str(exc)) from None

    @field_validator("ini")
    @classmethod
    def _ini(cls, value: str) -> str:
        if not value:
            return value
        try:
            return str(check_ini(value))
        except AxiscalError as exc:
            raise ValueError(str(exc)) from None

    @model_validator(mode="after")
    def _ini_is_linuxcncs(self) -> "ConnectForm":
        if self.ini and not self.controller.lower().startswith("linuxcnc:"):
            raise ValueError("ini: an INI file is LinuxCNC's: name the controller linuxcnc:HOST, or leave the INI file empty")
        return self


#: the forms of the page by name
FORMS: dict[str, type[_Form]] = {"visit": VisitForm, "plan": PlanForm, "connect": ConnectForm}


def checked(form: str, data: Any) -> Any:
    """``data`` read as the form ``form``; every refusal named by its field.

    Parameters
    ----------
    form : {"visit", "plan", "connect"}
        Which form: the campaign of a new visit, a test's plan, the instrument and controller.
    data : Any
        What the page sent (a JSON object).

    Returns
    -------
    pydantic.BaseModel
        The form's values, checked (numbers in the units of the field names).

    Raises
    ------
    FormErrors
        Naming each field that is missing or wrong, and each field that is not the form's.
    """
    if not isinstance(form, str) or form not in FORMS:
        raise AxiscalError(f"form must be one of {', '.join(FORMS)}, not {form!r}")
    if not isinstance(data, dict):
        raise FormErrors({"form": "the page must send the form's fields as a JSON object"})
    try:
        return FORMS[form].model_validate(data)
    except ValidationError as exc:
        fields: dict[str, str] = {}
        for error in exc.errors():
            where = str(error["loc"][0]) if error["loc"] else ""
            message = str(error["msg"]).removeprefix("Value error, ")
            if not where and ": " in message:
                where, message = message.split(": ", 1)
            fields.setdefault(where or "form", message)
        raise FormErrors(fields) from None
