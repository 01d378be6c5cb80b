"""Uncertainty budget files declared: four tables of numbers, each with its physical range.

The same tables may stand in campaign.toml's ``[uncertainty]``; there the campaign's model
inherits them (:class:`BudgetTables`).
"""

from __future__ import annotations

from typing import Any

from pydantic import Field, create_model

from axiscal.io.formats.base import FormatModel, Number, Text

__all__ = ["BUDGET_KEYS", "BUDGET_RANGES", "BUDGET_WORDS", "BudgetTables", "BudgetFile"]

#: what each key of a budget file is, per section (its unit is in its name; ``_U``: expanded, k = 2)
BUDGET_WORDS: dict[str, dict[str, str]] = {
    "instrument": {
        "length_U_ppm": "laser certificate: expanded uncertainty of a length reading, relative",
        "straightness_U_um": "straightness optics: expanded uncertainty of one reading",
        "wavelength_nm": "vacuum wavelength of the laser (default He-Ne, 632.991 nm)",
        "method": "refractive-index equation: ciddor (default), edlen, edlen1966 or shopfloor",
    },
    "air": {
        "temperature_u_K": "standard uncertainty of the air temperature sensor",
        "pressure_u_Pa": "standard uncertainty of the pressure sensor",
        "humidity_u_percent": "standard uncertainty of the humidity sensor",
        "temperature_C": "air temperature the sensitivities are taken at (default 20)",
        "pressure_Pa": "air pressure the sensitivities are taken at (default 101325)",
        "humidity_percent": "relative humidity the sensitivities are taken at (default 50)",
    },
    "machine": {
        "temperature_C": "mean machine (scale) temperature during the test (default 20)",
        "temperature_u_K": "standard uncertainty of that temperature",
        "expansion_per_K": "expansion coefficient used to normalise to 20 degC",
        "expansion_u_per_K": "its standard uncertainty",
    },
    "setup": {
        "misalignment_urad": "bound of the beam-to-axis angle (rectangular): cosine error",
        "eve_um": "environmental variation error from the drift test (full range)",
        "prism_deviation_u_arcsec": "squareness: uncertainty of the pentaprism's deviation from 90 degrees",
    },
}
#: the keys a budget file may hold, per section (docs/uncertainty.md)
BUDGET_KEYS: dict[str, tuple[str, ...]] = {section: tuple(words) for section, words in BUDGET_WORDS.items()}

#: the physical range of each number of a budget file, in the file's units (both ends allowed); a value
#: beyond it is a typing or unit mistake (a budget of 1e300 um), refused before any sum is formed.
#: The air conditions and the wavelength are bounded by the refractive-index equation itself.
BUDGET_RANGES: dict[tuple[str, str], tuple[float, float]] = {
    ("instrument", "length_U_ppm"): (0.0, 1000.0),
    ("instrument", "straightness_U_um"): (0.0, 1000.0),
    ("air", "temperature_u_K"): (0.0, 50.0),
    ("air", "pressure_u_Pa"): (0.0, 10000.0),
    ("air", "humidity_u_percent"): (0.0, 100.0),
    ("machine", "temperature_C"): (-50.0, 150.0),
    ("machine", "temperature_u_K"): (0.0, 50.0),
    ("machine", "expansion_per_K"): (-1e-3, 1e-3),
    ("machine", "expansion_u_per_K"): (0.0, 1e-3),
    ("setup", "misalignment_urad"): (0.0, 1e5),
    ("setup", "eve_um"): (0.0, 10000.0),
    ("setup", "prism_deviation_u_arcsec"): (0.0, 3600.0),
}


def _section(section: str) -> type[FormatModel]:
    fields: dict[str, Any] = {}
    for key, words in BUDGET_WORDS[section].items():
        if key == "method":
            fields[key] = (Text | None, Field(None, description=words))
            continue
        low, high = BUDGET_RANGES.get((section, key), (None, None))
        fields[key] = (Number | None, Field(None, ge=low, le=high, description=words))
    return create_model(f"Budget{section.title()}", __base__=FormatModel,
                        __doc__=f"The ``[{section}]`` table of a budget.", **fields)


_SECTIONS = {section: _section(section) for section in BUDGET_WORDS}

BudgetTables = create_model(
    "BudgetTables",
    __base__=FormatModel,
    __doc__="""The tables of a budget: ``[instrument]``, ``[air]``, ``[machine]``, ``[setup]``.

    Attributes
    ----------
    instrument, air, machine, setup : FormatModel or None
        A missing table or key is a zero contribution.
    """,
    **{section: (model | None, Field(None, description=f"the [{section}] table")) for section, model in _SECTIONS.items()},
)


class BudgetFile(BudgetTables):  # type: ignore[misc, valid-type]
    """A budget file (TOML, docs/uncertainty.md).

    Attributes
    ----------
    instrument, air, machine, setup : FormatModel or None
    """
