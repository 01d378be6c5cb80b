"""The figures of ``axiscal cmm acceptance --plot`` and ``axiscal cmm probing --plot``.

Drawn through :func:`axiscal.io.figures.pyplot` and saved atomically; lengths in mm, errors in um.
The plots draw the result objects; they compute nothing.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from axiscal.cmm.acceptance import AcceptanceResult
from axiscal.cmm.probing import ProbingResult
from axiscal.io.arguments import check_instance, check_path
from axiscal.io.figures import pyplot, save_figure, set_up_axes
from axiscal.units import MM, UM

__all__ = ["plot_acceptance", "plot_probing"]

_MARKERS = "os^vD<>ph*"


def plot_acceptance(path: str | Path, result: AcceptanceResult) -> Path:
    """Every error of indication against its length, with the MPE lines (and the guard band's).

    Parameters
    ----------
    path : str or Path
        Image to write (format from the suffix).
    result : AcceptanceResult
        What :func:`axiscal.cmm.evaluate_acceptance` returned.

    Returns
    -------
    Path
        The image written.

    Raises
    ------
    AxiscalError
        A result of the wrong kind, an unknown image format or a file that cannot be written.
    """
    check_instance("result", result, AcceptanceResult, what="an AcceptanceResult (evaluate_acceptance)")
    path = check_path("path", path)
    m = result.measurements
    error = result.error_m / UM
    nominal = m.nominal_m / MM
    plt = pyplot()
    tests = [t for t in ("E0", "E150") if t in result.test]
    fig, axes = plt.subplots(1, len(tests), figsize=(7.5 if len(tests) == 1 else 11, 5.4), squeeze=False)
    for ax, test in zip(axes[0], tests):
        mask = np.array([t == test for t in result.test])
        positions = list(dict.fromkeys(p for p, k in zip(m.position, mask) if k))
        for j, position in enumerate(positions):
            sel = mask & np.array([p == position for p in m.position])
            ax.plot(nominal[sel], error[sel], _MARKERS[j % len(_MARKERS)], ms=4, alpha=0.8, label=f"position {position}")
        bad = mask & np.array([v in ("fail", "inconclusive") for v in result.verdicts])
        if bad.any():
            ax.plot(nominal[bad], error[bad], "o", ms=10, mfc="none", mec="red", label="fail or no decision")
        order = np.argsort(nominal[mask])
        length = nominal[mask][order]
        mpe = result.mpe_m[mask][order] / UM
        if np.all(np.isfinite(mpe)):
            ax.plot(length, mpe, "k-", lw=1.2, label="MPE")
            ax.plot(length, -mpe, "k-", lw=1.2)
            U = result.U_m[mask][order] / UM
            if result.rule == "guard-band" and np.any(U > 0):
                ax.plot(length, mpe - U, "k--", lw=0.8, label="MPE - U (conformance proven inside)")
                ax.plot(length, -(mpe - U), "k--", lw=0.8)
                ax.plot(length, mpe + U, "k:", lw=0.8, label="MPE + U (non-conformance proven outside)")
                ax.plot(length, -(mpe + U), "k:", lw=0.8)
        set_up_axes(ax, xlabel="calibrated length / mm", ylabel=f"{test} (measured - calibrated) / µm",
                    title=f"{test}: {result.verdict_of(test)}", grid=True, zero_line=True, legend=True,
                    legend_options={"fontsize": 7, "ncol": 3, "loc": "upper center", "bbox_to_anchor": (0.5, -0.16)})
    fig.tight_layout()
    return save_figure(fig, path)


def plot_probing(path: str | Path, result: ProbingResult) -> Path:
    """The radial deviation of every probed point from its stylus's sphere (and from the styli's common sphere).

    Parameters
    ----------
    path : str or Path
        Image to write (format from the suffix).
    result : ProbingResult
        What :func:`axiscal.cmm.evaluate_probing` returned.

    Returns
    -------
    Path
        The image written.

    Raises
    ------
    AxiscalError
        A result of the wrong kind, an unknown image format or a file that cannot be written.
    """
    check_instance("result", result, ProbingResult, what="a ProbingResult (evaluate_probing)")
    path = check_path("path", path)
    plt = pyplot()
    labels = np.array(result.points.stylus)
    rows = 2 if result.composite is not None else 1
    fig, axes = plt.subplots(rows, 1, figsize=(7.5, 3.2 * rows), squeeze=False)
    top = axes[0][0]
    start = 0
    for j, (stylus, fit) in enumerate(result.fits.items()):
        index = np.arange(start, start + fit.residual_m.size)
        top.plot(index, fit.residual_m / UM, _MARKERS[j % len(_MARKERS)] + "-", ms=4, lw=0.6,
                 label=f"stylus {stylus}: form {fit.form_m / UM:.3f} µm")
        start += fit.residual_m.size
    set_up_axes(top, ylabel="radial deviation / µm", title="each stylus's least-squares sphere", grid=True,
                zero_line=True, legend=True, legend_options={"fontsize": 7})
    if result.composite is not None:
        bottom = axes[1][0]
        residual = result.composite.residual_m / UM
        for j, stylus in enumerate(result.fits):
            sel = np.flatnonzero(labels == stylus)
            bottom.plot(np.arange(sel.size) + sum(f.residual_m.size for f in list(result.fits.values())[:j]),
                        residual[sel], _MARKERS[j % len(_MARKERS)], ms=4, label=f"stylus {stylus}")
        set_up_axes(bottom, ylabel="radial deviation / µm",
                    title=f"the styli's common sphere: form {result.composite.form_m / UM:.3f} µm", grid=True,
                    zero_line=True, legend=True, legend_options={"fontsize": 7, "ncol": 5})
    axes[-1][0].set_xlabel("point")
    fig.tight_layout()
    return save_figure(fig, path)
