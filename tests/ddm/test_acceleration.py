"""Anderson acceleration (IQN-ILS) of the Robin loop's fixed-point map.

On affine maps x -> M x + c it must behave as GMRES does: reach the fixed point in about
n steps in dimension n, even where plain relaxation crawls (spectral radius near 1) or
diverges (an eigenvalue beyond -1); a history with dependent columns must be filtered,
not crash. And the answer of a Robin run must not depend on the loop that reached it.
"""

import numpy as np
import pandas as pd

from orchestrate.ddm.acceleration import Anderson
from orchestrate.model.scene import Settings
from orchestrate.model.scene_file import paper_scene
from orchestrate.run.solve import solve


def _affine_map(eigenvalues, seed=0):
    rng = np.random.default_rng(seed)
    basis, _ = np.linalg.qr(rng.standard_normal((len(eigenvalues), len(eigenvalues))))
    matrix = basis @ np.diag(eigenvalues) @ basis.T
    offset = rng.standard_normal(len(eigenvalues))
    fixed_point = np.linalg.solve(np.eye(len(eigenvalues)) - matrix, offset)
    return (lambda x: matrix @ x + offset), fixed_point


def _iterate(step, fixed_point, iterations):
    x = np.zeros_like(fixed_point)
    for _ in range(iterations):
        x = step(x)
    return np.linalg.norm(x - fixed_point) / np.linalg.norm(fixed_point)


def test_anderson_solves_a_slow_affine_map_in_about_n_steps():
    n = 20
    G, fixed_point = _affine_map(np.linspace(0.5, 0.995, n))
    anderson = Anderson(np.ones(n))
    assert _iterate(lambda x: anderson.step(x, G(x)), fixed_point, n + 3) < 1e-8
    # plain relaxation is nowhere near after as many steps
    assert _iterate(lambda x: 0.5 * x + 0.5 * G(x), fixed_point, n + 3) > 1e-2


def test_anderson_converges_where_relaxation_diverges():
    n = 12
    G, fixed_point = _affine_map(np.concatenate([np.linspace(-5.0, -3.5, 4),
                                                 np.linspace(0.2, 0.9, n - 4)]))
    anderson = Anderson(np.ones(n))
    assert _iterate(lambda x: anderson.step(x, G(x)), fixed_point, n + 3) < 1e-8
    assert _iterate(lambda x: 0.5 * x + 0.5 * G(x), fixed_point, n + 3) > 1.0


def test_dependent_history_is_filtered():
    anderson = Anderson(np.ones(3))
    x, g = np.zeros(3), np.array([1.0, 2.0, 3.0])
    for _ in range(4):                      # the same pair again and again
        result = anderson.step(x, g)
        assert np.all(np.isfinite(result))
    assert len(_filtered_anew(anderson, np.array([[1.0, 2.0], [1.0, 2.0], [0.0, 0.0]]))[0]) == 1


def _filtered_anew(anderson, columns):
    """The filter on a QR of ``columns`` (the newest last) factorised anew: (the kept
    columns' indices, Q, R)."""
    ordered = columns[:, ::-1]
    q, upper = np.linalg.qr(ordered)
    order, q, upper = anderson._filtered(q, upper, list(np.linalg.norm(ordered, axis=0)))
    return [columns.shape[1] - 1 - k for k in order], q, upper


def test_the_answer_does_not_depend_on_the_loop(tmp_path):
    """The paper's loop (gamma = 1/theta, fixed rho) and the accelerated active-set loop
    (Anderson, gamma = 0.5 E/b) at a penalty where both converge: same stresses."""
    scene = paper_scene()
    answers = {}
    for method in ("paper", "active-set"):
        robin = 0.5 if method == "active-set" else None
        settings = Settings(method=method, theta=1.0, robin=robin, eps_u=1e-10,
                            max_iterations=2000)
        summary = solve(scene, settings, tmp_path / method)
        answers[method] = (summary["iterations"],
                           pd.read_csv(tmp_path / method / "contact.csv").sigma_n.to_numpy())
    (paper_iterations, paper), (accelerated_iterations, accelerated) = answers.values()
    assert np.max(np.abs(paper - accelerated)) < 1e-6 * np.max(np.abs(paper))
    assert accelerated_iterations < paper_iterations / 3


def test_the_updated_qr_steps_as_a_new_factorisation_would():
    """The history's QR kept by rotations (qr_update.py) gives the iterates that a QR
    factorised anew at every step gives, with a full history and one that drops its
    oldest column (memory 20), to rounding."""
    n = 120
    G, fixed_point = _affine_map(np.linspace(-0.9, 0.999, n), seed=1)
    for memory in (200, 20):
        updated, anew = Anderson(np.ones(n), memory=memory), Anderson(np.ones(n), memory=memory)

        def step_anew(x, g):
            r = anew.record(x, g)
            if len(anew._residuals) == 1:
                return x + anew.first_relaxation * (g - x)
            d_residuals = np.diff(np.array(anew._residuals), axis=0).T
            d_images = np.diff(np.array(anew._images), axis=0).T
            order, q, upper = _filtered_anew(anew, d_residuals)
            return g - d_images[:, order] @ np.linalg.solve(upper, q.T @ r)
        x = y = np.zeros(n)
        for _ in range(100):
            x, y = updated.step(x, G(x)), step_anew(y, G(y))
            assert np.linalg.norm(x - y) <= 1e-10 * np.linalg.norm(y)


def test_qr_updates_are_factorisations():
    from orchestrate.ddm.qr_update import delete_column, prepend_column
    rng = np.random.default_rng(2)
    a = rng.standard_normal((50, 6))
    q, r = np.linalg.qr(a[:, 1:])
    q, r = prepend_column(q, r, a[:, 0])
    assert np.allclose(q @ r, a, atol=1e-12) and np.allclose(q.T @ q, np.eye(6), atol=1e-12)
    assert np.allclose(np.tril(r, -1), 0.0)
    q, r = delete_column(q, r, 2)
    assert np.allclose(q @ r, np.delete(a, 2, axis=1), atol=1e-12)
    assert np.allclose(q.T @ q, np.eye(5), atol=1e-12) and np.allclose(np.tril(r, -1), 0.0)
    assert prepend_column(q, r, a[:, 1] + a[:, 3]) is None       # in the span: anew
    square = rng.standard_normal((6, 6))                          # as many columns as rows
    q, r = np.linalg.qr(square)
    assert prepend_column(q, r, a[:6, 0]) is None
    q, r = delete_column(q, r, 4)                                 # economic again
    assert q.shape == (6, 5) and r.shape == (5, 5)
    assert np.allclose(q @ r, np.delete(square, 4, axis=1), atol=1e-12)


def test_the_answer_errors_are_exact_once_the_history_spans_the_map():
    """Anderson.answer_errors: the error of the newest image, part by part, is dG c for the
    share of its residual the secants span, exactly for an affine map, plus a bound of the
    rest. With n independent secants in dimension n nothing is left over: the bound is the
    error itself, each part apart (here: 3 slow entries beside 9 others, an image still far
    from the fixed point)."""
    n = 12
    G, fixed_point = _affine_map(np.linspace(0.9, 0.999, n), seed=1)
    parts = (np.arange(3), np.arange(3, n))
    anderson = Anderson(np.ones(n), memory=n, parts=parts)
    rng = np.random.default_rng(2)
    assert anderson.answer_errors() is None                   # no secant yet
    for _ in range(n + 1):                                      # independent secants
        x = rng.standard_normal(n)
        anderson.record(x, G(x))
    image_error = G(x) - fixed_point
    exact = [np.linalg.norm(image_error[part]) for part in parts]
    assert min(exact) > 1.0                                     # far from the answer
    np.testing.assert_allclose(anderson.answer_errors(), exact, rtol=1e-6)
