"""The unknowns of an identification and the machine they describe, through the model's own forward kinematics.

The parameter vector θ holds, for every axis the artefacts move, the coefficients of its error
motions in the chosen error functions (:mod:`axiscal.identification.basis`), the squareness terms
``EC0Y, EB0Z, EA0Z`` of the linear axes and the location errors of the rotary axes (ISO 230-7).
Given θ, the error motions at any axis positions are ``f(q) = Σ θ_k φ_k(u(q))`` and the volumetric
error is :meth:`axiscal.model.Machine.volumetric_error` of the machine with those squareness and
location terms, fed those error motions: there is no second kinematics.

To first order the volumetric error is linear in θ. Its Jacobian is built by linearity, one
perturbed basis function per column, all columns evaluated in one batch through the same forward
model (the points repeated once per column).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterable, Mapping
from dataclasses import dataclass

import numpy as np

from axiscal.conventions import AXIS_INDEX, PLANES, ROTARY_LETTERS, component_names, location_names
from axiscal.errors import AxiscalError
from axiscal.identification.basis import ErrorModel
from axiscal.model.machine import Axis, Machine
from axiscal.model.tables import ErrorTable

__all__ = ["Term", "ParameterSet", "STEP"]

#: the step of a perturbed column (metres or radians): small against the errors, large against rounding
STEP = 1e-6
#: most points evaluated in one batch of the Jacobian
_BATCH_POINTS = 65536
#: a travel shorter than this (metres or radians) does not move the axis
_MIN_SPAN = 1e-6


@dataclass(frozen=True)
class Term:
    """One unknown of the machine.

    Parameters
    ----------
    name : str
        ``"EXX:2"`` (coefficient 2 of EXX), ``"EC0Y"`` (squareness), ``"EX0C"`` (location).
    kind : {"motion", "squareness", "location"}
        What it is.
    letter : str
        The axis of a motion or location term; the turned axis of a squareness term.
    row : int
        The component (0 to 5: tx, ty, tz, ea, eb, ec) of a motion term; -1 otherwise.
    label : int
        The degree or knot of a motion term; 0 otherwise.
    unit : {"m", "rad"}
        The SI unit of its value.
    """

    name: str
    kind: str
    letter: str
    row: int = -1
    label: int = 0
    unit: str = "m"

    @property
    def component(self) -> str:
        """The ISO 230-1 name of the error the term belongs to (``EXX``, ``EC0Y``, ``EX0C``)."""
        return self.name.partition(":")[0]


def _straightness(letter: str, row: int) -> bool:
    return letter in AXIS_INDEX and row < 3 and row != AXIS_INDEX[letter]


class ParameterSet:
    """The free terms of a machine under an error model, and the machine any values of them describe.

    Parameters
    ----------
    machine : Machine
        The chain and the starting guess (its tables, squareness and location terms).
    model : ErrorModel
        The error functions.
    spans : mapping of str to (float, float)
        The travel of each axis the artefacts move (metres, radians for rotary axes).
    fix : iterable of str
        Terms kept at their starting value: a term (``"EBX:2"``), an error (``"EBX"``, ``"EC0Y"``,
        ``"EX0C"``), an axis letter (its six error motions), ``"squareness"`` or ``"location"``.

    Raises
    ------
    AxiscalError
        A fixed term that names nothing of this machine.
    """

    def __init__(self, machine: Machine, model: ErrorModel, spans: Mapping[str, tuple[float, float]], fix: Iterable[str] = ()):
        self.base = machine
        self.model = model
        self.spans = {k: (float(a), float(b)) for k, (a, b) in spans.items() if k in machine.letters and b - a > _MIN_SPAN}
        candidates: list[Term] = []
        for letter in machine.letters:
            if letter not in self.spans:
                continue
            for row, name in enumerate(component_names(letter)):
                for label in model.labels(straightness=_straightness(letter, row)):
                    candidates.append(Term(f"{name}:{label}", "motion", letter, row, label, "m" if row < 3 else "rad"))
        for reference, turned, term, _ in PLANES.values():
            if turned in machine.letters and reference in machine.letters:
                candidates.append(Term(term, "squareness", turned, unit="rad"))
        for letter in machine.rotary:
            for name in location_names(letter):
                candidates.append(Term(name, "location", letter, unit="m" if name[1] in AXIS_INDEX else "rad"))
        fixed = set()
        for word in fix:
            if not isinstance(word, str):
                raise AxiscalError(f"a fixed term is a name such as 'EBX:2', 'EBX', 'X' or 'squareness', not {word!r:.40}")
            hit = {t.name for t in candidates if word in (t.name, t.component, t.kind) or (t.kind == "motion" and word == t.letter)}
            known = {"squareness", "location", *machine.letters, *(n for k in machine.letters for n in component_names(k))}
            known |= {term for _, _, term, _ in PLANES.values()} | {n for k in machine.rotary for n in location_names(k)}
            if not hit and word not in known:  # an axis or error the artefacts leave alone has nothing to fix
                raise AxiscalError(
                    f"fix {word}: no such free term of chain '{machine.chain}' under {model.text} "
                    "(use a term such as EBX:2, an error such as EBX or EC0Y, an axis letter, squareness or location)"
                )
            fixed |= hit
        self.terms = tuple(t for t in candidates if t.name not in fixed)
        self.fixed = tuple(sorted(fixed))
        self._free_components = {(t.letter, t.row) for t in self.terms if t.kind == "motion"}

    @property
    def names(self) -> tuple[str, ...]:
        """The names of the free terms, in the order of θ."""
        return tuple(t.name for t in self.terms)

    def normalised(self, letter: str, q: np.ndarray) -> np.ndarray:
        """Positions of axis ``letter`` as ``u`` (-1 at the start of its travel, 1 at its end)."""
        a, b = self.spans[letter]
        return 2.0 * (q - a) / (b - a) - 1.0

    def start(self) -> np.ndarray:
        """θ of the starting guess: the machine's tables projected on the error functions (least squares).

        Returns
        -------
        ndarray, shape (P,)
        """
        theta = np.zeros(len(self.terms))
        for k, term in enumerate(self.terms):
            if term.kind == "squareness":
                theta[k] = self.base.squareness_rad.get(term.name, 0.0)
            elif term.kind == "location":
                theta[k] = self.base.location.get(term.name, 0.0)
        for letter, row in self._free_components:
            a, b = self.spans[letter]
            q = np.linspace(a, b, 201)
            values = self._table_values(letter, q)[row] - self._table_values(letter, np.array([a]))[row, 0]
            index = [k for k, t in enumerate(self.terms) if t.kind == "motion" and (t.letter, t.row) == (letter, row)]
            design = np.column_stack([self.model.evaluate(self.terms[k].label, self.normalised(letter, q)) for k in index])
            theta[index] = np.linalg.lstsq(design, values, rcond=None)[0]
        return theta

    def _table_values(self, letter: str, q: np.ndarray) -> np.ndarray:
        """The starting table of axis ``letter`` at q, holding its ends (6, N)."""
        table = self.base.table(letter)
        if not table.periodic:
            q = np.clip(q, table.start_m, table.end_m)
        return table.evaluate(q)

    def motions(self, theta: np.ndarray, positions: Mapping[str, np.ndarray]) -> dict[str, np.ndarray]:
        """Error motions (6, N) of every axis at ``positions`` for the values ``theta``."""
        out = {}
        for letter in self.base.letters:
            q = positions[letter]
            values = self._table_values(letter, q).copy()
            for row in range(6):
                if (letter, row) in self._free_components:
                    values[row] = 0.0
            out[letter] = values
        for k, term in enumerate(self.terms):
            if term.kind == "motion":
                out[term.letter][term.row] += theta[k] * self.model.evaluate(term.label, self.normalised(term.letter, positions[term.letter]))
        return out

    def machine(self, theta: np.ndarray, *, tool_m: np.ndarray | None = None) -> Machine:
        """The starting machine with the squareness and location terms of ``theta`` (tables unchanged)."""
        squareness = dict(self.base.squareness_rad)
        location = dict(self.base.location)
        for k, term in enumerate(self.terms):
            if term.kind == "squareness":
                squareness[term.name] = float(theta[k])
            elif term.kind == "location":
                location[term.name] = float(theta[k])
        tool = self.base.tool_m if tool_m is None else tuple(float(v) for v in tool_m)
        return dataclasses.replace(self.base, squareness_rad=squareness, location=location, tool_m=tool)

    def errors(self, theta: np.ndarray, positions: Mapping[str, np.ndarray], tool_m: np.ndarray) -> np.ndarray:
        """Volumetric error (N, 3), metres, of the machine ``theta`` describes, at ``positions``."""
        return self.machine(theta, tool_m=tool_m).volumetric_error(positions, errors=self.motions(theta, positions), workers=1)

    def jacobian(self, theta: np.ndarray, positions: Mapping[str, np.ndarray], tool_m: np.ndarray) -> np.ndarray:
        """d(volumetric error)/dθ at ``positions``, shape (N, 3, P): central differences of perturbed columns through the forward model.

        Central differences: the model's second-order terms (a rotation applied to itself) cancel,
        so a column is exact to ``STEP²`` and a combination the data cannot see has a singular
        value at rounding level, not at ``STEP``.
        """
        n = len(next(iter(positions.values())))
        out = np.empty((n, 3, len(self.terms)))
        motion = [k for k, t in enumerate(self.terms) if t.kind == "motion"]
        machine = self.machine(theta, tool_m=tool_m)
        motions = self.motions(theta, positions)
        per_batch = max(1, _BATCH_POINTS // max(2 * n, 1))
        for first in range(0, len(motion), per_batch):
            group = motion[first : first + per_batch]
            tiled = {k: np.tile(v, 2 * len(group)) for k, v in positions.items()}
            given = {k: np.tile(v, (1, 2 * len(group))) for k, v in motions.items()}
            for block, k in enumerate(group):
                term = self.terms[k]
                shift = STEP * self.model.evaluate(term.label, self.normalised(term.letter, positions[term.letter]))
                given[term.letter][term.row, 2 * block * n : (2 * block + 1) * n] += shift
                given[term.letter][term.row, (2 * block + 1) * n : (2 * block + 2) * n] -= shift
            moved = machine.volumetric_error(tiled, errors=given, workers=1).reshape(len(group), 2, n, 3)
            out[:, :, group] = np.moveaxis((moved[:, 0] - moved[:, 1]) / (2 * STEP), 0, -1)
        for k, term in enumerate(self.terms):
            if term.kind != "motion":
                step = np.zeros(len(self.terms))
                step[k] = STEP
                plus, minus = self.errors(theta + step, positions, tool_m), self.errors(theta - step, positions, tool_m)
                out[:, :, k] = (plus - minus) / (2 * STEP)
        return out

    def identified_machine(self, theta: np.ndarray) -> Machine:
        """The machine of ``theta`` with its error motions written as tables over each axis' travel.

        Axes the artefacts do not move, or whose motions are all fixed, keep their starting tables. A rotary axis' table covers the
        angles measured and is not periodic unless they span a full turn.
        """
        machine = self.machine(theta)
        axes = {}
        for letter in machine.letters:
            old = machine.axes[letter]
            if letter not in self.spans or not any((letter, row) in self._free_components for row in range(6)):
                axes[letter] = old
                continue
            a, b = self.spans[letter]
            q = self.model.table_positions(a, b)
            values = self.motions(theta, {k: q for k in machine.letters})[letter]
            rotary = letter in ROTARY_LETTERS
            interpolation = "linear" if self.model.kind == "spline" or rotary else "cubic"
            table = ErrorTable(letter, q, values, interpolation=interpolation, periodic=False if rotary else None)
            axes[letter] = Axis(letter, table, old.origin_m)
        return dataclasses.replace(machine, axes=axes)
