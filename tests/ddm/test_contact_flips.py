"""A contact set's update lets points into contact only where the iterate decides one of
them (orchestrate/ddm/robin.py, decided_entries): some point's penetration exceeds its
change over the last iteration. Points leaving are left to the update; once the iterates
stop changing every entry counts."""

import numpy as np

from orchestrate.ddm.robin import decided_entries, updated_contact_set


class FourPoints:
    """A contact of four points, the gap zero: a state is {(kind, side): values}."""

    contact_points = 4
    gap = np.zeros(4)

    def contact(self, x, kind, side):
        return x[kind, side]


def state(u, t):
    """Side A's displacement u and both sides' normal traction t (side B's u zero)."""
    return {("u", 0): np.asarray(u, float), ("u", 1): np.zeros(4),
            ("t", 0): np.asarray(t, float), ("t", 1): np.asarray(t, float)}


LAYOUT = FourPoints()
# point 0 in contact, in tension; points 1 and 2 free, penetrating by 1e-5 and 1e-3
# (u > gap); point 3 free, apart
PSI = np.array([1.0, 0.0, 0.0, 0.0])
IMAGE = state(u=[0.0, 1e-5, 1e-3, -1e-3], t=[2e-3, 0.0, 0.0, 0.0])
NEW_PSI = updated_contact_set(LAYOUT, PSI, IMAGE)


def test_the_semi_smooth_step_flips_the_tension_and_the_penetrations():
    assert list(NEW_PSI) == [0.0, 1.0, 1.0, 0.0]


def test_a_converged_iterate_lets_every_point_in():
    assert list(decided_entries(LAYOUT, PSI, NEW_PSI, IMAGE, IMAGE)) == list(NEW_PSI)


def test_entries_all_within_their_last_change_wait_and_a_point_leaving_does_not():
    """Points 1 and 2 penetrate by less than their change since the iterate before (1e-4
    and 2e-3); point 0's tension changed by more than itself, and it leaves."""
    before = state(u=[0.0, 1.1e-4, -1e-3, -1e-3], t=[-3e-3, 0.0, 0.0, 0.0])
    assert list(decided_entries(LAYOUT, PSI, NEW_PSI, before, IMAGE)) == [0.0, 0.0, 0.0, 0.0]


def test_one_decided_entry_takes_the_others_along():
    """Point 2's penetration (1e-3) changed by 1e-4 only: point 1 enters with it."""
    before = state(u=[0.0, 1.1e-4, 9e-4, -1e-3], t=[-3e-3, 0.0, 0.0, 0.0])
    assert list(decided_entries(LAYOUT, PSI, NEW_PSI, before, IMAGE)) == list(NEW_PSI)


def test_a_point_that_moves_but_does_not_enter_decides_nothing():
    """Point 3, apart, moved by 1e-3: no entry of its own to decide."""
    before = state(u=[0.0, 1.1e-4, -1e-3, 0.0], t=[-3e-3, 0.0, 0.0, 0.0])
    assert list(decided_entries(LAYOUT, PSI, NEW_PSI, before, IMAGE)) == [0.0, 0.0, 0.0, 0.0]
