"""Where a run leaves what the tool models: warnings, each with the measured value and
the limit it passed.

The model is linear elasticity with small displacements and strains, contact paired
along the indenter face's normal (the faces close, n1 ~ -n2), on the discretisation the
settings ask for, with a coating model whose error may have been estimated
(orchestrate/model/estimate.py). A run can converge, exactly, to an answer of that model
while the scene leaves it: a load that pushes the contact to a body's edge, moduli in
GPa under an MPa label, a coating as thick as its base. Each such case is a warning in
summary.json's "warnings" (code, message, value, limit), printed at the end of a run and
a column of a sweep's table; ``--strict`` makes them an exit status of their own
(orchestrate/errors.py, EXIT_WARNINGS).

    contact_at_edge        the contact reaches the end of the indenter's face or of the
                           base's top face: what lies beyond was not modelled
    large_descent          the stamp's descent over the smaller body's depth
    large_strain           the largest stress on the interfaces and in the coatings over
                           the modulus of the body it acts on: a strain
    stress_near_modulus    the same ratio near 1: the moduli and the loads are likely in
                           different units
    normal_mismatch        the largest angle between the paired faces' normals over the
                           contact: the pairing's error grows with its square
    coarse_contact         fewer interface elements across a contact zone than resolve
                           its pressure
    coarse_mesh            ... across the contact predicted before any work (the a priori
                           half-width), or across a narrow patch's part of it
    coarse_bond            a patch under the predicted contact's edge thinner than
                           BOND_RESOLUTION interface elements there: the bond's shear
                           peaks at the edge over about the coating's thickness, and its
                           largest value depends on the mesh
    model_error            a coating model chosen by the user whose estimated error
                           exceeds the tolerance (settings.model_tolerance)
    model_uncalibrated     ... whose error the estimate does not cover (its reason)
    bond_shear_model       a shell patch (chosen by the user or by auto) whose bond
                           shear, an answer the tolerance does not cover under
                           model_answers = "normal", is estimated off by more than it
    bond_shear_mesh        ... a stretch shell's, not estimated: the patch is thinner
                           than STRETCH_SHEAR_LEAST_ELEMENTS of its interface elements
                           at the predicted contact's edge, where its shear follows them
    thick_coating          a coating thicker than a share of its base's depth: not a thin
                           coating on a body
    singular_contact_peak  the largest contact pressure at a patch's end: a step under
                           the indenter, singular, its value mesh-dependent
    edge_contact_peak      the largest contact pressure near the edge of its contact zone,
                           on a patch modelled as a shell, under a curved indenter: the
                           coating bends and carries load to the contact's edges, over
                           about its thickness, which a 1D model's error estimate does not
                           cover (measured 0.8-30 %)

Values are computed in the solver's b and E and said in the scene's units.
"""

import numpy as np

from orchestrate.model.estimate import (ANSWER_NAMES, ANSWERS, END_MARGIN,
                                        STRETCH_SHEAR_LEAST_ELEMENTS, estimated_errors,
                                        not_estimated, worst_error)
from orchestrate.model.scene import SHELL_MODELS

STRAIN_LIMIT = 0.02          # linear elasticity drops the strain's quadratic term, about half
                             # the strain relative to it: 1 % at 2 % (model_tolerance's 1 %)
MODULUS_SHARE = 0.1          # a stress of a tenth of the modulus: a strain of 10 %
DESCENT_LIMIT = 0.01         # the descent over the smaller body's depth (small displacements)
MISMATCH_LIMIT_DEG = 10.0    # the pairing's error ~ (1 - cos): 1.5 % at 10 degrees
ELEMENTS_ACROSS = 10         # interface elements across a contact zone (its whole width)
BOND_RESOLUTION = 4.0        # a patch's thickness over the interface elements at the contact's
                             # edge from which the 2D coating's peak bond shear stays within
                             # 1 % (studies/bond_shear_mesh.py: results/bond_shear_mesh.md)
EDGE_SHARE = 0.5             # a peak this share of its zone's half-width off its centre is
                             # at the edge: a curved indenter's pressure peaks at the centre
COATING_SHARE = 0.25         # a coating's thickness over its base's depth


def _warning(code, message, value=None, limit=None):
    """A warning: its code, its text, the value measured and the limit it passed (None
    where the warning is not a number's)."""
    return {"code": code, "message": message,
            "value": None if value is None else float(value),
            "limit": None if limit is None else float(limit)}


def _unlike_bodies(scene):
    """Whether some contact pairs bodies of different elastic constants (Dundurs' beta
    may then differ from 0)."""
    base = (scene.base.E, scene.base.nu)
    return bool(scene.coatings) or (scene.indenter.E, scene.indenter.nu) != base


def base_depth(base):
    """How deep the base is below its face: a block's height, a roller's rim."""
    return base.height if base.shape == "block" else base.radius - base.shaft_radius


def mesh_warnings(problem, say, a):
    """The warnings of a mesh too coarse for the contact the scene will make, before any
    work: fewer than ELEMENTS_ACROSS interface elements across the a priori contact width
    2a (``a``: orchestrate/model/estimate.py's estimate, in b; a half model's mirrored), or
    across a patch's part of it (a pad narrower than the contact carries its own
    pressure). The limit is studies/resolution.py's (results/resolution.md). And a patch
    too thin for its elements at the predicted contact's edge (_bond_resolution_warnings)."""
    scene = problem.scene
    contacts = [i for i in problem.interfaces if i.kind == "contact"]
    if a == 0 or not contacts:
        return []
    centre = scene.contact_centre
    low, high = centre - a, centre + a
    x1 = np.concatenate([i.position[:, 0] for i in contacts])
    warnings = []

    def mirrored(start, end):          # a half model's stretch from the axis is twice as wide
        return (end - start) * (2.0 if scene.symmetric and start <= 0.0 else 1.0)
    stretches = [("the predicted contact", low, high)]
    stretches += [(f"coating[{n}]'s part of it", max(low, c.start), min(high, c.end))
                  for n, c in enumerate(scene.coatings, start=1)
                  if min(high, c.end) > max(low, c.start) and mirrored(c.start, c.end) < 2 * a]
    for what, start, end in stretches:
        element = _element_length(x1, start, end)
        across = (end - start if what == "the predicted contact" else mirrored(start, end)) / element
        if across < ELEMENTS_ACROSS:
            warnings.append(_warning(
                "coarse_mesh", f"{what}, [{say.length(start)}, {say.length(end)}] (a priori "
                f"half-width {say.length(a)}), is {across:.3g} interface elements across "
                f"(limit {ELEMENTS_ACROSS}; elements of {say.length(element)}): a smaller "
                "element_size (a length with its unit will do) or a higher mesh_level",
                across, ELEMENTS_ACROSS))
    return warnings + _bond_resolution_warnings(problem, a, say)


def _bond_resolution_warnings(problem, a, say):
    """A patch under an edge of the predicted contact (away from its ends) thinner than
    BOND_RESOLUTION interface elements there: the layer spreads the pressure's drop at
    the edge over about its thickness, which is where the bond's shear peaks; on longer
    elements that peak is the mesh's (studies/bond_shear_mesh.py)."""
    warnings = []
    for n, edge, element in edge_elements(problem, a):
        coating = problem.scene.coatings[n - 1]
        thick = coating.thickness / element
        if thick < BOND_RESOLUTION:
            warnings.append(_warning(
                "coarse_bond", f"coating[{n}] ({say.length(coating.thickness)} thick) is "
                f"{thick:.2g} interface elements thick at the predicted contact's edge "
                f"x1 = {say.length(edge)} (elements of {say.length(element)}; limit "
                f"{BOND_RESOLUTION:g}): the bond's shear peaks there over about the "
                "coating's thickness, so its largest value depends on the mesh: elements "
                f"of at most 1/{BOND_RESOLUTION:g} of the thickness there (element_size, "
                "contact_elements) resolve it", thick, BOND_RESOLUTION))
    return warnings


def edge_elements(problem, a):
    """(patch number, edge, interface element there) of every patch under an edge of
    the contact predicted with half-width ``a`` (a half model's: its edge off the axis),
    away from the patch's ends; of two such edges, the one of longer elements."""
    scene = problem.scene
    contacts = [i for i in problem.interfaces if i.kind == "contact"]
    if a == 0 or not contacts:
        return []
    x1 = np.concatenate([i.position[:, 0] for i in contacts])
    centre = scene.contact_centre
    edges = [centre + a] + ([] if scene.symmetric else [centre - a])
    found = []
    for n, coating in enumerate(scene.coatings, start=1):
        margin = coating.thickness * END_MARGIN
        inside = [(edge, _element_length(x1, edge, edge)) for edge in edges
                  if coating.start + margin < edge < coating.end - margin]
        if inside:
            found.append((n, *max(inside, key=lambda pair: pair[1])))
    return found


def elements_thick(problem, a):
    """{patch number: its thickness in interface elements} at an edge of the contact
    predicted with half-width ``a`` (edge_elements), for every patch under one."""
    return {n: problem.scene.coatings[n - 1].thickness / element
            for n, _, element in edge_elements(problem, a)}


def elements_across(x1, symmetric, zones):
    """(interface elements across, their length) of every contact zone [start, end] (a
    zone from a half model's axis: across its mirror image too); ``x1`` the contact
    points, the P2 elements' ends and midpoints."""
    counted = []
    for start, end in zones:
        width = (end - start) * (2.0 if symmetric and start <= 0.0 else 1.0)
        element = _element_length(x1, start, end)
        counted.append((width / element if element > 0 else 0.0, element))
    return counted


def _element_length(x1, start, end):
    """The interface elements' length over [start, end] (at least the points nearest
    to it): the points are the P2 elements' ends and midpoints, two to an element."""
    near = np.sort(x1[(x1 >= start - 1e-12) & (x1 <= end + 1e-12)])
    if len(near) < 3:
        near = np.sort(x1[np.argsort(np.abs(x1 - 0.5 * (start + end)))[:3]])
    return 2.0 * float(np.median(np.diff(near)))


def scene_warnings(scene, given, settings, say, a, thick=None):
    """The warnings known before any work, from the ``scene`` (its models chosen) and the
    scene as ``given`` (which patches the user modelled, not "auto"), both in the scene's
    units (the estimate's quantities are ratios: any consistent units do), its a
    priori contact half-width ``a`` in those units and ``thick``, each patch's thickness
    in interface elements at the predicted contact's edge (elements_thick)."""
    thick = thick or {}
    warnings = []
    if (scene.partial_slip and scene.load.tangential and scene.load.path == "at_once"
            and _unlike_bodies(scene)):
        kind = scene.load.tangential_kind
        warnings.append(_warning(
            "partial_slip_path", f"load.{kind} between unlike bodies (a coating, or an "
            f"indenter of another material): the load and the {kind.replace('_', ' ')} "
            "are applied at once, while pressing alone already slips between unlike bodies "
            "(Dundurs' beta is not 0), so the answer is that of proportional loading, not "
            "of pressing, then pulling (load.path = \"pressed_first\")"))
    depth = base_depth(scene.base)
    for number, (coating, asked) in enumerate(zip(scene.coatings, given.coatings), start=1):
        share = coating.thickness / depth
        if share > COATING_SHARE:
            warnings.append(_warning(
                "thick_coating", f"coating[{number}] is {100 * share:.3g} % as thick as its "
                f"base is deep ({say.units.length}: {coating.thickness:.4g} against "
                f"{depth:.4g}; limit {100 * COATING_SHARE:g} %): not a thin coating on a "
                "body; the base's clamping acts through it", share, COATING_SHARE))
        if coating.model not in SHELL_MODELS:
            continue
        errors = estimated_errors(scene, coating, a, thick.get(number))[coating.model]
        if errors is not None and "shear" not in ANSWERS[settings.model_answers]:
            warnings += _bond_shear_warnings(number, coating, errors["shear"],
                                             thick.get(number), settings)
        if asked.model not in SHELL_MODELS:
            continue
        reason = not_estimated(scene, coating, a)
        if reason:
            warnings.append(_warning(
                "model_uncalibrated", f"coating[{number}] is modelled as a {coating.model}, "
                f"whose error the estimate does not cover here ({reason}, in "
                f"{say.units.length}); model = \"elastic\" or \"auto\" is exact for the "
                "coating"))
            continue
        error = worst_error(errors, settings.model_answers)
        if error > settings.model_tolerance:
            each = ", ".join(f"{ANSWER_NAMES[name]} {100 * errors[name]:.3g} %"
                             if errors[name] is not None else
                             f"{ANSWER_NAMES[name]} not estimated on this mesh (the coating "
                             f"{thick[number]:.2g} of its elements thick at the contact's "
                             "edge)"
                             for name in ANSWERS[settings.model_answers])
            warnings.append(_warning(
                "model_error", f"coating[{number}] is modelled as a {coating.model}, whose "
                f"estimated errors are: {each} (tolerance {100 * settings.model_tolerance:g} "
                "%, settings.model_tolerance, on the answers settings.model_answers = "
                f"\"{settings.model_answers}\" names); model = \"auto\" chooses one "
                "within it", error,
                settings.model_tolerance))
    return warnings


def _bond_shear_warnings(number, coating, error, thick, settings):
    """bond_shear_model: a shell patch's bond shear estimated off by more than the
    tolerance (``error``); bond_shear_mesh: not estimated on elements that set it
    (``thick``: the coating's thickness in them at the predicted contact's edge)."""
    if error is None:
        return [_warning(
            "bond_shear_mesh", f"coating[{number}] is a {coating.model}: its bond shear is "
            f"not estimated, the coating being {thick:.2g} of its interface elements thick "
            f"at the predicted contact's edge (limit {STRETCH_SHEAR_LEAST_ELEMENTS:g}): "
            "there its shear overshoots by as much as the elements make it, not as its form "
            "says; model = \"elastic\" on elements of at most a quarter of its thickness "
            "there (element_size, contact_elements) for a bond shear", thick,
            STRETCH_SHEAR_LEAST_ELEMENTS)]
    if error > settings.model_tolerance:
        return [_warning(
            "bond_shear_model", f"coating[{number}] is a {coating.model}: its bond shear is "
            f"estimated {100 * error:.3g} % off the 2D coating's (tolerance "
            f"{100 * settings.model_tolerance:g} %, which model_answers = "
            f"\"{settings.model_answers}\" applies to the pressure and the bond's normal "
            "stress only); model_answers = \"all\" or model = \"elastic\" for a bond "
            "shear within it", error, settings.model_tolerance)]
    return []


class Say:
    """Numbers of the solver (b, E) as text in the scene's units."""

    def __init__(self, scales, units):
        self.scales, self.units = scales, units

    def length(self, value):
        return f"{self.in_units(value):.4g} {self.units.length}"

    def in_units(self, length):
        return length * self.scales.length

    def stress(self, value):
        return f"{value * self.scales.stress:.4g} {self.units.stress}"


def run_warnings(problem, results, contact_x1, contact_stress, say):
    """The warnings of a converged run: ``problem`` in b and E, ``results`` its summary
    entries (solve.py's _write_results, in b and E), the contact points' x1 and normal
    stresses, ``say`` a Say."""
    scene = problem.scene
    warnings = []
    warnings += _edge_warnings(problem, contact_x1[contact_stress < 0], say)
    warnings += _strain_warnings(scene, results, say)
    depth = min(scene.indenter.height, base_depth(scene.base))
    descent = abs(results["descent"] or 0.0)
    if descent > DESCENT_LIMIT * depth:
        warnings.append(_warning(
            "large_descent", f"the stamp's descent, {say.length(descent)}, is "
            f"{100 * descent / depth:.3g} % of the smaller body's depth {say.length(depth)} "
            f"(limit {100 * DESCENT_LIMIT:g} %): displacements are not small", descent / depth,
            DESCENT_LIMIT))
    mismatch = results["normal_mismatch_deg"]
    if mismatch > MISMATCH_LIMIT_DEG:
        warnings.append(_warning(
            "normal_mismatch", f"the paired faces' normals differ by up to {mismatch:.3g} "
            f"degrees over the contact (limit {MISMATCH_LIMIT_DEG:g}): the contact pairs "
            "points along the indenter's normal, assuming the faces close", mismatch,
            MISMATCH_LIMIT_DEG))
    warnings += _resolution_warnings(contact_x1, problem.scene.symmetric, results, say)
    contact = results["answers"]["contact"]
    away, ends = contact.get("peak_pressure"), contact.get("at_patch_ends", {}).get("peak_pressure")
    if ends and (not away or ends["value"] > away["value"]):
        warnings.append(_warning(
            "singular_contact_peak", f"the largest contact pressure, {say.stress(ends['value'])}"
            f" at x1 = {say.length(ends['x1'])}, is at a patch end: the indenter presses on "
            "the step of the patch's edge, a singular, mesh-dependent value; away from the "
            f"ends the peak is {say.stress(away['value']) if away else 'none'}",
            ends["value"] / away["value"] if away else None, 1.0 if away else None))
    found = edge_peak(problem, away, results["contact_zones"], contact_x1, contact_stress)
    if found:
        number, where, (start, end), at_centre = found
        warnings.append(_warning(
            "edge_contact_peak", f"the largest contact pressure, {say.stress(away['value'])} "
            f"at x1 = {say.length(where)}, is near the edge of its contact zone "
            f"[{say.length(start)}, {say.length(end)}] (the centre's "
            f"{say.stress(at_centre)}), on coating[{number}], a "
            f"{scene.coatings[number - 1].model}: the coating bends and gathers the load at "
            "the contact's edges, over about its thickness, where a 1D model's peak is off "
            "by more than its estimate says (0.8-30 % measured); model = \"elastic\" "
            "resolves it", away["value"] / at_centre, 1.0))
    return warnings


def edge_peak(problem, peak, zones, x1, stress):
    """(patch number, x1, its zone, the pressure at the zone's centre) where the contact
    pressure's ``peak`` (away from the patches' ends) lies near the edge of its zone on
    a patch modelled as a shell, under a curved indenter whose pressure would peak at the
    zone's centre; else None. ``x1``, ``stress``: the contact points (compression
    negative), in b and E.

    The coating, stiffer than its base, bends: the indenter's curvature held over the
    contact makes a bending moment that drops to nothing outside it, so the load gathers
    at the contact's edges over about the coating's thickness, where neither shell
    resolves it (the Timoshenko shell's rigid normal fibre concentrates it, the stretch
    shell spreads it by its own compliance): measured, the near-rigid cylinder's shell
    18.6 % above the 2D coating, a thin hard coating on a polymer under steel 15 % below
    it with the stretch shell (docs/findings.md). A zone with a patch's step in or at it
    has a shape of its own (singular_contact_peak)."""
    scene = problem.scene
    if not peak or scene.indenter.flat or not len(x1):
        return None
    where = peak["x1"]
    number = next((n for n, c in enumerate(scene.coatings, start=1)
                   if c.start <= where <= c.end and c.model in SHELL_MODELS), None)
    zone = next(((s, e) for s, e in zones if s - 1e-12 <= where <= e + 1e-12), None)
    if number is None or zone is None:
        return None
    start, end = zone
    if any(start - c.thickness <= x <= end + c.thickness
           for c in scene.coatings for x in scene.patch_ends(c)):
        return None
    from_axis = scene.symmetric and start <= 0.0
    centre = 0.0 if from_axis else 0.5 * (start + end)
    half_width = end if from_axis else 0.5 * (end - start)
    order = np.argsort(x1)
    at_centre = -float(np.interp(centre, x1[order], stress[order]))
    if abs(where - centre) <= EDGE_SHARE * half_width or not peak["value"] > at_centre > 0:
        return None
    return number, where, zone, at_centre


def _face_ends(scene):
    """x1 of the ends of the stretch of the indenter's face over the base (a half model:
    the symmetry axis is no end, None)."""
    indenter, base = scene.indenter, scene.base
    high = min(indenter.centre + indenter.width, base.top)
    low = None if scene.symmetric else max(indenter.centre - indenter.width, -base.top)
    return low, high


def _edge_warnings(problem, pressed, say):
    """``pressed``: x1 of every contact point under pressure."""
    if not len(pressed):
        return []
    low, high = _face_ends(problem.scene)
    warnings = []
    for end, reached in ((low, pressed.min()), (high, pressed.max())):
        if end is not None and abs(reached - end) <= 1e-9 * (1.0 + abs(end)):
            warnings.append(_warning(
                "contact_at_edge", f"the contact reaches the end of a face at x1 = "
                f"{say.length(end)}: the bodies beyond it, and the contact there, are not "
                "modelled (larger bodies, or a smaller load)", say.in_units(reached),
                say.in_units(end)))
    return warnings


def _strain_warnings(scene, results, say):
    """The largest stress away from the patches' ends over the modulus of the body it
    acts on: the contact pressure over the softer of the indenter and what it presses, a
    bond's stresses over the softer of coating and base, a coating's over its own."""
    found = []                                         # (ratio, what)
    softest_pressed = min([scene.base.E] + [c.E for c in scene.coatings])
    for extreme in _extremes(results["answers"]["contact"]):
        found.append((extreme["value"] / (softest_pressed if scene.indenter.rigid
                                          else min(scene.indenter.E, softest_pressed)),
                      f"the contact pressure {say.stress(extreme['value'])}"))
    for name, values in results["answers"]["bonds"].items():
        coating = scene.coatings[int(name.rsplit("coating", 1)[1]) - 1]
        for extreme in _extremes(values):
            found.append((abs(extreme["value"]) / min(coating.E, scene.base.E),
                          f"{name}'s stress {say.stress(extreme['value'])}"))
    for name, values in results["answers"]["coatings"].items():
        coating = scene.coatings[int(name[len("coating"):]) - 1]
        for extreme in _extremes(values):
            found.append((abs(extreme["value"]) / coating.E,
                          f"{name}'s stress {say.stress(extreme['value'])}"))
    if not found:
        return []
    ratio, what = max(found, key=lambda item: item[0])
    warnings = []
    if ratio > STRAIN_LIMIT:
        warnings.append(_warning(
            "large_strain", f"{what} is {100 * ratio:.3g} % of the modulus of the body it "
            f"acts on (limit {100 * STRAIN_LIMIT:g} %): strains are not small, and linear "
            "elasticity's error is of their size", ratio, STRAIN_LIMIT))
    if ratio > MODULUS_SHARE:
        warnings.append(_warning(
            "stress_near_modulus", f"{what} is {100 * ratio:.3g} % of the modulus of the "
            f"body it acts on (limit {100 * MODULUS_SHARE:g} %): are the moduli and the load "
            "in the units the scene says?", ratio, MODULUS_SHARE))
    return warnings


def _extremes(values):
    """Every extreme of an answer's group away from the patches' ends (within them the
    stresses are singular: they grow with the mesh, whatever the load)."""
    return [extreme for quantity, extreme in values.items()
            if quantity != "at_patch_ends" and extreme]


def _resolution_warnings(x1, symmetric, results, say):
    """Contact zones with fewer than ELEMENTS_ACROSS interface elements across them (a
    zone from a half model's axis: across its mirror image too). The interfaces' points
    ``x1`` are their P2 elements' ends and midpoints: an element is two point spacings."""
    if not len(x1):
        return []
    warnings = []
    zones = results["contact_zones"]
    for (start, end), (across, element) in zip(zones, elements_across(x1, symmetric, zones)):
        if across < ELEMENTS_ACROSS:
            warnings.append(_warning(
                "coarse_contact", f"the contact zone [{say.length(start)}, "
                f"{say.length(end)}] is {across:.3g} interface elements across "
                f"(limit {ELEMENTS_ACROSS}; elements of {say.length(element)}): its pressure "
                "is not resolved; a smaller element_size (it takes a length with its unit) "
                "or a higher mesh_level", across, ELEMENTS_ACROSS))
    return warnings


def forms_edited_warning():
    """A form or script edited while the run went on (provenance.py: its hashes at the
    end are not those at its start)."""
    return _warning("forms_edited", "a FreeFEM form or script was edited while the run "
                    "went on: its workers may have read either version (provenance records "
                    "the hashes at its start); run it again")
