"""Abbe-Bryan transfer (paper 000 eqs 4-5) in vector form."""

from __future__ import annotations

import numpy as np
import pytest

from axiscal.errors import AxiscalError
from axiscal.instruments.abbe import transfer_components, transfer_point


def test_paper000_eq4_pattern_with_the_slip_fixed():
    # paper 000 eq (4), X axis: positioning measured by the scale with Abbe offsets L_ax (along Z)
    # and L_ay (along Y); straightness by the PSD with Bryan offsets L_bx, L_by, L_bz.
    # The paper's second line reads -eps_x L_bx + eps_z L_bx; the cross product gives -eps_x L_bz.
    rng = np.random.default_rng(0)
    d = rng.normal(size=3) * 1e-6
    ex, ey, ez = rng.normal(size=3) * 1e-5
    l_ax, l_ay, l_bx, l_by, l_bz = rng.uniform(0.01, 0.1, 5)
    offsets = np.array([[0.0, l_ay, l_ax], [l_bx, l_by, l_bz], [l_bx, l_by, l_bz]])
    got = transfer_components(d, [ex, ey, ez], offsets)
    expected = [
        d[0] + ey * l_ax - ez * l_ay,
        d[1] - ex * l_bz + ez * l_bx,
        d[2] + ex * l_by - ey * l_bx,
    ]
    np.testing.assert_allclose(got, expected, rtol=1e-12)


def test_paper000_eq5_pattern_z_axis():
    # paper 000 eq (5), Z axis: straightness x, y by the PSD (L_bx, L_by, L_bz), positioning z by the
    # scale (Abbe offsets L_ax along X, L_ay along Y). Eq (5) is consistent with the vector form.
    rng = np.random.default_rng(1)
    d = rng.normal(size=3) * 1e-6
    ex, ey, ez = rng.normal(size=3) * 1e-5
    l_ax, l_ay, l_bx, l_by, l_bz = rng.uniform(0.01, 0.1, 5)
    offsets = np.array([[l_bx, l_by, l_bz], [l_bx, l_by, l_bz], [l_ax, l_ay, 0.0]])
    got = transfer_components(d, [ex, ey, ez], offsets)
    expected = [
        d[0] - ez * l_by + ey * l_bz,
        d[1] + ez * l_bx - ex * l_bz,
        d[2] - ey * l_ax + ex * l_ay,
    ]
    np.testing.assert_allclose(got, expected, rtol=1e-12)


def test_transfer_point_is_the_cross_product_and_batches():
    # 1 arcsec over a 100 mm arm: 0.485 um (paper 003 Table 3)
    arcsec = np.pi / 648000
    np.testing.assert_allclose(transfer_point([0, 0, 0], [0, 0, arcsec], [0, 0.1, 0]), [-0.4848e-6, 0, 0], atol=1e-10)
    rng = np.random.default_rng(2)
    delta, eps, arm = rng.normal(size=(3, 50, 3))
    np.testing.assert_allclose(transfer_point(delta, eps, arm), [d + np.cross(e, a) for d, e, a in zip(delta, eps, arm)])
    same = transfer_components(delta, eps, np.tile(arm[0], (3, 1)))
    np.testing.assert_allclose(same, transfer_point(delta, eps, arm[0]))
    with pytest.raises(AxiscalError):
        transfer_point([0, 0], [0, 0, 0], [0, 0, 0])
    with pytest.raises(AxiscalError):
        transfer_components(delta, eps, np.zeros((2, 3)))
