"""The plate of revolution (freefem/shell_revolution.idp) alone, against closed forms of
axisymmetric Mindlin plate theory (tests/forms/freefem/plate_revolution.edp).

The model, per radian: strains eps_r = u', eps_theta = u/r, kappa_r = beta',
kappa_theta = beta/r, gamma = w' + beta; forces N_r = Dm (eps_r + nu eps_theta),
N_theta = Dm (eps_theta + nu eps_r), M_r, M_theta likewise with Db, Q = Ds gamma
(Dm = E h/(1 - nu^2), Db = E h^3/(12 (1 - nu^2)), Ds = k' G h). The virtual work
int (N_r eps_r* + N_theta eps_theta* + M_r kappa_r* + M_theta kappa_theta* + Q gamma*) r dr
integrated by parts gives the equilibrium
    -(r N_r)' + N_theta = r p_r,   -(r Q)' = r p_z,   -(r M_r)' + M_theta + r Q = r m,
and at an edge N_r, Q, M_r equal the edge loads per unit length (outer edge), or minus
them (inner edge, outward normal -e_r).

Bending under p_z = q (r/r1)^n (a traction q (r/r1)^n along e_z on a face; m = 0).
(r Q)' = -r p_z gives Q = -q r^(n+1)/((n+2) r1^n) + c/r. With the moments,
(r M_r)' - M_theta = Db r (1/r (r beta)')', so Db (1/r (r beta)')' = Q, whence beta, and
w' = Q/Ds - beta gives w. The load's solution (c = 0, no constants):
    beta_p = -q r^(n+3)/((n+2)^2 (n+4) r1^n Db),
    w_p = -q r^(n+2)/((n+2)^2 r1^n Ds) + q r^(n+4)/((n+2)^2 (n+4)^2 r1^n Db),
    M_r = Db (n+3+nu) beta_p/r,  M_theta = Db (1 + (n+3) nu) beta_p/r;
and four load-free solutions (Q, beta, w; the moments follow):
    c:  Q = 1/r, beta = (r ln r/2 - r/4)/Db, w = ln r/Ds - (r^2 ln r/4 - r^2/4)/Db,
    C1: beta = r, w = -r^2/2;  C2: beta = 1/r, w = -ln r;  C3: w = 1.
This is the Kirchhoff general solution A + B r^2 + C ln r + D r^2 ln r plus the shear
terms ln r/Ds and w_p's first. A disc keeps C1 and C3 (regular on the axis); an annulus
takes all four, fixed by two conditions per edge: clamped w = beta = 0, simply supported
w = M_r = 0, free Q = M_r = 0 (mindlin_plate). For a uniform load (n = 0) on a disc of
radius a, with D = Db:
    clamped:  w = q (a^2 - r^2)^2/(64 D) + q (a^2 - r^2)/(4 Ds),  beta = q r (a^2 - r^2)/(16 D),
              M_r = q ((1 + nu) a^2 - (3 + nu) r^2)/16, M_theta = q ((1 + nu) a^2 - (1 + 3 nu) r^2)/16;
    simply supported:  w = q (a^2 - r^2) ((5 + nu)/(1 + nu) a^2 - r^2)/(64 D) + q (a^2 - r^2)/(4 Ds),
              beta = q r ((3 + nu)/(1 + nu) a^2 - r^2)/(16 D),
              M_r = q (3 + nu)(a^2 - r^2)/16, M_theta = q ((3 + nu) a^2 - (1 + 3 nu) r^2)/16;
Q = -q r/2 in both (q along e_z: w has the sign of q).

Membrane (Lame): with no distributed load -(r N_r)' + N_theta = 0 gives
u = A r + B/r, N_r = Dm ((1 + nu) A - (1 - nu) B/r^2), N_theta = Dm ((1 + nu) A
+ (1 - nu) B/r^2); a radial force F0 per unit length on the inner edge (along e_r):
N_r(r0) = -F0, and N_r(r1) = 0 (free) or u(r1) = 0 (clamped). eps_r + eps_theta = 2 A
is uniform, so with thickness stretch epsilon = -2 nu A/(1 - nu) and nothing else
changes.

The tests:
0. The element: symmetric, positive semi-definite, one zero-energy mode (w constant).
1. Uniform pressure on a disc, clamped or simply supported: w (degree 4), beta (3) and
   u = 0 lie in the P4 space, and the r-weighted integrands of the exact solution against
   any test function are polynomials of degree 6, which the 4-point rule integrates
   exactly: the discrete solution is exact to round-off on any mesh, thick or thin.
   So are radial face tractions, whose sum loads u and whose couple loads beta
   (face_shear_disc). Under p_z = q (r/a)^2 (w of degree 6) the errors decay at the P4
   rates.
2. Annuli (ln r and 1/r terms) under pressure or edge loads, clamped, simply supported
   or free: the P4 rates.
3. No shear locking: on one element the centre deflection's error under p_z = q (r/a)^2
   stays put from a/h = 10 to 1000.
4. Lame: the P4 rates; with stretch, epsilon exact.
5. Thickness stretch: a pressure p on both faces of a disc, its edge clamped (confined:
   eps_r = eps_theta = 0, sigma_zz = -p, epsilon = -p/C, C = E (1 - nu)/((1 + nu)(1 - 2 nu))
   the constrained modulus) or free to expand (sigma_r = sigma_theta = 0: epsilon = -p/E,
   u = nu p r/E), both exact. In bending (pressure on the top face only, clamped disc)
   w and beta are the plate's (the stretch terms couple epsilon to u only) and the
   loaded face, at w + h/2 epsilon, tends to the plate's deflection as h/a -> 0.
"""

import numpy as np
import pytest

# Material and geometry: none equal to the script's defaults, so an ignored argument fails.
YOUNG, POISSON, SHEAR_FACTOR = 3.5, 0.25, 0.9
RADIUS = 1.5                  # disc radius, annulus outer radius
INNER = 0.5                   # annulus inner radius
PRESSURE = -0.7               # p_z on the top face (along e_z: downwards)
SAMPLES = 8                   # points per element written by plate_revolution.edp
BENDING_FIELDS = ("w", "beta", "Q", "Mr", "Mtheta")


def stiffnesses(h):
    """Dm, Ds, Db: membrane, shear and bending stiffness of the plate law."""
    membrane = YOUNG * h / (1 - POISSON**2)
    shear = SHEAR_FACTOR * YOUNG / (2 * (1 + POISSON)) * h
    bending = YOUNG * h**3 / (12 * (1 - POISSON**2))
    return membrane, shear, bending


# --- closed forms -----------------------------------------------------------------------

def with_moments(r, beta, slope, bending, **fields):
    """The fields with M_r, M_theta of beta and its slope beta' (r > 0: an annulus's
    solutions)."""
    return dict(fields, beta=beta, Mr=bending * (slope + POISSON * beta / r),
                Mtheta=bending * (beta / r + POISSON * slope))


def load_solution(r, h, q, power, outer):
    """w, beta, Q, M_r, M_theta under p_z = q (r/outer)^n with no constant (docstring)."""
    _, ds, db = stiffnesses(h)
    n = power
    scale = q / outer**n
    beta_over_r = -scale * r**(n + 2) / ((n + 2)**2 * (n + 4) * db)
    return {"w": -scale * r**(n + 2) / ((n + 2)**2 * ds)
                 + scale * r**(n + 4) / ((n + 2)**2 * (n + 4)**2 * db),
            "beta": beta_over_r * r,
            "Q": -scale * r**(n + 1) / (n + 2),
            "Mr": db * (n + 3 + POISSON) * beta_over_r,
            "Mtheta": db * (1 + (n + 3) * POISSON) * beta_over_r}


def load_free_solutions(r, h):
    """The four load-free solutions c, C1, C2, C3 (docstring) at r, by name, each a
    function evaluated only when used, so that a disc never takes ln 0."""
    _, ds, db = stiffnesses(h)

    def shear_solution():
        log = np.log(r)
        beta = (r * log / 2 - r / 4) / db
        return with_moments(r, beta, (log / 2 + 1 / 4) / db, db, Q=1 / r,
                            w=log / ds - (r**2 * log / 4 - r**2 / 4) / db)

    def linear_rotation():
        one = np.ones_like(r)
        return {"w": -r**2 / 2, "beta": r, "Q": 0 * r, "Mr": db * (1 + POISSON) * one,
                "Mtheta": db * (1 + POISSON) * one}

    def inverse_rotation():
        return with_moments(r, 1 / r, -1 / r**2, db, Q=0 * r, w=-np.log(r))

    def translation():
        return {"w": np.ones_like(r), "beta": 0 * r, "Q": 0 * r, "Mr": 0 * r, "Mtheta": 0 * r}

    return {"c": shear_solution, "C1": linear_rotation, "C2": inverse_rotation,
            "C3": translation}


# The two conditions of each support: fields held at 0, or (Q, M_r) met by the edge loads.
SUPPORT_CONDITIONS = {"clamp": ("w", "beta"), "simple": ("w", "Mr"), "free": ("Q", "Mr")}


def edge_value(field, loads, outward):
    """The value of `field` that an edge's loads (transverse force, moment per unit
    length) set: Q and M_r equal them on the outer edge (outward = 1), minus them on the
    inner one (outward = -1); w and beta are held at 0."""
    return {"Q": outward * loads[0], "Mr": outward * loads[1]}.get(field, 0.0)


def mindlin_plate(r, h, q, power=0, inner=0.0, inner_support="free", outer_support="clamp",
                  outer=RADIUS, inner_loads=(0.0, 0.0), outer_loads=(0.0, 0.0)):
    """w, beta, Q, M_r, M_theta at r of a disc (inner = 0: regular on the axis) or an
    annulus under p_z = q (r/outer)^n, supported as named (SUPPORT_CONDITIONS), with a
    transverse force and a moment per unit length on each edge (edge_value)."""
    used = ("C1", "C3") if inner == 0 else ("c", "C1", "C2", "C3")
    edges = [(outer, outer_support, outer_loads, 1)]
    if inner > 0:
        edges.append((inner, inner_support, inner_loads, -1))
    matrix, right = [], []
    for radius, support, loads, outward in edges:
        edge = np.array([radius], dtype=float)
        particular = load_solution(edge, h, q, power, outer)
        free = [load_free_solutions(edge, h)[k]() for k in used]
        for field in SUPPORT_CONDITIONS[support]:
            matrix.append([solution[field][0] for solution in free])
            right.append(edge_value(field, loads, outward) - particular[field][0])
    constants = np.linalg.solve(matrix, right)
    fields = load_solution(r, h, q, power, outer)
    for constant, k in zip(constants, used):
        solution = load_free_solutions(r, h)[k]()
        fields = {name: fields[name] + constant * solution[name] for name in fields}
    return fields


def clamped_disc(r, h, q, a=RADIUS):
    """The clamped disc under a uniform p_z = q, explicitly (docstring)."""
    _, ds, db = stiffnesses(h)
    return {"w": q * (a**2 - r**2)**2 / (64 * db) + q * (a**2 - r**2) / (4 * ds),
            "beta": q * r * (a**2 - r**2) / (16 * db), "Q": -q * r / 2,
            "Mr": q * ((1 + POISSON) * a**2 - (3 + POISSON) * r**2) / 16,
            "Mtheta": q * ((1 + POISSON) * a**2 - (1 + 3 * POISSON) * r**2) / 16}


def simply_supported_disc(r, h, q, a=RADIUS):
    """The simply supported disc under a uniform p_z = q, explicitly (docstring)."""
    _, ds, db = stiffnesses(h)
    nu = POISSON
    return {"w": q * (a**2 - r**2) * ((5 + nu) / (1 + nu) * a**2 - r**2) / (64 * db)
                 + q * (a**2 - r**2) / (4 * ds),
            "beta": q * r * ((3 + nu) / (1 + nu) * a**2 - r**2) / (16 * db), "Q": -q * r / 2,
            "Mr": q * (3 + nu) * (a**2 - r**2) / 16,
            "Mtheta": q * ((3 + nu) * a**2 - (1 + 3 * nu) * r**2) / 16}


def lame_annulus(r, h, inner_force, outer_support, inner=INNER, outer=RADIUS):
    """u, N_r, N_theta and the constants A, B of the annulus under a radial force
    inner_force per unit length on its inner edge, its outer edge free or clamped."""
    dm, _, _ = stiffnesses(h)
    # N_r(r0) = -F0 and N_r(r1) = 0, or u(r1) = 0, for (A, B)
    matrix = [[dm * (1 + POISSON), -dm * (1 - POISSON) / inner**2],
              [dm * (1 + POISSON), -dm * (1 - POISSON) / outer**2] if outer_support == "free"
              else [outer, 1 / outer]]
    a, b = np.linalg.solve(matrix, [-inner_force, 0.0])
    return {"u": a * r + b / r, "Nr": dm * ((1 + POISSON) * a - (1 - POISSON) * b / r**2),
            "Ntheta": dm * ((1 + POISSON) * a + (1 - POISSON) * b / r**2), "A": a, "B": b}


def face_shear_disc(r, h, top, bottom, a=RADIUS):
    """The clamped disc under radial tractions `top` and `bottom` on its faces: the
    in-plane load p_r = top + bottom and the couple m = h/2 (top - bottom) per unit area.
    -(r N_r)' + N_theta = r p_r gives u = p_r r (a - r)/(3 Dm) (u(0) = u(a) = 0), and
    (r M_r)' - M_theta = -r m (Q = 0) gives beta = m r (a - r)/(3 Db), w = -int beta."""
    dm, _, db = stiffnesses(h)
    load, couple = top + bottom, h / 2 * (top - bottom)
    return {"u": load * r * (a - r) / (3 * dm),
            "Nr": load * ((a - 2 * r) + POISSON * (a - r)) / 3,
            "Ntheta": load * ((a - r) + POISSON * (a - 2 * r)) / 3,
            "w": couple * (a - r)**2 * (a + 2 * r) / (18 * db),
            "beta": couple * r * (a - r) / (3 * db), "Q": 0 * r,
            "Mr": couple * ((a - 2 * r) + POISSON * (a - r)) / 3,
            "Mtheta": couple * ((a - r) + POISSON * (a - 2 * r)) / 3}


# --- running the script -----------------------------------------------------------------

def plate(run_freefem, tmp_path, elements=1, levels=1, **options):
    """Run plate_revolution.edp with the material above and `options` (its names without
    the dash); return one record array per mesh (elements, 2 elements, ...)."""
    arguments = {"E": YOUNG, "nu": POISSON, "kshear": SHEAR_FACTOR, "outer": RADIUS,
                 "elements": elements, "levels": levels, **options}
    command = []
    for option, value in arguments.items():
        command += [f"-{option}", value if isinstance(value, str) else repr(value)]
    output = tmp_path / f"plate_{len(list(tmp_path.glob('plate_*.csv')))}.csv"
    run_freefem("plate_revolution.edp", *command, "-output", str(output))
    data = np.genfromtxt(output, delimiter=",", names=True)
    meshes = []
    for level in range(levels):
        mesh = data[data["elements"] == elements * 2**level]
        inner = arguments.get("inner", 0.0)
        np.testing.assert_allclose(mesh["r"], np.linspace(inner, RADIUS, SAMPLES * elements
                                                          * 2**level + 1), atol=1e-14)
        meshes.append(mesh)
    return meshes


def relative_error(computed, exact):
    return float(np.max(np.abs(computed - exact)) / np.max(np.abs(exact)))


def errors_by_mesh(meshes, exact_at, fields):
    """{field: [relative max error on each mesh]} against exact_at(r)[field]."""
    errors = {field: [] for field in fields}
    for mesh in meshes:
        exact = exact_at(mesh["r"])
        for field in fields:
            errors[field].append(relative_error(mesh[field], exact[field]))
    return errors


def orders(errors):
    """Convergence orders between successive meshes (the element size halves)."""
    errors = np.asarray(errors)
    return np.log2(errors[:-1] / errors[1:])


# --- the closed forms themselves --------------------------------------------------------

REFERENCE_CASES = [dict(power=0, outer_support="clamp"), dict(power=0, outer_support="simple"),
                   dict(power=2, outer_support="clamp"),
                   dict(power=0, inner=INNER, inner_support="clamp", outer_support="free"),
                   dict(power=1, inner=INNER, inner_support="simple", outer_support="simple"),
                   dict(power=0, inner=INNER, inner_support="free", outer_support="clamp",
                        inner_loads=(0.4, -0.3))]


@pytest.mark.parametrize("case", REFERENCE_CASES,
                         ids=["clamped-disc", "supported-disc", "clamped-disc-r^2",
                              "annulus-clamp-free", "annulus-simple-simple-r",
                              "annulus-loaded-free-clamp"])
def test_plate_solutions_solve_the_mindlin_equations(case):
    """The closed forms satisfy the constitutive laws and the equilibrium (central
    differences) and their edge conditions."""
    h, q = 0.2, 0.9
    _, ds, db = stiffnesses(h)
    inner = case.get("inner", 0.0)
    r = np.linspace(inner + 0.05, RADIUS - 0.05, 41)
    step = 1e-5

    def fields(at):
        return mindlin_plate(at, h, q, **case)

    here, ahead, behind = fields(r), fields(r + step), fields(r - step)
    slope = {name: (ahead[name] - behind[name]) / (2 * step) for name in here}
    rq_slope = ((r + step) * ahead["Q"] - (r - step) * behind["Q"]) / (2 * step)
    rmr_slope = ((r + step) * ahead["Mr"] - (r - step) * behind["Mr"]) / (2 * step)
    load = q * (r / RADIUS)**case["power"]
    scale = {name: np.max(np.abs(here[name])) for name in here}
    np.testing.assert_allclose(ds * (slope["w"] + here["beta"]), here["Q"], atol=1e-7 * scale["Q"])
    np.testing.assert_allclose(db * (slope["beta"] + POISSON * here["beta"] / r), here["Mr"],
                               atol=1e-7 * scale["Mr"])
    np.testing.assert_allclose(db * (here["beta"] / r + POISSON * slope["beta"]), here["Mtheta"],
                               atol=1e-7 * scale["Mtheta"])
    np.testing.assert_allclose(-rq_slope, r * load, atol=1e-7 * q)
    np.testing.assert_allclose(-rmr_slope + here["Mtheta"] + r * here["Q"], 0,
                               atol=1e-7 * scale["Mr"])
    edges = [(RADIUS, case["outer_support"], case.get("outer_loads", (0.0, 0.0)), 1)]
    if inner:
        edges.append((inner, case["inner_support"], case.get("inner_loads", (0.0, 0.0)), -1))
    for radius, support, loads, outward in edges:
        at_edge = fields(np.array([radius]))
        for name in SUPPORT_CONDITIONS[support]:
            assert abs(at_edge[name][0] - edge_value(name, loads, outward)) < 1e-12 * scale[name], \
                (support, name)


@pytest.mark.parametrize("support, explicit", [("clamp", clamped_disc),
                                               ("simple", simply_supported_disc)])
def test_explicit_disc_formulas_agree_with_the_general_solution(support, explicit):
    h, q = 0.3, 0.9
    r = np.linspace(0, RADIUS, 31)
    general = mindlin_plate(r, h, q, outer_support=support)
    for name, values in explicit(r, h, q).items():
        np.testing.assert_allclose(general[name], values, rtol=1e-12, atol=1e-12, err_msg=name)


def test_lame_solution_solves_the_membrane_equations():
    h, force = 0.2, 0.9
    r = np.linspace(INNER, RADIUS, 21)
    dm, _, _ = stiffnesses(h)
    for support in ("free", "clamp"):
        solution = lame_annulus(r, h, force, support)
        a, b = solution["A"], solution["B"]
        np.testing.assert_allclose(solution["u"], a * r + b / r)
        strain_r, strain_theta = a - b / r**2, solution["u"] / r
        np.testing.assert_allclose(solution["Nr"], dm * (strain_r + POISSON * strain_theta),
                                   atol=1e-14)
        np.testing.assert_allclose(solution["Ntheta"], dm * (strain_theta + POISSON * strain_r),
                                   atol=1e-14)
        # -(r N_r)' + N_theta = 0: r N_r = Dm ((1 + nu) A r - (1 - nu) B/r)
        rnr_slope = dm * ((1 + POISSON) * a + (1 - POISSON) * b / r**2)
        np.testing.assert_allclose(rnr_slope, solution["Ntheta"], atol=1e-14)
        assert solution["Nr"][0] == pytest.approx(-force)
        end = solution["Nr"][-1] if support == "free" else solution["u"][-1]
        assert abs(end) < 1e-12


def test_face_shear_solution_solves_the_plate_equations():
    h, top, bottom = 0.2, 0.9, -0.4
    dm, _, db = stiffnesses(h)
    r = np.linspace(0.05, RADIUS - 0.05, 31)
    step = 1e-5
    here, ahead, behind = (face_shear_disc(at, h, top, bottom) for at in (r, r + step, r - step))
    slope = {name: (ahead[name] - behind[name]) / (2 * step) for name in here}
    np.testing.assert_allclose(here["Nr"], dm * (slope["u"] + POISSON * here["u"] / r))
    np.testing.assert_allclose(here["Ntheta"], dm * (here["u"] / r + POISSON * slope["u"]))
    np.testing.assert_allclose(here["Mr"], db * (slope["beta"] + POISSON * here["beta"] / r))
    np.testing.assert_allclose(here["Mtheta"], db * (here["beta"] / r + POISSON * slope["beta"]))
    np.testing.assert_allclose(slope["w"], -here["beta"], atol=1e-9)     # Q = 0
    rnr_slope = ((r + step) * ahead["Nr"] - (r - step) * behind["Nr"]) / (2 * step)
    rmr_slope = ((r + step) * ahead["Mr"] - (r - step) * behind["Mr"]) / (2 * step)
    np.testing.assert_allclose(-rnr_slope + here["Ntheta"], r * (top + bottom), atol=1e-9)
    np.testing.assert_allclose(-rmr_slope + here["Mtheta"], r * h / 2 * (top - bottom), atol=1e-9)
    edge = face_shear_disc(np.array([RADIUS]), h, top, bottom)
    assert abs(edge["u"][0]) + abs(edge["w"][0]) + abs(edge["beta"][0]) < 1e-15


# --- the element ----------------------------------------------------------------------

@pytest.mark.parametrize("stretch", [0, 1], ids=["plate", "stretch"])
@pytest.mark.parametrize("element", [0, 3], ids=["on-axis", "off-axis"])
def test_element_matrix_has_one_zero_energy_mode(run_freefem, tmp_path, element, stretch):
    """An element of a disc on 4 elements, h/size = 1/25: symmetric, positive
    semi-definite, and its one zero-energy mode is the rigid motion w = constant (the
    first element with its axis degrees of freedom u(0), beta(0) still free)."""
    size = RADIUS / 4
    h = size / 25
    matrix_file = tmp_path / "element.csv"
    plate(run_freefem, tmp_path, elements=4, thickness=h, stretch=stretch,
          matrix=str(matrix_file), matrixElement=element)
    stiffness = np.loadtxt(matrix_file, delimiter=",")
    assert stiffness.shape == (15 + 3 * stretch,) * 2  # 5 functions of u, w, beta; 3 of epsilon
    largest = np.abs(stiffness).max()
    assert np.abs(stiffness - stiffness.T).max() < 1e-14 * largest
    eigenvalues, modes = np.linalg.eigh(stiffness / largest)
    assert abs(eigenvalues[0]) < 1e-14 and eigenvalues[1] > 1e-5 * (h / size)**2, eigenvalues[:3]
    translation = np.zeros(len(stiffness))
    translation[[5, 6]] = 1 / np.sqrt(2)               # the two hats of w
    assert abs(modes[:, 0] @ translation) == pytest.approx(1, abs=1e-12)


# --- 1. discs: exact under a uniform pressure, P4 rates under a parabolic one ------------

DISC_SUPPORTS = {"clamp": clamped_disc, "simple": simply_supported_disc}


@pytest.mark.parametrize("slenderness", [10, 1000], ids=["a/h=10", "a/h=1000"])
@pytest.mark.parametrize("support", ["clamp", "simple"])
def test_uniform_pressure_on_a_disc_is_exact(run_freefem, tmp_path, support, slenderness):
    """On 1, 2 and 4 elements (the module docstring, 1.); u and epsilon are exact zeros."""
    h = RADIUS / slenderness
    meshes = plate(run_freefem, tmp_path, elements=1, levels=3, thickness=h,
                   outerSupport=support, topNormal=PRESSURE)
    errors = errors_by_mesh(meshes, lambda r: DISC_SUPPORTS[support](r, h, PRESSURE),
                            BENDING_FIELDS)
    round_off = 1e-12 + 1e-14 * slenderness**2      # grows as the stiffness ratio Ds/Db
    for name, values in errors.items():
        assert max(values) < round_off, (name, values)
    for mesh in meshes:
        assert np.max(np.abs(mesh["u"])) == 0 and np.max(np.abs(mesh["epsilon"])) == 0


def test_shear_deformation_matters_for_a_thick_disc(run_freefem, tmp_path):
    """a/h = 2: the shear term q a^2/(4 Ds) is a third of the clamped centre deflection."""
    h = RADIUS / 2
    _, ds, db = stiffnesses(h)
    centre = plate(run_freefem, tmp_path, thickness=h, outerSupport="clamp",
                   topNormal=PRESSURE)[0]["w"][0]
    kirchhoff = PRESSURE * RADIUS**4 / (64 * db)
    assert centre == pytest.approx(kirchhoff + PRESSURE * RADIUS**2 / (4 * ds), rel=1e-12)
    assert abs(centre - kirchhoff) > 0.1 * abs(centre)


def test_radial_face_tractions_on_a_clamped_disc_are_exact(run_freefem, tmp_path):
    """Radial tractions on both faces load u (their sum) and beta (their couple, arm
    h/2); the solution (face_shear_disc) is polynomial: exact on 2 elements."""
    h, top, bottom = 0.2, 0.9, -0.4
    mesh = plate(run_freefem, tmp_path, elements=2, thickness=h, outerSupport="clamp",
                 topRadial=top, bottomRadial=bottom)[0]
    exact = face_shear_disc(mesh["r"], h, top, bottom)
    for name in ("u", "Nr", "Ntheta", "w", "beta", "Mr", "Mtheta"):
        assert relative_error(mesh[name], exact[name]) < 1e-12, name
    assert np.max(np.abs(mesh["Q"])) < 1e-12 * np.max(np.abs(exact["Mr"])) / h


DISPLACEMENTS = ("w", "beta")
MOMENTS = ("Mr", "Mtheta")


@pytest.mark.parametrize("slenderness", [10, 1000], ids=["a/h=10", "a/h=1000"])
@pytest.mark.parametrize("support", ["clamp", "simple"])
def test_parabolic_pressure_on_a_disc_converges_at_the_p4_rates(run_freefem, tmp_path,
                                                                support, slenderness):
    """p_z = q (r/a)^2: w of degree 6, beta of degree 5. On 1, 2, 4, 8 elements w and
    beta converge at order 5 (w approaches it from below), the moments at order 4
    (derivatives of beta, read on the cubic through the Gauss points); Q = -q r^3/(4 a^2)
    is a cubic, exact. On finer meshes the thin plate's round-off, growing as the
    stiffness ratio Ds/Db ~ (a/h)^2, meets the error."""
    h = RADIUS / slenderness
    meshes = plate(run_freefem, tmp_path, elements=1, levels=4, thickness=h,
                   outerSupport=support, topNormal=PRESSURE, power=2.0)
    errors = errors_by_mesh(meshes, lambda r: mindlin_plate(r, h, PRESSURE, power=2,
                                                            outer_support=support),
                            DISPLACEMENTS + MOMENTS + ("Q",))
    for name in DISPLACEMENTS:
        assert np.all(orders(errors[name]) > 4.3), (name, errors[name])
        assert errors[name][-1] < 5e-7, (name, errors[name])
    for name in MOMENTS:
        assert np.all(orders(errors[name]) > 3.9), (name, errors[name])
    assert max(errors["Q"]) < 1e-8, errors["Q"]


# --- 2. annuli: ln r and 1/r ------------------------------------------------------------

# Fields and forces on 8 to 64 elements: every order above the first bound, the last
# above the second (orders 5 and 4, approached from below).
FIELD_RATES, FORCE_RATES = (4.4, 4.8), (3.4, 3.8)


def assert_rates(errors, rates, name):
    measured = orders(errors)
    assert np.all(measured > rates[0]) and measured[-1] > rates[1], (name, errors, measured)


ANNULI = {"clamp-free-uniform": dict(inner_support="clamp", outer_support="free", q=PRESSURE),
          "simple-simple-linear": dict(inner_support="simple", outer_support="simple",
                                       q=PRESSURE, power=1),
          "loaded-free-clamp": dict(inner_support="free", outer_support="clamp", q=0.0,
                                    inner_loads=(0.4, -0.3)),
          "clamp-loaded-free": dict(inner_support="clamp", outer_support="free", q=0.0,
                                    outer_loads=(-0.2, 0.5))}


def annulus_options(inner_support, outer_support, q, power=0, inner_loads=(0.0, 0.0),
                    outer_loads=(0.0, 0.0)):
    """plate_revolution.edp's options for an ANNULI case."""
    return dict(inner=INNER, innerSupport=inner_support, outerSupport=outer_support,
                topNormal=q, power=float(power), innerTransverse=inner_loads[0],
                innerMoment=inner_loads[1], outerTransverse=outer_loads[0],
                outerMoment=outer_loads[1])


@pytest.mark.parametrize("name", ANNULI)
def test_annular_plate_converges_at_the_p4_rates(run_freefem, tmp_path, name):
    """Pressure, or transverse force and moment on a free edge; a/h = 10 on 8, 16, 32,
    64 elements: w and beta at order 5, the forces at order 4, both approached from
    below (the 1/r terms are steep near r0 = r1/3)."""
    case = ANNULI[name]
    h = RADIUS / 10
    meshes = plate(run_freefem, tmp_path, elements=8, levels=4, thickness=h,
                   **annulus_options(**case))
    closed_form = {key: value for key, value in case.items() if key != "q"}
    errors = errors_by_mesh(meshes, lambda r: mindlin_plate(r, h, case["q"], inner=INNER,
                                                            **closed_form),
                            BENDING_FIELDS)
    for field in DISPLACEMENTS:
        assert_rates(errors[field], FIELD_RATES, field)
        assert errors[field][-1] < 1e-9, (field, errors[field])
    for field in ("Q",) + MOMENTS:
        assert_rates(errors[field], FORCE_RATES, field)


# --- 3. no shear locking ----------------------------------------------------------------

def test_centre_deflection_error_does_not_grow_with_slenderness(run_freefem, tmp_path):
    """Clamped disc under p_z = q (r/a)^2 on one element: the centre deflection's relative
    error at a/h = 100 and 1000 stays within 10 % of that at a/h = 10. Under the full
    5-point rule the shear term locks and this fails (tried by swapping the rule: the
    error grows several times over)."""
    centre_errors = []
    for slenderness in (10, 100, 1000):
        h = RADIUS / slenderness
        centre = plate(run_freefem, tmp_path, thickness=h, outerSupport="clamp",
                       topNormal=PRESSURE, power=2.0)[0]["w"][0]
        exact = mindlin_plate(np.array([0.0]), h, PRESSURE, power=2)["w"][0]
        centre_errors.append(abs(centre / exact - 1))
    assert 0 < centre_errors[0] < 1e-2, centre_errors
    assert all(0.9 < error / centre_errors[0] < 1.1 for error in centre_errors), centre_errors


# --- 4. membrane: Lame ------------------------------------------------------------------

MEMBRANE_FIELDS = ("u", "Nr", "Ntheta")
INNER_FORCE = 0.8             # radial force per unit length on the inner edge, along e_r


@pytest.mark.parametrize("stretch", [0, 1], ids=["plate", "stretch"])
@pytest.mark.parametrize("support", ["free", "clamp"])
def test_lame_annulus_converges_at_the_p4_rates(run_freefem, tmp_path, support, stretch):
    """A radial force on the inner edge, the outer edge free (w = 0 there: simply
    supported, which leaves u free) or clamped, 8 to 64 elements: u at order 5, N_r and
    N_theta at order 4. With stretch T33 vanishes and epsilon = -2 nu A/(1 - nu) to
    round-off, and u is the plate's: the discrete trace u' + u/r keeps its exact value
    2 A at the Gauss points, where the stretch term sees it."""
    h = RADIUS / 10
    meshes = plate(run_freefem, tmp_path, elements=8, levels=4, thickness=h, inner=INNER,
                   outerSupport="simple" if support == "free" else "clamp",
                   innerRadial=INNER_FORCE, stretch=stretch)

    def exact(r):
        return lame_annulus(r, h, INNER_FORCE, support)

    errors = errors_by_mesh(meshes, exact, MEMBRANE_FIELDS)
    assert_rates(errors["u"], FIELD_RATES, "u")
    assert errors["u"][-1] < 1e-9, errors["u"]
    for name in ("Nr", "Ntheta"):
        assert_rates(errors[name], FORCE_RATES, name)
    epsilon = -2 * POISSON / (1 - POISSON) * exact(np.array([INNER]))["A"] if stretch else 0.0
    for mesh in meshes:
        assert np.max(np.abs(mesh["w"])) < 1e-12 and np.max(np.abs(mesh["beta"])) < 1e-12
        np.testing.assert_allclose(mesh["epsilon"], epsilon, rtol=1e-11)
        assert np.max(np.abs(mesh["T33"])) < 1e-13 * INNER_FORCE


# --- 5. thickness stretch ---------------------------------------------------------------

def constrained_modulus():
    return YOUNG * (1 - POISSON) / ((1 + POISSON) * (1 - 2 * POISSON))


@pytest.mark.parametrize("support", ["clamp", "simple"], ids=["confined", "free-to-expand"])
def test_pressure_on_both_faces_of_a_disc_compresses_it_by_the_3d_law(run_freefem, tmp_path,
                                                                      support):
    """A pressure p on the top face and the equal reaction on the bottom face. Clamped:
    eps_r = eps_theta = 0, epsilon = -p/C, the thickness change -p h/C. Simply supported,
    the edge free to move radially: sigma_r = sigma_theta = 0, epsilon = -p/E, u = nu p r/E.
    Both states lie in the space: exact, on 2 elements."""
    h, p = 0.3, 0.04
    mesh = plate(run_freefem, tmp_path, elements=2, thickness=h, outerSupport=support,
                 stretch=1, topNormal=-p, bottomNormal=p)[0]
    assert np.max(np.abs(mesh["w"])) < 1e-12 * p * h and np.max(np.abs(mesh["beta"])) < 1e-12
    np.testing.assert_allclose(mesh["T33"], -p * h, rtol=1e-11)
    if support == "clamp":
        np.testing.assert_allclose(h * mesh["epsilon"], -p * h / constrained_modulus(), rtol=1e-11)
        assert np.max(np.abs(mesh["u"])) < 1e-14
    else:
        np.testing.assert_allclose(mesh["epsilon"], -p / YOUNG, rtol=1e-11)
        np.testing.assert_allclose(mesh["u"], POISSON * p / YOUNG * mesh["r"], rtol=1e-11,
                                   atol=1e-16)
        assert np.max(np.abs(mesh["Nr"])) < 1e-12 * p * h
        assert np.max(np.abs(mesh["Ntheta"])) < 1e-12 * p * h


@pytest.mark.parametrize("slenderness", [10, 100])
def test_with_stretch_a_bent_disc_has_the_plate_deflection(run_freefem, tmp_path, slenderness):
    """Pressure on the top face only, clamped disc. The stretch terms couple epsilon to u
    alone: w and beta are the plate's (to round-off), and u = 0, T33 = q h/2 (half the
    load on epsilon: its arm is h/2), epsilon = q/(2 C) uniform, exactly. The loaded
    face's deflection w + h/2 epsilon is the plate's plus q h/(4 C), less than a fraction
    16 Db h/(C a^4) ~ (h/a)^4 of the centre deflection: it tends to the plate's."""
    h = RADIUS / slenderness
    plain, stretched = (plate(run_freefem, tmp_path, elements=2, thickness=h,
                              outerSupport="clamp", stretch=stretch, topNormal=PRESSURE)[0]
                        for stretch in (0, 1))
    for name in ("w", "beta", "Q", "Mr", "Mtheta"):
        assert relative_error(stretched[name], plain[name]) < 1e-12, name
    np.testing.assert_allclose(stretched["epsilon"], PRESSURE / (2 * constrained_modulus()),
                               rtol=1e-10)
    np.testing.assert_allclose(stretched["T33"], PRESSURE * h / 2, rtol=1e-10)
    assert np.max(np.abs(stretched["u"])) < 1e-12 * np.max(np.abs(stretched["w"]))
    _, _, db = stiffnesses(h)
    top_face = stretched["w"][0] + h / 2 * stretched["epsilon"][0]
    compression = PRESSURE * h / (4 * constrained_modulus())
    assert top_face == pytest.approx(plain["w"][0] + compression, rel=1e-10)
    assert 0 < compression / plain["w"][0] < 16 * db * h / (constrained_modulus() * RADIUS**4)
