"""The closed forms of a sliding and a partially slipping line contact
(studies/line_contact_stresses.py), the references of the frictional scenes: each
against an independent evaluation or a published value."""

import math
import warnings

import numpy as np
import pytest
from scipy import integrate

from studies.line_contact_stresses import (cattaneo_traction, flamant_stresses, hertz_line,
                                           largest, principal_shear, sliding_stresses,
                                           stick_half_width, unloading_traction, von_mises)

POINTS = [(0.0, 0.5), (0.4, 0.3), (-0.7, 0.9), (1.5, 0.2), (-1.3, 0.6), (0.95, 0.05),
          (0.2, 1.7)]


@pytest.mark.parametrize("mu", [0.0, 0.3, 0.6])
def test_mcewens_closed_form_is_the_quadrature_of_flamants_point_loads(mu):
    """Inside, beside and below the contact, under and outside it, to rounding."""
    a, p0 = 1.3, 2.0

    def pressure(s):
        return p0 * math.sqrt(max(1.0 - (s / a) ** 2, 0.0))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", integrate.IntegrationWarning)
        for x, z in POINTS:
            closed = np.array(sliding_stresses(a * x, a * z, a, p0, mu, 0.3)[:3])
            quadrature = np.array(flamant_stresses(a * x, a * z, a, pressure,
                                                   lambda s: mu * pressure(s)))
            assert np.allclose(closed, quadrature, rtol=0, atol=1e-12 * p0), (x, z)


def test_the_largest_principal_shear_under_hertz_is_johnsons():
    """0.300 p0 at z = 0.786 a on the axis (Johnson, Contact Mechanics, section 4.2),
    whatever nu."""
    value, x, z = largest(lambda sx, sz, txz, sy: principal_shear(sx, sz, txz), 0.0, 0.3)
    assert value == pytest.approx(0.300, abs=5e-4)
    assert z == pytest.approx(0.786, abs=5e-4) and abs(x) < 1e-6


def test_friction_brings_the_largest_von_mises_stress_to_the_surface_near_mu_0_3():
    """Below the surface, closer to it and ahead of the axis as mu grows; at the surface
    from mu between 0.25 and 0.3 (Johnson, section 7.2: for mu above about 0.3 the
    surface yields first)."""
    depths = {mu: largest(von_mises, mu, 0.3)[2] for mu in (0.0, 0.1, 0.2, 0.25, 0.3, 0.5)}
    assert depths[0.0] > depths[0.1] > depths[0.2] > depths[0.25] > 0.3
    assert depths[0.3] == depths[0.5] == 0.0
    value, x, z = largest(von_mises, 0.0, 0.3)
    assert abs(x) < 1e-6 and value == pytest.approx(0.5575, abs=1e-4)   # the axis


def test_the_partial_slip_traction_carries_the_tangential_force():
    """Cattaneo: the traction integrates to Q = (Q / mu P) mu P, is mu p in the slip
    zone and continuous at its edge; Q -> mu P leaves no stick zone."""
    F, R, modulus, mu = 0.02, 40.0, 0.55, 0.3
    a, p0 = hertz_line(F, R, modulus)
    assert math.pi * a * p0 / 2 == pytest.approx(F)
    for share in (0.2, 0.5, 0.9):
        c = stick_half_width(a, share)
        force = integrate.quad(lambda s: float(cattaneo_traction(s, a, p0, mu, share)), -a, a,
                               points=[-c, c], limit=200, epsabs=0, epsrel=1e-12)[0]
        assert force == pytest.approx(share * mu * F, rel=1e-9)
        slip = np.linspace(c, a, 7)[1:-1]
        assert np.allclose(cattaneo_traction(slip, a, p0, mu, share),
                           mu * p0 * np.sqrt(1 - (slip / a) ** 2), rtol=1e-14)
        # inside the stick zone the step to its edge falls like sqrt(2 eps)
        eps = 1e-12
        assert float(cattaneo_traction(c * (1 - eps), a, p0, mu, share)) == pytest.approx(
            float(cattaneo_traction(c, a, p0, mu, share)), abs=2 * mu * p0 * math.sqrt(2 * eps))
    assert stick_half_width(a, 1.0) == 0.0


def test_the_unloading_traction_carries_its_force_and_reverses_at_the_edges():
    """Mindlin and Deresiewicz: after Q* and back to Q the traction integrates to Q, is
    -mu p in the reversed slip zone c' <= |x| <= a, stays q* (the peak's traction)
    inside Cattaneo's stick zone of Q* shifted by the uniform stick term, and is
    Cattaneo's at Q = Q* (no turn)."""
    F, R, modulus, mu = 0.02, 40.0, 0.55, 0.5
    a, p0 = hertz_line(F, R, modulus)
    for peak, share in ((0.75, 0.25), (0.5, -0.5), (0.6, 0.0)):
        turned = stick_half_width(a, 0.5 * (peak - share))
        kinks = sorted({turned, stick_half_width(a, peak)})
        force = integrate.quad(lambda s: float(unloading_traction(s, a, p0, mu, peak, share)),
                               -a, a, points=[-k for k in kinks] + kinks,
                               limit=200, epsabs=1e-13 * mu * F, epsrel=1e-12)[0]
        assert force == pytest.approx(share * mu * F, rel=1e-9, abs=1e-12 * mu * F)
        reversed_slip = np.linspace(turned, a, 7)[1:-1]
        assert np.allclose(unloading_traction(reversed_slip, a, p0, mu, peak, share),
                           -mu * p0 * np.sqrt(1 - (reversed_slip / a) ** 2), rtol=1e-13)
    x = np.linspace(-a, a, 41)
    assert np.allclose(unloading_traction(x, a, p0, mu, 0.5, 0.5),
                       cattaneo_traction(x, a, p0, mu, 0.5), rtol=0, atol=1e-15 * p0)
    # fully reversed (Q = -Q*): the mirror image of Cattaneo's
    assert np.allclose(unloading_traction(x, a, p0, mu, 0.5, -0.5),
                       -cattaneo_traction(x, a, p0, mu, 0.5), rtol=0, atol=1e-14 * p0)
