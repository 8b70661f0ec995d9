"""The field below a frictionless line contact against McEwen's closed form
(studies/line_contact_field.py): the base's recovered stresses give the largest von
Mises stress and its depth within 1 % on a block of 128 a at mesh level 2, and a finite
block's excess falls like 1/W (its sigma_11 of order P/W)."""

import pytest

from studies.line_contact_field import run
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
