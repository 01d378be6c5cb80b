"""The workbench's forms, checked once where the page sends them: each mistake named with its field.

A form arrives as JSON from the page (numbers in the units the labels say: mm, um, nm, s). Each is
a pydantic model; :func:`checked` turns a refusal into :class:`FormErrors`, whose ``fields`` maps
each field to one sentence that the page prints next to it.
"""

from __future__ import annotations

import datetime as _dt
import math
from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field, ValidationError, field_validator, model_validator

from axiscal.errors import AxiscalError

__all__ = ["FormErrors", "VisitForm", "PlanForm", "ConnectForm", "checked"]

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
    model_config = ConfigDict(extra="forbid", str_strip_whitespace=True)


def _finite(value: float) -> float:
    if not math.isfinite(value):
        raise ValueError("must be a finite number")
    return value


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

    _check_finite = field_validator("wavelength_nm", "A_um", "E_um", "R_um", "B_um")(_finite)


class PlanForm(_Form):
    """A positioning test's plan: travel in mm, dwell in s, the program's dialect."""

    axis: Literal["X"] = "X"
    start_mm: float = Field(ge=0.0, le=200.0)
    end_mm: float = Field(ge=0.0, le=200.0)
    targets: int = Field(ge=2, le=100)
    runs: int = Field(ge=1, le=10)
    overrun_mm: float = Field(gt=0.0, le=50.0)
    dwell_s: float = Field(gt=0.0, le=60.0)
    dialect: Literal["linuxcnc", "fanuc", "sinumerik", "heidenhain", "grbl", "marlin"] = "linuxcnc"
    seed: int = Field(default=1, ge=0, le=2**31)

    _check_finite = field_validator("start_mm", "end_mm", "overrun_mm", "dwell_s")(_finite)

    @model_validator(mode="after")
    def _travel(self) -> "PlanForm":
        if self.end_mm <= self.start_mm:
            raise ValueError("end_mm: the end must lie beyond the start")
        return self


class ConnectForm(_Form):
    """The instrument and the controller, as ``axiscal run`` names them."""

    instrument: str = Field(default="sim", min_length=1, max_length=200)
    controller: str = Field(default="sim", min_length=1, max_length=200)


def checked(form: type[_Form], data: Any) -> Any:
    """``data`` read as ``form``; every refusal named by its field.

    Parameters
    ----------
    form : type
        :class:`VisitForm`, :class:`PlanForm` or :class:`ConnectForm`.
    data : Any
        What the page sent (a JSON object).

    Returns
    -------
    an instance of ``form``

    Raises
    ------
    FormErrors
        Naming each field that is missing or wrong, and each field that is not the form's.
    """
    if not isinstance(data, dict):
        raise FormErrors({"form": "the page must send the form's fields as a JSON object"})
    try:
        return form.model_validate(data)
    except ValidationError as exc:
        fields: dict[str, str] = {}
        for error in exc.errors():
            where = str(error["loc"][0]) if error["loc"] else ""
            message = str(error["msg"]).removeprefix("Value error, ")
            if not where and ": " in message:
                where, message = message.split(": ", 1)
            fields.setdefault(where or "form", message)
        raise FormErrors(fields) from None
