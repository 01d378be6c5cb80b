"""ISO 10360-5:2010 probing tests of a CMM on a calibrated test sphere.

Single stylus: 25 points spread over the upper half of the sphere; an unconstrained least-squares
(Gaussian) sphere is fitted to them. The form error PForm.Sph.1x25::SS:Tact is the range of the
radial distances of the 25 points from its centre; the size error PSize.Sph.1x25::SS:Tact is its
diameter less the calibrated diameter.

Several styli (the multi-stylus test, five styli of 25 points each): a sphere is fitted to the
points of all the styli together, giving the form PForm.Sph.5x25::MS:Tact and the size
PSize.Sph.5x25::MS:Tact of that one sphere; a sphere is also fitted to each stylus's points, and
the location value PLoc.Sph.5x25::MS:Tact is the largest of the ranges of the X, Y and Z
coordinates of their centres. The single-stylus figures are those of the first stylus in the file.

The file: ``x_mm, y_mm, z_mm`` of each probed point (the centre of the stylus tip, corrected for
its radius as the CMM software reports it), and ``stylus`` (a label) when there are several.

Points that cannot give these figures are refused, not evaluated:

- points bunched on too little of the sphere (a circle, a small cap). The least-squares sphere's
  centre and radius then follow the probing scatter many times over: with ``u`` the unit
  directions from the centre to the points and ``J = [u, 1]`` the fit's Jacobian, the standard
  deviation of each parameter is ``sqrt(diag((J^T J)^-1))`` times the scatter of the points
  (the Gauss-Markov covariance). ISO 10360-5's pattern (25 points over a hemisphere: the pole,
  rings at 22.5, 45, 67.5 and 90 degrees from it) gives 0.55 at most; 25 points on a 45-degree
  cap 1.8, on a 30-degree cap 4.0, on a 10-degree cap 35, on a circle 10^6 and more. Above
  :data:`SPREAD_LIMIT` (3) the size alone may be off by six times the points' scatter, more than
  the form (the range of 25 points is some four times their scatter): the size and the location
  mean nothing against their MPE, so the test is refused naming the stylus, rather than printed
  with a warning beside a verdict, which would be read past.
- a fitted diameter more than 10 % from the calibrated one: the points were not probed on that
  sphere (a diameter in another unit, points not corrected for the stylus tip).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.cmm.acceptance import combined_verdict
from axiscal.cmm.mpe import LIMIT_M
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_array, check_choice, check_instance, check_mapping, check_number, check_path
from axiscal.io.arguments import render_checked
from axiscal.io.tabular import read_csv
from axiscal.io.templates import render_template
from axiscal.uncertainty.decision import DECISION_RULES, decide
from axiscal.units import MM, UM

__all__ = [
    "PROBING_FIGURES",
    "SPREAD_LIMIT",
    "fit_spread",
    "SphereFit",
    "fit_sphere",
    "SpherePoints",
    "read_sphere_points",
    "ProbingResult",
    "probing_test",
    "evaluate_probing",
]

#: figure key -> how ISO 10360-5:2010 names it ({n}: styli, {m}: points per stylus)
PROBING_FIGURES: dict[str, str] = {
    "pform": "PForm.Sph.1x{m}::SS:Tact",
    "psize": "PSize.Sph.1x{m}::SS:Tact",
    "pform_ms": "PForm.Sph.{n}x{m}::MS:Tact",
    "psize_ms": "PSize.Sph.{n}x{m}::MS:Tact",
    "ploc": "PLoc.Sph.{n}x{m}::MS:Tact",
}
_POINTS = 25
_LIMIT_M = 1e3  # no probed coordinate is a kilometre away
#: the largest standard deviation of the fitted centre's coordinates and radius per unit of the points' scatter
#: (:func:`fit_spread`) a probing test takes; ISO 10360-5's pattern gives 0.55
SPREAD_LIMIT = 3.0
#: a fitted diameter this far from the calibrated one (a fraction of it) was not probed on that sphere
_PLAUSIBLE = 0.1


@dataclass(frozen=True)
class SphereFit:
    """An unconstrained least-squares sphere.

    Attributes
    ----------
    centre_m : ndarray, shape (3,)
        Centre, metres.
    radius_m : float
        Radius, metres.
    residual_m : ndarray, shape (n,)
        Radial distance of each point from the centre less the radius, metres.
    """

    centre_m: np.ndarray
    radius_m: float
    residual_m: np.ndarray

    def __post_init__(self) -> None:
        object.__setattr__(self, "centre_m", check_array("centre_m", self.centre_m, ndim=1, last=3))
        object.__setattr__(self, "radius_m", check_number("radius_m", self.radius_m, positive=True))
        object.__setattr__(self, "residual_m", check_array("residual_m", self.residual_m, ndim=1))

    @property
    def diameter_m(self) -> float:
        """Diameter, metres."""
        return 2.0 * self.radius_m

    @property
    def form_m(self) -> float:
        """Form error: the range of the radial distances, metres."""
        return float(np.ptp(self.residual_m))


def fit_sphere(points_m: Any) -> SphereFit:
    """The least-squares sphere of points: centre and radius minimising the sum of squared radial deviations.

    An algebraic fit (linear in the centre and ``r**2 - |c|**2``) starts Gauss-Newton iterations on
    the geometric residuals ``|p - c| - r`` (ISO 10360-5 asks for the unconstrained Gaussian sphere).

    Parameters
    ----------
    points_m : array_like, shape (n, 3)
        Points, metres; at least 4, not all in one plane.

    Returns
    -------
    SphereFit

    Raises
    ------
    AxiscalError
        Fewer than 4 points, points not of shape (n, 3) or not finite, points in one plane or on
        one line (no sphere through them).

    Examples
    --------
    >>> fit = fit_sphere([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1]])
    >>> [round(float(v), 12) + 0.0 for v in fit.centre_m], round(fit.radius_m, 12)
    ([0.0, 0.0, 0.0], 1.0)
    """
    points = check_array("points_m", points_m, ndim=2, last=3, min_len=4, limit=_LIMIT_M)
    return _fit(points)


def _fit(points: np.ndarray) -> SphereFit:
    origin = points.mean(axis=0)
    p = points - origin
    scale = float(np.sqrt(np.mean(np.sum(p * p, axis=1))))
    if not scale > 0:
        raise AxiscalError("points_m are all the same point: no sphere through them")
    q = p / scale
    a = np.column_stack([2.0 * q, np.ones(len(q))])
    b = np.sum(q * q, axis=1)
    solution, _, rank, singular = np.linalg.lstsq(a, b, rcond=None)
    if rank < 4 or singular[-1] < 1e-9 * singular[0]:
        raise AxiscalError("points_m lie in one plane or on one line: no sphere through them")
    centre = solution[:3]
    radius = float(np.sqrt(max(solution[3] + centre @ centre, 0.0)))
    for _ in range(100):
        d = q - centre
        distance = np.sqrt(np.sum(d * d, axis=1))
        if np.any(distance == 0):
            raise AxiscalError("points_m: a point lies at the centre of the fitted sphere")
        residual = distance - radius
        jacobian = np.column_stack([-d / distance[:, None], -np.ones(len(q))])
        step = np.linalg.lstsq(jacobian, -residual, rcond=None)[0]
        centre = centre + step[:3]
        radius += float(step[3])
        if np.max(np.abs(step)) < 1e-15:
            break
    d = q - centre
    residual = (np.sqrt(np.sum(d * d, axis=1)) - radius) * scale
    return SphereFit(centre * scale + origin, abs(radius) * scale, residual)


def fit_spread(points_m: Any, fit: SphereFit) -> float:
    """How far the fitted sphere follows the points' scatter: the largest standard deviation of its parameters per unit.

    With ``u`` the unit directions from the fitted centre to the points and ``J = [u, 1]`` the
    Jacobian of the geometric residuals in the centre and the radius, the covariance of the
    parameters is ``s^2 (J^T J)^-1`` for points scattered by ``s`` about the sphere (Gauss-Markov).
    The result is the square root of the largest diagonal term of ``(J^T J)^-1``: how many times
    the scatter of the points the worst-determined parameter (a coordinate of the centre or the
    radius) may be off. Dimensionless; it depends only on how the points spread over the sphere.

    Parameters
    ----------
    points_m : array_like, shape (n, 3)
        The points the sphere was fitted to, metres.
    fit : SphereFit
        Their sphere (:func:`fit_sphere`).

    Returns
    -------
    float
        0.55 for ISO 10360-5's 25 points over a hemisphere, about 0.4 for points spread over the
        whole sphere, growing without bound as the points close onto a circle.

    Raises
    ------
    AxiscalError
        Points not of shape (n, 3) or not finite, fewer than 4, or a fit of the wrong kind.

    Examples
    --------
    >>> points = [[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]]
    >>> round(fit_spread(points, fit_sphere(points)), 4)
    0.7071
    """
    points = check_array("points_m", points_m, ndim=2, last=3, min_len=4, limit=_LIMIT_M)
    check_instance("fit", fit, SphereFit, what="a SphereFit (fit_sphere)")
    return _spread(points, fit)


def _spread(points: np.ndarray, fit: SphereFit) -> float:
    d = points - fit.centre_m
    distance = np.sqrt(np.sum(d * d, axis=1))
    if np.any(distance == 0):
        return math.inf
    jacobian = np.column_stack([d / distance[:, None], np.ones(len(d))])
    singular = np.linalg.svd(jacobian, compute_uv=False)
    if not singular[-1] > 1e-12 * singular[0]:
        return math.inf
    covariance = np.linalg.inv(jacobian.T @ jacobian)
    return float(np.sqrt(np.max(np.diag(covariance))))


@dataclass(frozen=True)
class SpherePoints:
    """Points probed on a test sphere, SI.

    Attributes
    ----------
    points_m : ndarray, shape (n, 3)
        Metres.
    stylus : tuple of str
        The stylus of each point (``"1"`` for all when the file has no ``stylus`` column).
    path : str
        The file read (``"<data>"`` when built in Python).
    """

    points_m: np.ndarray
    stylus: tuple[str, ...]
    path: str = "<data>"

    def __post_init__(self) -> None:
        points = check_array("points_m", self.points_m, ndim=2, last=3, min_len=4, limit=_LIMIT_M)
        if isinstance(self.stylus, (str, bytes)) or not isinstance(self.stylus, (tuple, list)) or not all(
                isinstance(s, str) and s for s in self.stylus):
            raise AxiscalError("stylus must be a sequence of labels (non-empty str), one per point")
        if len(self.stylus) != len(points):
            raise AxiscalError(f"stylus has {len(self.stylus)} labels for {len(points)} points: one per point")
        if not isinstance(self.path, (str, Path)):
            raise AxiscalError(f"path must be the file's name (a str), not {self.path!r}")
        object.__setattr__(self, "points_m", points)
        object.__setattr__(self, "stylus", tuple(self.stylus))
        object.__setattr__(self, "path", str(self.path))

    @property
    def styli(self) -> tuple[str, ...]:
        """The styli in the order they first appear."""
        return tuple(dict.fromkeys(self.stylus))


def read_sphere_points(path: str | Path) -> SpherePoints:
    """Read the points of a probing test: ``x_mm, y_mm, z_mm`` and, for several styli, ``stylus``.

    Parameters
    ----------
    path : str or Path
        The CSV file.

    Returns
    -------
    SpherePoints

    Raises
    ------
    AxiscalError
        A missing file or column, a cell that is not a number, an empty stylus label, fewer than 4
        points of a stylus; naming the file and line.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "sphere.csv"
    >>> _ = path.write_text("x_mm,y_mm,z_mm\\n10,0,0\\n-10,0,0\\n0,10,0\\n0,-10,0\\n0,0,10\\n")
    >>> read_sphere_points(path).styli
    ('1',)
    """
    table = read_csv(check_path("path", path), min_rows=4)
    table.require("x_mm", "y_mm", "z_mm")
    points = np.column_stack([table.numeric(c) for c in ("x_mm", "y_mm", "z_mm")]) * MM
    if table.has("stylus"):
        stylus = table.text("stylus")
        for i, label in enumerate(stylus):
            if not label:
                raise AxiscalError("stylus needs a label", path=table.path, line=table.line_of(i))
    else:
        stylus = ["1"] * len(table)
    for label in dict.fromkeys(stylus):
        rows = [i for i, s in enumerate(stylus) if s == label]
        if len(rows) < 4:
            raise AxiscalError(f"stylus {label} has {len(rows)} points: a sphere needs at least 4",
                               path=table.path, line=table.line_of(rows[-1]))
    return SpherePoints(points, tuple(stylus), table.path)


@dataclass(frozen=True)
class ProbingResult:
    """The probing figures of a test sphere, each against its MPE.

    Attributes
    ----------
    points : SpherePoints
    calibrated_diameter_m : float
        The test sphere's calibrated diameter, metres.
    fits : dict
        Stylus -> :class:`SphereFit` of its points.
    composite : SphereFit or None
        The sphere of all the styli's points (None with one stylus).
    figures_m : dict
        Figure key (:data:`PROBING_FIGURES`) -> value, metres (size errors signed).
    names : dict
        Figure key -> its ISO 10360-5 name.
    mpe_m : dict
        Figure key -> MPE, metres (only those stated).
    uncertainty_m : float
        Expanded test uncertainty (k = 2) of each figure, metres.
    rule : str
        The decision rule.
    warnings : tuple of str
    """

    points: SpherePoints
    calibrated_diameter_m: float
    fits: dict[str, SphereFit]
    composite: SphereFit | None
    figures_m: dict[str, float]
    names: dict[str, str]
    mpe_m: dict[str, float]
    uncertainty_m: float
    rule: str
    warnings: tuple[str, ...] = field(default=())

    def __post_init__(self) -> None:
        check_instance("points", self.points, SpherePoints, what="SpherePoints (read_sphere_points)")

    @property
    def verdicts(self) -> dict[str, str]:
        """Figure key -> ``"pass"``, ``"fail"``, ``"inconclusive"`` (or ``"not assessed"`` without an MPE)."""
        return {key: decide(abs(value), self.mpe_m[key], self.uncertainty_m, rule=self.rule).verdict
                if key in self.mpe_m else "not assessed" for key, value in self.figures_m.items()}

    @property
    def verdict(self) -> str:
        """The test's verdict: every figure stated with an MPE."""
        return combined_verdict(self.verdicts.values())

    def payload(self) -> dict[str, Any]:
        """The JSON object of ``axiscal cmm probing --json``.

        Returns
        -------
        dict
            ``figures`` (key -> ``name``, ``value_um``, ``mpe_um``, ``verdict``), ``<key>_um`` for
            each figure, ``styli`` (label -> ``points``, ``centre_mm``, ``diameter_mm``,
            ``form_um``, ``size_um``), ``calibrated_diameter_mm``, ``uncertainty_um``,
            ``decision_rule``, ``verdict``, ``warnings``.
        """
        verdicts = self.verdicts
        counts = {s: self.points.stylus.count(s) for s in self.fits}
        out: dict[str, Any] = {
            "standard": "ISO 10360-5:2010",
            "figures": {key: {"name": self.names[key], "value_um": value / UM,
                              "mpe_um": self.mpe_m[key] / UM if key in self.mpe_m else None,
                              "verdict": verdicts[key]} for key, value in self.figures_m.items()},
        }
        out.update({f"{key}_um": value / UM for key, value in self.figures_m.items()})
        out.update({
            "styli": {s: {"points": counts[s], "centre_mm": (f.centre_m / MM).tolist(), "diameter_mm": f.diameter_m / MM,
                          "form_um": f.form_m / UM, "size_um": (f.diameter_m - self.calibrated_diameter_m) / UM}
                      for s, f in self.fits.items()},
            "calibrated_diameter_mm": self.calibrated_diameter_m / MM,
            "uncertainty_um": self.uncertainty_m / UM,
            "decision_rule": self.rule,
            "decision_statement": DECISION_RULES[self.rule],
            "verdict": self.verdict,
            "warnings": list(self.warnings),
        })
        return out

    def report(self) -> str:
        """The readable summary."""
        return render_checked(render_template, "cmm_probing.txt.j2", **self.payload()).rstrip("\n")


def probing_test(
    points: SpherePoints,
    *,
    calibrated_diameter_m: float,
    mpe_m: Mapping[str, float] | None = None,
    uncertainty_m: float = 0.0,
    rule: str = "guard-band",
) -> ProbingResult:
    """Form, size and (several styli) location figures of points probed on a calibrated sphere.

    Parameters
    ----------
    points : SpherePoints
        What :func:`read_sphere_points` returns.
    calibrated_diameter_m : float, keyword-only
        The test sphere's calibrated diameter, metres (> 0); each stylus's sphere must come within
        10 % of it.
    mpe_m : mapping, optional, keyword-only
        Figure key (``"pform"``, ``"psize"``, ``"pform_ms"``, ``"psize_ms"``, ``"ploc"``) -> MPE, metres (> 0,
        at most :data:`axiscal.cmm.mpe.LIMIT_M`).
    uncertainty_m : float, keyword-only
        Expanded test uncertainty (k = 2) of each figure, metres (0 to :data:`axiscal.cmm.mpe.LIMIT_M`).
    rule : {"guard-band", "simple"}, keyword-only
        The decision rule (:mod:`axiscal.uncertainty.decision`).

    Returns
    -------
    ProbingResult

    Raises
    ------
    AxiscalError
        Arguments of the wrong kind or out of range, an MPE of a figure the data cannot give, a
        stylus's points spread over too little of the sphere (:func:`fit_spread` above
        :data:`SPREAD_LIMIT`), a stylus's sphere more than 10 % from the calibrated diameter.

    Examples
    --------
    >>> p = SpherePoints([[.01, 0, 0], [-.01, 0, 0], [0, .01, 0], [0, -.01, 0], [0, 0, .01]], ("1",) * 5)
    >>> r = probing_test(p, calibrated_diameter_m=0.0199996)
    >>> round(r.figures_m["psize"] / 1e-6, 6), round(r.figures_m["pform"] / 1e-6, 6)
    (0.4, 0.0)
    """
    check_instance("points", points, SpherePoints, what="SpherePoints (read_sphere_points)")
    options = _options(calibrated_diameter_m, mpe_m, uncertainty_m, rule)
    return _probing(points, **options)


def _options(calibrated_diameter_m, mpe_m, uncertainty_m, rule) -> dict[str, Any]:
    calibrated_diameter_m = check_number("calibrated_diameter_m", calibrated_diameter_m, positive=True, high=_LIMIT_M)
    limits: dict[str, float] = {}
    if mpe_m is not None:
        check_mapping("mpe_m", mpe_m, what="a mapping of figure keys to MPE in metres")
        for key, value in mpe_m.items():
            check_choice("mpe_m figure", key, PROBING_FIGURES)
            limits[key] = check_number(f"mpe_m['{key}']", value, unit="metres", positive=True, high=LIMIT_M)
    uncertainty_m = check_number("uncertainty_m", uncertainty_m, nonnegative=True, high=LIMIT_M)
    check_choice("decision rule", rule, DECISION_RULES)
    return dict(calibrated_diameter_m=calibrated_diameter_m, mpe_m=limits, uncertainty_m=uncertainty_m, rule=rule)


def _probing(points: SpherePoints, *, calibrated_diameter_m, mpe_m, uncertainty_m, rule) -> ProbingResult:
    styli = points.styli
    labels = np.array(points.stylus)
    where = None if points.path == "<data>" else points.path
    fits = {}
    for s in styli:
        mine = points.points_m[labels == s]
        try:
            fits[s] = _fit(mine)
        except AxiscalError as exc:
            raise AxiscalError(f"stylus {s}: {exc.message}", path=where) from None
        spread = _spread(mine, fits[s])
        if spread > SPREAD_LIMIT:
            raise AxiscalError(
                f"stylus {s}: the points cover too little of the sphere to fit it: its centre and diameter may be off by "
                f"{spread:.3g} times the points' scatter (ISO 10360-5's 25 points over a hemisphere: 0.55; at most "
                f"{SPREAD_LIMIT:g} is taken); probe the standard's pattern", path=where)
        diameter = fits[s].diameter_m
        if abs(diameter - calibrated_diameter_m) > _PLAUSIBLE * calibrated_diameter_m:
            raise AxiscalError(
                f"stylus {s}: the points lie on a sphere {diameter / MM:.6g} mm across, not on the calibrated one "
                f"(calibrated_diameter_m {calibrated_diameter_m / MM:.6g} mm): is the diameter in mm, are the points "
                "the tip's centres corrected for its radius?", path=where)
    counts = [int(np.sum(labels == s)) for s in styli]
    warnings = []
    if any(c != _POINTS for c in counts):
        warnings.append(f"ISO 10360-5 probes {_POINTS} points with each stylus; here "
                        + ", ".join(f"stylus {s}: {c}" for s, c in zip(styli, counts)))
    m = counts[0] if len(set(counts)) == 1 else f"({'/'.join(map(str, counts))})"
    first = fits[styli[0]]
    figures = {"pform": first.form_m, "psize": first.diameter_m - calibrated_diameter_m}
    composite = None
    if len(styli) > 1:
        if len(styli) != 5:
            warnings.append(f"the multi-stylus test of ISO 10360-5 uses 5 styli; here {len(styli)}")
        composite = _fit(points.points_m)
        centres = np.array([fits[s].centre_m for s in styli])
        figures.update(pform_ms=composite.form_m, psize_ms=composite.diameter_m - calibrated_diameter_m,
                       ploc=float(np.max(np.ptp(centres, axis=0))))
    names = {key: PROBING_FIGURES[key].format(n=len(styli), m=counts[0] if key in ("pform", "psize") else m)
             for key in figures}
    unusable = sorted(set(mpe_m) - set(figures))
    if unusable:
        raise AxiscalError(f"an MPE is given for {', '.join(unusable)}, which needs points of several styli (a stylus column)")
    return ProbingResult(points, calibrated_diameter_m, fits, composite, figures, names, dict(mpe_m), uncertainty_m, rule,
                         tuple(warnings))


def evaluate_probing(
    path: str | Path,
    *,
    calibrated_diameter_m: float,
    mpe_m: Mapping[str, float] | None = None,
    uncertainty_m: float = 0.0,
    rule: str = "guard-band",
) -> ProbingResult:
    """The probing test of a file (what ``axiscal cmm probing`` does).

    Parameters
    ----------
    path : str or Path
        The points, read by :func:`read_sphere_points`.
    calibrated_diameter_m, mpe_m, uncertainty_m, rule : keyword-only
        As :func:`probing_test`.

    Returns
    -------
    ProbingResult

    Raises
    ------
    AxiscalError
        A bad file (naming it and the line) or argument.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "sphere.csv"
    >>> _ = path.write_text("x_mm,y_mm,z_mm\\n10,0,0\\n-10,0,0\\n0,10,0\\n0,-10,0\\n0,0,10.001\\n")
    >>> r = evaluate_probing(path, calibrated_diameter_m=0.02, mpe_m={"pform": 2e-6})
    >>> r.verdicts["pform"]
    'pass'
    """
    path = check_path("path", path)
    options = _options(calibrated_diameter_m, mpe_m, uncertainty_m, rule)
    points = read_sphere_points(path)
    try:
        return _probing(points, **options)
    except AxiscalError as exc:
        raise exc.located(path=path) from None
