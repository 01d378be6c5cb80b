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
from axiscal.workbench.connection import check_spec

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
    axes: list[Literal["X"]] = Field(min_length=1, max_length=1)
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
    """The instrument and the controller, as ``axiscal run`` names them: each checked before connecting."""

    instrument: str = Field(default="sim", min_length=1, max_length=200)
    controller: str = Field(default="sim", min_length=1, max_length=200)

    @field_validator("instrument", "controller")
    @classmethod
    def _spec(cls, value: str, info: ValidationInfo) -> str:
        try:
            return check_spec(info.field_name, value)
        except AxiscalError as exc:
            raise ValueError(str(exc)) from None


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
