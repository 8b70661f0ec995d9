"""model = "auto": the cheapest coating model whose estimated error is within tolerance.

The estimate is a priori: from quantities of the scene, before any mesh, calibrated on
the measured errors of the paper's scene (orchestrate/adequacy.py, ``--fit``) and
checked on scenes it never saw (the README's "Choosing the coating model").

The quantity is the relative error of the peak contact stress against the 2D coating
model (which is exact for the coating, up to its mesh). It is governed by

    x = h2 / a        the coating's thickness over the contact half-width a, estimated by
                      plane-strain Hertz from the load (a descent is turned into a force
                      by the compliance of the two bodies of finite depth, Johnson,
                      Contact Mechanics (1985) eq. 5.43; the coatings left out)
    c = E* / M2       the bodies' contact modulus over the coating's constrained modulus
                      M2 = E2 (1 - nu2) / ((1 + nu2)(1 - 2 nu2)), the stiffness of a
                      bonded layer pressed through its thickness
    q = E* k / E3     the Poisson swelling of a coating bonded on a base surface that the
                      contact compresses laterally, k = nu2 (1 + nu3)(1 - 2 nu3) / (1 - nu2)

The Timoshenko shell ("shell") has no through-thickness compliance: it is too stiff by
about the layer's compression, h2 (1/M2 - k/E3), against the contact's compliance a/E*
(the k term: a coating bonded on a base whose surface the contact squeezes sideways
swells in thickness, so that for a stiff coating the rigid fibre is too soft); thicker
layers add terms in x^2:

    shell:          e = x (K1 c + K2 q) + x^2 (K3 + K4 c)

The stretch shell carries that compression. What remains, for a soft coating, is the
variation of the compression through a thick layer (the stretch shell's displacement is
linear through the thickness), of order x^2; for a stiff thick coating the stretch
shell is too soft by a few tenths of a per cent, a plateau whose cause is not isolated:

    stretch_shell:  |e| = max(S x^2 c^s, min(T x^2, P))

The 2D coating model ("elastic") is the reference: its estimate is 0 (its error is the
mesh's, 0.03 % on the paper's mesh, README). The constants are fitted to the calibration
set (adequacy.py --fit, which says how); |e| is the estimate.

Cost: the estimated number of unknowns of the whole problem (problem_size.py), counted
before any mesh. Costs within COST_TIE of the cheapest count as the same, and then the
more faithful model wins: on the paper's mesh the 2D coating needs no more unknowns than
a shell until it must refine (thinner than about b/32), and a run's time follows its
unknowns (README, benchmarks).
"""

import math

from .discretization import discretize
from .problem_size import estimated_dofs
from .scene import MODELS

AUTO = "auto"
FIDELITY = ("shell", "stretch_shell", "elastic")   # least to most faithful
COST_TIE = 1.1

# Fitted on the calibration set (results/adequacy/calibration.csv) by
# ``python -m orchestrate.adequacy --fit``
SHELL = (0.2528, -0.2192, 0.02848, 0.2154)              # K1, K2, K3, K4
STRETCH_SOFT_COATING = (0.02672, 0.8696)                # S, s
STRETCH_STIFF_COATING = (0.01727, 0.003896)             # T, P


# ---- the contact half-width ------------------------------------------------------------

def contact_modulus(scene):
    """E* of the indenter and the base (plane strain)."""
    ind, base = scene.indenter, scene.base
    return 1.0 / ((1 - ind.nu ** 2) / ind.E + (1 - base.nu ** 2) / base.E)


def relative_radius(scene):
    """R of the contact, 1/R = 1/R_indenter + 1/R_base (a flat face: infinite)."""
    curvature = (0.0 if scene.indenter.flat else 1.0 / scene.indenter.radius)
    if scene.base.shape == "roller":
        curvature += 1.0 / scene.base.radius
    return math.inf if curvature == 0 else 1.0 / curvature


def _face_half_width(scene):
    """Half the width of the indenter's face over the base: a flat punch's contact."""
    if scene.symmetric:
        return min(scene.indenter.width, scene.base.top)
    return scene.indenter.width


def _hertz_half_width(force, radius, modulus):
    return math.sqrt(4.0 * force * radius / (math.pi * modulus))


def _body_depths(scene):
    """(E, nu, depth) of each body: how far below its face it is held."""
    ind, base = scene.indenter, scene.base
    depth = base.height if base.shape == "block" else base.radius - base.shaft_radius
    return ((ind.E, ind.nu, ind.height), (base.E, base.nu, depth))


def descent_of_force(scene, force):
    """The stamp's descent that presses with ``force`` (Johnson eq. 5.43 per body: the
    approach of the contact's centre to a point held at depth d below it,
    2 F (1 - nu^2)/(pi E) (ln(2 d / a) - nu / (2 (1 - nu))); the logarithm kept at
    least 1, so that the descent grows with the force when a nears d)."""
    a = _hertz_half_width(force, relative_radius(scene), contact_modulus(scene))
    return sum(2.0 * force * (1 - nu ** 2) / (math.pi * E)
               * (max(math.log(2.0 * d / a), 1.0) - nu / (2.0 * (1.0 - nu)))
               for E, nu, d in _body_depths(scene))


def contact_half_width(scene):
    """The a priori contact half-width a (0 without load)."""
    face = _face_half_width(scene)
    radius = relative_radius(scene)
    load = scene.load
    if (load.force or load.displacement or 0.0) == 0.0:
        return 0.0
    if math.isinf(radius):
        return face
    force = load.force
    if force is None:                     # bisection on log F: descent grows with F
        low, high = -60.0, 60.0
        for _ in range(200):
            middle = 0.5 * (low + high)
            if descent_of_force(scene, math.exp(middle)) < load.displacement:
                low = middle
            else:
                high = middle
        force = math.exp(0.5 * (low + high))
    return min(_hertz_half_width(force, radius, contact_modulus(scene)), face)


# ---- the estimate ----------------------------------------------------------------------

def constrained_modulus(E, nu):
    return E * (1 - nu) / ((1 + nu) * (1 - 2 * nu))


def scene_ratios(scene, coating):
    """(x, c, q) of a patch (the module's docstring)."""
    a = contact_half_width(scene)
    modulus = contact_modulus(scene)
    base = scene.base
    x = math.inf if a == 0 else coating.thickness / a
    c = modulus / constrained_modulus(coating.E, coating.nu)
    q = modulus * coating.nu * (1 + base.nu) * (1 - 2 * base.nu) / ((1 - coating.nu) * base.E)
    return x, c, q


def estimated_errors(scene, coating):
    """{model: estimated |relative error| of the peak contact stress} of a patch."""
    x, c, q = scene_ratios(scene, coating)
    if math.isinf(x):                         # no load, no contact: every model is exact
        return {model: 0.0 for model in MODELS}
    k1, k2, k3, k4 = SHELL
    (S, s), (T, P) = STRETCH_SOFT_COATING, STRETCH_STIFF_COATING
    return {"shell": abs(x * (k1 * c + k2 * q) + x ** 2 * (k3 + k4 * c)),
            "stretch_shell": max(S * x ** 2 * c ** s, min(T * x ** 2, P)),
            "elastic": 0.0}


# ---- the choice ------------------------------------------------------------------------

def estimated_unknowns(scene, settings):
    return sum(estimated_dofs(discretize(scene, settings)).values())


def choose_models(scene, settings):
    """(the scene with every "auto" patch's model chosen, the choice's report or None)."""
    auto = [n for n, c in enumerate(scene.coatings) if c.model == AUTO]
    if not auto:
        return scene, None
    tolerance = settings.model_tolerance
    a = contact_half_width(scene)
    # while a patch is decided, the other undecided ones are shells (the cheapest)
    models = [("shell" if c.model == AUTO else c.model) for c in scene.coatings]
    patches = []
    for n in auto:
        coating = scene.coatings[n]
        errors = estimated_errors(scene, coating)
        unknowns = {}
        for model in FIDELITY:
            trial = list(models)
            trial[n] = model
            unknowns[model] = round(estimated_unknowns(scene.with_models(trial), settings))
        passing = [m for m in FIDELITY if errors[m] <= tolerance]   # elastic always passes
        cheapest = min(unknowns[m] for m in passing)
        chosen = [m for m in passing if unknowns[m] <= COST_TIE * cheapest][-1]
        models[n] = chosen
        patches.append({"patch": n + 1, "model": chosen, "estimated_error": errors[chosen],
                        "h2_over_a": coating.thickness / a if a else math.inf,
                        "estimated_errors": errors, "estimated_unknowns": unknowns})
    report = {"tolerance": tolerance, "contact_half_width_estimate": a,
              "patches": patches}
    return scene.with_models(models), report
