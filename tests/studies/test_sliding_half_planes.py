"""The half-plane reference of sliding contact (studies/sliding_half_planes.py): Hertz's
pressure without friction, no effect of friction between bodies of one material
(Dundurs' beta = 0), the load carried, and friction pushing the pressure towards the
trailing edge under a stiffer cylinder (the module's docstring: Betti's reciprocity)."""

import math

import numpy as np
import pytest

from studies.sliding_half_planes import centre_and_edges, sliding_contact

P, R = 1.0e-3, 100.0


def _hertz(upper, lower):
    star = 1.0 / sum((1 - nu ** 2) / E for E, nu in (upper, lower) if not math.isinf(E))
    a = math.sqrt(4 * P * R / (math.pi * star))
    return a, 2 * P / (math.pi * a)


@pytest.mark.parametrize("upper", [(1.0, 0.3), (math.inf, 0.3), (3.0, 0.25)])
def test_without_friction_it_is_hertz(upper):
    lower = (1.0, 0.3)
    a, p0 = _hertz(upper, lower)
    x, p, _ = sliding_contact(P, R, 0.0, upper, lower, cells=1600)
    assert p.max() / p0 == pytest.approx(1.0, abs=2e-3)
    centre, low, high = centre_and_edges(x, p)
    cell = x[1] - x[0]
    assert abs(low + a) < cell and abs(high - a) < cell
    assert abs(centre) < 1e-12 * a
    inside = np.abs(x) < 0.9 * a
    np.testing.assert_allclose(p[inside], p0 * np.sqrt(1 - (x[inside] / a) ** 2), rtol=0,
                               atol=3e-3 * p0)


def test_friction_between_bodies_of_one_material_changes_nothing():
    body = (1.0, 0.3)
    x0, p0, d0 = sliding_contact(P, R, 0.0, body, body, cells=800)
    x1, p1, d1 = sliding_contact(P, R, 0.5, body, body, cells=800)
    np.testing.assert_array_equal(p0, p1)


def test_the_load_is_carried_and_friction_moves_the_pressure_backwards():
    x, p, _ = sliding_contact(P, R, 0.5, (math.inf, 0.3), (1.0, 0.3), cells=1600)
    assert np.sum(p) * (x[1] - x[0]) == pytest.approx(P, rel=1e-12)
    assert (p >= 0).all()
    centre, low, high = centre_and_edges(x, p)
    a, _ = _hertz((math.inf, 0.3), (1.0, 0.3))
    assert centre < -0.05 * a and low < -a and high < a    # against the sliding, -x
