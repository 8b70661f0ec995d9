"""The stamp's partner balanced (orchestrate/ddm/force_balance.py).

On a worker written out in numpy (a symmetric positive definite matrix K, trace rows T
on a contact side and a bond side, Robin terms T' diag(omega alpha) T): the offset the
balance finds makes the partner's contact carry the stamp's force, whether it was
probed (a new matrix) or predicted from the last solve, and a probe is asked once per
matrix. In the loop (FreeFEM workers): the contact force equals the stamp's at every
iteration, the answer is the unbalanced loop's, and it takes fewer iterations.
"""

from dataclasses import replace
from types import SimpleNamespace

import numpy as np
import pytest

import orchestrate
from orchestrate.ddm.force_balance import ForceBalance
from studies.indenter_contrast import scene_with

CONTACT, BOND = (0, 1), (1, 1)
FORCE = 0.37


class LinearWorker:
    """A Robin solve K u + sum T' diag(omega alpha) T u = loads + sum T' diag(omega alpha) g
    for a contact side (one component) and a bond side (two)."""

    def __init__(self, rng, dofs=40, contact_points=7, bond_points=5):
        root = rng.normal(size=(dofs, dofs))
        self.K = root @ root.T + dofs * np.eye(dofs)
        self.loads = rng.normal(size=dofs)
        self.rows = {CONTACT: [rng.normal(size=(contact_points, dofs))],
                     BOND: [rng.normal(size=(bond_points, dofs)) for _ in range(2)]}
        self.weight = {CONTACT: rng.uniform(0.1, 1.0, contact_points),
                       BOND: rng.uniform(0.1, 1.0, bond_points)}
        self.solves = 0

    def solve(self, data, names):
        self.solves += 1
        matrix, rhs = self.K.copy(), self.loads.copy()
        for key, rows in self.rows.items():
            alpha, g = data[key]
            for row, datum in zip(rows, np.atleast_2d(g)):
                matrix += row.T @ np.diag(self.weight[key] * alpha) @ row
                rhs += row.T @ (self.weight[key] * alpha * datum)
        u = np.linalg.solve(matrix, rhs)
        traces = {key: np.array([row @ u for row in rows]) for key, rows in self.rows.items()}
        traces[CONTACT] = traces[CONTACT][0]
        return traces, {}, None


def _problem(worker, rng):
    contact_points, bond_points = len(worker.weight[CONTACT]), len(worker.weight[BOND])
    normal = np.column_stack([rng.uniform(-0.2, 0.2, contact_points),
                              rng.uniform(0.9, 1.0, contact_points)])
    interfaces = [
        SimpleNamespace(kind="contact", weight=worker.weight[CONTACT], normal=normal,
                        components=1, size=contact_points),
        SimpleNamespace(kind="bond", weight=worker.weight[BOND],
                        normal=np.tile([0.0, 1.0], (bond_points, 1)), components=2,
                        size=bond_points)]
    return SimpleNamespace(interfaces=interfaces, scene=SimpleNamespace(half_force=FORCE))


def _data(worker, rng, active):
    contact = len(worker.weight[CONTACT])
    return {CONTACT: (np.where(active, 3.0, 0.0), rng.normal(size=(1, contact))),
            BOND: (np.full(len(worker.weight[BOND]), 2.0),
                   rng.normal(size=(2, len(worker.weight[BOND]))))}


def _carried(balance, worker, data):
    traces, _, _ = worker.solve(data, ["partner"])
    return balance.force_of(data, traces)


@pytest.fixture
def setup():
    rng = np.random.default_rng(7)
    worker = LinearWorker(rng)
    problem = _problem(worker, rng)
    return rng, worker, ForceBalance(problem, "partner", [CONTACT, BOND]), problem


def test_a_new_matrix_is_probed_and_its_solve_shifted_to_carry_the_force(setup):
    rng, worker, balance, problem = setup
    data = _data(worker, rng, np.arange(7) < 5)
    traces, _, _ = worker.solve(data, ["partner"])
    assert abs(balance.force_of(data, traces) - FORCE) > 0.1     # unbalanced, it does not
    shifted, shifted_traces = balance.settled(data, traces, worker.solve)
    assert worker.solves == 2                                     # the solve and its probe
    # the traces it returns are those of a solve of the shifted data (exact linearity)
    solved, _, _ = worker.solve(shifted, ["partner"])
    for key in solved:
        np.testing.assert_allclose(shifted_traces[key], solved[key], rtol=1e-10, atol=1e-12)
    assert balance.force_of(shifted, shifted_traces) == pytest.approx(FORCE, rel=1e-10)
    # the shift is along the contact's normal on its side B alone
    np.testing.assert_array_equal(shifted[BOND][1], data[BOND][1])
    step = (np.atleast_2d(shifted[CONTACT][1]) - data[CONTACT][1])[0]
    n2 = problem.interfaces[0].normal[:, 1]
    np.testing.assert_allclose(step / n2, step[0] / n2[0])


def test_later_data_of_the_same_matrix_are_shifted_before_the_solve(setup):
    rng, worker, balance, problem = setup
    active = np.arange(7) < 5
    data = _data(worker, rng, active)
    traces, _, _ = worker.solve(data, ["partner"])
    balance.settled(data, traces, worker.solve)
    for _ in range(3):
        later = balance.balanced(_data(worker, rng, active))
        assert _carried(balance, worker, later) == pytest.approx(FORCE, rel=1e-10)
        traces, _, _ = worker.solve(later, ["partner"])
        balance.settled(later, traces, worker.solve)
    assert worker.solves == 2 + 3 * 2         # one probe only (and _carried's solves)


def test_a_changed_matrix_is_probed_again(setup):
    rng, worker, balance, problem = setup
    data = _data(worker, rng, np.arange(7) < 5)
    traces, _, _ = worker.solve(data, ["partner"])
    balance.settled(data, traces, worker.solve)
    changed = _data(worker, rng, np.arange(7) < 6)                # a point more in contact
    assert balance.balanced(changed) is changed                   # nothing to predict from
    traces, _, _ = worker.solve(changed, ["partner"])
    solves = worker.solves
    shifted, shifted_traces = balance.settled(changed, traces, worker.solve)
    assert worker.solves == solves + 1
    assert balance.force_of(shifted, shifted_traces) == pytest.approx(FORCE, rel=1e-10)


# ---- in the loop --------------------------------------------------------------------

@pytest.fixture(scope="module")
def contrast_runs():
    """The contrast study's scene at E1/E3 = 10 (orchestrate/scenes/gallery/
    near_rigid_cylinder.toml, its indenter ten times the base's modulus), mesh level 1,
    balanced (the default) and not; the coating inside the base's worker, as auto takes
    it at the default eps_u (here 1e-8, below auto's reach: asked)."""
    scene, settings = scene_with(10.0)
    settings = replace(settings, eps_u=1e-8, bonds="inside")
    return {balance: orchestrate.solve(scene, replace(settings, force_balance=balance))
            for balance in ("auto", "off")}


def test_the_partner_carries_the_stamps_force_at_every_iteration(contrast_runs):
    balanced = contrast_runs["auto"]
    assert balanced.summary["strategy"]["force_balance"] == "coated_base"
    force = balanced.history["contact_force"].to_numpy()
    half_force = scene_with(10.0)[0].half_force
    # the contact force is the mean of both sides' tractions: the stamp's side carries
    # the force in its own solve, its partner by the balance
    np.testing.assert_allclose(force, half_force, rtol=1e-8)
    unbalanced = contrast_runs["off"].history["contact_force"].to_numpy()
    assert abs(unbalanced[0] - half_force) > 0.1 * half_force


def test_balanced_the_loop_answers_the_same_in_fewer_iterations(contrast_runs):
    balanced, unbalanced = contrast_runs["auto"], contrast_runs["off"]
    assert balanced.summary["converged"] and unbalanced.summary["converged"]
    for name in ("peak_contact_stress", "contact_half_width"):
        assert balanced.summary[name] == pytest.approx(unbalanced.summary[name], rel=1e-6)
    # measured at mesh level 1: 16 iterations against 34
    assert balanced.summary["iterations"] < 0.75 * unbalanced.summary["iterations"]
