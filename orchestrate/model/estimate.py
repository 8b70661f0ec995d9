"""The a priori estimates of a scene: the contact's half-width (Hertz: a cylinder in
plane strain, a sphere's contact radius in an axisymmetric scene) and each coating
model's error, before any mesh (but for whether the stretch shell's bond shear is set by
its mesh, told by the plan); what ``model = "auto"`` chooses by (orchestrate/run/plan.py)
and what the warnings model_error, model_uncalibrated, bond_shear_model and
bond_shear_mesh say (orchestrate/run/validity.py).

The estimate is a priori: from quantities of the scene, before any mesh, calibrated on
measured errors (studies/adequacy.py, ``--fit``) and checked on scenes it never saw
(docs/findings.md, "Choosing the coating model"). The forms are the same in plane strain
and for a body of revolution; their constants are fitted per family (PLANE, REVOLUTION).

Three answers are estimated, each as a relative error against the 2D coating model
(exact for the coating, up to its mesh): the peak contact stress ("contact"), the peak
normal stress on the bond under the contact ("bond") and the bond's largest shear
("shear"); auto judges those settings.model_answers names (ANSWERS). They are governed by

    x = h2 / a        the coating's thickness over the contact half-width a, estimated by
                      Hertz from the load (a descent is turned into a force by the
                      compliance of the two bodies of finite depth, Johnson, Contact
                      Mechanics (1985) eq. 5.43; the coatings left out)
    c = E* / M2       the bodies' contact modulus over the coating's constrained modulus
                      M2 = E2 (1 - nu2) / ((1 + nu2)(1 - 2 nu2)), the stiffness of a
                      bonded layer pressed through its thickness
    g = E* / G2       ... over the coating's shear modulus, which sets how a thick soft
                      layer squeezes out sideways under a contact
    q = E* k / E3     the Poisson swelling of a coating bonded on a base surface that the
                      contact compresses laterally, k = nu2 (1 + nu3)(1 - 2 nu3) / (1 - nu2)
    p = E* nu2 (1 + nu2) / E2   the Poisson share of a layer's in-plane stress: pressed
                      by p0 it carries nu2/(1 - nu2) p0 sideways, against E2/(1 - nu2^2)
                      eps from its stretch by the contact's strain, eps ~ p0/E*

The Timoshenko shell ("shell") has no through-thickness compliance: it is too stiff by
about the layer's compression, h2 (1/M2 - k/E3), against the contact's compliance a/E*
(the k term: a coating bonded on a base whose surface the contact squeezes sideways
swells in thickness, so that for a stiff coating the rigid fibre is too soft); thicker
layers add terms in x^2. For the contact and bond stresses, with constants of their own:

    shell:          e = x (K1 c + K2 q) + x^2 (K3 + K4 c)

The stretch shell carries that compression. What remains is the layer's sideways
squeeze and the variation of the compression through a thick layer (its displacement is
linear through the thickness), of order x^2; for a stiff thick coating its contact
stress is too soft by a few tenths of a per cent, a plateau whose cause is not isolated:

    stretch_shell:  contact |e| = max(S x^2 g^s, min(T x^2, P)),   bond |e| = B x^2

The bond's shear is where the shells part from the 2D coating: the shell's error does
not vanish as the coating thins, the stretch shell's falls slowly (docs/findings.md,
"The bond shear and the coating's Poisson ratio"). Under a contact pressure the layer carries an in-plane stress of
-nu2/(1 - nu2) times it; where the pressure changes, at the contact's edge, that
stress's gradient times h2 is bond shear, of the same order in h2 as the shear the
layer's stretching carries. The Timoshenko shell leaves that stress out, so its bond
shear misses a share that grows with p (and, fitted, as the coating thins: with nu2 = 0
it is still off, by a second cause not isolated); the stretch shell carries it with the
compression constant through the thickness, and applies the pressure's gradient at a
point where the layer spreads it over its thickness, so it overshoots, more on soft
coatings (g) and thicker ones. Both errors fall as the indenter stiffens against the
base (indenter_share: 1/2 for bodies alike, 1 under a rigid indenter), and less so as
the coating thins: the factor exp((r + u ln x)(share - 1/2)), r and u negative for both
shells, fitted in each family on its own (the calibration sets' off-share scenes, thin
coatings under rigid indenters among them: without u the Timoshenko shell's shear on
the held-out balls' 1-2 um films was estimated 0.2-0.36 times its error). Both as a
share of the answer, at most all of it:

    shell:          shear |e| = s1 / (1 + s1),   s1 = S p^s x^t exp((r + u ln x)(share - 1/2))
    stretch_shell:  shear |e| = s2 / (1 + s2),   s2 = S g^s x^t exp((r + u ln x)(share - 1/2))

On elements longer than about twice the coating's thickness at the contact's edge the
stretch shell's overshoot there follows the elements, not this form: its shear is then
not estimated (STRETCH_SHEAR_LEAST_ELEMENTS; the run's mesh is known to the plan, not
to this module, which takes the thickness in elements as given).

The 2D coating model ("elastic") is the reference: its estimate is 0 (its error is the
mesh's, 0.03 % in peak pressure on the paper's mesh, docs/findings.md; its bond shear,
whose peak at the contact's edge is steep, is the most mesh-dependent answer). |e| is
the estimate.

Where the estimate was not calibrated, or cannot hold, the 1D models are "not
estimated" and auto takes the 2D model: a scene outside the span its family's constants
were fitted on (the indenter's stiffness against the base's, indenter_share, h2/a: a
0.1 mm polymer coating twice as thick as the Hertz half-width, h2/a = 2.1, had the
shell's contact estimate 12 times its measured error; and g: a hard lacquer 100 times
stiffer than the polymer it coats, g seven times below the span, had the stretch
shell's pressure 15 % off where its form said 0.02 %), a coating Poisson ratio outside
NU2_CALIBRATED
(towards 0.5 the shell's error changes sign and no longer follows x: measured -0.6 to
-2.4 % at 0.45-0.49), and a patch end within the contact, where the contact presses on
a step the forms know nothing of (measured 1.6-8.3 % for the shell against 0.003-2.2 %
from its form); that includes the end of a patch that stands proud of the face under
the contact's centre (a ring around a bare centre) where the profile's gap, less the
patch's step, is within the approach a^2/R: the indenter reaches the step (measured on
a sphere: the shell 10 % off at the centre, where its form said 0.3 %).

"""

from dataclasses import dataclass
import math

from orchestrate.model.layered_contact import layered_half_width
from orchestrate.model.scene import MODELS

ANSWERS = {                     # the estimated answers, by the setting model_answers
    "normal": ("contact", "bond"),
    "all": ("contact", "bond", "shear"),
}
ANSWER_NAMES = {"contact": "peak contact stress", "bond": "bond's normal stress",
                "shear": "bond's shear"}


def answers_text(answers):
    """The answers of a model_answers setting, in words."""
    names = [ANSWER_NAMES[name] for name in ANSWERS[answers]]
    return ", ".join(names[:-1]) + " and " + names[-1]


@dataclass(frozen=True)
class Calibration:
    """The estimate's constants for one family of scenes (the module's docstring),
    fitted by ``python -m studies.adequacy --fit``."""
    shell_contact: tuple        # K1, K2, K3, K4
    shell_bond: tuple           # K1, K2, K3, K4
    shell_shear: tuple          # S, s, t, r, u
    stretch_soft_coating: tuple  # S, s
    stretch_stiff_coating: tuple  # T, P
    stretch_bond: float         # B
    stretch_shear: tuple        # S, s, t, r, u
    indenter_share: tuple       # the span of indenter_share it was fitted on
    thickest: float             # ... and the largest h2/a
    coating_compliance: tuple   # ... and the span of g = E*/G2


# Fitted on the plane-strain calibration set (results/adequacy/plane_calibration.csv)
PLANE = Calibration(
    shell_contact=(0.2488, -0.233, 0.0315, 0.1778),
    shell_bond=(0.2754, -0.272, 0.1329, 0.33),
    shell_shear=(0.1826, 0.7745, -0.6409, -6.878, -1.394),
    stretch_soft_coating=(0.01591, 0.5717),
    stretch_stiff_coating=(0.05189, 0.003903),
    stretch_bond=0.03806,
    stretch_shear=(0.2999, 1.012, 0.3306, -1.743, -0.2874),
    indenter_share=(0.2308, 1.0),
    thickest=0.9498,
    coating_compliance=(0.1429, 28.57))
# Fitted on the axisymmetric calibration set (results/adequacy/revolution_calibration.csv)
REVOLUTION = Calibration(
    shell_contact=(0.2685, -0.293, 0.03995, 0.2487),
    shell_bond=(0.3941, -0.509, 0.3361, 0.1105),
    shell_shear=(0.1844, 0.6406, -0.4539, -6.393, -1.6),
    stretch_soft_coating=(0.0169, 0.5824),
    stretch_stiff_coating=(0.02544, 0.005168),
    stretch_bond=0.07942,
    stretch_shear=(0.2503, 0.756, 0.4858, -2.082, -0.54),
    indenter_share=(0.3333, 1.0),
    thickest=0.9015,
    coating_compliance=(0.1429, 14.29))

NU2_CALIBRATED = (0.1, 0.4)    # the coating Poisson ratios the estimate holds for
# The stretch shell's bond shear is not estimated on a coating thinner than this many of
# its interface elements at the predicted contact's edge: it applies the pressure's
# gradient at the bond point, and on elements longer than about twice its thickness the
# overshoot this gives at the edge follows the elements, not the form (make adequacy's
# plane scenes, measured error over 0.5 %, on the stretch shell's own mesh: at 0.13-0.4
# elements 5 of 16 estimates within a factor 2, from 0.24 to 23 times the error; at
# 0.5-0.64, 10 of 10; from 0.8, 100 of 103)
STRETCH_SHEAR_LEAST_ELEMENTS = 0.45
END_MARGIN = 0.5               # a patch end this many thicknesses from the contact is in it
SPAN_MARGIN = 1e-3             # relative: the calibrated spans are kept to 4 digits
BISECTIONS = 64                # halvings of [-60, 60] in log F: below a double's resolution


def calibration(scene):
    """The constants of the scene's family: axisymmetric or plane strain."""
    return REVOLUTION if scene.axisymmetric else PLANE


# ---- the contact half-width ------------------------------------------------------------

def contact_modulus(scene):
    """E* of the indenter and the base (plane strain; a rigid indenter adds nothing)."""
    ind, base = scene.indenter, scene.base
    compliance = 0.0 if ind.rigid else (1 - ind.nu ** 2) / ind.E
    return 1.0 / (compliance + (1 - base.nu ** 2) / base.E)


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


def _hertz_half_width(force, radius, modulus, revolution=False):
    """Hertz's contact half-width of a cylinder (plane strain: F per unit width), or the
    contact radius of a sphere (``revolution``: F the total force)."""
    if revolution:
        return (0.75 * force * radius / modulus) ** (1.0 / 3.0)
    return math.sqrt(4.0 * force * radius / (math.pi * modulus))


def _layer_half_width(force, radius, thickness, modulus, revolution=False):
    """The contact half-width of a thin layer of constrained ``modulus`` M pressed alone
    (Winkler: p = M (delta - x^2 / 2R) / h2): F = 2 M a^3 / (3 R h2) per unit width, or
    F = pi M a^4 / (4 R h2) under a sphere (``revolution``)."""
    if revolution:
        return (4.0 * force * radius * thickness / (math.pi * modulus)) ** 0.25
    return (1.5 * force * radius * thickness / modulus) ** (1.0 / 3.0)


def _body_depths(scene):
    """(E, nu, depth) of each body: how far below its face it is held."""
    ind, base = scene.indenter, scene.base
    depth = base.height if base.shape == "block" else base.radius - base.shaft_radius
    if ind.rigid:
        return ((base.E, base.nu, depth),)
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
    if scene.axisymmetric and force is None:    # Hertz: the approach is a^2 / R
        return min(math.sqrt(radius * load.displacement), face)
    if force is None:                     # bisection on log F: descent grows with F
        low, high = -60.0, 60.0
        for _ in range(BISECTIONS):
            middle = 0.5 * (low + high)
            if descent_of_force(scene, math.exp(middle)) < load.displacement:
                low = middle
            else:
                high = middle
        force = math.exp(0.5 * (low + high))
    return min(_hertz_half_width(force, radius, contact_modulus(scene), scene.axisymmetric),
               face)


def predicted_half_width(scene, a=None):
    """The contact half-width the mesh and the first contact set are sized to: the
    bodies' estimate ``a`` (contact_half_width, the model estimate's variable) or, under
    a force, that of the coating patch under the contact's centre, whichever is wider:
    pressed as a thin layer alone (_layer_half_width) where it is thinner than that
    contact, else as a half-space of its own modulus under the indenter (Hertz). A
    compliant coating spreads the contact well beyond the bodies' estimate (a polymer
    film on steel: four times); a stiff one leaves the bodies' estimate."""
    a = contact_half_width(scene) if a is None else a
    force = scene.load.force
    if not force:
        return a
    centre = scene.contact_centre
    under = [c for c in scene.coatings if c.start <= centre <= c.end]
    radius = relative_radius(scene)
    if not under or math.isinf(radius):
        return a
    coating = under[0]
    layer = _layer_half_width(force, radius, coating.thickness,
                              constrained_modulus(coating.E, coating.nu), scene.axisymmetric)
    if coating.thickness >= layer:          # thick: the coating is the half-space
        indenter = scene.indenter
        compliance = 0.0 if indenter.rigid else (1 - indenter.nu ** 2) / indenter.E
        layer = _hertz_half_width(force, radius,
                                  1.0 / (compliance + (1 - coating.nu ** 2) / coating.E),
                                  scene.axisymmetric)
    return min(max(a, layer), max(a, _face_half_width(scene)))


def first_contact_half_width(scene, predicted):
    """The half-width the loop's first contact set is drawn to (Strategy.first_contact):
    under a force in plane strain, the contact of the indenter with the coating under the
    contact's centre as a layer on the base (layered_contact.py); else ``predicted``
    (predicted_half_width, which sizes the mesh). Hertz's bounds leave a stiff coating's
    set wide, and the loop shrinks it a point or two an update."""
    force, radius = scene.load.force, relative_radius(scene)
    under = [c for c in scene.coatings if c.start <= scene.contact_centre <= c.end]
    if not force or scene.axisymmetric or math.isinf(radius) or not under:
        return predicted
    layer, base, indenter = under[0], scene.base, scene.indenter
    return min(layered_half_width(force, radius, (layer.E, layer.nu, layer.thickness),
                                  (base.E, base.nu),
                                  None if indenter.rigid else (indenter.E, indenter.nu)),
               _face_half_width(scene))


# ---- the estimate ----------------------------------------------------------------------

def constrained_modulus(E, nu):
    return E * (1 - nu) / ((1 + nu) * (1 - 2 * nu))


def scene_ratios(scene, coating, a=None):
    """(x, c, q, g, p) of a patch (the module's docstring); a: the scene's
    contact_half_width, if known."""
    a = contact_half_width(scene) if a is None else a
    modulus = contact_modulus(scene)
    base = scene.base
    x = math.inf if a == 0 else coating.thickness / a
    c = modulus / constrained_modulus(coating.E, coating.nu)
    q = modulus * coating.nu * (1 + base.nu) * (1 - 2 * base.nu) / ((1 - coating.nu) * base.E)
    g = modulus * 2 * (1 + coating.nu) / coating.E
    p = modulus * coating.nu * (1 + coating.nu) / coating.E
    return x, c, q, g, p


def indenter_share(scene):
    """E* over the base's plane-strain modulus: how much of the contact's compliance is
    the base's (1/2 for bodies alike, 1 under a rigid indenter, towards 0 under a soft
    one)."""
    return contact_modulus(scene) * (1 - scene.base.nu ** 2) / scene.base.E


def not_estimated(scene, coating, a=None, calibrated=True):
    """Why the 1D models' errors are not estimated for this patch (None: they are);
    ``calibrated``: also where the scene lies outside the span its family's constants
    were fitted on (indenter_share, h2/a, g; studies/adequacy.py fits with it off)."""
    if scene.frictional:
        return ("friction: the estimate is calibrated on frictionless contacts (the "
                "friction traction loads the coating's top in shear)")
    low, high = NU2_CALIBRATED
    if not low <= coating.nu <= high:
        return f"coating Poisson ratio {coating.nu:g} outside the calibrated [{low:g}, {high:g}]"
    a = contact_half_width(scene) if a is None else a
    if a == 0:
        return None
    constants = calibration(scene)
    share, (low, high) = indenter_share(scene), constants.indenter_share
    if calibrated and not low * (1 - SPAN_MARGIN) <= share <= high * (1 + SPAN_MARGIN):
        return (f"the indenter's stiffness against the base's (E* over the base's modulus "
                f"{share:.3g}) outside the calibrated [{low:.3g}, {high:.3g}]")
    if calibrated and coating.thickness / a > constants.thickest * (1 + SPAN_MARGIN):
        return (f"h2/a = {coating.thickness / a:.3g} thicker than the calibrated "
                f"{constants.thickest:.3g}")
    g, (low, high) = scene_ratios(scene, coating, a)[3], constants.coating_compliance
    if calibrated and not low * (1 - SPAN_MARGIN) <= g <= high * (1 + SPAN_MARGIN):
        return (f"the contact's modulus over the coating's shear modulus (E*/G2 {g:.3g}) "
                f"outside the calibrated [{low:.3g}, {high:.3g}]")
    centre = scene.indenter.centre
    step = coating.thickness - sum(c.thickness for c in scene.coatings
                                   if c.start <= centre <= c.end)
    radius = relative_radius(scene)
    for end in scene.patch_ends(coating):
        distance = abs(end - centre)
        if distance <= a + END_MARGIN * coating.thickness:
            return f"patch end x1 = {end:g} within the contact (estimated half-width {a:.3g})"
        if step > 0 and distance ** 2 / (2 * radius) - step <= a ** 2 / radius:
            return (f"patch end x1 = {end:g} reached by the indenter: the patch stands "
                    f"{step:.3g} proud of the face under the contact's centre, and the "
                    f"profile pressed in by about a^2/R = {a ** 2 / radius:.3g} meets its step")
    return None


def estimated_errors(scene, coating, a=None, elements_thick=None):
    """{model: {"contact": |e|, "bond": |e|, "shear": |e|}} of a patch (the module's
    docstring); a 1D model's is None where it is not estimated (not_estimated).
    ``elements_thick``: the coating's thickness in the stretch shell's interface
    elements at the predicted contact's edge, where known; below
    STRETCH_SHEAR_LEAST_ELEMENTS its bond shear is None (not estimated)."""
    a = contact_half_width(scene) if a is None else a
    x, c, q, g, p = scene_ratios(scene, coating, a)
    exact = {answer: 0.0 for answer in ANSWERS["all"]}
    if math.isinf(x):                         # no load, no contact: every model is exact
        return {model: dict(exact) for model in MODELS}
    if not_estimated(scene, coating, a):
        return {"shell": None, "stretch_shell": None, "elastic": exact}
    constants = calibration(scene)

    def shell(k1, k2, k3, k4):
        return abs(x * (k1 * c + k2 * q) + x ** 2 * (k3 + k4 * c))

    stiffening = indenter_share(scene) - 0.5

    def saturating(ratio, S, s, t, r, u):     # grows like S ratio^s x^t, at most 1
        share = S * ratio ** s * x ** t * math.exp((r + u * math.log(x)) * stiffening)
        return share / (1.0 + share)

    (S, s), (T, P) = constants.stretch_soft_coating, constants.stretch_stiff_coating
    return {"shell": {"contact": shell(*constants.shell_contact),
                      "bond": shell(*constants.shell_bond),
                      "shear": saturating(p, *constants.shell_shear)},
            "stretch_shell": {"contact": max(S * x ** 2 * g ** s, min(T * x ** 2, P)),
                              "bond": constants.stretch_bond * x ** 2,
                              "shear": (None if stretch_shear_mesh_bound(elements_thick)
                                        else saturating(g, *constants.stretch_shear))},
            "elastic": exact}


def stretch_shear_mesh_bound(elements_thick):
    """Whether the stretch shell's bond shear follows its mesh rather than its form: a
    coating ``elements_thick`` interface elements thick at the contact's edge (None:
    not known) below STRETCH_SHEAR_LEAST_ELEMENTS."""
    return elements_thick is not None and elements_thick < STRETCH_SHEAR_LEAST_ELEMENTS


def worst_error(errors, answers="all"):
    """The largest of a model's estimated errors of the ``answers`` (ANSWERS' key;
    infinite: not estimated, the model's or one of those answers')."""
    if errors is None or any(errors[name] is None for name in ANSWERS[answers]):
        return math.inf
    return max(errors[name] for name in ANSWERS[answers])
