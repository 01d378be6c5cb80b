"""Laser interferometer lengths: fringe counts, environmental and material compensation, set-up errors.

Paper 003 (Zhang, Huang and Wang 2008, "Errors analysis of interferometry and accuracy measurement
for NC machine tools"):

- eq (1): ``L = N lambda / (2 m n)``, the displacement from the fringe count ``N``; ``lambda`` is the
  wavelength in air, i.e. the vacuum wavelength divided by the refractive index of air
  (:mod:`axiscal.instruments.air`); ``m`` the optical fold (passes of the measuring beam) and, in the paper's
  notation, ``n`` the electronic interpolation of the fringe counter;
- section 2.1, eqs (2)-(3) and Table 1: the cosine (collimation) error; the laser reads the
  projection of the motion on the beam, short by ``L (1 - cos a)``;
- section 2.2, eq (6) and Table 3: the Abbe error, arm times angle;
- the dead-path error and the normalisation of a length to 20 degC (ISO 1:2016,
  ``L20 = Lt / (1 + alpha (t - 20))``), which every laser calibration applies.

The paper fits polynomials and line families to Tables 1 and 3 (eqs 4-5, 7-18); this module uses
the exact relations instead (see docs/interferometry.md).  All lengths in metres, angles in
radians, temperatures in degC, pressures in Pa.
"""

from __future__ import annotations

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.instruments.air import air_inputs, refractive_index
from axiscal.instruments.reports import render_report
from axiscal.io.arguments import check_array, check_broadcast, check_count, check_mapping, check_number
from axiscal.materials import STEEL_EXPANSION_PER_K
from axiscal.units import MM, NM

__all__ = [
    "fringe_report",
    "fringe_text",
    "HENE_WAVELENGTH_NM",
    "REFERENCE_TEMPERATURE_C",
    "length_from_fringes",
    "fringes_from_length",
    "normalise_to_20c",
    "compensated_length",
    "dead_path_error",
    "cosine_error",
    "misalignment_for_cosine_error",
    "abbe_error",
]

#: nominal vacuum wavelength of a stabilised He-Ne laser, nm
HENE_WAVELENGTH_NM = 632.991
#: ISO 1 reference temperature, degC
REFERENCE_TEMPERATURE_C = 20.0


def _finite(name: str, values) -> np.ndarray:
    array = check_array(name, values, finite=False)
    if not np.all(np.isfinite(array)):
        raise AxiscalError(f"{name} is not a finite number")
    return array


def _mean_material_temperature(material_temperature_c) -> np.ndarray:
    temperatures = _finite("material_temperature_c", material_temperature_c)
    if np.any(temperatures <= -273.15):
        raise AxiscalError("material_temperature_c below absolute zero is not a temperature in degC")
    if temperatures.size == 0:
        raise AxiscalError("material_temperature_c holds no temperature")
    if temperatures.ndim > 2:
        raise AxiscalError(
            f"material temperatures must have shape (n,) or (n, k) for k sensors, got {temperatures.ndim} dimensions"
        )
    if temperatures.ndim == 2:
        if temperatures.shape[1] == 0:
            raise AxiscalError("material temperatures need at least one sensor per reading")
        return temperatures.mean(axis=1)
    return temperatures


def length_from_fringes(
    counts,
    *,
    wavelength_nm=HENE_WAVELENGTH_NM,
    index_of_air=1.0,
    optical_fold: int = 1,
    interpolation: int = 1,
) -> np.ndarray:
    """Displacement from a fringe count, paper 003 eq (1), in metres.

    ``L = N lambda0 / (2 m k n_air)``: a count ``N`` of ``1/k`` fringes, measuring beam folded ``m``
    times (1 for a linear retroreflector set-up, 2 for a plane-mirror interferometer), vacuum
    wavelength ``lambda0`` and refractive index ``n_air``.

    Parameters
    ----------
    counts : float or array_like
        Counter value N (fringes times ``interpolation``).
    wavelength_nm : float or array_like, nm, keyword-only
        Vacuum wavelength, default 632.991 nm (He-Ne).
    index_of_air : float or array_like, keyword-only
        Refractive index of the air in the beam (default 1: the reading of an uncompensated
        laser); compute it with :func:`axiscal.instruments.air.refractive_index`.
    optical_fold : int, keyword-only
        m, passes of the measuring beam (default 1).
    interpolation : int, keyword-only
        k, the counter's electronic subdivision of one fringe (the paper's ``n``; default 1).

    Returns
    -------
    ndarray, metres
        Broadcast shape of the inputs.
    """
    optical_fold = check_count("optical_fold", optical_fold)
    interpolation = check_count("interpolation", interpolation)
    index = _finite("index_of_air (refractive index of air)", index_of_air)
    if np.any(index < 1.0):
        raise AxiscalError("index_of_air (refractive index of air) below 1 is not physical")
    wavelength = _finite("wavelength_nm", wavelength_nm)
    if np.any(wavelength <= 0.0):
        raise AxiscalError("wavelength_nm must be a positive number of nanometres")
    n, index, wavelength = check_broadcast(counts=_finite("counts (fringe count)", counts), index_of_air=index, wavelength_nm=wavelength)
    return n * wavelength * NM / (2.0 * optical_fold * interpolation * index)


def fringes_from_length(
    length_m,
    *,
    wavelength_nm=HENE_WAVELENGTH_NM,
    index_of_air=1.0,
    optical_fold: int = 1,
    interpolation: int = 1,
) -> np.ndarray:
    """Inverse of :func:`length_from_fringes`: the (fractional) count that a displacement produces.

    Parameters
    ----------
    length_m : float or array_like
        Displacement, metres.
    wavelength_nm, index_of_air, optical_fold, interpolation : keyword-only
        As :func:`length_from_fringes`.

    Returns
    -------
    ndarray
        Counter value N.
    """
    unit = length_from_fringes(
        1.0, wavelength_nm=wavelength_nm, index_of_air=index_of_air, optical_fold=optical_fold, interpolation=interpolation
    )
    length, unit = check_broadcast(length_m=_finite("length_m", length_m), wavelength_nm=unit)
    return length / unit


def normalise_to_20c(length_m, material_temperature_c, *, expansion_per_k=STEEL_EXPANSION_PER_K) -> np.ndarray:
    """Length of a part at the ISO 1 reference temperature of 20 degC, in metres.

    ``L20 = Lt / (1 + alpha (t - 20))``.

    Parameters
    ----------
    length_m : float or array_like, shape (n,) or broadcastable, metres
        Length measured with the material at temperature t.
    material_temperature_c : float or array_like, shape (n,) or (n, k), degC
        Material temperature; with shape (n, k) the k sensor readings of each row are averaged.
    expansion_per_k : float or array_like, 1/K, keyword-only
        Linear expansion coefficient alpha; default 11.5e-6 (steel).

    Returns
    -------
    ndarray, metres
    """
    temperature = _mean_material_temperature(material_temperature_c)
    alpha = _finite("expansion_per_k (expansion coefficient)", expansion_per_k)
    if np.any(np.abs(alpha) >= 1e-3):
        raise AxiscalError("expansion_per_k must be a coefficient per kelvin below 1e-3 (steel: 11.5e-6)")
    length, temperature, alpha = check_broadcast(
        length_m=_finite("length_m", length_m), material_temperature_c=temperature, expansion_per_k=alpha
    )
    return length / (1.0 + alpha * (temperature - REFERENCE_TEMPERATURE_C))


def compensated_length(
    reading_m,
    *,
    air_temperature_c,
    pressure_pa,
    humidity_pct,
    material_temperature_c=None,
    expansion_per_k=STEEL_EXPANSION_PER_K,
    wavelength_nm=HENE_WAVELENGTH_NM,
    co2_ppm=450.0,
    method: str = "ciddor",
) -> np.ndarray:
    """Length from a raw laser reading, corrected for the air and normalised to 20 degC.

    The raw reading is what the counter gives with the vacuum wavelength (index 1). The true
    length in air is ``reading / n`` (paper 003 eq 1 with lambda = lambda0 / n); if a material
    temperature is given, the result is then normalised to 20 degC (ISO 1):
    ``L20 = reading / (n (1 + alpha (t_material - 20)))``.

    Parameters
    ----------
    reading_m : float or array_like, shape (n,), metres
        Raw reading computed with index 1.
    air_temperature_c, pressure_pa, humidity_pct : float or array_like, keyword-only
        Air temperature (degC), pressure (Pa) and relative humidity (%) along the beam, scalars
        or one value per reading.
    material_temperature_c : None, float or array_like, shape (n,) or (n, k), degC, keyword-only
        Temperature of the machine's scale or workpiece; rows of k sensors are averaged.
        ``None`` (default): no material normalisation.
    expansion_per_k : float, 1/K, keyword-only
        Expansion coefficient of the material (default 11.5e-6, steel).
    wavelength_nm : float, nm, keyword-only
        Vacuum wavelength (default 632.991 nm).
    co2_ppm : float, umol/mol, keyword-only
        CO2 content (default 450).
    method : str, keyword-only
        Refractive-index equation, see :func:`axiscal.instruments.air.refractive_index` (default "ciddor").

    Returns
    -------
    ndarray, metres
        Broadcast shape of the inputs (the sensor axis of a 2-D material temperature removed).
    """
    reading = _finite("reading_m (laser reading)", reading_m)
    index = refractive_index(air_temperature_c, pressure_pa, humidity_pct, wavelength_nm, co2_ppm=co2_ppm, method=method)
    try:
        length = reading / np.asarray(index)
        if material_temperature_c is not None:
            length = normalise_to_20c(length, material_temperature_c, expansion_per_k=expansion_per_k)
    except ValueError as exc:
        if isinstance(exc, AxiscalError):
            raise
        raise AxiscalError(f"laser readings and environment values do not match in shape: {exc}") from None
    return np.asarray(length)


def dead_path_error(dead_path_m, *, index_at_datum, index_now) -> np.ndarray:
    """Dead-path error: what a change of air index over the unmeasured path adds to a reading, metres.

    With the reflector at distance D from the interferometer when the counter was zeroed (index
    ``n0``) and a compensation that divides by the present index ``n1``, the reading exceeds the
    true displacement by ``D (n1 - n0) / n1``. Subtract it from the reading to correct.

    Parameters
    ----------
    dead_path_m : float or array_like, metres
        Distance interferometer-reflector at the datum.
    index_at_datum, index_now : float or array_like, keyword-only
        Refractive index of air when the counter was zeroed and now.

    Returns
    -------
    ndarray, metres
    """
    n0 = _finite("index_at_datum", index_at_datum)
    n1 = _finite("index_now", index_now)
    for name, index in (("index_at_datum", n0), ("index_now", n1)):
        if np.any(index < 1.0):
            raise AxiscalError(f"{name} (a refractive index of air) below 1 is not physical")
    dead, n0, n1 = check_broadcast(dead_path_m=_finite("dead_path_m", dead_path_m), index_at_datum=n0, index_now=n1)
    return dead * (n1 - n0) / n1


def cosine_error(length_m, misalignment_rad) -> np.ndarray:
    """Cosine (collimation) error, paper 003 eqs (2)-(3): ``L (1 - cos a)``, metres.

    The beam at angle ``a`` to the motion sees the projection ``L cos a`` of a motion ``L``: the
    laser reads short by the returned amount (positive). Add it to the reading to correct.

    Parameters
    ----------
    length_m : float or array_like, metres
        True displacement along the axis.
    misalignment_rad : float or array_like, rad
        Angle between beam and motion.

    Returns
    -------
    ndarray
        How much the laser reads short, metres (broadcast shape of the inputs).

    Raises
    ------
    AxiscalError
        If an input is not finite.

    Examples
    --------
    >>> round(float(cosine_error(1.0, 1e-3)) * 1e9, 3)  # 1 m at 1 mrad: 0.5 um
    500.0
    """
    length, angle = check_broadcast(
        length_m=_finite("length_m", length_m), misalignment_rad=_finite("misalignment_rad", misalignment_rad)
    )
    return length * 2.0 * np.sin(angle / 2.0) ** 2


def misalignment_for_cosine_error(relative_error) -> np.ndarray:
    """Beam misalignment that gives a relative cosine error ``e = 1 - cos a``, radians.

    The inverse of :func:`cosine_error` per unit length: ``a = 2 asin(sqrt(e / 2))``. Use it to set
    an alignment tolerance from an error budget (0.1 ppm: 1.54 arc minutes).

    Parameters
    ----------
    relative_error : float or array_like, dimensionless
        Cosine error as a fraction of the length (1e-6 for 1 ppm), 0 to 2.

    Returns
    -------
    ndarray
        Misalignment angle, radians.

    Raises
    ------
    AxiscalError
        If the error is not finite or outside 0 to 2.
    """
    error = _finite("relative_error (relative cosine error)", relative_error)
    if np.any((error < 0.0) | (error > 2.0)):
        raise AxiscalError("relative_error: a relative cosine error lies between 0 and 2")
    return 2.0 * np.arcsin(np.sqrt(error / 2.0))


def abbe_error(arm_m, angle_rad) -> np.ndarray:
    """Abbe error, paper 003 eq (6) with k = 1: offset of the measuring line times the rotation, metres.

    A carriage that turns by ``angle`` (pitch or yaw) moves a point at perpendicular distance
    ``arm`` from the measuring line by ``arm * sin(angle)`` along the line; to first order that is
    ``arm * angle`` (1 arcsec at 100 mm: 0.485 um). The sign is that of the product; which way the
    point moves depends on the geometry (a rotation eps about +Z moves a point at +h on Y by
    ``-h sin(eps)`` along X). For three-dimensional offsets use the vector form in
    :mod:`axiscal.instruments.abbe`.

    Parameters
    ----------
    arm_m : float or array_like, metres
        Abbe offset between the beam and the line of interest.
    angle_rad : float or array_like, rad
        Angular error motion of the carriage.

    Returns
    -------
    ndarray
        The Abbe error, metres.

    Raises
    ------
    AxiscalError
        If an input is not finite.
    """
    arm, angle = check_broadcast(arm_m=_finite("arm_m (Abbe arm)", arm_m), angle_rad=_finite("angle_rad", angle_rad))
    return arm * np.sin(angle)


def fringe_report(
    counts: float,
    *,
    optical_fold: int = 1,
    interpolation: int = 1,
    temperature_c: float,
    pressure_pa: float,
    humidity_pct: float,
    wavelength_nm: float = HENE_WAVELENGTH_NM,
    co2_ppm: float = 450.0,
    method: str = "ciddor",
    material_temperature_c=(),
    expansion_per_k: float = STEEL_EXPANSION_PER_K,
) -> dict:
    """A length from a fringe count (paper 003 eq 1), in air and at 20 degC, as ``axiscal fringes`` shows it.

    Parameters
    ----------
    counts : float
        Counter value N (fringes times ``interpolation``).
    optical_fold, interpolation : int, keyword-only
        Passes of the measuring beam and counts per fringe.
    temperature_c, pressure_pa, humidity_pct : float, keyword-only
        Air temperature (degC), pressure (Pa) and relative humidity (%).
    wavelength_nm, co2_ppm, method : keyword-only
        Vacuum wavelength (nm), CO2 (umol/mol) and refractive-index equation.
    material_temperature_c : sequence of float, keyword-only
        Material temperatures, degC (averaged); empty: no normalisation to 20 degC.
    expansion_per_k : float, keyword-only
        Material expansion coefficient, 1/K.

    Returns
    -------
    dict
        ``counts``, ``optical_fold``, ``interpolation``, ``refractive_index``,
        ``vacuum_length_mm``, ``length_in_air_mm``, ``length_at_20c_mm`` (None without material
        temperatures), ``material_temperature_c``, ``expansion_per_k`` and the air conditions:
        the JSON the command prints.

    Raises
    ------
    AxiscalError
        For values :func:`length_from_fringes` or :func:`compensated_length` refuse.
    """
    check_number("counts", counts)
    if isinstance(material_temperature_c, (str, bytes)) or not hasattr(material_temperature_c, "__iter__"):
        raise AxiscalError(f"material_temperature_c must be a sequence of temperatures in degC, not {material_temperature_c!r}")
    vacuum = float(length_from_fringes(counts, wavelength_nm=wavelength_nm, optical_fold=optical_fold, interpolation=interpolation))
    air = dict(air_temperature_c=temperature_c, pressure_pa=pressure_pa, humidity_pct=humidity_pct, wavelength_nm=wavelength_nm, co2_ppm=co2_ppm, method=method)
    in_air = float(compensated_length(vacuum, **air))
    material = [float(t) for t in material_temperature_c]
    at_20c = float(compensated_length(vacuum, material_temperature_c=[material], expansion_per_k=expansion_per_k, **air)[0]) if material else None
    return {
        "counts": counts,
        "optical_fold": optical_fold,
        "interpolation": interpolation,
        "refractive_index": refractive_index(temperature_c, pressure_pa, humidity_pct, wavelength_nm, co2_ppm=co2_ppm, method=method),
        "vacuum_length_mm": vacuum / MM,
        "length_in_air_mm": in_air / MM,
        "length_at_20c_mm": None if at_20c is None else at_20c / MM,
        "material_temperature_c": material,
        "expansion_per_k": expansion_per_k,
        **air_inputs(temperature_c, pressure_pa, humidity_pct, wavelength_nm, co2_ppm, method),
    }


def fringe_text(report: dict) -> str:
    """The text ``axiscal fringes`` prints for a :func:`fringe_report` (template ``instruments/fringes.txt.j2``).

    Parameters
    ----------
    report : dict
        From :func:`fringe_report`.

    Returns
    -------
    str
    """
    check_mapping("report", report, ("material_temperature_c", "length_in_air_mm"), what="the dict fringe_report returns")
    material = report["material_temperature_c"]
    mean = sum(material) / len(material) if material else None
    return render_report("instruments/fringes.txt.j2", r=report, mean_material_c=mean)
