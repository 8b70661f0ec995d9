"""A cylinder on an uncoated block under a force load against plane-strain Hertz.

The scene of studies/hertz.py: a circular face of radius R = 40 b pressed on a flat
block, both of E = 1, nu = 0.3, both bodies W wide (half model) and W high, under the
force F = pi E* a^2 / (4 R) that gives the Hertz half-width a = 1 b, with
E* = E / (2 (1 - nu^2)) and the peak pressure p0 = 2 F / (pi a).

Measured (python -m studies.hertz, the Robin loop to eps_u = 1e-9; errors against
Hertz, mesh level 1):

    W    peak      half-width
    4    +2.22 %   -2.55 %
    5    +1.42 %   -1.92 %
    6    +0.98 %   -1.41 %
    8    +0.54 %   -0.70 %
    16   +0.11 %   +0.03 %
    32   +0.02 %   +0.05 %

The error is the finite bodies': the pressure (p^2 fitted by an ellipse) is off Hertz by
about 0.36 (a/W)^2 in p0 and in a from W = 4 to 16 (a clamped finite body is stiffer
than a half-space: a higher, narrower contact); mesh levels 2 and 3 change the peak by
at most 0.01 %, theta = 1e-4 instead of 1e-3 by at most 0.02 %. The half-width estimate
(the edge of the loaded points) scatters by up to 0.2 % between mesh levels.

W = 6 is the smallest size at which both are within 2 % with a margin above that
scatter (W = 5 passes by 0.08 % on the half-width). The test asserts the issue's 2 % on both at W = 6, level 1, and the trend:
a smaller body (W = 4) is stiffer, its peak further above Hertz and its contact
narrower. Two runs, about 2 s."""

import math

import pytest

from studies.hertz import hertz, hertz_force, hertz_scene, run

pytestmark = pytest.mark.slow       # not in the everyday subset (make test-fast)

TOLERANCE = 0.02        # the 2 %


@pytest.fixture(scope="module")
def runs():
    return {size: run(size, mesh_level=1) for size in (4.0, 6.0)}


def test_the_scene_is_hertz_with_a_unit_half_width():
    scene = hertz_scene(6.0)
    assert scene.coatings == () and scene.symmetric and scene.contact_zone == (0.0, 2.0)
    a, p0 = hertz(scene.load.force)
    assert a == pytest.approx(1.0, rel=1e-12)
    assert scene.load.force == pytest.approx(hertz_force())
    assert p0 == pytest.approx(2.0 * scene.load.force / math.pi, rel=1e-12)


def test_peak_and_half_width_within_two_percent_of_hertz(runs):
    result = runs[6.0]
    assert abs(result["force_error"]) < 1e-4     # the force load is met
    assert abs(result["peak_error"]) < TOLERANCE, result
    assert abs(result["half_width_error"]) < TOLERANCE, result


def test_a_smaller_body_is_further_from_hertz(runs):
    small, large = runs[4.0], runs[6.0]
    assert small["peak_error"] > large["peak_error"] > 0
    assert small["half_width_error"] < large["half_width_error"] < 0
