"""A run decided before any work: the scene checked against the settings and made
dimensionless, every "auto" patch's model chosen, the discrete problem, its size
against the machine, how it is solved (its Strategy: orchestrate/ddm/strategy.py, with
the coarse level's problem where it has two levels), and the warnings the scene already
has (a Plan).

model = "auto" takes, per patch, the cheapest coating model whose estimated errors
(orchestrate/model/estimate.py) of the answers settings.model_answers names are within
the tolerance. Cost: the estimated number of unknowns of the whole problem
(orchestrate/mesh/problem_size.py), counted before any mesh. Costs within COST_TIE of the cheapest count as the same, and then the more
faithful model wins: on the paper's mesh the 2D coating needs no more unknowns than a
shell until it must refine (thinner than about b/32), and a run's time follows its
unknowns (docs/findings.md, "Speed and accuracy").

On a mesh fine enough for two levels, inner_solve = "auto" leaves the coarse level out
(_coarse_left_out)
- where some side's neighbour is more than hold_contrast times as stiff as its body
  (ddm/robin_parameters.py): the coarse level models the loop with every side held,
  which crawls under such a contrast (the near-rigid cylinder at mesh level 2: two
  levels stagnated and fell back to the direct solve in 57 s; iterated with the sides
  released, 85 iterations and 7.5 s);
- where a coating is more than hold_contrast times softer than its base: there one level
  took fewer iterations per contact set than two (the gallery's polymer coating at mesh
  level 2: 19 against 128, 2.2 s against 13.9 s; the paper's scene under coatings of
  E/10 and E/30: 15-21 against 19-38);
- where the first contact set is the half-planes' contact across several contact faces'
  gap (ddm/first_contact.py's profile_contact: a cylinder across pads and the bare base
  between them), the answer's set or near it: the coarse level's first state adds
  little there, and its loop took more iterations per contact set than one level's. Measured, one
  level against two, mesh levels 2/3: the gallery's pads 6.3/16.1 s against 7.6/18.8 s
  (final set 18/31 iterations against 49/70), the discrete example's shell patches
  1.5/3.6 s against 2.0/3.8 s;
- where the coarse level's maps would not pay, by the measure auto applies to a direct
  solve on that mesh (strategy.maps_would_pay, auto_direct_unknowns): probing them cost
  more than the iterations they save. Measured at mesh level 2 with the sides split on
  one level: the gallery's coated roller 6.8 s with two levels against 3.3 s with one,
  TiN 5.0 against 2.0 s, the thick ceramic 18.1 against 8.3 s, the anodised aluminium
  3.7 against 1.8 s; where the maps pay (the paper's scenes) two levels were as fast or
  faster (the paper's scene at mesh level 3: 3.1 s against 4.9 s, 16 iterations against
  115).

Below auto_two_level_mesh_level auto takes no coarse level. It had taken one on mesh level
1 where the coarse level's maps cost at most a tenth of the fine ones to probe: the
gallery's 1 um pads (0.04), two levels 2.6 s and 59 iterations against one level's 3.4 s
and 134. With the contact's sides split far and the pads inside the base's worker
(ddm/robin_parameters.py), one level takes 64 iterations in the same time, 17 of them in
the final contact set against the two levels' 33.
"""

from contextlib import contextmanager
from dataclasses import dataclass, replace

from orchestrate.ddm.coarse import coarse_problem
from orchestrate.ddm.first_contact import contact_spans_faces
from orchestrate.ddm.robin_parameters import contrast_exceeds, soft_coating
from orchestrate.ddm.strategy import DIRECT, maps_would_pay, plan_strategy
from orchestrate.errors import LengthsError, ParameterError
from orchestrate.mesh.discretization import contact_reach, discretize
from orchestrate.mesh.problem_size import check_direct_size, check_size, estimated_dofs
from orchestrate.model.estimate import (ANSWERS, contact_half_width, estimated_errors,
                                        first_contact_half_width, not_estimated,
                                        predicted_half_width, worst_error)
from orchestrate.model.scene import MESH_LEVEL_LIMIT, check_compatible
from orchestrate.model.units import dimensionless
from orchestrate.run.validity import Say, elements_thick, mesh_warnings, scene_warnings

AUTO = "auto"
FIDELITY = ("shell", "stretch_shell", "elastic")   # least to most faithful
COST_TIE = 1.1


def choose_models(scene, settings, a=None, edge=None):
    """(the scene with every "auto" patch's model chosen, the choice's report or None);
    ``a``: the scene's a priori contact half-width, if known; ``edge``: the half-width
    whose edges a patch's elements are counted at (the predicted one; ``a`` if None)."""
    auto = [n for n, c in enumerate(scene.coatings) if c.model == AUTO]
    if not auto:
        return scene, None
    tolerance, answers = settings.model_tolerance, settings.model_answers
    a = contact_half_width(scene) if a is None else a
    edge = a if edge is None else edge
    # while a patch is decided, the other undecided ones are shells (the cheapest)
    models = [("shell" if c.model == AUTO else c.model) for c in scene.coatings]
    patches = []
    for n in auto:
        coating = scene.coatings[n]
        unknowns, refused, thick = {}, {}, None
        for model in FIDELITY:
            trial = list(models)
            trial[n] = model
            try:
                problem = discretize(scene.with_models(trial), settings)
            except ParameterError as error:     # its mesh too fine for the machine (a
                refused[model] = error          # nanometre-thin 2D coating, uniform faces)
                continue
            unknowns[model] = round(sum(estimated_dofs(problem).values()))
            if model == "stretch_shell":        # its bond shear may follow its mesh
                thick = elements_thick(problem, edge).get(n + 1)
        errors = estimated_errors(scene, coating, a, thick)
        passing = [m for m in FIDELITY if m in unknowns
                   and worst_error(errors[m], answers) <= tolerance]
        if not passing:                 # elastic always passes the tolerance: refused too
            raise refused["elastic"]
        cheapest = min(unknowns[m] for m in passing)
        chosen = [m for m in passing if unknowns[m] <= COST_TIE * cheapest][-1]
        models[n] = chosen
        patches.append({"patch": n + 1, "model": chosen,
                        "estimated_error": worst_error(errors[chosen], answers),
                        "not_estimated": not_estimated(scene, coating, a),
                        "h2_over_a": coating.thickness / a if a else None,
                        "stretch_shell_elements_thick": thick,
                        "estimated_errors": errors, "estimated_unknowns": unknowns,
                        "refused": {model: str(error) for model, error in refused.items()}})
    report = {"tolerance": tolerance, "answers_judged": ANSWERS[answers],
              "contact_half_width_estimate": a, "patches": patches}
    return scene.with_models(models), report


@dataclass(frozen=True)
class Plan:
    """A run decided before any work (prepare)."""

    scene: object          # the scene as given, every "auto" patch's model chosen
    problem: object        # the problem of its dimensionless form
    model_choice: object   # the choice's report, or None
    scales: object         # Scales back to the scene's units
    warnings: tuple        # what validity.py knows of the scene before any work
    strategy: object       # how it is solved (orchestrate/ddm/strategy.py)
    coarse: object         # the coarse level's problem where the strategy has two levels


def _decided_models(scene, settings):
    """The dimensionless scene with its "auto" patches chosen, on the mesh a run sizes
    to its contact: (scene, model choice, scales, settings sized, a, predicted)."""
    check_compatible(scene, settings)
    solved, scales = dimensionless(scene)
    a = contact_half_width(solved)           # the a priori estimate, made once
    predicted = predicted_half_width(solved, a)     # with a compliant coating's spread
    settings = settings.sized_to(predicted, contact_reach(solved))  # the mesh sized to
                                                                      # the contact
    solved, model_choice = choose_models(solved, settings, a, predicted)
    return solved, model_choice, scales, settings, a, predicted


def model_choice(scene, settings):
    """The choice of a run's "auto" patches (its report, or None), as prepare makes it,
    without the rest of the plan."""
    with lengths_in_units(scene):
        return _decided_models(scene, settings)[1]


def _coarse_left_out(problem, settings, first_contact):
    """Why auto leaves out the coarse level the mesh level would take, judged on the fine
    problem and the half-width its first contact set is drawn to (the module's text), or
    None."""
    if settings.inner_solve != AUTO or not settings.two_levels:
        return None
    if contact_spans_faces(problem, first_contact):
        return ("the first contact set is the half-planes' contact across the faces' gap, "
                "where one level answered faster")
    contrast = f"hold_contrast {settings.hold_contrast:g}"
    if contrast_exceeds(problem, settings.robin_sides, settings.hold_contrast):
        return (f"a side releases its inactive points under a neighbour more than "
                f"{contrast} times as stiff, which the coarse level's fixed maps cannot "
                "model")
    if soft_coating(problem, settings.hold_contrast):
        return (f"a coating more than {contrast} times softer than its base, where one "
                "level took fewer iterations per contact set than two")
    return None


def _coarse_maps_left_out(coarse, settings):
    """Why auto leaves out the coarse level whose problem is ``coarse`` (its maps would
    not pay: the module's text), or None."""
    if settings.inner_solve != AUTO or maps_would_pay(coarse, settings):
        return None
    return (f"the coarse level's maps would not pay: some worker's interface unknowns on "
            f"its mesh, weighted by its dofs, above auto_direct_unknowns "
            f"{settings.auto_direct_unknowns}")


def prepare(scene, settings):
    """Everything checked and decided before any work (a Plan). ParameterError for
    settings the scene cannot take or a problem too large, its lengths in the scene's
    units."""
    with lengths_in_units(scene):
        return _prepared(scene, settings)


@contextmanager
def lengths_in_units(scene):
    """A LengthsError of the scene made dimensionless (the mesh's checks) said in the
    scene's units."""
    try:
        yield
    except LengthsError as error:
        say = Say(dimensionless(scene)[1], scene.units)
        raise error.in_units(say.length) from None


def _prepared(scene, settings):
    solved, model_choice, scales, settings, a, predicted = _decided_models(scene, settings)
    problem, coarse = discretize(solved, settings), None
    # one level, its gamma, where the coarse level would not help (left_out), or has no
    # frictional solve (strategy._inner_solve)
    frictional = settings.inner_solve == AUTO and settings.two_levels and scene.frictional
    first_contact = first_contact_half_width(solved, predicted)
    left_out = _coarse_left_out(problem, settings, first_contact)
    if left_out is None and settings.two_levels and not frictional:
        coarse = coarse_problem(solved, settings)
        left_out = _coarse_maps_left_out(coarse, settings)
    if left_out or frictional:
        settings = replace(settings, auto_two_level_mesh_level=MESH_LEVEL_LIMIT + 1)
        problem, coarse = discretize(solved, settings), None
    check_size(problem)
    strategy = plan_strategy(settings, problem, coarse, predicted, left_out, first_contact)
    if strategy.inner_solve.planned == DIRECT:     # asked: its dense system must fit
        check_direct_size(problem)
    chosen = scene.with_models([c.model for c in solved.coatings])
    say = Say(scales, scene.units)
    return Plan(chosen, problem, model_choice, scales,
                tuple(scene_warnings(chosen, scene, settings, say, a * scales.length,
                                     elements_thick(problem, predicted))
                      + mesh_warnings(problem, say, predicted)),
                strategy, coarse if strategy.two_levels else None)

