"""studies/indentation.py's closed forms: Hertz's subsurface maximum under a sphere, against
Johnson's (Contact Mechanics, section 3.4: for nu = 0.3 the largest shear stress on the
axis is 0.31 p0 at z = 0.48 a, so the von Mises stress 0.62 p0 there)."""

import math

import pytest

from studies.indentation import NU, hertz_radius, hertz_subsurface


def test_hertz_subsurface_maximum_is_johnsons():
    assert NU == 0.3
    force = 20.0
    a = hertz_radius(force)
    p0 = 1.5 * force / (math.pi * a ** 2)
    largest, depth = hertz_subsurface(force)
    assert largest / p0 == pytest.approx(0.62, abs=0.005)
    assert depth / a == pytest.approx(0.48, abs=0.01)
