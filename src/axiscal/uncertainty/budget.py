"""The uncertainty budget of a length measurement with a laser interferometer (ISO/TR 230-9, ISO 230-2:2014 Annex A).

A budget file (TOML, docs/uncertainty.md) states the standard uncertainties (k = 1) of the
influences, or expanded ones (k = 2) where a key ends in ``_U``. :func:`length_components` turns it
into the standard uncertainty of each contribution at a measured length L, SI:

- ``device`` = L * length_U_ppm / 2 (laser certificate, relative, k = 2);
- ``air`` = L * sqrt(sum_i (dn/dx_i u(x_i))^2) over air temperature, pressure and humidity, the
  sensitivities dn/dx_i taken numerically from :func:`axiscal.instruments.air.refractive_index`
  (Ciddor by default) at the stated air conditions;
- ``machine_expansion`` = L * |T - 20 degC| * u(alpha);
- ``machine_temperature`` = L * alpha * u(T);
- ``misalignment`` = L (1 - cos theta_max) / (2 sqrt 3), the cosine error of the bound as a
  rectangular distribution of that full width;
- ``eve`` = EVE / (2 sqrt 3), the environmental variation error (full range) as a rectangular
  distribution.

The combination goes through GTC (the GUM Tree Calculator): each influence is an uncertain real
with its name, and the components are its budget.
"""

from __future__ import annotations

from collections.abc import Callable

import math
from dataclasses import dataclass, fields
from pathlib import Path

from axiscal.errors import AxiscalError
from axiscal.instruments.air import METHODS, refractive_index
from axiscal.io.arguments import check_mapping, check_number
from axiscal.io.arguments import check_instance, type_name
from axiscal.io.arguments import check_path
from axiscal.io.formats.base import read_format, validate_data
from axiscal.io.formats.budget import BUDGET_KEYS, BUDGET_RANGES, BudgetFile, BudgetTables
from axiscal.units import ARCSEC, UM

__all__ = [
    "COMPONENTS",
    "BUDGET_KEYS",
    "BUDGET_RANGES",
    "HE_NE_WAVELENGTH_NM",
    "Budget",
    "budget_from_dict",
    "budget_from_tables",
    "read_budget",
    "air_sensitivities",
    "length_model",
    "length_components",
]

#: names of the contributions, in the order of the budget table
COMPONENTS = ("device", "air", "machine_expansion", "machine_temperature", "misalignment", "eve")

#: vacuum wavelength of a He-Ne laser, nm
HE_NE_WAVELENGTH_NM = 632.991

_PPM = 1e-6
_URAD = 1e-6
_REFERENCE_C = 20.0
_RECTANGULAR = 2.0 * math.sqrt(3.0)  # full width / standard uncertainty of a rectangular distribution


@dataclass(frozen=True)
class Budget:
    """Uncertainties of the influences on a laser length measurement, SI (a missing key is zero).

    Parameters
    ----------
    length_U_rel : float
        Expanded (k = 2) relative uncertainty of a length reading (certificate), dimensionless.
    air_temperature_u_K, air_pressure_u_Pa, air_humidity_u_percent : float
        Standard uncertainties of the air sensors, K, Pa and percent relative humidity.
    air_temperature_C, air_pressure_Pa, air_humidity_percent : float
        Air conditions at which the sensitivities of the refractive index are taken (degC, Pa, %).
    machine_temperature_C : float
        Mean machine (scale) temperature during the test, degC.
    machine_temperature_u_K : float
        Standard uncertainty of that temperature, K.
    expansion_per_K, expansion_u_per_K : float
        Expansion coefficient used to normalise to 20 degC and its standard uncertainty, 1/K.
    misalignment_rad : float
        Bound of the beam-to-axis angle (rectangular distribution), rad.
    eve_m : float
        Environmental variation error from the drift test (full range), m.
    straightness_U_m : float
        Expanded (k = 2) uncertainty of one straightness reading, m.
    prism_deviation_u_rad : float
        Standard uncertainty of the pentaprism's deviation from 90 degrees (squareness), rad.
    wavelength_nm : float
        Vacuum wavelength of the laser (default He-Ne, 632.991 nm).
    method : str
        Refractive-index equation of :func:`axiscal.instruments.air.refractive_index` ("ciddor").
    source : str
        Where the budget came from, for messages.

    Raises
    ------
    AxiscalError
        A value that is not a finite number, a negative uncertainty, a value outside its physical
        range (:data:`BUDGET_RANGES`, here in SI), an unknown method.
    """

    length_U_rel: float = 0.0
    air_temperature_u_K: float = 0.0
    air_pressure_u_Pa: float = 0.0
    air_humidity_u_percent: float = 0.0
    air_temperature_C: float = 20.0
    air_pressure_Pa: float = 101325.0
    air_humidity_percent: float = 50.0
    machine_temperature_C: float = 20.0
    machine_temperature_u_K: float = 0.0
    expansion_per_K: float = 0.0
    expansion_u_per_K: float = 0.0
    misalignment_rad: float = 0.0
    eve_m: float = 0.0
    straightness_U_m: float = 0.0
    prism_deviation_u_rad: float = 0.0
    wavelength_nm: float = HE_NE_WAVELENGTH_NM
    method: str = "ciddor"
    source: str = "<budget>"

    def __post_init__(self) -> None:
        for f in fields(self):
            value = getattr(self, f.name)
            if f.name in ("method", "source"):
                continue
            if not isinstance(value, (int, float)) or isinstance(value, bool) or not math.isfinite(value):
                raise AxiscalError(f"budget value {f.name} must be a finite number, got {value!r}", path=self.source)
            object.__setattr__(self, f.name, float(value))
        for name in _UNCERTAINTIES:
            if getattr(self, name) < 0:
                raise AxiscalError(f"budget value {name} must not be negative, got {getattr(self, name):g}", path=self.source)
        for name, (low, high) in _SI_RANGES.items():
            if not low <= getattr(self, name) <= high:
                raise AxiscalError(f"budget value {name} must be {low:g} to {high:g}, got {getattr(self, name):g}",
                                   path=self.source)
        if self.method not in METHODS:
            raise AxiscalError(f"unknown refractive-index method '{self.method}'; use one of {', '.join(METHODS)}", path=self.source)


# Budget fields that are uncertainties or bounds (never negative)
_UNCERTAINTIES = ("length_U_rel", "air_temperature_u_K", "air_pressure_u_Pa", "air_humidity_u_percent",
                  "machine_temperature_u_K", "expansion_u_per_K", "misalignment_rad", "eve_m",
                  "straightness_U_m", "prism_deviation_u_rad")

# (section, key) -> (Budget field, factor to SI)
_FIELDS: dict[tuple[str, str], tuple[str, float]] = {
    ("instrument", "length_U_ppm"): ("length_U_rel", _PPM),
    ("instrument", "wavelength_nm"): ("wavelength_nm", 1.0),
    ("air", "temperature_u_K"): ("air_temperature_u_K", 1.0),
    ("air", "pressure_u_Pa"): ("air_pressure_u_Pa", 1.0),
    ("air", "humidity_u_percent"): ("air_humidity_u_percent", 1.0),
    ("air", "temperature_C"): ("air_temperature_C", 1.0),
    ("air", "pressure_Pa"): ("air_pressure_Pa", 1.0),
    ("air", "humidity_percent"): ("air_humidity_percent", 1.0),
    ("machine", "temperature_C"): ("machine_temperature_C", 1.0),
    ("machine", "temperature_u_K"): ("machine_temperature_u_K", 1.0),
    ("machine", "expansion_per_K"): ("expansion_per_K", 1.0),
    ("machine", "expansion_u_per_K"): ("expansion_u_per_K", 1.0),
    ("setup", "misalignment_urad"): ("misalignment_rad", _URAD),
    ("setup", "eve_um"): ("eve_m", UM),
    ("instrument", "straightness_U_um"): ("straightness_U_m", UM),
    ("setup", "prism_deviation_u_arcsec"): ("prism_deviation_u_rad", ARCSEC),
}


# Budget field -> its range in SI
_SI_RANGES = {_FIELDS[key][0]: (low * _FIELDS[key][1], high * _FIELDS[key][1]) for key, (low, high) in BUDGET_RANGES.items()}


def budget_from_dict(
    data: dict, *, source: str = "<budget>", text: str | None = None,
    locate: Callable[[str, str | None], int | None] | None = None,
) -> Budget:
    """Build a :class:`Budget` from the parsed TOML tables (keys of docs/uncertainty.md).

    Parameters
    ----------
    data : dict
        ``{"instrument": {...}, "air": {...}, "machine": {...}, "setup": {...}}``; a missing
        section or key is a zero contribution (air and machine conditions default to 20 degC,
        101325 Pa and 50 %).
    source : str, keyword-only
        File name for messages.
    text : str, optional, keyword-only
        The TOML text, to name the line of a bad key.
    locate : callable, optional, keyword-only
        ``locate(section, key)`` -> line, for a budget held inside another file; takes
        precedence over ``text``.

    Returns
    -------
    Budget

    Raises
    ------
    AxiscalError
        ``data`` that is not a mapping, an unknown section or key, a value that is not a number, a negative uncertainty, a
        value outside its physical range (:data:`BUDGET_RANGES`), air conditions outside the range of the refractive-index
        equation.

    Examples
    --------
    >>> budget_from_dict({"setup": {"eve_um": 1.0}}).eve_m
    1e-06
    """
    from axiscal.io.schema import TomlLines

    check_mapping("data", data, what="the tables of a budget (a dict)")
    if not isinstance(source, (str, Path)):
        raise AxiscalError(f"source must be the file name for messages (a str), not {type_name(source)}")
    if locate is not None and not callable(locate):
        raise AxiscalError(f"locate must be a function of (section, key), not {type_name(locate)}")
    if text is not None and not isinstance(text, str):
        raise AxiscalError(f"text must be the TOML text (a str), not {type_name(text)}")
    lines = TomlLines(text) if text is not None and locate is None else None
    tables = validate_data(BudgetFile, data, path=source, lines=lines)
    if locate is None:
        def locate(section: str, key: str | None = None) -> int | None:
            return None if lines is None else lines.of(section, key=key) or lines.of("", key=section)
    return budget_from_tables(tables, source=source, locate=locate)


def budget_from_tables(
    tables: BudgetTables, *, source: str = "<budget>", locate: Callable[[str, str | None], int | None] | None = None,
) -> Budget:
    """Build a :class:`Budget` from validated budget tables (a budget file or campaign.toml's ``[uncertainty]``).

    Parameters
    ----------
    tables : axiscal.io.formats.BudgetTables
        The validated tables (values in the file's units).
    source : str, keyword-only
        File name for messages.
    locate : callable, optional, keyword-only
        ``locate(section, key)`` -> line, to name the line of the method or the air conditions.

    Returns
    -------
    Budget

    Raises
    ------
    AxiscalError
        An unknown refractive-index method; air conditions outside the range of the refractive-index equation.
    """
    check_instance("tables", tables, BudgetTables, what="validated budget tables (axiscal.io.formats.BudgetTables)")

    def line(section: str, key: str | None = None) -> int | None:
        return None if locate is None else locate(section, key)

    values: dict[str, object] = {}
    for section in BUDGET_KEYS:
        table = getattr(tables, section)
        if table is None:
            continue
        for key, value in table.given().items():
            if key == "method":
                values["method"] = value
                continue
            name, factor = _FIELDS[(section, key)]
            values[name] = float(value) * factor
    try:
        budget = Budget(**values, source=source)
    except AxiscalError as exc:  # the method is the one value only Budget itself checks
        raise exc.located(line=line("instrument", "method")) from None
    try:  # air conditions the refractive-index equation refuses (hPa for Pa, ...) show here, not later
        air_sensitivities(budget)
    except AxiscalError as exc:
        raise AxiscalError(f"[air] conditions: {exc.message}", path=source, line=line("air")) from None
    return budget


def read_budget(path: str | Path) -> Budget:
    """Read a budget file (TOML, docs/uncertainty.md).

    Parameters
    ----------
    path : str or Path
        The budget file.

    Returns
    -------
    Budget

    Raises
    ------
    AxiscalError
        A missing or malformed file, or a bad key, naming the file and line.
    """
    tables, lines = read_format(BudgetFile, check_path("path", path))
    return budget_from_tables(tables, source=str(path),
                              locate=lambda section, key=None: lines.of(section, key=key) or lines.of("", key=section))


def air_sensitivities(budget: Budget) -> dict[str, float]:
    """Sensitivities of the refractive index of air at the budget's air conditions.

    Central differences of :func:`axiscal.instruments.air.refractive_index` (the budget's
    method and wavelength) at ``air_temperature_C``, ``air_pressure_Pa``, ``air_humidity_percent``.

    Parameters
    ----------
    budget : Budget

    Returns
    -------
    dict
        ``{"temperature": dn/dT (1/K), "pressure": dn/dp (1/Pa), "humidity": dn/dh (1/%)}``.

    Raises
    ------
    AxiscalError
        Air conditions or a wavelength outside the range of the refractive-index equation; a
        ``budget`` that is not a :class:`Budget`.
    """
    check_budget(budget)
    base = {"temperature": budget.air_temperature_C, "pressure": budget.air_pressure_Pa, "humidity": budget.air_humidity_percent}
    steps = {"temperature": 0.01, "pressure": 1.0, "humidity": 0.1}
    out: dict[str, float] = {}
    for name, step in steps.items():
        if name == "humidity":  # stay inside 0..100 %
            step = min(step, max(1e-6, min(base[name], 100.0 - base[name])))
        hi, lo = dict(base), dict(base)
        hi[name] += step
        lo[name] -= step
        n_hi, n_lo = (
            refractive_index(c["temperature"], c["pressure"], c["humidity"], budget.wavelength_nm, method=budget.method)
            for c in (hi, lo)
        )
        out[name] = (n_hi - n_lo) / (2.0 * step)
    return out


def length_model(budget: Budget, length_m: float):
    """The GUM model of the error of a laser length reading over ``length_m``, as a GTC uncertain real.

    Each influence is a named GTC elementary uncertain real (label = the component it feeds, see
    :data:`COMPONENTS`; the air has three, ``air temperature``, ``air pressure``, ``air humidity``,
    and the machine two), all of infinite degrees of freedom (type B). The value is the error
    estimate (zero: the corrections are applied), its uncertainty the combined standard uncertainty.

    Parameters
    ----------
    budget : Budget
    length_m : float
        Measured length L (the travel of the test), m.

    Returns
    -------
    GTC.lib.UncertainReal
        The length error, m.

    Raises
    ------
    AxiscalError
        As :func:`air_sensitivities`; a ``length_m`` that is not a finite number.
    """
    from GTC import ureal

    length = abs(check_number("length_m", length_m))
    c = air_sensitivities(budget)
    device = ureal(0.0, budget.length_U_rel / 2.0, label="device")
    air_t = ureal(budget.air_temperature_C, budget.air_temperature_u_K, label="air temperature")
    air_p = ureal(budget.air_pressure_Pa, budget.air_pressure_u_Pa, label="air pressure")
    air_h = ureal(budget.air_humidity_percent, budget.air_humidity_u_percent, label="air humidity")
    alpha = ureal(budget.expansion_per_K, budget.expansion_u_per_K, label="machine_expansion")
    temperature = ureal(budget.machine_temperature_C, budget.machine_temperature_u_K, label="machine_temperature")
    cosine = length * (1.0 - math.cos(budget.misalignment_rad))
    misalignment = ureal(0.0, cosine / _RECTANGULAR, label="misalignment")
    eve = ureal(0.0, budget.eve_m / _RECTANGULAR, label="eve")
    delta_n = (
        c["temperature"] * (air_t - budget.air_temperature_C)
        + c["pressure"] * (air_p - budget.air_pressure_Pa)
        + c["humidity"] * (air_h - budget.air_humidity_percent)
    )
    nominal = budget.expansion_per_K * (budget.machine_temperature_C - _REFERENCE_C)
    expansion = alpha * (temperature - _REFERENCE_C) - nominal
    return length * (device + delta_n + expansion) + misalignment + eve


def length_components(budget: Budget, length_m: float) -> dict[str, float]:
    """Standard uncertainty of each contribution at a measured length, from the GTC budget.

    Parameters
    ----------
    budget : Budget
    length_m : float
        Measured length L, m.

    Returns
    -------
    dict of str to float
        One entry per name of :data:`COMPONENTS`, m (k = 1); the air's three sensors combined in
        quadrature.

    Raises
    ------
    AxiscalError
        As :func:`air_sensitivities`.

    Examples
    --------
    >>> round(length_components(Budget(length_U_rel=0.5e-6), 1.0)["device"] * 1e6, 6)
    0.25
    """
    from GTC import reporting

    check_budget(budget)
    out = dict.fromkeys(COMPONENTS, 0.0)
    for influence in reporting.budget(length_model(budget, length_m), trim=0):
        key = "air" if influence.label.startswith("air ") else influence.label
        out[key] = math.hypot(out[key], abs(influence.u))
    return out


def check_budget(budget: object, name: str = "budget") -> Budget:
    """``budget`` if it is a :class:`Budget`, else refused naming ``name``."""
    return check_instance(name, budget, Budget)


def as_budget(budget: Budget | str | Path, name: str = "budget") -> Budget:
    """``budget`` itself, or the budget read from the file it names; anything else refused."""
    if isinstance(budget, Budget):
        return budget
    if isinstance(budget, (str, Path)):
        return read_budget(budget)
    raise AxiscalError(f"{name} must be a Budget or the path of a budget file, not {type_name(budget)}")
