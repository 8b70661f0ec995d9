"""The Timoshenko-type shell element alone (freefem/shell.idp) against analytical
Timoshenko beam solutions, on a cantilever clamped at x1 = 0 (tests/forms/freefem/
shell_cantilever.edp: v = w = gamma = 0 at x1 = 0, free at x1 = L).

Equilibrium of the weak form a2(u, u*) = int T11 v*' + T13 (w*' + gamma*) + M11 gamma*'
(integration by parts): -T11' = p1, -T13' = p3, -M11' + T13 = 0, with T11(L) = N0,
T13(L) = P, M11(L) = 0 at the free end; constitutive laws v' = T11/Dm,
w' + gamma = T13/Ds, gamma' = M11/Db (Dm, Ds, Db: membrane, shear, bending stiffness).

1. End loads N0, P: v is linear, gamma quadratic, w cubic, all inside the P4 space, so
   the Galerkin solution must be the exact one up to round-off, for every thickness
   from h/L = 1 to 1/128 (a missing or mis-scaled stiffness, a wrong load dof, or a
   loss of accuracy to round-off for thin shells fails it). At h/L = 1 the shear
   deflection P L/Ds is ~43 % of the tip deflection: a model without the shear term
   (Euler-Bernoulli) is caught. Note that this test alone cannot reveal shear locking:
   any conforming space containing the cubic is exact at every thickness.
2. Distributed loads p1 = p3 = exp(x1): the solution is not polynomial; the errors on
   N = 1, 2, 4, 8 elements must decay at order >= 4 (P4: ~5) down to < 1e-8 relative,
   for a moderate (h/L = 0.1) and a thin (h/L = 1/128) shell. Shear locking slows the
   decay for the thin shell.
3. Locking in its severe form makes the error at a fixed mesh grow without bound as the
   thickness goes to 0 ((L/h)^2 for linear elements); here it must stay put between
   h/L = 1/128 and 1/2048.

Shear locking. Integrating the shear term exactly (5 Gauss points) made this element
lock mildly wherever it is longer than the shell is thick: the constraint w' + gamma ~ 0
confined gamma to continuous P3, and at h/L = 1/128 gamma's orders fell to 3.7, 3.9, 4.1
with 7.3e-7 on 8 elements. shell.idp now integrates the stiffness with 4 Gauss points,
exact for membrane and bending, one degree short for shear (reduced integration): gamma
reaches 1.1e-4, 4.3e-6, 1.5e-7, 4.9e-9 on N = 1, 2, 4, 8 at both thicknesses, the level
of a P4 interpolant of the exact solution. Tests 2 and 3 would catch a return of locking.
"""

import math

import numpy as np
import pytest

# Material and loads: none equal to the script's defaults, so an ignored argument fails.
YOUNG, POISSON, SHEAR_FACTOR = 3.5, 0.25, 0.9
END_AXIAL, END_TRANSVERSE = 1.3, 0.7
END_LENGTH = 2.0          # end loads: any length works, the solution is in the space
EXP_LENGTH = 1.0          # exp load: errors of the order of P4 interpolation of exp(x1)
SAMPLES = 8               # points per element written by shell_cantilever.edp


def stiffnesses(h):
    """Membrane, shear and bending stiffness of the paper's (6)."""
    membrane = YOUNG * h / (1 - POISSON**2)
    shear = SHEAR_FACTOR * YOUNG / (2 * (1 + POISSON)) * h
    bending = YOUNG * h**3 / (12 * (1 - POISSON**2))
    return membrane, shear, bending


def end_load_solution(x, length, h, axial=END_AXIAL, transverse=END_TRANSVERSE):
    """v, w, gamma under N0, P at x1 = L: T11 = N0, T13 = P, M11 = P (x - L)."""
    dm, ds, db = stiffnesses(h)
    v = axial * x / dm
    gamma = transverse * (x**2 / 2 - length * x) / db
    w = transverse * x / ds - transverse * (x**3 / 6 - length * x**2 / 2) / db
    return v, w, gamma


def exp_load_solution(x, length, h):
    """v, w, gamma under p1 = p3 = exp(x1): T11 = T13 = e^L - e^x,
    M11 = e^L (x - L + 1) - e^x, and v = w = gamma = 0 at x = 0."""
    dm, ds, db = stiffnesses(h)
    e_l = math.exp(length)
    v = (e_l * x - np.exp(x) + 1) / dm
    gamma = (e_l * (x**2 / 2 - (length - 1) * x) - np.exp(x) + 1) / db
    w = ((e_l * x - np.exp(x) + 1) / ds
         - (e_l * (x**3 / 6 - (length - 1) * x**2 / 2) - np.exp(x) + 1 + x) / db)
    return v, w, gamma


def stretch_correction(x, length, h):
    """With thickness stretch, v under p1 = p3 = exp(x1) is the Timoshenko v minus
    r Gs epsilon'(x)/Dm; w and gamma are unchanged (T13, M11 are statically determined
    and the bending law is the same).

    T11 = e^L - e^x is statically determined; T11 = Dm e + r T33 and
    T33 = S (epsilon + r e) (S = C h, r = nu/(1 - nu)) with T33 = Gs epsilon''
    (Gs = G h^3/12; epsilon'(0) = epsilon'(L) = 0, nothing fixes or loads epsilon):
    eliminating e, epsilon'' - m^2 epsilon = m^2 (r/Dm) T11 with
    m^2 = S/(Gs (1 + S r^2/Dm)). Solution: -(r/Dm) e^L + A e^x + B1 e^(-m x)
    + B2 e^(-m (L - x)), A = m^2 r/(Dm (m^2 - 1)), B1, B2 from the end conditions (the
    decaying form: m L reaches 10^4 for thin shells). Then e = (T11 - r T33)/Dm and
    v = int e = (int T11 - r Gs epsilon')/Dm."""
    dm = YOUNG * h / (1 - POISSON**2)
    s_stiff = YOUNG * (1 - POISSON) / ((1 + POISSON) * (1 - 2 * POISSON)) * h
    r = POISSON / (1 - POISSON)
    gs = YOUNG / (2 * (1 + POISSON)) * h**3 / 12
    m = math.sqrt(s_stiff / (gs * (1 + s_stiff * r**2 / dm)))
    a = m**2 * r / (dm * (m**2 - 1))
    decay = math.exp(-m * length)
    # epsilon'(0) = a - m b1 + m b2 decay = 0, epsilon'(L) = a e^L - m b1 decay + m b2 = 0
    b1, b2 = np.linalg.solve([[-m, m * decay], [-m * decay, m]], [-a, -a * math.exp(length)])
    slope = a * np.exp(x) - m * b1 * np.exp(-m * x) + m * b2 * np.exp(-m * (length - x))
    return -r * gs * slope / dm


def exp_load_resultants(x, length):
    e_l = math.exp(length)
    return e_l - np.exp(x), e_l - np.exp(x), e_l * (x - length + 1) - np.exp(x)


def relative_error(computed, exact):
    return float(np.max(np.abs(computed - exact)) / np.max(np.abs(exact)))


def cantilever(run_freefem, tmp_path, length, h, elements, load, stretch=0, **loads):
    """Run shell_cantilever.edp (stretch 1: the shell with thickness stretch); check and
    return its columns x1, v, w, gamma."""
    output = tmp_path / f"cantilever_{load}_{elements}_{stretch}.csv"
    arguments = ["-length", repr(length), "-thickness", repr(h), "-E", repr(YOUNG),
                 "-nu", repr(POISSON), "-kshear", repr(SHEAR_FACTOR), "-stretch", str(stretch),
                 "-elements", str(elements), "-load", load, "-output", str(output)]
    for name, value in loads.items():
        arguments += [f"-{name}", repr(value)]
    run_freefem("shell_cantilever.edp", *arguments)
    with open(output) as csv:
        assert csv.readline().strip() == "x1,v,w,gamma"
    x, v, w, gamma = np.loadtxt(output, delimiter=",", skiprows=1, unpack=True)
    # 8 equally spaced points per element, the end point once: the whole of [0, L].
    np.testing.assert_allclose(x, np.linspace(0, length, SAMPLES * elements + 1),
                               rtol=0, atol=1e-14 * length)
    return x, v, w, gamma


# --- the reference solutions themselves ----------------------------------------------

@pytest.mark.parametrize("load", ["end", "exp"])
def test_reference_solutions_solve_the_timoshenko_equations(load):
    """The closed forms satisfy the constitutive laws, equilibrium and the clamp (by
    central differences, at L = 2 so that the (L - 1) terms are exercised)."""
    length, h = 2.0, 0.3
    dm, ds, db = stiffnesses(h)
    x = np.linspace(0.1, length - 0.1, 37)
    step = 1e-4
    if load == "end":
        def solution(s):
            return end_load_solution(s, length, h)
        t11 = np.full_like(x, END_AXIAL)
        t13 = np.full_like(x, END_TRANSVERSE)
        m11 = END_TRANSVERSE * (x - length)
        end = (END_AXIAL, END_TRANSVERSE, 0.0)
    else:
        def solution(s):
            return exp_load_solution(s, length, h)
        t11, t13, m11 = exp_load_resultants(x, length)
        end = tuple(float(r) for r in exp_load_resultants(np.array(length), length))
        # equilibrium of the resultants: -T11' = p1, -T13' = p3, M11' = T13
        slope = [(a - b) / (2 * step) for a, b in
                 zip(exp_load_resultants(x + step, length), exp_load_resultants(x - step, length))]
        np.testing.assert_allclose(-slope[0], np.exp(x), rtol=1e-7)
        np.testing.assert_allclose(-slope[1], np.exp(x), rtol=1e-7)
        np.testing.assert_allclose(slope[2], t13, rtol=1e-7, atol=1e-7)
    assert end == pytest.approx((END_AXIAL, END_TRANSVERSE, 0.0) if load == "end"
                                else (0.0, 0.0, 0.0), abs=1e-14)
    v, w, gamma = solution(x)
    dv, dw, dgamma = [(a - b) / (2 * step) for a, b in zip(solution(x + step), solution(x - step))]
    np.testing.assert_allclose(dm * dv, t11, rtol=1e-7, atol=1e-7)
    np.testing.assert_allclose(ds * (dw + gamma), t13, rtol=1e-6, atol=1e-6)
    np.testing.assert_allclose(db * dgamma, m11, rtol=1e-7, atol=1e-7)
    assert solution(np.array(0.0)) == pytest.approx((0.0, 0.0, 0.0), abs=1e-12)


# --- 1. end loads: exact to round-off at every thickness -------------------------------

@pytest.mark.parametrize("stretch", [0, 1], ids=["shell", "stretch_shell"])
@pytest.mark.parametrize("ratio", [1, 1 / 2, 1 / 8, 1 / 32, 1 / 128],
                         ids=["h/L=1", "h/L=1/2", "h/L=1/8", "h/L=1/32", "h/L=1/128"])
def test_end_loaded_cantilever_is_exact(run_freefem, tmp_path, ratio, stretch):
    """Also with thickness stretch: no load pulls the faces apart, epsilon = -nu/(1 - nu)
    eps11 takes up the Poisson contraction and the Timoshenko solution is exact."""
    h = ratio * END_LENGTH
    x, v, w, gamma = cantilever(run_freefem, tmp_path, END_LENGTH, h, 2, "end", stretch,
                                axial=END_AXIAL, transverse=END_TRANSVERSE)
    exact = end_load_solution(x, END_LENGTH, h)
    for name, computed, reference in zip(("v", "w", "gamma"), (v, w, gamma), exact):
        assert relative_error(computed, reference) < 1e-9, name


def test_shear_deformation_matters_for_a_thick_cantilever(run_freefem, tmp_path):
    """h/L = 1: the tip deflection is P L/Ds + P L^3/(3 Db); Euler-Bernoulli's
    P L^3/(3 Db) alone is off by ~43 %, so a missing shear term is caught."""
    h = END_LENGTH
    _, ds, db = stiffnesses(h)
    _, _, w, _ = cantilever(run_freefem, tmp_path, END_LENGTH, h, 2, "end",
                            axial=END_AXIAL, transverse=END_TRANSVERSE)
    euler_bernoulli = END_TRANSVERSE * END_LENGTH**3 / (3 * db)
    timoshenko = euler_bernoulli + END_TRANSVERSE * END_LENGTH / ds
    assert w[-1] == pytest.approx(timoshenko, rel=1e-9)
    assert abs(w[-1] - euler_bernoulli) / abs(w[-1]) > 0.1


# --- 2. distributed exp load: convergence at order >= 4 --------------------------------

MESHES = (1, 2, 4, 8)


def exp_load_errors(run_freefem, tmp_path, ratio, meshes=MESHES, stretch=0):
    """Relative max errors {field: [error on N elements for N in meshes]}."""
    h = ratio * EXP_LENGTH
    errors = {"v": [], "w": [], "gamma": []}
    for elements in meshes:
        x, v, w, gamma = cantilever(run_freefem, tmp_path, EXP_LENGTH, h, elements, "exp",
                                    stretch)
        exact = list(exp_load_solution(x, EXP_LENGTH, h))
        if stretch:
            exact[0] = exact[0] + stretch_correction(x, EXP_LENGTH, h)
        for name, computed, reference in zip(("v", "w", "gamma"), (v, w, gamma), exact):
            errors[name].append(relative_error(computed, reference))
    return errors


CASES = [(ratio, field) for ratio in (0.1, 1 / 128) for field in ("v", "w", "gamma")]
CASE_IDS = [f"h/L={'0.1' if ratio == 0.1 else '1/128'}-{field}" for ratio, field in CASES]


@pytest.mark.parametrize("ratio, field", CASES, ids=CASE_IDS)
def test_exp_load_errors_decay_at_order_at_least_four(run_freefem, tmp_path, ratio, field):
    errors = np.array(exp_load_errors(run_freefem, tmp_path, ratio)[field])
    orders = np.log2(errors[:-1] / errors[1:])   # the element size halves each time
    assert np.all(orders >= 4), (errors, orders)


def test_with_stretch_the_exp_load_errors_decay_to_its_own_solution(run_freefem, tmp_path):
    """With thickness stretch, v follows stretch_correction, w and gamma are the
    Timoshenko ones. epsilon is P2 (shell.idp) and has boundary layers of width
    ~h/6.5 at the ends, resolved once elements are shorter (h/L = 0.1 on 64, 128, 256
    elements): v then converges at the order of epsilon' in P2, 2 (measured 1.7, 1.8);
    w and gamma stay at the Timoshenko element's level."""
    errors = exp_load_errors(run_freefem, tmp_path, 0.1, meshes=(64, 128, 256), stretch=1)
    v = np.array(errors["v"])
    assert np.all(np.log2(v[:-1] / v[1:]) >= 1.6) and v[-1] < 1e-6, v
    for field in ("w", "gamma"):
        assert max(errors[field]) < 1e-10, (field, errors[field])


@pytest.mark.parametrize("ratio, field", CASES, ids=CASE_IDS)
def test_exp_load_error_on_eight_elements_is_below_1e_8(run_freefem, tmp_path, ratio, field):
    """A P4 interpolant of the exact solution on 8 elements is off by ~7e-9 (w) and
    ~5e-9 (gamma) relative; a locking-free P4 element reaches that level."""
    errors = exp_load_errors(run_freefem, tmp_path, ratio)[field]
    assert errors[-1] < 1e-8, errors


# --- 3. no severe locking: the error at a fixed mesh does not grow as h -> 0 ----------

def test_thin_limit_error_is_bounded_uniformly_in_thickness(run_freefem, tmp_path):
    """On 4 elements, 16 times thinner (h/L = 1/128 -> 1/2048) must not change the
    errors of w and gamma by more than a factor 2 (a locking element: ~256)."""
    thin = exp_load_errors(run_freefem, tmp_path, 1 / 128, meshes=(4,))
    thinner = exp_load_errors(run_freefem, tmp_path, 1 / 2048, meshes=(4,))
    for field in ("w", "gamma"):
        ratio = thinner[field][0] / thin[field][0]
        assert 0.5 < ratio < 2, (field, thin[field], thinner[field])
