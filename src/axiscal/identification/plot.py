"""Plots of an identification: residuals per artefact and the identified error motions with their uncertainty bands (matplotlib imported lazily).

Translations in um, rotations in urad; bands are ± 2 standard uncertainties (k = 2).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from axiscal.conventions import ROTARY_LETTERS, component_names
from axiscal.io.figures import pyplot, save_figure, set_up_axes
from axiscal.units import ANGLE_UNITS, MM, UM

__all__ = ["plot_residuals", "plot_motions", "residuals_figure", "motions_figure"]

_URAD = ANGLE_UNITS["urad"]
_DEG = ANGLE_UNITS["deg"]


#: the longest artefact name a figure's title shows whole (a longer one is cut: the figure keeps its size)
_TITLE_NAME = 60


def plot_residuals(result, name: str, path: str | Path) -> Path:
    """The residuals of artefact ``name`` in reading order, um.

    Parameters
    ----------
    result : Identification
        The identification.
    name : str
        An artefact of it.
    path : str or Path
        Figure file (format from the suffix).

    Returns
    -------
    Path
    """
    return save_figure(residuals_figure(result, name), path)


def residuals_figure(result, name: str) -> Any:
    """The figure :func:`plot_residuals` saves, drawn and laid out but not saved.

    A caller that wants it in two formats saves it twice (:func:`axiscal.io.figures.save_figure`)
    instead of drawing it twice.

    Parameters
    ----------
    result : Identification
        The identification.
    name : str
        An artefact of it.

    Returns
    -------
    matplotlib.figure.Figure
        Open: the caller saves and closes it.
    """
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(8, 3))
    r = result.residuals[name] / UM
    ax.plot(np.arange(1, r.size + 1), r, ".", ms=3)
    shown = name if len(name) <= _TITLE_NAME else name[:_TITLE_NAME - 3] + "..."
    set_up_axes(ax, xlabel="reading", ylabel="residual / µm", title=f"{shown} ({result.kinds[name]})", zero_line=True)
    fig.tight_layout()
    return fig


def plot_motions(result, letter: str, path: str | Path) -> Path:
    """The six identified error motions of axis ``letter`` with their k = 2 bands.

    Parameters
    ----------
    result : Identification
        The identification.
    letter : str
        An identified axis.
    path : str or Path
        Figure file (format from the suffix).

    Returns
    -------
    Path
    """
    return save_figure(motions_figure(result, letter), path)


def motions_figure(result, letter: str) -> Any:
    """The figure :func:`plot_motions` saves, drawn and laid out but not saved.

    A caller that wants it in two formats saves it twice (:func:`axiscal.io.figures.save_figure`)
    instead of drawing it twice.

    Parameters
    ----------
    result : Identification
        The identification.
    letter : str
        An identified axis.

    Returns
    -------
    matplotlib.figure.Figure
        Open: the caller saves and closes it.
    """
    plt = pyplot()
    a, b = result.spans[letter]
    q = np.linspace(a, b, 201)
    rotary = letter in ROTARY_LETTERS
    x = q / (_DEG if rotary else MM)
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.5))
    for row, name in enumerate(component_names(letter)):
        value, band = result.motion_band(letter, row, q)
        factor = UM if row < 3 else _URAD
        ax = axes[0 if row < 3 else 1]
        line, = ax.plot(x, value / factor, label=name)
        if np.all(np.isfinite(band)):
            ax.fill_between(x, (value - 2 * band) / factor, (value + 2 * band) / factor, color=line.get_color(), alpha=0.2)
    for ax, unit in zip(axes, ("µm", "µrad")):
        set_up_axes(ax, xlabel=f"{letter} / {'deg' if rotary else 'mm'}", ylabel=f"error / {unit}", legend=True)
    fig.suptitle(f"Axis {letter}: identified error motions (bands ± 2u, k = 2)")
    fig.tight_layout()
    return fig
