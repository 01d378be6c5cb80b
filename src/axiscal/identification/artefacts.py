"""The measurement equation of each artefact: what it reads, as a function of the volumetric error at the machine points it uses.

Every artefact reads the machine at N points (axis positions and a tool point). With ``e_i`` the
volumetric error there (actual minus nominal, workpiece frame, :meth:`axiscal.model.Machine.volumetric_error`)
and ``x_i`` the nominal point the machine reports, the residuals are:

- ball plate (Kunzmann, Trapet and Waeldele 1990): ``x_i + e_i - (R (c_b - c̄) + t)`` per
  coordinate, ``c_b`` the certified centre of the ball probed, ``c̄`` the centroid of the balls
  measured, ``(R, t)`` the plate's pose (fitted): its turn about that centroid and where the
  centroid stands, so that nothing depends on the frame of the certificate;
- step gauge: ``n · (x_i - s) + n · e_i - (p + L_f)``, ``s, n`` the line, ``L_f`` the certified face
  position, ``p`` the gauge's place along the line (fitted);
- ballbar network: ``|x_i + e_i - c_k| - ℓ_i``, ``c_k`` the centre ball of setup k (fitted),
  ``ℓ_i`` the calibrated length plus the bar's reading;
- multilateration (Schwenke et al., CIRP Annals 54/1, 2005): ``|x_i + e_i - s_j| + d_j - ρ_i``,
  ``s_j`` the position of station j and ``d_j`` its dead path (both fitted);
- R-test (Weikert, CIRP Annals 53/1, 2004; ISO 10791-6): ``d_k · e_i + z_k - m_ik`` for sensor k
  of direction ``d_k`` (workpiece frame) and zero offset ``z_k`` (fitted).

Each residual depends on the error at one point, along one direction: the Jacobian of the
residuals is ``direction · ∂e/∂θ`` for the machine's terms and an analytic block for the
artefact's own unknowns (its pose, place, centres, stations, offsets).

This module is the top of the artefacts: their common part is :mod:`axiscal.identification.equation`,
each kind is in :mod:`~axiscal.identification.plates`, :mod:`~axiscal.identification.lengths` or
:mod:`~axiscal.identification.rtest`; the kinds a file may name are here, and every name stays
importable from here.
"""

from __future__ import annotations

from axiscal.identification.equation import MISFIT_M, Artefact, axis_positions, r_test_positions
from axiscal.identification.lengths import BallbarNetwork, Multilateration
from axiscal.identification.plates import BallPlate, StepGauge
from axiscal.identification.rtest import RTest

__all__ = [
    "MISFIT_M",
    "Artefact",
    "BallPlate",
    "StepGauge",
    "BallbarNetwork",
    "Multilateration",
    "RTest",
    "axis_positions",
    "r_test_positions",
    "ARTEFACT_KINDS",
]


#: the kind named in an artefact file -> its class
ARTEFACT_KINDS = {cls.kind: cls for cls in (BallPlate, StepGauge, BallbarNetwork, Multilateration, RTest)}
