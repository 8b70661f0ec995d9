"""Friction between unlike bodies shifts the pressure (studies/sliding_shift.py): a rigid
cylinder sliding on a block 128 b wide, mu = 0.5, against the independent half-plane
solution (studies/sliding_half_planes.py). Measured at mesh level 1: the centre of
pressure -0.1206 a against -0.1205 a, the ends within 0.011 a (an element is 0.088 a),
the peak pressure within 0.02 %."""

import pytest

from studies.sliding_shift import run

pytestmark = pytest.mark.slow


def test_the_pressure_moves_against_the_sliding_as_the_half_planes_say():
    row = run("rigid", 0.5, mesh_level=1)
    assert row["centre_reference"] < -0.1                  # the effect is there
    assert abs(row["centre"] - row["centre_reference"]) < 0.005, row
    assert abs(row["low"] - row["low_reference"]) < 0.02, row
    assert abs(row["high"] - row["high_reference"]) < 0.02, row
    assert abs(row["peak_error"]) < 1e-3, row
