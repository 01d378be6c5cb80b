"""Names and units of measured results at the edge: SI inside, um / mm / urad in files and on screen.

:meth:`axiscal.measurement.pipeline.MeasurementSystem.process` returns SI columns named with
their unit: the six errors per axis ``EXX_m`` .. ``ECX_rad``, the scale positions ``x_m``, the
spatial error ``ex_m`` .. ``e_m`` and the corrected point ``px_m`` .. ``pz_m``. Files, the CLI and
the dashboard show the same values as ``EXX_um``, ``ECX_urad``, ``x_mm``, ``ex_um``, ``px_mm``:
error translations in micrometres, positions in millimetres, angles in microradians. This module
is the one place that maps one onto the other.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_mapping
from axiscal.units import MM, UM, URAD

__all__ = ["display_name", "display_factor", "to_display"]

def _split(name: str) -> tuple[str, str, float]:
    """(stem, display unit, SI per display unit) of an SI result name, or the name unchanged."""
    if not isinstance(name, str):
        raise AxiscalError(f"name must be a result name such as 'ex_m', not {name!r}")
    if name.endswith("_rad"):
        return name[: -len("_rad")], "urad", URAD
    if name.endswith("_m"):
        stem = name[: -len("_m")]
        # error translations (EXX, ex, e) in um; positions (x, x_cmd, px) in mm
        return (stem, "um", UM) if stem[:1] in ("E", "e") else (stem, "mm", MM)
    return name, "", 1.0


def display_name(name: str) -> str:
    """The display name of an SI result column.

    Parameters
    ----------
    name : str
        A result name as :meth:`MeasurementSystem.process` gives it (``"ex_m"``, ``"EAX_rad"``,
        ``"x_m"``); names without ``_m`` or ``_rad`` (``"t_s"``, ``"fault"``) stay as they are.

    Returns
    -------
    str
        ``"ex_um"``, ``"EAX_urad"``, ``"x_mm"``, ...

    Examples
    --------
    >>> display_name("EXX_m"), display_name("px_m"), display_name("EBZ_rad"), display_name("t_s")
    ('EXX_um', 'px_mm', 'EBZ_urad', 't_s')
    """
    stem, unit, _ = _split(name)
    return f"{stem}_{unit}" if unit else name


def display_factor(name: str) -> float:
    """SI units per display unit of result ``name`` (divide the SI value by it); 1 for other names.

    Parameters
    ----------
    name : str
        SI result name.

    Returns
    -------
    float

    Examples
    --------
    >>> display_factor("ex_m") == 1e-6, display_factor("x_m") == 1e-3
    (True, True)
    """
    return _split(name)[2]


def to_display(results: Mapping[str, np.ndarray]) -> dict[str, np.ndarray]:
    """SI result columns converted to their display names and units.

    Parameters
    ----------
    results : mapping of str to ndarray
        Columns named as :func:`display_name` expects (SI).

    Returns
    -------
    dict of str to ndarray
        The same columns, in the same order, renamed and scaled (``t_s`` and ``fault`` unchanged).

    Raises
    ------
    AxiscalError
        If two columns would get the same display name.

    Examples
    --------
    >>> import numpy as np
    >>> to_display({"t_s": np.array([0.5]), "ex_m": np.array([2e-6])})
    {'t_s': array([0.5]), 'ex_um': array([2.])}
    """
    check_mapping("results", results, what="a mapping of result names to arrays")
    out: dict[str, np.ndarray] = {}
    for name, value in results.items():
        stem, unit, factor = _split(name)
        check_array(f"results['{name}']", value, finite=False)  # NaN: a faulty frame's result
        shown = f"{stem}_{unit}" if unit else name
        if shown in out:
            raise AxiscalError(f"result columns '{name}' and another both show as '{shown}'")
        out[shown] = np.asarray(value) / factor if unit else value
    return out
