"""The plane-strain P2 elasticity form of freefem/elasticity.idp, alone.

Every body of the scene (Omega1, Omega3, the 2D coating) is discretised with this form,
so it is checked here apart from the domain decomposition:

* Patch tests (tests/forms/freefem/elasticity_patch.edp): on an unstructured, distorted mesh
  of a quadrilateral, a linear displacement field with Dirichlet data on the whole
  boundary, or with its exact traction sigma.n on two sides and Dirichlet data on the
  other two, must be reproduced to round-off, and so must its constant stresses (the
  stress macros, with this file's own plane-strain Lame constants) -- for nu = 0.3 and
  the nearly incompressible nu = 0.49.  This catches a wrong strain, energy, Lame
  constant, stress macro or sign of the traction term.
* Manufactured solution (tests/forms/freefem/elasticity_manufactured.edp): a smooth
  non-polynomial field with its body force f = -div sigma(u), derived by hand in the
  script and checked here by finite differences; on distorted square(n, n) meshes,
  n = 4, 8, 16, 32, the L2 and H1-seminorm errors must converge at the P2 orders 3 and 2
  (at least 2.8 and 1.8 over the last two refinements).  This catches errors that a
  linear field cannot see (e.g. in the load vector or in second-order consistency).
"""

import numpy as np
import pandas as pd
import pytest

E = 1.0
# a generic linear field: u1 = c10 + c11 x + c12 y, u2 = c20 + c21 x + c22 y
COEFFICIENTS = {"c10": 0.31, "c11": 0.72, "c12": -0.43, "c20": -0.17, "c21": 0.56,
                "c22": 0.94}
ROUND_OFF = 1e-10
LEVELS = (4, 8, 16, 32)


def lame(young, poisson):
    """Plane-strain Lame constants (lambda, mu)."""
    return (young * poisson / ((1 + poisson) * (1 - 2 * poisson)),
            young / (2 * (1 + poisson)))


def _relative_max_error(computed, exact):
    return float(np.max(np.abs(computed - exact)) / np.max(np.abs(exact)))


@pytest.mark.parametrize("boundary", ["dirichlet", "traction"])
@pytest.mark.parametrize("nu", [0.3, 0.49])
def test_patch_linear_field_is_reproduced_to_round_off(run_freefem, tmp_path, nu, boundary):
    arguments = ["-E", E, "-nu", nu, "-boundary", boundary, "-output", tmp_path / "patch"]
    for name, value in COEFFICIENTS.items():
        arguments += [f"-{name}", value]
    run_freefem("elasticity_patch.edp", *arguments)
    c = COEFFICIENTS

    nodes = pd.read_csv(tmp_path / "patch_displacement.csv")
    x, y = nodes["x"].to_numpy(), nodes["y"].to_numpy()
    # the mesh is not trivial: many P2 nodes, most of them interior
    assert len(nodes) > 300
    exact = np.concatenate([c["c10"] + c["c11"] * x + c["c12"] * y,
                            c["c20"] + c["c21"] * x + c["c22"] * y])
    computed = np.concatenate([nodes["u1"], nodes["u2"]])
    assert _relative_max_error(computed, exact) < ROUND_OFF

    lam, mu = lame(E, nu)
    trace = c["c11"] + c["c22"]
    exact_stress = {"s11": lam * trace + 2 * mu * c["c11"],
                    "s22": lam * trace + 2 * mu * c["c22"],
                    "s12": mu * (c["c12"] + c["c21"]),
                    "s33": lam * trace}
    stresses = pd.read_csv(tmp_path / "patch_stress.csv")
    size = max(abs(value) for value in exact_stress.values())
    for name, value in exact_stress.items():
        error = float(np.max(np.abs(stresses[name].to_numpy() - value))) / size
        assert error < ROUND_OFF, (name, error)


# The manufactured solution, written independently of the FreeFEM script.
def _u1(x, y):
    return np.sin(np.pi * x) * np.cos(np.pi * y)


def _u2(x, y):
    return np.exp(x) * np.sin(y)


def _minus_div_sigma(x, y, lam, mu, step=1e-4):
    """f = -div sigma(u) by second-order central differences of u."""
    def second(u, dx, dy):
        if dx and dy:  # mixed derivative
            return (u(x + step, y + step) - u(x + step, y - step)
                    - u(x - step, y + step) + u(x - step, y - step)) / (4 * step**2)
        ex, ey = step * dx, step * dy
        return (u(x + ex, y + ey) - 2 * u(x, y) + u(x - ex, y - ey)) / step**2
    u1xx, u1yy, u1xy = second(_u1, 1, 0), second(_u1, 0, 1), second(_u1, 1, 1)
    u2xx, u2yy, u2xy = second(_u2, 1, 0), second(_u2, 0, 1), second(_u2, 1, 1)
    # sigma11,x + sigma12,y and sigma12,x + sigma22,y
    f1 = -((lam + 2 * mu) * u1xx + lam * u2xy + mu * (u1yy + u2xy))
    f2 = -((lam + 2 * mu) * u2yy + lam * u1xy + mu * (u1xy + u2xx))
    return f1, f2


def _convergence(run_freefem, tmp_path, nu):
    rows = []
    for n in LEVELS:
        output = tmp_path / f"manufactured_{n}"
        run_freefem("elasticity_manufactured.edp", "-E", E, "-nu", nu, "-elements", n,
                    "-output", output)
        rows.append(pd.read_csv(f"{output}_errors.csv"))
    return pd.concat(rows, ignore_index=True)


@pytest.mark.parametrize("nu", [0.3, 0.49])
def test_manufactured_body_force_is_minus_div_sigma(run_freefem, tmp_path, nu):
    run_freefem("elasticity_manufactured.edp", "-E", E, "-nu", nu, "-elements", 2,
                "-output", tmp_path / "manufactured")
    samples = pd.read_csv(tmp_path / "manufactured_samples.csv")
    x, y = samples["x"].to_numpy(), samples["y"].to_numpy()
    np.testing.assert_allclose(samples["u1"], _u1(x, y), rtol=0, atol=1e-14)
    np.testing.assert_allclose(samples["u2"], _u2(x, y), rtol=0, atol=1e-14)
    step = 1e-6
    for name, u in (("u1", _u1), ("u2", _u2)):
        ddx = (u(x + step, y) - u(x - step, y)) / (2 * step)
        ddy = (u(x, y + step) - u(x, y - step)) / (2 * step)
        np.testing.assert_allclose(samples[f"d{name}dx"], ddx, rtol=0, atol=1e-8)
        np.testing.assert_allclose(samples[f"d{name}dy"], ddy, rtol=0, atol=1e-8)
    lam, mu = lame(E, nu)
    f1, f2 = _minus_div_sigma(x, y, lam, mu)
    size = max(np.max(np.abs(f1)), np.max(np.abs(f2)))
    # finite-difference error (truncation + round-off) ~ 1e-5 of size; a wrong term ~ 1
    assert np.max(np.abs(samples["f1"] - f1)) < 1e-5 * size
    assert np.max(np.abs(samples["f2"] - f2)) < 1e-5 * size


@pytest.mark.parametrize("nu", [0.3, 0.49])
def test_manufactured_solution_converges_at_p2_orders(run_freefem, tmp_path, nu):
    errors = _convergence(run_freefem, tmp_path, nu)
    h = errors["h"].to_numpy()
    rates = {}
    for norm in ("l2", "h1"):
        e = errors[f"{norm}_error"].to_numpy()
        rates[norm] = np.log(e[:-1] / e[1:]) / np.log(h[:-1] / h[1:])
    print(f"nu = {nu}\n{errors.to_string()}\nL2 rates {rates['l2']}\nH1 rates {rates['h1']}")
    # the mesh sizes halve, and the errors are relative errors well below 1 on the finest
    np.testing.assert_allclose(h[:-1] / h[1:], 2.0, rtol=0.03)
    assert errors["l2_error"].iloc[-1] < 1e-4 * errors["l2_norm"].iloc[-1]
    assert errors["h1_error"].iloc[-1] < 1e-2 * errors["h1_norm"].iloc[-1]
    assert np.all(rates["l2"][-2:] >= 2.8), rates["l2"]
    assert np.all(rates["h1"][-2:] >= 1.8), rates["h1"]
