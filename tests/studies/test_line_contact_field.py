"""The field below a line contact, frictionless and sliding, against McEwen's closed form
(studies/line_contact_field.py): the base's recovered stresses give the largest von
Mises stress and its depth within 1 % on a block of 128 a at mesh level 2, and a finite
block's excess falls like 1/W (its sigma_11 of order P/W)."""

import pytest

from studies.line_contact_field import run, run_sliding
from studies.report import power_fit

pytestmark = pytest.mark.slow       # not in the everyday subset (make test-fast)


def test_the_largest_von_mises_stress_and_its_depth_are_mcewens_within_1_percent():
    row = run(128.0, 200.0, 2)
    assert abs(row["von_mises_error"]) < 0.01, row
    assert abs(row["depth_error"]) < 0.01, row


def test_a_finite_blocks_excess_falls_like_one_over_its_size():
    rows = [run(size, 40.0 if size <= 32 else 200.0, 1) for size in (16.0, 32.0, 64.0)]
    errors = [row["von_mises_error"] for row in rows]
    assert all(error > 0 for error in errors)          # the block is stiffer in sigma_11
    _, slope = power_fit([16.0, 32.0, 64.0], errors)
    assert -1.15 < slope < -0.85, errors


# Full sliding (issue's must-show): McEwen's largest von Mises stress lies below the
# surface at mu = 0.1 (0.565 p0 at x = 0.285 a, z = 0.669 a), its depth within 1 % at
# mesh level 2 only; on the surface from mu of about 0.27 (mu = 0.3: 0.667 p0 at
# x = 0.287 a; mu = 0.5: 0.975 p0 at x = 0.447 a), within 0.4 % from mesh level 1.
@pytest.fixture(scope="module", params=[(0.1, 2), (0.3, 1), (0.5, 1)],
                ids=["mu 0.1", "mu 0.3", "mu 0.5"])
def sliding(request):
    mu, level = request.param
    return run_sliding(128.0, 200.0, level, mu)


def test_sliding_the_largest_von_mises_stress_is_mcewens_within_1_percent(sliding):
    assert abs(sliding["von_mises_error"]) < 0.01, sliding
    if sliding["depth_reference"] > 0:
        assert abs(sliding["depth"] / sliding["depth_reference"] - 1) < 0.01, sliding
    else:                       # on the surface, as McEwen's
        assert sliding["depth"] == 0.0, sliding
    # ahead of the axis, towards the sliding, by McEwen's x1 within 0.03 a (the field
    # is flat along x1 there: its nodes are b/32 apart)
    assert abs(sliding["x1"] - sliding["x1_reference"]) < 0.03, sliding


def test_sliding_the_friction_force_is_mu_times_the_normal_force(sliding):
    assert abs(sliding["friction_ratio"] - sliding["mu"]) < 1e-9 * sliding["mu"], sliding


def test_sliding_the_face_is_in_tension_behind_the_contact(sliding):
    """McEwen: 2 mu p0 at the trailing edge x1 = -a, a cusp (sigma_x falls like
    sqrt(-x/a - 1) outside): at mesh level 2 the base's nodal stresses gave 0.86-0.88 of
    it at the edge or the first node behind it, 0.81-0.83 at level 1 (rising as the
    square root of the element size)."""
    assert -1.05 < sliding["face_tension_x1"] <= -1.0 + 1e-9, sliding
    assert 0.8 < sliding["face_tension"] <= 1.0, sliding
