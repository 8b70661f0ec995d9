"""Partial slip against Cattaneo, and a load path against Mindlin and Deresiewicz
(studies/partial_slip.py): a cylinder on a block of its own material (W = 16 a, mesh
level 1). Pulled by Q = mu P / 2, measured: the stick zone's half-width c/a within
0.55 % of sqrt(1 - Q/(mu P)), its centre 0.008 a off the axis, the friction traction
within 0.034 mu p0 of Cattaneo's (at the stick zone's ends). Pressed, pulled to
mu P / 2 and turned to -mu P / 2: the zone stuck through the turn within 0.52 % of
c'/a = sqrt(1 - (Q* - Q)/(2 mu P)), the traction within 0.034 mu p0 of theirs."""

import pytest

from studies.partial_slip import run, run_path

pytestmark = pytest.mark.slow


def test_the_stick_zone_and_the_traction_are_cattaneos():
    row = run(16.0, 40.0, 1, 0.5)
    assert abs(row["stick_error"]) < 0.01, row
    assert abs(row["stick_centre"]) < 0.01, row
    assert row["traction_error"] < 0.05, row
    assert row["shift"] > 0                     # the stamp moved with the force, +x1


def test_a_turned_tangential_force_reverses_the_slip_as_mindlin_and_deresiewicz():
    row = run_path(16.0, 40.0, 1, 0.5, -0.5)
    assert abs(row["stick_error"]) < 0.01, row
    assert abs(row["stick_centre"]) < 0.01, row
    assert row["traction_error"] < 0.05, row
    assert abs(row["tangential_force_error"]) < 1e-9, row
    assert min(row["pressed_iterations"], row["peak_iterations"]) > 0, row
