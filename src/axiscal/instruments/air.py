"""Refractive index of air for laser interferometry.

Implements the equations as NIST's Engineering Metrology Toolbox gives them (J. A. Stone and
J. H. Zimmerman, "Index of Refraction of Air", Appendix A and B):

- ``"ciddor"``: Ciddor, Appl. Opt. 35 (1996) 1566, with the BIPM 1981/91 compressibility
  (NIST Appendix A-III);
- ``"edlen"``: the updated Edlen equation of Birch and Downs, Metrologia 30 (1993) 155 and
  31 (1994) 315, with NIST's modified water-vapour term (Appendix A-IV); standard air holds
  450 ppm CO2, other contents take Edlen's factor ``1 + 0.540 (x - 0.00045)`` (NIST's calculator
  has no CO2 input for Edlen: at the default 450 ppm the factor is 1);
- ``"edlen1966"``: Edlen, Metrologia 2 (1966) 71, in his units (pressures in torr; standard
  air with 300 ppm CO2, corrected by ``1 + 0.540 (x - 0.0003)``);
- ``"shopfloor"``: NIST's simple shop-floor formula (Appendix B), for 633 nm only.

The saturation vapour pressure is the IAPWS-IF97 saturation equation over water and the IAPWS
sublimation equation of Wagner, Saul and Pruss (1994) over ice, switched at 0 degC as NIST does
(Appendix A-I); relative humidity becomes a mole fraction with the enhancement factor of
Appendix A-II.

Units at the boundary are spelled in names: temperature in degC, pressure in Pa, relative
humidity in percent, vacuum wavelength in nm, CO2 mole fraction in ppm (umol/mol).
"""

from __future__ import annotations

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.instruments.reports import render_report
from axiscal.io.arguments import check_array, check_broadcast, check_choice, check_mapping, check_number
from axiscal.units import LENGTH_UNITS, PPM, UM

__all__ = [
    "METHODS",
    "WAVELENGTH_RANGE_NM",
    "TEMPERATURE_RANGE_C",
    "PRESSURE_RANGE_PA",
    "CO2_RANGE_PPM",
    "saturation_vapour_pressure",
    "water_vapour_mole_fraction",
    "refractive_index",
    "air_report",
    "air_inputs",
    "air_text",
]

#: names accepted by :func:`refractive_index`
METHODS = ("ciddor", "edlen", "edlen1966", "shopfloor")

#: vacuum wavelengths (nm) each equation accepts: 300-1700 nm is the range of NIST's calculator and
#: check table for both Ciddor and Edlen; the shop-floor formula is for He-Ne light (633 nm), and
#: over 628-638 nm dispersion changes n by less than 1e-7
WAVELENGTH_RANGE_NM: dict[str, tuple[float, float]] = {
    "ciddor": (300.0, 1700.0),
    "edlen": (300.0, 1700.0),
    "edlen1966": (300.0, 1700.0),
    "shopfloor": (628.0, 638.0),
}
#: air temperatures (degC) and pressures (Pa) accepted: the conditions of NIST's check table with
#: margin; outside them a value is far more likely a unit slip (K for degC, hPa or kPa for Pa)
TEMPERATURE_RANGE_C = (-40.0, 100.0)
PRESSURE_RANGE_PA = (10e3, 140e3)
#: CO2 mole fractions (umol/mol) accepted
CO2_RANGE_PPM = (0.0, 2000.0)

_KELVIN = 273.15
_NM = LENGTH_UNITS["nm"]
#: Pa per kPa, the pressure unit of NIST's shop-floor formula
_PA_PER_KPA = 1e3
_TORR = 101325.0 / 760.0

# IAPWS-IF97 saturation-pressure equation (over liquid water), NIST Appendix A-I
_K = (
    1.16705214528e03,
    -7.24213167032e05,
    -1.70738469401e01,
    1.20208247025e04,
    -3.23255503223e06,
    1.49151086135e01,
    -4.82326573616e03,
    4.05113405421e05,
    -2.38555575678e-01,
    6.50175348448e02,
)
# IAPWS sublimation pressure (over ice), NIST Appendix A-I
_ICE_A1 = -13.928169
_ICE_A2 = 34.7078238
_TRIPLE_T = 273.16
_TRIPLE_P = 611.657


def _as_float(values: np.ndarray):
    return float(values) if np.ndim(values) == 0 else values


def saturation_vapour_pressure(temperature_c, *, over: str = "auto"):
    """Saturation vapour pressure of water, IAPWS, in Pa.

    Parameters
    ----------
    temperature_c : float or ndarray, degC
        Air temperature.
    over : {"auto", "water", "ice"}, keyword-only
        ``"water"``: IAPWS-IF97 over liquid water; ``"ice"``: IAPWS sublimation pressure over
        ice; ``"auto"`` (default): ice below 0 degC, water otherwise, as NIST does.

    Returns
    -------
    float or ndarray, Pa
        Same shape as ``temperature_c``.
    """
    check_choice("phase (over)", over, ("auto", "water", "ice"))
    t = _temperature(temperature_c)
    kelvin = t + _KELVIN
    k1, k2, k3, k4, k5, k6, k7, k8, k9, k10 = _K
    omega = kelvin + k9 / (kelvin - k10)
    a = omega**2 + k1 * omega + k2
    b = k3 * omega**2 + k4 * omega + k5
    c = k6 * omega**2 + k7 * omega + k8
    x = -b + np.sqrt(b**2 - 4.0 * a * c)
    over_water = 1e6 * (2.0 * c / x) ** 4
    theta = kelvin / _TRIPLE_T
    over_ice = _TRIPLE_P * np.exp(_ICE_A1 * (1.0 - theta**-1.5) + _ICE_A2 * (1.0 - theta**-1.25))
    if over == "water":
        result = over_water
    elif over == "ice":
        result = over_ice
    else:
        result = np.where(t < 0.0, over_ice, over_water)
    return _as_float(result)


def water_vapour_mole_fraction(temperature_c, pressure_pa, humidity_pct):
    """Mole fraction of water vapour from relative humidity (NIST Appendix A-II), dimensionless.

    ``x_v = (h / 100) f(p, t) p_sv(t) / p`` with the enhancement factor
    ``f = 1.00062 + 3.14e-8 p + 5.6e-7 t^2``.

    Parameters
    ----------
    temperature_c : float or array_like
        Air temperature, degC.
    pressure_pa : float or array_like
        Air pressure, Pa.
    humidity_pct : float or array_like
        Relative humidity, percent.

    Returns
    -------
    float or ndarray
        Mole fraction x_v, dimensionless.
    """
    t, p, h = check_broadcast(
        temperature_c=_temperature(temperature_c),
        pressure_pa=check_array("pressure_pa", pressure_pa),
        humidity_pct=check_array("humidity_pct", humidity_pct),
    )
    if np.any(p <= 0.0):
        raise AxiscalError(f"pressure_pa must be positive, got {float(p[p <= 0].flat[0]):g} Pa")
    _check_range(h, (0.0, 100.0), "relative humidity humidity_pct", "%")
    enhancement = 1.00062 + 3.14e-8 * p + 5.6e-7 * t**2
    return _as_float(h / 100.0 * enhancement * saturation_vapour_pressure(t) / p)


def _wavenumber_squared(wavelength_nm):
    """``1 / lambda^2`` with lambda in um, the variable of the dispersion formulas."""
    return (UM / (np.asarray(wavelength_nm) * _NM)) ** 2


def _ciddor(t, p, h, wavelength_nm, co2_ppm):
    kelvin = t + _KELVIN
    s = _wavenumber_squared(wavelength_nm)
    x_v = water_vapour_mole_fraction(t, p, h)
    r_as = 1e-8 * (5792105.0 / (238.0185 - s) + 167917.0 / (57.362 - s))
    r_vs = 1.022e-8 * (295.235 + 2.6422 * s - 0.032380 * s**2 + 0.004028 * s**3)
    molar_mass_air = 0.0289635 + 1.2011e-8 * (co2_ppm - 400.0)
    r_axs = r_as * (1.0 + 5.34e-7 * (co2_ppm - 450.0))
    compressibility = (
        1.0
        - (p / kelvin)
        * (1.58123e-6 - 2.9331e-8 * t + 1.1043e-10 * t**2 + (5.707e-6 - 2.051e-8 * t) * x_v + (1.9898e-4 - 2.376e-6 * t) * x_v**2)
        + (p / kelvin) ** 2 * (1.83e-11 - 0.765e-8 * x_v**2)
    )
    gas_constant = 8.314472
    molar_mass_water = 0.018015
    density_axs = 101325.0 * molar_mass_air / (0.9995922115 * gas_constant * 288.15)
    density_vs = 0.00985938
    density_v = x_v * p * molar_mass_water / (compressibility * gas_constant * kelvin)
    density_a = (1.0 - x_v) * p * molar_mass_air / (compressibility * gas_constant * kelvin)
    return 1.0 + (density_a / density_axs) * r_axs + (density_v / density_vs) * r_vs


def _edlen_birch_downs(t, p, h, wavelength_nm, co2_ppm):
    s = _wavenumber_squared(wavelength_nm)
    standard = 1e-8 * (8342.54 + 2406147.0 / (130.0 - s) + 15998.0 / (38.9 - s))
    standard = standard * (1.0 + 0.540e-6 * (co2_ppm - 450.0))
    x = (1.0 + 1e-8 * (0.601 - 0.00972 * t) * p) / (1.0 + 0.003661 * t)
    n_tp = 1.0 + p * standard * x / 96095.43
    p_v = h / 100.0 * saturation_vapour_pressure(t)
    return n_tp - 292.75 / (t + _KELVIN) * (3.7345 - 0.0401 * s) * p_v * 1e-10


def _edlen_1966(t, p, h, wavelength_nm, co2_ppm):
    # Edlen's own units: pressures in torr (101325/760 Pa)
    s = _wavenumber_squared(wavelength_nm)
    standard = 1e-8 * (8342.13 + 2406030.0 / (130.0 - s) + 15997.0 / (38.9 - s))
    standard = standard * (1.0 + 0.540e-6 * (co2_ppm - 300.0))
    p_torr = p / _TORR
    n_tp = 1.0 + p_torr * standard * (1.0 + 1e-6 * (0.817 - 0.0133 * t) * p_torr) / (720.775 * (1.0 + 0.0036610 * t))
    f_torr = h / 100.0 * saturation_vapour_pressure(t) / _TORR
    return n_tp - (5.722 - 0.0457 * s) * f_torr * 1e-8


def _shopfloor(t, p, h, wavelength_nm, co2_ppm):
    return 1.0 + 7.86e-4 * (p / _PA_PER_KPA) / (273.0 + t) - 1.5e-11 * h * (t**2 + 160.0)


def _temperature(temperature_c) -> np.ndarray:
    """Air temperatures in degC as an array, refused when not finite or below absolute zero."""
    t = check_array("temperature_c", temperature_c)
    if np.any(t <= -_KELVIN):
        raise AxiscalError(f"temperature_c {float(t[t <= -_KELVIN].flat[0]):g} degC is below absolute zero")
    return t


def _check_range(values: np.ndarray, bounds: tuple[float, float], what: str, unit: str, hint: str = "") -> None:
    low, high = bounds
    outside = (values < low) | (values > high)
    if np.any(outside):
        raise AxiscalError(f"{what} {float(values[outside].flat[0]):g} {unit} is outside the range {low:g} to {high:g} {unit}{hint}")


_EQUATIONS = {"ciddor": _ciddor, "edlen": _edlen_birch_downs, "edlen1966": _edlen_1966, "shopfloor": _shopfloor}


def refractive_index(temperature_c, pressure_pa, humidity_pct, wavelength_nm, *, co2_ppm=450.0, method: str = "ciddor"):
    """Refractive index of moist air (phase index) for a vacuum wavelength.

    Parameters
    ----------
    temperature_c : float or array_like, degC
        Air temperature.
    pressure_pa : float or array_like, Pa
        Total air pressure, 10 to 140 kPa (:data:`PRESSURE_RANGE_PA`).
    humidity_pct : float or array_like, percent
        Relative humidity, 0 to 100.
    wavelength_nm : float or array_like, nm
        Vacuum wavelength (He-Ne: 632.991 nm).  Must lie in the method's range
        (:data:`WAVELENGTH_RANGE_NM`).
    co2_ppm : float or array_like, umol/mol, keyword-only
        CO2 mole fraction (default 450, NIST's default).  The shop-floor formula ignores it.
    method : {"ciddor", "edlen", "edlen1966", "shopfloor"}, keyword-only
        ``"ciddor"`` (default) Ciddor 1996; ``"edlen"`` Birch and Downs 1993/1994 with NIST's
        water term; ``"edlen1966"`` Edlen 1966; ``"shopfloor"`` NIST's simple formula.

    Returns
    -------
    float or ndarray
        The refractive index n, broadcast shape of the inputs; a float for scalar inputs.

    Raises
    ------
    AxiscalError
        For an unknown method, NaN, humidity outside 0-100 %, a pressure that is not positive or
        outside :data:`PRESSURE_RANGE_PA`, a temperature outside :data:`TEMPERATURE_RANGE_C`, CO2
        outside :data:`CO2_RANGE_PPM`, a wavelength outside the method's range
        (:data:`WAVELENGTH_RANGE_NM`), or a water vapour pressure not below the air pressure.
    """
    if not isinstance(method, str) or method not in _EQUATIONS:
        raise AxiscalError(f"unknown refractive-index method {method!r}; use one of {', '.join(METHODS)}")
    named = dict(temperature_c=temperature_c, pressure_pa=pressure_pa, humidity_pct=humidity_pct, wavelength_nm=wavelength_nm, co2_ppm=co2_ppm)
    arrays = {name: check_array(name, value, finite=False) for name, value in named.items()}
    for name, values in arrays.items():
        if not np.all(np.isfinite(values)):
            raise AxiscalError(f"{name} for the refractive index of air is not a finite number")
    t, p, h, wavelength, co2 = check_broadcast(**arrays)
    _check_range(h, (0.0, 100.0), "relative humidity", "%")
    if np.any(p <= 0.0):
        raise AxiscalError(f"air pressure must be positive, got {float(p[p <= 0].flat[0]):g} Pa")
    _check_range(p, PRESSURE_RANGE_PA, "air pressure", "Pa", " (in pascals: 1013.25 hPa is 101325 Pa)")
    _check_range(t, TEMPERATURE_RANGE_C, "air temperature", "degC", " (degrees Celsius, not kelvin)")
    _check_range(co2, CO2_RANGE_PPM, "CO2 mole fraction", "ppm")
    _check_range(wavelength, WAVELENGTH_RANGE_NM[method], "vacuum wavelength", "nm", f" of the '{method}' equation")
    vapour = h / 100.0 * saturation_vapour_pressure(t)
    if np.any(vapour >= p):
        where = np.argmax((vapour >= p).ravel())
        raise AxiscalError(
            f"water vapour pressure {vapour.flat[where]:.0f} Pa at {h.flat[where]:g} % and {t.flat[where]:g} degC "
            f"is not below the air pressure {p.flat[where]:g} Pa"
        )
    return _as_float(_EQUATIONS[method](t, p, h, wavelength, co2))


def air_report(
    temperature_c: float,
    pressure_pa: float,
    humidity_pct: float,
    wavelength_nm: float = 632.991,
    *,
    co2_ppm: float = 450.0,
    method: str = "ciddor",
) -> dict:
    """The refractive index of air with what is shown of it (``axiscal air``).

    Parameters
    ----------
    temperature_c, pressure_pa, humidity_pct, wavelength_nm : float
        Air temperature (degC), pressure (Pa), relative humidity (%) and vacuum wavelength (nm).
    co2_ppm : float, keyword-only
        CO2 content, umol/mol.
    method : str, keyword-only
        Equation, see :func:`refractive_index`.

    Returns
    -------
    dict
        ``refractive_index``, ``n_minus_1_ppm``, ``wavelength_in_air_nm`` and the inputs
        (``method``, ``temperature_c``, ``pressure_pa``, ``humidity_pct``, ``wavelength_nm``,
        ``co2_ppm``): the JSON the command prints.

    Raises
    ------
    AxiscalError
        As :func:`refractive_index`.

    Examples
    --------
    >>> round(air_report(20.0, 101325.0, 0.0, 633.0)["n_minus_1_ppm"], 3)
    271.8
    """
    n = refractive_index(temperature_c, pressure_pa, humidity_pct, wavelength_nm, co2_ppm=co2_ppm, method=method)
    return {
        "refractive_index": n,
        "n_minus_1_ppm": (n - 1.0) / PPM,
        "wavelength_in_air_nm": wavelength_nm / n,
        **air_inputs(temperature_c, pressure_pa, humidity_pct, wavelength_nm, co2_ppm, method),
    }


def air_inputs(temperature_c, pressure_pa, humidity_pct, wavelength_nm, co2_ppm, method) -> dict:
    """The air conditions as a report lists them (``method``, ``temperature_c``, ... ``co2_ppm``).

    Parameters
    ----------
    temperature_c, pressure_pa, humidity_pct, wavelength_nm, co2_ppm : float
        As :func:`refractive_index`.
    method : str
        The equation.

    Returns
    -------
    dict
    """
    check_choice("refractive-index method", method, METHODS)
    for name, value in (("temperature_c", temperature_c), ("pressure_pa", pressure_pa), ("humidity_pct", humidity_pct),
                        ("wavelength_nm", wavelength_nm), ("co2_ppm", co2_ppm)):
        check_number(name, value)
    return {
        "method": method,
        "temperature_c": temperature_c,
        "pressure_pa": pressure_pa,
        "humidity_pct": humidity_pct,
        "wavelength_nm": wavelength_nm,
        "co2_ppm": co2_ppm,
    }


def air_text(report: dict) -> str:
    """The text ``axiscal air`` prints for an :func:`air_report` (template ``instruments/air.txt.j2``).

    Parameters
    ----------
    report : dict
        From :func:`air_report`.

    Returns
    -------
    str
    """
    check_mapping("report", report, ("refractive_index", "n_minus_1_ppm"), what="the dict air_report returns")
    return render_report("instruments/air.txt.j2", r=report)
