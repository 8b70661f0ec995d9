"""The half-planes' contact across a gap profile (orchestrate/model/half_space_contact.py)
against closed forms: Hertz's cylinder (Johnson, Contact Mechanics, 4.43-4.45), whole and
as a half model, and two cylinders far apart sharing a force."""

import math

import numpy as np
import pytest

from orchestrate.model.half_space_contact import contact_pressure, face_strips

RADIUS, FORCE = 20.0, 0.003
COMPLIANCE = 2.0 * (1.0 - 0.3 ** 2)     # 1/E1* + 1/E3*, two bodies of E = 1, nu = 0.3


def hertz(force):
    """(half-width, peak pressure) of a cylinder under ``force`` per unit length."""
    a = math.sqrt(4.0 * force * RADIUS * COMPLIANCE / math.pi)
    return a, 2.0 * force / (math.pi * a)


def solved(x, gap, mirrored=False, force=FORCE):
    lower, upper = face_strips(x)
    pressure, _ = contact_pressure(lower, upper, gap, COMPLIANCE, force, mirrored)
    widths = (upper - lower) * (2.0 if mirrored else 1.0)
    return pressure, float(np.dot(pressure, widths))


@pytest.mark.parametrize("mirrored", [False, True])
def test_a_cylinder_on_a_flat_gives_hertz(mirrored):
    a, peak = hertz(FORCE)
    x = np.linspace(0.0 if mirrored else -3.0 * a, 3.0 * a, 151 if mirrored else 301)
    pressure, force = solved(x, x ** 2 / (2.0 * RADIUS), mirrored)
    spacing = x[1] - x[0]
    assert force == pytest.approx(FORCE, rel=1e-12)
    assert np.max(np.abs(x[pressure > 0.0])) == pytest.approx(a, abs=spacing)
    assert pressure.max() == pytest.approx(peak, rel=2e-3)
    inside = np.abs(x) < 0.9 * a
    assert pressure[inside] == pytest.approx(peak * np.sqrt(1.0 - (x[inside] / a) ** 2),
                                             rel=1e-2)


def test_two_cylinders_far_apart_share_the_force_as_two_hertz_contacts():
    """Bumps 30 half-widths apart, on two faces given in either order: each carries half
    the force with Hertz's half-width for it."""
    a, _ = hertz(FORCE / 2.0)
    centre = 30.0 * a
    left = np.linspace(-centre - 3.0 * a, -centre + 3.0 * a, 241)
    right = -left[::-1]
    x = np.concatenate([right, left])                    # faces in any order
    gap = np.minimum((x - centre) ** 2, (x + centre) ** 2) / (2.0 * RADIUS)
    lower, upper = zip(face_strips(right), face_strips(left))
    pressure, _ = contact_pressure(np.concatenate(lower), np.concatenate(upper), gap,
                                   COMPLIANCE, FORCE)
    spacing = left[1] - left[0]
    for side in (x > 0.0, x < 0.0):
        touching = x[side & (pressure > 0.0)]
        assert touching.max() - touching.min() == pytest.approx(2.0 * a, abs=2.0 * spacing)
        widths = np.concatenate(upper) - np.concatenate(lower)
        assert np.dot(pressure[side], widths[side]) == pytest.approx(FORCE / 2.0, rel=1e-9)
