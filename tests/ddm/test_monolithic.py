"""The Robin loop against a monolithic solve of the same discrete penalised problem, on
every kind of scene, and equilibrium (bodies of revolution, contrast and rigid
indenters, friction: the same checks in test_monolithic_revolution.py,
test_monolithic_contrast.py, test_monolithic_friction.py and
test_monolithic_partial_slip.py).

freefem/monolithic.edp builds every subdomain with the workers' own includes, couples
them by the penalty on the same interface points and iterates the contact set to a
fixed point. Run to a tight tolerance, the domain decomposition must give the same
interface traces and stresses to 1e-6 relative: the test that the Robin data, the trace
operators (flat and curved, bodies and shells with and without thickness stretch, plane
and of revolution), the active-set logic and the force load are right. Both loops are
checked on the paper's scene: the accelerated active-set loop at the default penalty,
and the paper's own loop (gamma = 1/theta, fixed relaxation) at a penalty soft enough
for it to converge in a few hundred iterations (at theta = 1e-3 it would need ~10^5,
docs/method.md).

Equilibrium (to 1e-5 relative): the contact force, the force on the bonds, the stamp's
reaction on the indenter and the base's support reaction (consistent nodal reactions)
are one force, and every patch carries on its bond what it receives on its top."""

from dataclasses import replace

import numpy as np
import pandas as pd
import pytest

import orchestrate
from orchestrate.run.monolithic import monolithic_solution
from orchestrate.model.scene import Scene, Settings
from orchestrate.model.scene_file import SCENES_DIR, apply_overrides, load_scene, paper_scene
from orchestrate.run.solve import solve


def _file(name, **overrides):
    scene, _ = load_scene(SCENES_DIR / f"{name}.toml")
    return apply_overrides(scene, overrides)


def _off_centre_full_model():
    """A full model with nothing symmetric: an off-centre cylinder over a 2D patch and a
    shell patch of different thickness, under a force."""
    scene = _file("cylinder")
    coatings = (replace(scene.coatings[0], start=-1.5, end=-0.4, model="elastic", thickness=0.25),
                replace(scene.coatings[0], start=-0.1, end=1.2, E=2.0))
    return Scene(indenter=replace(scene.indenter, centre=0.3), base=scene.base,
                 coatings=coatings, load=scene.load, symmetric=False)


TIGHT = Settings(eps_u=1e-10)
CASES = {
    "paper, shell, active-set loop": (paper_scene(), TIGHT),
    # iterated, the coating inside the base's worker (freefem/coated_base.edp: the bond's
    # penalty in its matrix, whose rounding keeps the estimate above 1e-10: at eps_u
    # 1e-8), and each its own worker, exchanged across the bond
    "paper, shell, iterated contact sets": (
        paper_scene(), Settings(eps_u=1e-8, inner_solve="iterate", bonds="inside")),
    "paper, shell, iterated, bond exchanged (auto's choice without contrast)": (
        paper_scene(), Settings(eps_u=1e-10, inner_solve="iterate")),
    "three patches, shell and 2D, iterated inside the base's worker": (
        _file("discrete", **{"coating[2].model": "elastic"}),
        Settings(eps_u=1e-8, inner_solve="iterate", bonds="inside")),
    "coated roller, stretch shell, iterated inside the base's worker": (
        _file("roller", model="stretch_shell"),
        Settings(eps_u=1e-8, inner_solve="iterate", bonds="inside")),
    # the contact's sides split far: nearly a Dirichlet-Neumann exchange
    # (robin_parameters.py)
    "cylinder on a coated block, inside the base's worker, the contact's sides split far": (
        _file("cylinder"),
        Settings(eps_u=1e-8, inner_solve="iterate", bonds="inside", contact_split=256.0)),
    "paper, shell, paper loop, theta 1": (
        paper_scene(), Settings(method="paper", theta=1.0, eps_u=1e-10, max_iterations=2000)),
    "paper, 2D coating, h2 b/8": (paper_scene(model="elastic"), TIGHT),
    # at eps_u 1e-9: its estimate ends at 7-9e-11 on a quiet machine, and the workers'
    # last digits, which differ from run to run, once held it above 1e-10 (stagnated)
    "paper, 2D coating, two levels, mesh level 2": (
        paper_scene(model="elastic"), Settings(eps_u=1e-9, mesh_level=2,
                                               inner_solve="two-level")),
    # the coarse level models one worker for the base and its patches (coarse.py)
    # (on the paper's mesh: its coarse level has interface elements twice as long)
    "three patches, shell and 2D, two levels, inside the base's worker": (
        _file("discrete", **{"coating[2].model": "elastic"}),
        Settings(eps_u=1e-8, inner_solve="two-level", bonds="inside")),
    "paper, 2D coating, h2 b/2, E2 5E": (paper_scene(model="elastic", h2=0.5, E2=5.0), TIGHT),
    "paper under a force": (paper_scene(force=7.7e-4), TIGHT),
    "cylinder on a coated block": (_file("cylinder"), TIGHT),
    "coated roller, shell": (_file("roller"), TIGHT),
    "coated roller, 2D coating": (_file("roller", model="elastic"), TIGHT),
    "paper, stretch shell, h2 b/2, E2 E/5": (
        paper_scene(model="stretch_shell", h2=0.5, E2=0.2), TIGHT),
    "coated roller, stretch shell": (_file("roller", model="stretch_shell"), TIGHT),
    "three patches, shell and 2D": (_file("discrete", **{"coating[2].model": "elastic"}), TIGHT),
    "full model, off-centre": (_off_centre_full_model(), TIGHT),
    # a patch wider than the indenter's face: its top a contact under the face, free
    # beyond (discretization.py's partners_in)
    "a shell wider than the indenter's face": (
        _file("cylinder", **{"indenter.width": 1.5, "coating[1].end": 3.0}), TIGHT),
    "a 2D coating wider than the indenter's face": (
        _file("cylinder", **{"indenter.width": 1.5, "coating[1].end": 3.0,
                             "coating[1].model": "elastic"}), TIGHT),
    "a shell across an off-centre indenter's face, full model": (
        _file("cylinder", **{"symmetric": False, "indenter.centre": 0.7,
                             "indenter.width": 1.5, "coating[1].start": -3.0,
                             "coating[1].end": 3.0}), TIGHT),
}


EVERYDAY = "paper, shell, active-set loop"     # the one case of the fast subset


@pytest.fixture(scope="module", params=[
    pytest.param(name, marks=() if name == EVERYDAY else pytest.mark.slow) for name in CASES])
def case(request, tmp_path_factory):
    return solved_case(CASES[request.param], tmp_path_factory)


def solved_case(scene_and_settings, tmp_path_factory):
    """A case the tests below read: the Robin loop's summary and folder, the problem, and
    the monolithic solve's traces and stresses (the sibling files' fixtures too)."""
    scene, settings = scene_and_settings
    out = tmp_path_factory.mktemp("ddm")
    summary = solve(scene, settings, out)
    problem, traces, stresses = monolithic_solution(scene, settings)
    return summary, out, problem, traces, stresses


def _relative_difference(a, b):
    return float(np.max(np.abs(a - b)) / np.max(np.abs(b)))


def test_robin_loop_equals_monolithic_solve(case):
    summary, out, problem, traces, stresses = case
    assert summary["converged"]
    ddm = pd.read_csv(out / "traces.csv")
    contact = pd.read_csv(out / "contact.csv")
    bond = pd.read_csv(out / "interface.csv")
    for i, interface in enumerate(problem.interfaces):
        rows = ddm[ddm.interface == interface.name]
        if interface.kind == "friction":     # its contact's rows carry it
            name = problem.interfaces[interface.contact].name
            rows = ddm[ddm.interface == name]
            pairs = [(rows.a_t, traces[i, 0]), (rows.b_t, traces[i, 1])]
            mono = stresses[i]
            computed = contact[contact.interface == name].sigma_t.to_numpy()
        np.testing.assert_allclose(rows.s, interface.s, rtol=0, atol=1e-14)
        if interface.kind == "friction":
            pass
        elif interface.kind == "contact":
            pairs = [(rows.a_n, traces[i, 0]), (rows.b_n, traces[i, 1])]
            mono = stresses[i]
            computed = contact[contact.interface == interface.name].sigma_n.to_numpy()
        else:
            pairs = [(rows.a_t, traces[i, 0][0]), (rows.a_n, traces[i, 0][1]),
                     (rows.b_t, traces[i, 1][0]), (rows.b_n, traces[i, 1][1])]
            mono = stresses[i][1]
            computed = bond[bond.interface == interface.name].sigma_n.to_numpy()
        for values, reference in pairs:
            if not np.any(reference):     # a rigid indenter's tangential trace
                assert not np.any(values.to_numpy()), interface.name
                continue
            assert _relative_difference(values.to_numpy(), reference) < 1e-6, interface.name
        if np.max(np.abs(mono)) > 0:
            assert _relative_difference(computed, mono) < 1e-6, interface.name
        else:
            assert np.all(computed == 0), interface.name
    if problem.scene.load.force is not None:
        assert abs(summary["descent"] / traces["descent"] - 1) < 1e-6
    if problem.scene.partial_slip:
        assert abs(summary["stamp_shift"] / traces["shift"] - 1) < 1e-6


def test_forces_balance(case):
    summary = case[0]
    force = summary["contact_force"]
    assert force > 0
    for name in ("interface_force", "stamp_reaction", "base_reaction"):
        if name == "interface_force" and not case[2].bonds:
            continue
        assert abs(summary[name] - force) < 1e-5 * force, name
    if case[2].scene.load.force is not None:
        assert abs(summary["total_force"] / case[2].scene.load.force - 1) < 1e-5
    # on a flat base the friction force is mu times the normal one (none without it),
    # under partial slip the stamp's tangential force (a given shift's: below mu P); the
    # stamp carries it
    scene = case[2].scene
    expected = (scene.load.tangential_force if scene.partial_slip
                else scene.friction * force if scene.sliding else 0.0)
    if scene.load.tangential_displacement is not None:
        expected = summary["tangential_force"]
        assert 0 < abs(expected) <= scene.friction * force * (1 + 1e-9)
    assert abs(summary["tangential_force"] - expected) < 1e-6 * force
    assert abs(summary["stamp_tangential_force"] - expected) < 1e-5 * force


def test_every_patch_passes_on_what_it_receives(case):
    summary, problem = case[0], case[2]
    forces = summary["interfaces"]
    scale = summary["contact_force"]
    for number in range(1, len(problem.scene.coatings) + 1):
        received = forces.get(f"contact-coating{number}", {"force": 0.0})["force"]
        passed = forces[f"bond-coating{number}"]["force"]
        assert abs(received - passed) < 1e-5 * scale, number


@pytest.mark.slow
def test_the_2d_coating_of_the_bodies_modulus_is_one_body_with_them():
    """With E2 = E the 2D coating and the base are one material: the contact stress must
    match the scene without coating (the base grown by h2) within discretisation error.
    Measured as relative L2 distances between contact-stress curves: on the paper's mesh
    the coated-uncoated distance (0.27 %) is of the size of that mesh's discretisation
    error, estimated by the change to the next mesh (0.20 %), and it halves on the next
    mesh (0.13 %). Solved by the Robin loop to eps_u = 1e-8 (the monolithic solve's
    curves within 6e-10 of the peak, in a third of its time)."""
    from studies.claims import distance

    coated = paper_scene(h2=0.125, E2=1.0, model="elastic")
    uncoated = apply_overrides(replace(coated, coatings=()), {"base.height": 8.125})
    curves = {}
    for level in (1, 2):
        for name, scene in (("coated", coated), ("uncoated", uncoated)):
            contact = orchestrate.solve(scene, Settings(mesh_level=level, eps_u=1e-8)).contact
            top = contact[contact.interface == contact.interface.iloc[0]]  # the coating's
            curves[level, name] = (top.x1.to_numpy(), top.sigma_n.to_numpy())  # or the base's
    gap = {level: distance(curves[level, "coated"], curves[level, "uncoated"]) for level in (1, 2)}
    x_coarse, coarse = curves[1, "uncoated"]
    x_fine, fine = curves[2, "uncoated"]
    mesh_change = distance((x_coarse, np.interp(x_coarse, x_fine, fine)), (x_coarse, coarse))
    assert gap[1] < 1.5 * mesh_change
    assert gap[2] < 0.6 * gap[1]


def test_the_monolithic_answer_does_not_depend_on_its_first_contact_set():
    """Started from the a priori set (the points within the estimated half-width, as the
    Robin loop starts) the monolithic solve reaches the answer it reaches grown from the
    first point touched, in fewer solves: three patches and the bare base between them,
    four contact interfaces read from the first set's file in the problem file's order.
    The same to rounding: the two solves' last factorisations differ in their last
    digits (4e-14 of the largest trace seen), a different answer by far more than 1e-10."""
    from orchestrate.run import monolithic_of, prepare
    plan = prepare(_file("discrete", **{"coating[2].model": "elastic"}), Settings())
    cold, _ = monolithic_of(plan.problem)
    primed, _ = monolithic_of(plan.problem, half_width=plan.strategy.first_contact)
    assert plan.strategy.first_contact > 0
    assert primed["solves"] < cold["solves"]
    for i, interface in enumerate(plan.problem.interfaces):
        for side in (0, 1):
            scale = max(np.max(np.abs(cold[i, s])) for s in (0, 1))
            assert np.max(np.abs(primed[i, side] - cold[i, side])) <= 1e-10 * scale, \
                interface.name
    assert primed["descent"] == pytest.approx(cold["descent"], rel=1e-10)
