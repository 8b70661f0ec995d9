"""Partial slip against Cattaneo (studies/partial_slip.py): a cylinder on a block of its
own material pulled by Q = mu P / 2; measured at mesh level 1: the stick zone's
half-width c/a within 0.55 % of sqrt(1 - Q/(mu P)), its centre 0.008 a off the axis,
the friction traction within 0.034 mu p0 of Cattaneo's (at the stick zone's ends)."""

import pytest

from studies.partial_slip import run

pytestmark = pytest.mark.slow


def test_the_stick_zone_and_the_traction_are_cattaneos():
    row = run(16.0, 40.0, 1, 0.5)
    assert abs(row["stick_error"]) < 0.01, row
    assert abs(row["stick_centre"]) < 0.01, row
    assert row["traction_error"] < 0.05, row
    assert row["shift"] > 0                     # the stamp moved with the force, +x1
