"""One call from a run file to the evaluated positioning test, its JSON object and its text report.

Reads the file with :func:`axiscal.positioning.reader.read_positioning_run` and evaluates it with
the ISO 230-2 (:func:`axiscal.positioning.evaluation.iso230_2`) or VDI/DGQ 3441
(:func:`axiscal.positioning.evaluation.vdi3441`) estimators. The result holds SI values; the
JSON object and the text report (the Jinja2 template ``templates/positioning_report.txt.j2``)
give micrometres and millimetres for a linear axis, arcseconds and degrees for a rotary axis, as
their names say.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path
from typing import Any

import numpy as np

from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_choice, check_optional_number, render_checked
from axiscal.materials import STEEL_EXPANSION_PER_K
from axiscal.positioning.evaluation import (
    STANDARDS,
    Iso230Result,
    PositioningRun,
    Vdi3441Result,
    iso230_2,
    iso_edition,
    require_finite,
    vdi3441,
)
from axiscal.positioning.reader import read_positioning_run
from axiscal.units import ARCSEC, DEG, MM, UM

__all__ = ["DISPLAY_UNITS", "PositioningEvaluation", "evaluate_positioning_file", "render_template"]

#: (target unit, deviation unit) of the JSON object, the text report and the plot, and their SI factors
DISPLAY_UNITS = {False: (("mm", MM), ("um", UM)), True: (("deg", DEG), ("arcsec", ARCSEC))}


@lru_cache(maxsize=1)
def _environment():
    import jinja2

    env = jinja2.Environment(
        loader=jinja2.PackageLoader("axiscal", "templates"),
        trim_blocks=True,
        lstrip_blocks=True,
        keep_trailing_newline=False,
        undefined=jinja2.StrictUndefined,
        autoescape=False,
    )
    env.filters["cell"] = _cell
    env.filters["heading"] = _heading
    return env


def render_template(name: str, **context: Any) -> str:
    """Render the text template ``name`` shipped under ``axiscal/templates``.

    Parameters
    ----------
    name : str
        File name of the template, e.g. ``"positioning_report.txt.j2"``.
    **context
        The template's variables.

    Returns
    -------
    str
        The rendered text without a trailing newline.

    Examples
    --------
    >>> render_template("positioning_report.txt.j2", source="x.csv", standard="vdi3441", target_count=2,
    ...                 runs=1, directions="each way", compensated=False, columns=[], rows=[], figures=[],
    ...                 unit="um").splitlines()[0]
    'x.csv: vdi3441, 2 targets, 1 run each way'
    """
    return render_checked(_render, name, **context)


def _render(name: str, **context: Any) -> str:
    return _environment().get_template(name).render(**context).rstrip("\n")


def _cell(value: float, width: int = 9) -> str:
    return f"{'n/a':>{width}}" if not np.isfinite(value) else f"{value:>{width}.3f}"


def _heading(name: str) -> str:
    return f"{name:>9}" if len(name) <= 9 else name


@dataclass(frozen=True)
class PositioningEvaluation:
    """A positioning test read from a file and evaluated to one standard (SI units).

    Attributes
    ----------
    run : PositioningRun
        Target positions and deviations, metres (radians for a rotary axis).
    result : Iso230Result or Vdi3441Result
        The figures of the standard asked for, metres (radians).
    compensated : bool
        True when the file held raw laser readings that were compensated for the air (and the
        material temperature).
    run_labels : tuple of str
        The ``run`` identifiers of the file, in the column order of the deviation arrays.
    file_warnings : tuple of str
        What the reader said about the file (e.g. a rotary test that does not cover the circle).
    compensation : str
        What the compensation applied, in words (:attr:`RunFile.compensation`; "" when none).
    """

    run: PositioningRun
    result: Iso230Result | Vdi3441Result
    compensated: bool
    run_labels: tuple[str, ...]
    file_warnings: tuple[str, ...] = ()
    compensation: str = ""

    @property
    def standard(self) -> str:
        """The standard evaluated, e.g. ``"iso230-2:2014"`` or ``"vdi3441"``."""
        return self.result.standard

    @property
    def warnings(self) -> tuple[str, ...]:
        """What the reader should know about the file and the figures (e.g. s cannot be estimated from one run)."""
        return self.file_warnings + self.result.warnings

    @property
    def units(self) -> tuple[str, str]:
        """The display units of targets and deviations: ("mm", "um"), or ("deg", "arcsec") for a rotary axis."""
        (target, _), (deviation, _) = DISPLAY_UNITS[self.run.rotary]
        return target, deviation

    def per_target(self) -> dict[str, np.ndarray]:
        """The per-target values in display units (see :attr:`units`), named with their unit.

        Returns
        -------
        dict of str to ndarray, each of shape (m,)
            For a linear axis ``target_mm, mean_up_um, mean_down_um, s_up_um, s_down_um,
            mean_um, B_um`` and, for ISO 230-2, ``R_up_um, R_down_um, R_um``; for VDI/DGQ 3441
            ``U_um, s_mean_um, Ps_um``. For a rotary axis the same in ``_deg`` and ``_arcsec``.
            Values that do not apply (the direction not tested) are NaN.
        """
        (t_unit, t_factor), (u, factor) = DISPLAY_UNITS[self.run.rotary]
        result = self.result
        st = result.stats
        out = {
            f"target_{t_unit}": st.targets / t_factor,
            f"mean_up_{u}": st.mean_up / factor,
            f"mean_down_{u}": st.mean_down / factor,
            f"s_up_{u}": st.s_up / factor,
            f"s_down_{u}": st.s_down / factor,
            f"mean_{u}": st.mean / factor,
            f"B_{u}": st.reversal / factor,
        }
        if isinstance(result, Iso230Result):
            out.update({
                f"R_up_{u}": result.repeatability_up / factor,
                f"R_down_{u}": result.repeatability_down / factor,
                f"R_{u}": result.repeatability / factor,
            })
        else:
            out.update({f"U_{u}": result.reversal_span / factor, f"s_mean_{u}": result.s_mean / factor,
                        f"Ps_{u}": result.scatter / factor})
        return out

    def per_target_um(self) -> dict[str, np.ndarray]:
        """The per-target values in display units; the same as :meth:`per_target` (kept for its callers).

        Returns
        -------
        dict of str to ndarray, each of shape (m,)
            See :meth:`per_target`.
        """
        return self.per_target()

    def to_dict(self) -> dict[str, Any]:
        """The JSON object of the evaluation: axis figures in um (arcsec for a rotary axis) under the standard's symbols.

        Returns
        -------
        dict
            ``standard``, ``unit`` ("um", or "arcsec" for a rotary axis), ``coverage_factor``
            (ISO 230-2 only), every axis figure by its symbol (NaN, written null, where s cannot
            be estimated or, for a one-direction test, where the figure needs both directions),
            ``runs``, ``target_count``, ``compensated``, ``warnings`` and ``targets`` (see
            :meth:`per_target`). A rotary or one-direction test adds ``axis`` ("rotary") and
            ``directions`` (["+"] or ["-"]).
        """
        result = self.result
        _, (unit, factor) = DISPLAY_UNITS[self.run.rotary]
        body: dict[str, Any] = {"standard": result.standard, "unit": unit}
        if self.run.rotary:
            body["axis"] = "rotary"
        if not self.run.bidirectional:
            body["directions"] = list(self.run.directions)
        if isinstance(result, Iso230Result):
            body["coverage_factor"] = result.coverage
        body.update({name: value / factor for name, value in result.figures().items()})
        body.update(
            runs=self.run.runs,
            target_count=int(self.run.targets.size),
            compensated=self.compensated,
            compensation=self.compensation,
            warnings=list(self.warnings),
            targets=self.per_target(),
        )
        return body

    def report(self) -> str:
        """The readable report: the per-target table and the axis figures in um (arcsec for a rotary axis).

        Figures that do not apply read "n/a".

        Returns
        -------
        str
            Text of several lines, without a trailing newline.
        """
        _, (unit, factor) = DISPLAY_UNITS[self.run.rotary]
        per = self.per_target()
        names = list(per)
        widths = [max(9, len(n)) for n in names]
        rows = [[_cell(per[n][i], w) for n, w in zip(names, widths)] for i in range(self.run.targets.size)]
        return render_template(
            "positioning_report.txt.j2",
            source=self.run.source,
            standard=self.result.standard,
            target_count=int(self.run.targets.size),
            runs=self.run.runs,
            directions="each way" if self.run.bidirectional else f"in the {self.run.directions[0]} direction only",
            compensated=self.compensated,
            compensation=self.compensation,
            columns=names,
            rows=rows,
            figures=[(name, value / factor) for name, value in self.result.figures().items()],
            unit=unit,
        )

    def plot(
        self, path: str | Path, *, title: str = "", overlay: Mapping[str, Any] | None = None, figures_table: bool = True
    ) -> Path:
        """Write the positioning plot (see :func:`axiscal.positioning.plot.plot_positioning`).

        Parameters
        ----------
        path : str or Path
            The figure file; its suffix gives the format (.png, .svg, .pdf, ...).
        title : str, keyword-only
            Title of the plot (default: file, standard, k, targets and runs).
        overlay : mapping, keyword-only
            Another test's per-target means to draw behind (see :func:`plot_positioning`).
        figures_table : bool, keyword-only
            Draw the table of axis figures beside the plot (default True; a report that shows
            the figures itself leaves it out).

        Returns
        -------
        Path
            ``path``.

        Raises
        ------
        AxiscalError
            If the suffix names no figure format or the file cannot be written.
        """
        from axiscal.positioning.plot import plot_positioning

        return plot_positioning(self.run, self.result, path, title=title, compensated=self.compensation or self.compensated, overlay=overlay,
                                figures_table=figures_table)


def evaluate_positioning_file(
    path: str | Path,
    *,
    standard: str = "iso230-2:2014",
    wavelength_nm: float | None = None,
    expansion_per_k: float | None = None,
) -> PositioningEvaluation:
    """Read a positioning test (linear or rotary, one direction or both) from CSV and evaluate it to ``standard``.

    Parameters
    ----------
    path : str or Path
        The run file (columns in docs/positioning.md): ``target_<unit>, run, direction`` and
        ``deviation_<unit>`` or ``actual_<unit>`` (``target_deg`` with ``deviation_arcsec`` for a
        rotary axis); a filled-in plan of ``axiscal plan`` too.
    standard : str, keyword-only
        One of :data:`axiscal.positioning.evaluation.STANDARDS`: ``"iso230-2:2014"`` (default),
        ``":2006"``, ``":1997"``, ``":1988"``, ``"jis-b6192"`` (the 1988 formulas, k = 3) or
        ``"vdi3441"``.
    wavelength_nm : float, optional, keyword-only
        Vacuum wavelength of the laser, nm, for raw laser readings (default 632.991 nm).
    expansion_per_k : float, optional, keyword-only
        Expansion coefficient of the material, 1/K, for raw laser readings with a material
        temperature (default :data:`axiscal.materials.STEEL_EXPANSION_PER_K`).

    Returns
    -------
    PositioningEvaluation
        The run and the figures in SI units.

    Raises
    ------
    AxiscalError
        For an unknown standard; for a file the reader refuses (naming the file and line); for
        ``wavelength_nm`` or ``expansion_per_k`` that is NaN or infinite, or given with a file
        that holds no raw laser readings (they would do nothing).

    Examples
    --------
    >>> evaluation = evaluate_positioning_file("examples/positioning_run.csv")  # doctest: +SKIP
    >>> round(evaluation.result.A / UM, 3)  # doctest: +SKIP
    14.936
    """
    require_finite(wavelength_nm=wavelength_nm, expansion_per_k=expansion_per_k)
    check_choice("standard", standard, STANDARDS)
    check_optional_number("wavelength_nm", wavelength_nm, positive=True)
    check_optional_number("expansion_per_k", expansion_per_k)
    edition = None if standard == "vdi3441" else iso_edition(standard)
    data = read_positioning_run(
        path,
        wavelength_nm=wavelength_nm,
        expansion_per_k=STEEL_EXPANSION_PER_K if expansion_per_k is None else expansion_per_k,
    )
    if not data.compensated:
        for name, value in (("wavelength_nm", wavelength_nm), ("expansion_per_k", expansion_per_k)):
            if value is not None:
                raise AxiscalError(
                    f"{name} applies to raw laser readings (actual_<unit> with the environment columns);"
                    " this file holds none",
                    path=data.run.source,
                )
    result = vdi3441(data.run) if edition is None else iso230_2(data.run, edition=edition)
    return PositioningEvaluation(
        run=data.run, result=result, compensated=data.compensated, run_labels=data.run_labels, file_warnings=data.warnings,
        compensation=data.compensation
    )
