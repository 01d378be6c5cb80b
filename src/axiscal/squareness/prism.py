"""The reference's own error in a squareness set-up: the prism's deviation by reversal (paper 004 eqs 2-5) and by autocollimator and wedge (paper 002 eq 22), and a PSD set-up's angular resolution (paper 004 eq 1)."""

from __future__ import annotations

from dataclasses import dataclass

from axiscal.io.arguments import check_number

__all__ = [
    "ReversalResult",
    "prism_reversal",
    "prism_deviation_from_wedge",
    "psd_angular_resolution",
]


@dataclass(frozen=True)
class ReversalResult:
    """Paper 004's prism reversal (eqs 2-5).

    Attributes
    ----------
    prism_deviation_rad : float
        ``alpha_p = (alpha_1 + alpha_2) / 2``, the prism's deviation from 90 degrees, radians.
    squareness_rad : float
        ``alpha_0 = (alpha_2 - alpha_1) / 2``, the squareness of the two stages, radians.
    """

    prism_deviation_rad: float
    squareness_rad: float


def prism_reversal(alpha1_rad: float, alpha2_rad: float) -> ReversalResult:
    """Prism deviation and squareness from a measurement and its reversal (paper 004 eqs 2-5).

    With the laser on one side, ``alpha_1 = alpha_p - alpha_0`` (eq 2); with laser and prism turned
    round, ``alpha_2 = alpha_0 + alpha_p`` (eq 3). The paper's eqs (4)-(5) are missing from the
    text; solving 2-3 gives ``alpha_0 = (alpha_2 - alpha_1) / 2`` and ``alpha_p = (alpha_1 + alpha_2) / 2``.
    Each ``alpha_i = delta_d_i / L_0`` (spot travel over stage travel).

    Parameters
    ----------
    alpha1_rad, alpha2_rad : float
        The angles of the first and the reversed measurement, radians.

    Returns
    -------
    ReversalResult

    Raises
    ------
    AxiscalError
        An angle that is not finite.

    Examples
    --------
    >>> result = prism_reversal(3e-5, 5e-5)
    >>> round(result.prism_deviation_rad, 9), round(result.squareness_rad, 9)
    (4e-05, 1e-05)
    """
    alpha1_rad = check_number("alpha1_rad", alpha1_rad, unit="radians")
    alpha2_rad = check_number("alpha2_rad", alpha2_rad, unit="radians")
    return ReversalResult(
        prism_deviation_rad=(alpha1_rad + alpha2_rad) / 2.0, squareness_rad=(alpha2_rad - alpha1_rad) / 2.0
    )


def prism_deviation_from_wedge(alpha1_rad: float, alpha2_rad: float) -> float:
    """Magnitude of a pentaprism's deviation from 90 deg by autocollimator and wedge (paper 002 eq 22).

    ``|D| = |alpha_1 - alpha_2| / 4``: ``alpha_1`` is the angle between the autocollimator's beam
    and the beam back from the wedge, ``alpha_2`` that between the autocollimator's transmitted
    beam and the beam back from the mirror, radians. The method gives the size of the error only;
    its sign must come from the set-up (or from a reversal, :func:`prism_reversal`).

    Parameters
    ----------
    alpha1_rad, alpha2_rad : float
        The two autocollimator angles, radians.

    Returns
    -------
    float
        ``|D|``, radians.

    Raises
    ------
    AxiscalError
        An angle that is not finite.

    Examples
    --------
    >>> prism_deviation_from_wedge(5e-5, 1e-5)
    1e-05
    """
    alpha1_rad = check_number("alpha1_rad", alpha1_rad, unit="radians")
    alpha2_rad = check_number("alpha2_rad", alpha2_rad, unit="radians")
    return abs(alpha1_rad - alpha2_rad) / 4.0


def psd_angular_resolution(linear_resolution_m: float, travel_m: float) -> float:
    """Angular resolution ``r = a / L`` of a PSD squareness set-up (paper 004 eq 1), radians.

    Parameters
    ----------
    linear_resolution_m : float
        Linear resolution ``a`` of the PSD, metres.
    travel_m : float
        Travel ``L`` of the stage over which the spot is followed, metres.

    Notes
    -----
    0.3 um over 18 mm is 16.7 urad = 3.4 arcsec = 0.057 arcmin; the paper's "0.06 arcsec" is arc
    minutes (a unit slip in the paper), and so is its "0.001 arcsec" for 1000 mm.

    Returns
    -------
    float
        ``a / L``, radians.

    Raises
    ------
    AxiscalError
        A resolution or travel that is not a positive length.

    Examples
    --------
    >>> from axiscal.units import UM, MM
    >>> round(psd_angular_resolution(0.3 * UM, 18 * MM), 7)
    1.67e-05
    """
    linear_resolution_m = check_number("linear_resolution_m", linear_resolution_m, positive=True, unit="metres")
    travel_m = check_number("travel_m", travel_m, positive=True, unit="metres")
    return linear_resolution_m / travel_m
