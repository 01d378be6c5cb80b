"""ISO 10360-2:2009 length measurement test of a CMM: E0, E150 and the repeatability range R0.

The CMM measures a set of calibrated lengths (gauge blocks or the steps of a step gauge): five
lengths, three times each, in seven positions of the measuring volume (clause 6.3), 105 values of
E0; with the 150 mm ram offset the same in two positions for E150 (clause 6.4). Each error of
indication is ``E = measured - calibrated``; the repeatability range R0 is the range of the three
repeated measurements of one length in one position, the largest over the sets (clause 6.3.4).

Conformance (clause 7, ISO 14253-1:2017): every ``|E|`` is held against the MPE at its length with
the test uncertainty ``U(L) = U0 + L * u_per_m``. Under the guard band a value proves conformance
when ``|E| <= MPE - U``, non-conformance when ``|E| > MPE + U``; in between no decision can be
made ("inconclusive"). The test passes when every value passes and R0 is within R0,MPL, fails
when any value or R0 fails, and is inconclusive otherwise. Under the simple rule ``|E| <= MPE``.

The file: one row per measurement, ``position`` (a label), ``length`` (a label of the gauge or
step), ``nominal_mm`` (its calibrated length), ``measured_mm``, ``repeat`` (1, 2, 3), and
optionally ``ram_offset_mm`` (0 for E0, 150 for E150). A measured length more than 10 % from its
nominal is refused (an error of indication is micrometres: such a value is in another unit, or of
another gauge), as is an MPE or R0,MPL stated for a test the file has no value of.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.cmm.mpe import LIMIT_M, Mpe
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_choice, check_instance, check_number, check_path, render_checked
from axiscal.io.tabular import read_csv
from axiscal.io.templates import render_template
from axiscal.uncertainty.decision import DECISION_RULES, decide
from axiscal.units import MM, UM

__all__ = [
    "RAM_OFFSET_M",
    "LengthMeasurements",
    "read_length_measurements",
    "LengthSet",
    "AcceptanceResult",
    "length_acceptance",
    "evaluate_acceptance",
    "combined_verdict",
]

#: the ram axis stylus tip offset of the E150 test, metres
RAM_OFFSET_M = 150 * MM
#: ISO 10360-2:2009 6.3: seven positions, five lengths, three repeats
_POSITIONS, _LENGTHS, _REPEATS = 7, 5, 3
#: a measured length this far from its nominal (a fraction of it) is in another unit or of another gauge
_PLAUSIBLE = 0.1


@dataclass(frozen=True)
class LengthMeasurements:
    """The measurements of a length test, SI, one entry per measurement.

    Attributes
    ----------
    position : tuple of str
        The position (orientation in the volume) of each measurement.
    length : tuple of str
        The gauge or step measured.
    nominal_m : ndarray, shape (n,)
        Calibrated lengths, metres (> 0).
    measured_m : ndarray, shape (n,)
        Indicated lengths, metres.
    repeat : ndarray of int, shape (n,)
        The repeat number of each measurement.
    ram_offset_m : ndarray, shape (n,)
        The ram axis stylus tip offset, metres (0 for E0, 0.15 for E150).
    path : str
        The file read (``"<data>"`` when built in Python).
    lines : tuple of int
        The file line of each measurement (empty when built in Python).
    """

    position: tuple[str, ...]
    length: tuple[str, ...]
    nominal_m: np.ndarray
    measured_m: np.ndarray
    repeat: np.ndarray
    ram_offset_m: np.ndarray
    path: str = "<data>"
    lines: tuple[int, ...] = ()

    def __post_init__(self) -> None:
        for name in ("position", "length"):
            value = getattr(self, name)
            if isinstance(value, (str, bytes)) or not isinstance(value, (tuple, list)) or not all(
                    isinstance(v, str) and v for v in value):
                raise AxiscalError(f"{name} must be a sequence of labels (non-empty str), one per measurement")
            object.__setattr__(self, name, tuple(value))
        n = len(self.position)
        if n == 0:
            raise AxiscalError("a length test needs at least one measurement")
        nominal = check_array("nominal_m", self.nominal_m, ndim=1)
        if np.any(nominal <= 0):
            raise AxiscalError(f"nominal_m must be positive lengths of metres, not {nominal[nominal <= 0][0]:g}")
        measured = check_array("measured_m", self.measured_m, ndim=1)
        repeat = check_array("repeat", self.repeat, unit="", ndim=1)
        if np.any(repeat != np.round(repeat)) or np.any(repeat < 1):
            raise AxiscalError("repeat must hold whole numbers from 1")
        offset = check_array("ram_offset_m", self.ram_offset_m, ndim=1)
        if np.any(offset < 0):
            raise AxiscalError("ram_offset_m must be non-negative lengths of metres")
        for name, array in (("length", self.length), ("nominal_m", nominal), ("measured_m", measured),
                            ("repeat", repeat), ("ram_offset_m", offset)):
            if len(array) != n:
                raise AxiscalError(f"{name} has {len(array)} entries, position has {n}: one per measurement")
        if not isinstance(self.path, (str, Path)):
            raise AxiscalError(f"path must be the file's name (a str), not {self.path!r}")
        if not isinstance(self.lines, tuple) or self.lines and len(self.lines) != n:
            raise AxiscalError("lines must be a tuple of one file line per measurement (or empty)")
        object.__setattr__(self, "path", str(self.path))
        far = np.flatnonzero(np.abs(measured - nominal) > _PLAUSIBLE * nominal)
        if far.size:
            k = int(far[0])
            raise AxiscalError(
                f"the measured length {measured[k] / MM:.6g} mm is {measured[k] / nominal[k]:.4g} times the nominal "
                f"{nominal[k] / MM:.6g} mm: an error of indication is micrometres, so one of the two is in another unit "
                "(both are mm) or of another gauge",
                path=None if self.path == "<data>" else self.path, line=self.lines[k] if self.lines else None)
        object.__setattr__(self, "nominal_m", nominal)
        object.__setattr__(self, "measured_m", measured)
        object.__setattr__(self, "repeat", repeat.astype(int))
        object.__setattr__(self, "ram_offset_m", offset)

    @property
    def error_m(self) -> np.ndarray:
        """Errors of indication ``measured - nominal``, metres."""
        return self.measured_m - self.nominal_m

    def line_of(self, index: int) -> int | None:
        """The file line of measurement ``index`` (None when built in Python)."""
        return self.lines[index] if self.lines else None


def read_length_measurements(path: str | Path) -> LengthMeasurements:
    """Read a length test file: ``position, length, nominal_mm, measured_mm, repeat[, ram_offset_mm]``.

    Parameters
    ----------
    path : str or Path
        The CSV file.

    Returns
    -------
    LengthMeasurements

    Raises
    ------
    AxiscalError
        A missing file or column, a cell that is not a number, a nominal length that is not
        positive, a measured length more than 10 % from its nominal (another unit), a repeat that is
        not a whole number from 1, the same measurement given twice; each naming the file and line.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "e0.csv"
    >>> _ = path.write_text("position,length,nominal_mm,measured_mm,repeat\\n1,L1,100,100.0012,1\\n")
    >>> round(float(read_length_measurements(path).error_m[0]) / 1e-6, 6)
    1.2
    """
    table = read_csv(check_path("path", path))
    table.require("position", "length", "nominal_mm", "measured_mm", "repeat")
    nominal = table.numeric("nominal_mm")
    measured = table.numeric("measured_mm")
    repeat = table.numeric("repeat")
    offset = table.numeric("ram_offset_mm") if table.has("ram_offset_mm") else np.zeros(len(table))
    position, length = table.text("position"), table.text("length")
    for i, (label_p, label_l) in enumerate(zip(position, length)):
        if not label_p or not label_l:
            raise AxiscalError("position and length need a label", path=table.path, line=table.line_of(i))
    bad = np.flatnonzero(nominal <= 0)
    if bad.size:
        raise AxiscalError(f"nominal_mm must be positive, not {nominal[bad[0]]:g}", path=table.path, line=table.line_of(int(bad[0])))
    bad = np.flatnonzero((repeat != np.round(repeat)) | (repeat < 1))
    if bad.size:
        raise AxiscalError(f"repeat must be a whole number from 1, not {repeat[bad[0]]:g}", path=table.path,
                           line=table.line_of(int(bad[0])))
    bad = np.flatnonzero(offset < 0)
    if bad.size:
        raise AxiscalError(f"ram_offset_mm must not be negative, not {offset[bad[0]]:g}", path=table.path,
                           line=table.line_of(int(bad[0])))
    seen: dict[tuple, int] = {}
    for i, key in enumerate(zip(position, length, offset.tolist(), repeat.tolist())):
        if key in seen:
            raise AxiscalError(f"position {key[0]}, length {key[1]}, repeat {int(key[3])} is given twice "
                               f"(first on line {table.line_of(seen[key])})", path=table.path, line=table.line_of(i))
        seen[key] = i
    return LengthMeasurements(tuple(position), tuple(length), nominal * MM, measured * MM, repeat.astype(int),
                              offset * MM, table.path, tuple(table.line_of(i) for i in range(len(table))))


@dataclass(frozen=True)
class LengthSet:
    """The repeated measurements of one length in one position.

    Attributes
    ----------
    test : {"E0", "E150"}
    position, length : str
    nominal_m : float
        Calibrated length, metres.
    indices : tuple of int
        The measurements of the set.
    range_m : float
        Range of the errors of the set (its contribution to R0), metres.
    outside : int
        How many of its values did not pass.
    """

    test: str
    position: str
    length: str
    nominal_m: float
    indices: tuple[int, ...]
    range_m: float
    outside: int

    def __post_init__(self) -> None:
        check_choice("test", self.test, ("E0", "E150"))
        object.__setattr__(self, "nominal_m", check_number("nominal_m", self.nominal_m, positive=True))
        object.__setattr__(self, "range_m", check_number("range_m", self.range_m, nonnegative=True))


def combined_verdict(verdicts: Any) -> str:
    """The verdict of several: ``"fail"`` if any fails, else ``"inconclusive"`` if any is, else ``"pass"``.

    Parameters
    ----------
    verdicts : iterable of str
        ``"pass"``, ``"fail"`` or ``"inconclusive"`` each; ``"not assessed"`` entries are left out.

    Returns
    -------
    str
        ``"not assessed"`` when nothing was assessed.

    Examples
    --------
    >>> combined_verdict(["pass", "inconclusive", "pass"])
    'inconclusive'
    """
    if isinstance(verdicts, (str, bytes)):
        raise AxiscalError(f"verdicts must be a sequence of verdicts, not {verdicts!r}")
    values = [v for v in verdicts if v != "not assessed"]
    for v in values:
        check_choice("verdict", v, ("pass", "fail", "inconclusive"))
    if not values:
        return "not assessed"
    return "fail" if "fail" in values else "inconclusive" if "inconclusive" in values else "pass"


@dataclass(frozen=True)
class AcceptanceResult:
    """E0, E150 and R0 of a length test, each value against its MPE.

    Attributes
    ----------
    measurements : LengthMeasurements
    test : tuple of str
        ``"E0"`` or ``"E150"`` for each measurement (by its ram offset).
    mpe_m : ndarray, shape (n,)
        The MPE at each measurement's length, metres (NaN where no MPE was stated).
    U_m : ndarray, shape (n,)
        The expanded test uncertainty (k = 2) at each length, metres.
    verdicts : tuple of str
        ``"pass"``, ``"fail"``, ``"inconclusive"`` or ``"not assessed"`` for each measurement.
    sets : tuple of LengthSet
    mpe, mpe_150 : Mpe or None
        The MPE stated for E0 and for E150.
    r0_mpl_m : float or None
        R0,MPL, metres.
    rule : str
        The decision rule (a key of :data:`axiscal.uncertainty.DECISION_RULES`).
    uncertainty_m, uncertainty_per_m : float
        U0 (metres) and the length term (metres per metre) of the test uncertainty.
    warnings : tuple of str
    """

    measurements: LengthMeasurements
    test: tuple[str, ...]
    mpe_m: np.ndarray
    U_m: np.ndarray
    verdicts: tuple[str, ...]
    sets: tuple[LengthSet, ...]
    mpe: Mpe | None
    mpe_150: Mpe | None
    r0_mpl_m: float | None
    rule: str
    uncertainty_m: float
    uncertainty_per_m: float
    warnings: tuple[str, ...] = field(default=())

    def __post_init__(self) -> None:
        check_instance("measurements", self.measurements, LengthMeasurements,
                       what="LengthMeasurements (read_length_measurements)")

    @property
    def error_m(self) -> np.ndarray:
        """The errors of indication, metres."""
        return self.measurements.error_m

    @property
    def r0_m(self) -> float:
        """R0: the largest range of a set of E0 repeats, metres (NaN without E0 measurements)."""
        ranges = [s.range_m for s in self.sets if s.test == "E0"]
        return max(ranges) if ranges else float("nan")

    @property
    def r0_verdict(self) -> str:
        """R0 against R0,MPL (simple comparison: a range of repeats carries no artefact uncertainty)."""
        if self.r0_mpl_m is None or not np.isfinite(self.r0_m):
            return "not assessed"
        return decide(self.r0_m, self.r0_mpl_m).verdict

    def verdict_of(self, test: str) -> str:
        """The verdict of all values of ``test`` (``"E0"`` or ``"E150"``)."""
        check_choice("test", test, ("E0", "E150"))
        return combined_verdict(v for t, v in zip(self.test, self.verdicts) if t == test)

    @property
    def verdict(self) -> str:
        """The test's verdict: E0, E150 and R0 together."""
        return combined_verdict([self.verdict_of("E0"), self.verdict_of("E150"), self.r0_verdict])

    def decisive(self, test: str) -> int | None:
        """The measurement of ``test`` that settles its verdict: the worst verdict, then the least margin to the MPE.

        Returns
        -------
        int or None
            Its index; None when the test has no measurement or no MPE.
        """
        check_choice("test", test, ("E0", "E150"))
        rank = {"fail": 0, "inconclusive": 1, "pass": 2}
        chosen = [i for i, t in enumerate(self.test) if t == test and self.verdicts[i] in rank]
        if not chosen:
            return None
        margin = self.mpe_m - np.abs(self.error_m) - self.U_m
        return min(chosen, key=lambda i: (rank[self.verdicts[i]], margin[i]))

    def summary(self, test: str) -> dict[str, Any] | None:
        """Figures of ``test`` (``"E0"`` or ``"E150"``) in um, or None when the file has none."""
        check_choice("test", test, ("E0", "E150"))
        mask = np.array([t == test for t in self.test])
        if not mask.any():
            return None
        error = self.error_m[mask]
        worst = int(np.argmax(np.abs(error)))
        decisive = self.decisive(test)
        mpe = self.mpe if test == "E0" else self.mpe_150
        out = {
            "count": int(mask.sum()),
            "max_abs_um": float(np.max(np.abs(error)) / UM),
            "max_um": float(error.max() / UM),
            "min_um": float(error.min() / UM),
            "at_nominal_mm": float(self.measurements.nominal_m[mask][worst] / MM),
            "mpe": None if mpe is None else mpe.payload(),
            "verdict": self.verdict_of(test),
            "counts": {v: sum(1 for t, w in zip(self.test, self.verdicts) if t == test and w == v)
                       for v in ("pass", "inconclusive", "fail")},
        }
        if decisive is not None:
            out["decisive"] = {
                "position": self.measurements.position[decisive], "length": self.measurements.length[decisive],
                "nominal_mm": float(self.measurements.nominal_m[decisive] / MM),
                "error_um": float(self.error_m[decisive] / UM), "mpe_um": float(self.mpe_m[decisive] / UM),
                "U_um": float(self.U_m[decisive] / UM), "verdict": self.verdicts[decisive],
            }
        return out

    def payload(self) -> dict[str, Any]:
        """The JSON object of ``axiscal cmm acceptance --json``.

        Returns
        -------
        dict
            ``E0`` and ``E150`` (:meth:`summary`, or None), ``R0_um``, ``R0_mpl_um``, ``R0_verdict``,
            ``verdict``, ``decision_rule``, ``uncertainty_um``, ``uncertainty_um_per_m``,
            ``retest_sets``, ``warnings`` and ``measurements`` (one object per value).
        """
        m = self.measurements
        return {
            "standard": "ISO 10360-2:2009",
            "E0": self.summary("E0"),
            "E150": self.summary("E150"),
            "R0_um": None if not np.isfinite(self.r0_m) else self.r0_m / UM,
            "R0_mpl_um": None if self.r0_mpl_m is None else self.r0_mpl_m / UM,
            "R0_verdict": self.r0_verdict,
            "verdict": self.verdict,
            "decision_rule": self.rule,
            "decision_statement": DECISION_RULES[self.rule],
            "uncertainty_um": self.uncertainty_m / UM,
            "uncertainty_um_per_m": self.uncertainty_per_m / UM,
            "retest_sets": self.retest_sets(),
            "warnings": list(self.warnings),
            "measurements": [
                {"test": self.test[i], "position": m.position[i], "length": m.length[i],
                 "nominal_mm": float(m.nominal_m[i] / MM), "repeat": int(m.repeat[i]),
                 "error_um": float(self.error_m[i] / UM),
                 "mpe_um": None if not np.isfinite(self.mpe_m[i]) else float(self.mpe_m[i] / UM),
                 "U_um": float(self.U_m[i] / UM), "verdict": self.verdicts[i]}
                for i in range(len(m.position))
            ],
        }

    def retest_sets(self) -> list[dict[str, Any]]:
        """Sets that ISO 10360-2:2009 7.1 lets be measured again.

        When at most five sets of a test have one value, and only one, that did not pass, each
        may be measured three more times in the same configuration; the test then passes if all
        the new values pass. Those sets, as ``{"test", "position", "length"}``; empty otherwise.
        """
        out = []
        for test in ("E0", "E150"):
            single = [s for s in self.sets if s.test == test and s.outside == 1]
            others = [s for s in self.sets if s.test == test and s.outside > 1]
            if single and len(single) <= 5 and not others:
                out += [{"test": test, "position": s.position, "length": s.length} for s in single]
        return out

    def report(self) -> str:
        """The readable summary."""
        return render_checked(render_template, "cmm_acceptance.txt.j2", **self.payload()).rstrip("\n")


def length_acceptance(
    measurements: LengthMeasurements,
    *,
    mpe: Mpe | None = None,
    mpe_150: Mpe | None = None,
    r0_mpl_m: float | None = None,
    uncertainty_m: float = 0.0,
    uncertainty_per_m: float = 0.0,
    rule: str = "guard-band",
) -> AcceptanceResult:
    """E0, E150 and R0 of length measurements, each value decided against its MPE (ISO 10360-2, ISO 14253-1).

    Parameters
    ----------
    measurements : LengthMeasurements
        What :func:`read_length_measurements` returns.
    mpe : Mpe, optional, keyword-only
        E0,MPE. Without it the errors are given and not assessed; with it the measurements must
        hold E0 values.
    mpe_150 : Mpe, optional, keyword-only
        E150,MPE (stated apart from E0's); without it E150 is given and not assessed; with it the
        measurements must hold E150 values (a ram offset above 0).
    r0_mpl_m : float, optional, keyword-only
        R0,MPL, metres (> 0, at most :data:`axiscal.cmm.mpe.LIMIT_M`); the measurements must hold
        E0 values.
    uncertainty_m : float, keyword-only
        U0, the expanded test uncertainty (k = 2) at zero length, metres (0 to
        :data:`axiscal.cmm.mpe.LIMIT_M`).
    uncertainty_per_m : float, keyword-only
        Its growth with length, metres per metre (0 to :data:`axiscal.cmm.mpe.LIMIT_M`):
        ``U(L) = U0 + L * uncertainty_per_m``.
    rule : {"guard-band", "simple"}, keyword-only
        The decision rule (:mod:`axiscal.uncertainty.decision`).

    Returns
    -------
    AcceptanceResult

    Raises
    ------
    AxiscalError
        Arguments of the wrong kind or out of range, an MPE or R0,MPL of a test the measurements
        hold no value of.

    Examples
    --------
    >>> m = LengthMeasurements(("1",) * 3, ("L5",) * 3, [0.5] * 3, [0.5 + 2.0e-6, 0.5 + 2.2e-6, 0.5 + 2.6e-6], [1, 2, 3],
    ...                        [0.0] * 3)
    >>> r = length_acceptance(m, mpe=Mpe(1.5e-6, k=333.0), uncertainty_m=0.5e-6)
    >>> r.verdicts, round(r.r0_m / 1e-6, 6)
    (('pass', 'pass', 'inconclusive'), 0.6)
    """
    check_instance("measurements", measurements, LengthMeasurements, what="LengthMeasurements (read_length_measurements)")
    options = _options(mpe, mpe_150, r0_mpl_m, uncertainty_m, uncertainty_per_m, rule)
    return _acceptance(measurements, **options)


def _options(mpe, mpe_150, r0_mpl_m, uncertainty_m, uncertainty_per_m, rule) -> dict[str, Any]:
    """The options of a length test, checked once."""
    if mpe is not None:
        check_instance("mpe", mpe, Mpe, what="an Mpe")
    if mpe_150 is not None:
        check_instance("mpe_150", mpe_150, Mpe, what="an Mpe")
    if r0_mpl_m is not None:
        r0_mpl_m = check_number("r0_mpl_m", r0_mpl_m, positive=True, high=LIMIT_M)
    uncertainty_m = check_number("uncertainty_m", uncertainty_m, nonnegative=True, high=LIMIT_M)
    uncertainty_per_m = check_number("uncertainty_per_m", uncertainty_per_m, unit="metres per metre", nonnegative=True,
                                     high=LIMIT_M)
    check_choice("decision rule", rule, DECISION_RULES)
    return dict(mpe=mpe, mpe_150=mpe_150, r0_mpl_m=r0_mpl_m, uncertainty_m=uncertainty_m,
                uncertainty_per_m=uncertainty_per_m, rule=rule)


def _acceptance(m: LengthMeasurements, *, mpe, mpe_150, r0_mpl_m, uncertainty_m, uncertainty_per_m, rule) -> AcceptanceResult:
    n = len(m.position)
    test = tuple("E150" if offset > 0 else "E0" for offset in m.ram_offset_m)
    where = None if m.path == "<data>" else m.path
    for name, stated, which in (("mpe", mpe, "E0"), ("r0_mpl_m", r0_mpl_m, "E0"), ("mpe_150", mpe_150, "E150")):
        if stated is not None and which not in test:
            rows = "a row with ram_offset_mm above 0" if which == "E150" else "a row with ram_offset_mm 0 or none"
            raise AxiscalError(f"{name} is given, but the measurements hold no {which} value ({rows}): "
                               f"{which} cannot be assessed", path=where)
    U = uncertainty_m + m.nominal_m * uncertainty_per_m
    mpe_m = np.full(n, np.nan)
    for name, stated in (("E0", mpe), ("E150", mpe_150)):
        mask = np.array([t == name for t in test])
        if stated is not None and mask.any():
            mpe_m[mask] = stated._at(m.nominal_m[mask])
    error = m.error_m
    verdicts = tuple(
        "not assessed" if not np.isfinite(mpe_m[i]) else decide(abs(error[i]), mpe_m[i], U[i], rule=rule).verdict
        for i in range(n)
    )
    groups: dict[tuple[str, str, str], list[int]] = {}
    for i in range(n):
        groups.setdefault((test[i], m.position[i], m.length[i]), []).append(i)
    sets = []
    warnings = []
    for (name, position, length), indices in groups.items():
        nominal = m.nominal_m[indices]
        if np.ptp(nominal) > 0:
            raise AxiscalError(f"{name} position {position}, length {length}: the nominal length differs between repeats",
                               path=m.path, line=m.line_of(indices[1]))
        sets.append(LengthSet(name, position, length, float(nominal[0]), tuple(indices), float(np.ptp(error[indices])),
                              sum(1 for i in indices if verdicts[i] not in ("pass", "not assessed"))))
    e0 = [s for s in sets if s.test == "E0"]
    positions = {s.position for s in e0}
    lengths_per_position = {p: {s.length for s in e0 if s.position == p} for p in positions}
    repeats = {len(s.indices) for s in e0}
    if e0 and (len(positions) != _POSITIONS or any(len(v) != _LENGTHS for v in lengths_per_position.values())
               or repeats != {_REPEATS}):
        warnings.append(f"ISO 10360-2 asks for {_POSITIONS} positions x {_LENGTHS} lengths x {_REPEATS} repeats "
                        f"({_POSITIONS * _LENGTHS * _REPEATS} values of E0); this test has {len(positions)} positions, "
                        f"{sum(len(s.indices) for s in e0)} values")
    offsets = {float(o) for o in m.ram_offset_m if o > 0}
    if offsets and offsets != {RAM_OFFSET_M}:
        warnings.append(f"E150 is measured with a ram offset of 150 mm; this file has {', '.join(f'{o / MM:g}' for o in sorted(offsets))} mm")
    return AcceptanceResult(m, test, mpe_m, U, verdicts, tuple(sets), mpe, mpe_150, r0_mpl_m, rule, uncertainty_m,
                            uncertainty_per_m, tuple(warnings))


def evaluate_acceptance(
    path: str | Path,
    *,
    mpe: Mpe | None = None,
    mpe_150: Mpe | None = None,
    r0_mpl_m: float | None = None,
    uncertainty_m: float = 0.0,
    uncertainty_per_m: float = 0.0,
    rule: str = "guard-band",
) -> AcceptanceResult:
    """The length test of a file (what ``axiscal cmm acceptance`` does).

    Parameters
    ----------
    path : str or Path
        The measurements, read by :func:`read_length_measurements`.
    mpe, mpe_150, r0_mpl_m, uncertainty_m, uncertainty_per_m, rule : keyword-only
        As :func:`length_acceptance`.

    Returns
    -------
    AcceptanceResult

    Raises
    ------
    AxiscalError
        A bad file (naming it and the line) or argument.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "e0.csv"
    >>> _ = path.write_text("position,length,nominal_mm,measured_mm,repeat\\n1,L1,100,100.0012,1\\n")
    >>> evaluate_acceptance(path, mpe=Mpe(1.5e-6, k=333.0)).verdict
    'pass'
    """
    path = check_path("path", path)
    options = _options(mpe, mpe_150, r0_mpl_m, uncertainty_m, uncertainty_per_m, rule)
    return _acceptance(read_length_measurements(path), **options)
