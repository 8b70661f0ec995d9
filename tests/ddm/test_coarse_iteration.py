"""The coarse correction's (I - B)^-1 (orchestrate/ddm/coarse.py, iteration_inverse)
against B formed step by step: an iteration whose steps each solve their own workers
(S maps a step's data to its own state entries) from data their laws compute from the
state the earlier steps left. Random maps and laws; the bonds inside a worker are one
step whose bonds' data come after it."""

import numpy as np
import pytest

from orchestrate.ddm.coarse import iteration_inverse


def _iteration(S, L, data_step, state_step):
    """B, formed: the steps applied one after the other to every column of the identity."""
    state = np.eye(S.shape[0])
    for step in range(int(data_step.max()) + 1):
        data = (L @ state)[data_step == step]
        rows = state_step == step
        state = state.copy()
        state[rows] = S[rows][:, data_step == step] @ data
    return state


def _random_problem(seed, steps, data_size=12):
    """S (2n x n: each data entry's trace and traction rows, in its own step) and a
    sparse L (n x 2n) with a few entries per row, contracting enough for I - B to be
    regular."""
    rng = np.random.default_rng(seed)
    n = data_size
    data_step = rng.integers(0, steps, size=n)
    state_step = np.concatenate([data_step, data_step])    # a trace and a traction each
    S = np.zeros((2 * n, n))
    for step in range(steps):
        own = data_step == step
        rows = state_step == step
        S[np.ix_(rows, own)] = rng.normal(scale=0.3, size=(rows.sum(), own.sum()))
    L = np.zeros((n, 2 * n))
    for row in range(n):
        L[row, rng.choice(2 * n, size=3, replace=False)] = rng.normal(scale=0.5, size=3)
    return S, L, data_step, state_step


@pytest.mark.parametrize("steps", [1, 2, 3])
def test_the_inverse_is_that_of_the_iteration_formed_step_by_step(steps):
    S, L, data_step, state_step = _random_problem(steps, steps)
    B = _iteration(S, L, data_step, state_step)
    r = np.random.default_rng(9).normal(size=S.shape[0])
    expected = np.linalg.solve(np.eye(len(B)) - B, r)
    assert np.allclose(iteration_inverse(S, L, data_step, state_step)(r), expected,
                       rtol=1e-10, atol=1e-12)


def test_bonds_inside_take_their_data_from_the_state_after_the_one_step():
    """One step for every worker, the bonds' data (step 1 against the state's 0) from
    its result: B = (I - S L_b)^-1 S L_a, the bonds' rows of L in L_b."""
    S, L, _, _ = _random_problem(5, 1)
    n = L.shape[0]
    bonds = np.zeros(n, dtype=bool)
    bonds[::3] = True
    L_b = np.where(bonds[:, None], L, 0.0)
    B = np.linalg.solve(np.eye(2 * n) - S @ L_b, S @ (L - L_b))
    r = np.random.default_rng(8).normal(size=2 * n)
    inverse = iteration_inverse(S, L, bonds.astype(int), np.zeros(2 * n, dtype=int))
    assert np.allclose(inverse(r), np.linalg.solve(np.eye(2 * n) - B, r),
                       rtol=1e-10, atol=1e-12)
