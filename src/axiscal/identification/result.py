"""The result of an identification: the identified machine, each unknown with its uncertainty, the residuals and what the data cannot separate.

Results hold numbers; :mod:`axiscal.identification.output` writes them (the machine folder,
``identify.json``) and :mod:`axiscal.identification.plot` draws them for ``identify.html``.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.identification.basis import parse_model
from axiscal.model.machine import Machine
from axiscal.units import ANGLE_UNITS, UM

__all__ = ["Combination", "Undetermined", "Identification"]

_URAD = ANGLE_UNITS["urad"]


@dataclass(frozen=True)
class Combination:
    """A linear combination ``Σ c_k x_k`` of unknowns (SI units), with its value and standard uncertainty when determined.

    Parameters
    ----------
    terms : dict of str to float
        Unknown name to coefficient (the largest is 1).
    value : float or None
        Its estimate (SI units of the terms), None for a combination the data cannot see.
    u : float or None
        Its standard uncertainty.
    """

    terms: dict
    value: float | None = None
    u: float | None = None

    @property
    def text(self) -> str:
        """``"EBX:1 - 0.35 ECY:1"``."""
        parts = []
        for name, c in self.terms.items():
            sign = "-" if c < 0 else "+"
            size = "" if abs(abs(c) - 1.0) < 5e-4 else f"{abs(c):.3g} "
            parts.append(f"{sign} {size}{name}")
        text = " ".join(parts)
        return text[2:] if text.startswith("+ ") else "-" + text[2:]


@dataclass(frozen=True)
class Undetermined:
    """Unknowns the data cannot separate: which they are, the combinations not seen, and those determined instead.

    Parameters
    ----------
    names : tuple of str
        The unknowns tied together.
    hidden : tuple of Combination
        Combinations of them the data cannot see (they keep their starting values).
    determined : tuple of Combination
        Combinations of them the data determine, with value and uncertainty.
    """

    names: tuple
    hidden: tuple
    determined: tuple


@dataclass(frozen=True)
class Identification:
    """What :func:`axiscal.identify` found.

    Parameters
    ----------
    machine : Machine
        The identified machine (its tables over the travel the artefacts covered).
    model : str
        The error functions (``"poly:3"``).
    names : tuple of str
        Every unknown: the machine's terms, then each artefact's own.
    terms : tuple of Term
        The machine's terms (the first ``len(terms)`` of ``names``).
    values : ndarray, shape (P,)
        Estimates, SI units.
    std : ndarray, shape (P,)
        Standard uncertainties, SI; NaN for an unknown the data cannot separate from others.
    covariance_all : ndarray, shape (P, P)
        Covariance of all unknowns (meaningful for determined unknowns and combinations only).
    residuals : dict of str to ndarray
        Residuals of each artefact, metres.
    kinds : dict of str to str
        The kind of each artefact.
    undetermined : tuple of Undetermined
        What the data cannot separate.
    rank : int
        Number of determined combinations.
    condition : float
        Condition number of the determined part of the scaled Jacobian.
    residual_std : float
        Standard deviation of all residuals (unweighted), metres.
    fixed : tuple of str
        Terms kept at their starting values.
    spans : dict of str to (float, float)
        The travel of each identified axis (metres, radians).
    kind_std : dict of str to float
        The residual standard deviation of each kind of artefact, by which its residuals were
        weighted, metres.
    """

    machine: Machine
    model: str
    names: tuple
    terms: tuple
    values: np.ndarray
    std: np.ndarray
    covariance_all: np.ndarray
    residuals: dict
    kinds: dict
    undetermined: tuple
    rank: int
    condition: float
    residual_std: float
    fixed: tuple = ()
    spans: dict = field(default_factory=dict)
    kind_std: dict = field(default_factory=dict)

    @property
    def covariance(self) -> np.ndarray:
        """Covariance of the machine's terms, shape (T, T), SI units (order of :attr:`terms`)."""
        p = len(self.terms)
        return self.covariance_all[:p, :p]

    @property
    def determined(self) -> np.ndarray:
        """Boolean mask (P,) of the unknowns the data determine on their own."""
        return np.isfinite(self.std)

    def value(self, name: str) -> tuple[float, float]:
        """Estimate and standard uncertainty of one unknown.

        Parameters
        ----------
        name : str
            An unknown of :attr:`names` (``"EC0Y"``, ``"EXX:2"``, ``"plate_xy:tz"``).

        Returns
        -------
        (float, float)
            Value and standard uncertainty, SI units; the uncertainty is NaN for an unknown the
            data determine only together with others.

        Raises
        ------
        AxiscalError
            No unknown of that name.
        """
        if name not in self.names:
            raise AxiscalError(f"no unknown named {name!r}; e.g. {', '.join(self.names[:4])}")
        k = self.names.index(name)
        return float(self.values[k]), float(self.std[k])

    def motion_band(self, letter: str, row: int, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """An identified error motion and its standard uncertainty at chosen positions.

        Parameters
        ----------
        letter : str
            An identified axis.
        row : int
            The component, 0 to 5 (tx, ty, tz, ea, eb, ec).
        q : ndarray, shape (N,)
            Positions, metres (radians for a rotary axis).

        Returns
        -------
        value, u : ndarray, shape (N,)
            The motion and its standard uncertainty, metres or radians; the uncertainty is NaN
            where the motion's coefficients are not all determined.
        """
        model = parse_model(self.model)
        a, b = self.spans[letter]
        u = 2.0 * (q - a) / (b - a) - 1.0
        index = [k for k, t in enumerate(self.terms) if t.kind == "motion" and t.letter == letter and t.row == row]
        design = np.column_stack([model.evaluate(self.terms[k].label, u) for k in index]) if index else np.zeros((len(q), 0))
        value = design @ self.values[index] if index else np.zeros(len(q))
        if index and np.all(self.determined[index]):
            band = np.sqrt(np.maximum(np.einsum("ij,jk,ik->i", design, self.covariance_all[np.ix_(index, index)], design), 0.0))
        else:
            band = np.full(len(q), np.nan)
        return value, band

    def summary(self) -> dict:
        """Everything of ``identify.json`` (display units spelled in the keys)."""
        units = {t.name: t.unit for t in self.terms}

        def display(name: str) -> tuple[float, str]:
            """Factor to and name of the display unit: um for lengths, urad for angles (a pose's rx, ry, rz)."""
            angle = units.get(name) == "rad" or (name not in units and name.endswith((":rx", ":ry", ":rz")))
            return (1.0 / _URAD, "urad") if angle else (1.0 / UM, "um")

        parameters = []
        for k, name in enumerate(self.names):
            factor, unit = display(name)
            parameters.append({
                "name": name,
                "machine": k < len(self.terms),
                "value": self.values[k] * factor,
                "u": None if not np.isfinite(self.std[k]) else self.std[k] * factor,
                "unit": unit,
            })
        return {
            "model": self.model,
            "rank": self.rank,
            "unknowns": len(self.names),
            "condition_number": self.condition,
            "residual_std_um": self.residual_std / UM,
            "residual_std_um_by_kind": {k: v / UM for k, v in self.kind_std.items()},
            "fixed": list(self.fixed),
            "travel": {k: list(v) for k, v in self.spans.items()},
            "parameters": parameters,
            "covariance_si": {"names": [t.name for t in self.terms], "matrix": self.covariance.tolist()},
            "residuals": {
                name: {
                    "kind": self.kinds[name],
                    "count": int(r.size),
                    "rms_um": float(np.sqrt(np.mean(r**2))) / UM,
                    "largest_um": float(np.max(np.abs(r))) / UM,
                }
                for name, r in self.residuals.items()
            },
            "undetermined": [
                {
                    "unknowns": list(u.names),
                    "not_determined": [c.text for c in u.hidden],
                    "determined_instead": [{"combination": c.text, "value_si": c.value, "u_si": c.u} for c in u.determined],
                }
                for u in self.undetermined
            ],
        }

    def write(self, folder: str | Path) -> dict:
        """Write the machine folder, ``identify.json`` and ``identify.html`` (see :func:`axiscal.identification.write_identification`)."""
        from axiscal.identification.output import write_identification

        return write_identification(self, folder)

    def report(self) -> str:
        """The HTML report as text (figures referred to by file name; :meth:`write` writes them)."""
        from axiscal.identification.output import report_html

        return report_html(self)
