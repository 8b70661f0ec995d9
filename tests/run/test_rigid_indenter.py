"""A rigid indenter (indenter.rigid = true): no body, one unknown pressed by the stamp
(freefem/subdomain_rigid.idp, rigid.edp). Its physics against plane-strain Hertz with
the base's E* alone; the model against elastic indenters 10^4 and 10^5 times stiffer
than the base (the monolithic solve of each: the same mesh and penalty; the difference
shrinks as 1/E); the scene's unit of stress and its inputs. (The Robin loop against the monolithic solve of the same
problem, under a force and a descent: tests/ddm/test_monolithic.py.)"""

from dataclasses import replace
import math

import numpy as np
import pytest

import orchestrate
from orchestrate.errors import ParameterError
from orchestrate.model.scene import Base, Indenter, Load, Scene, Settings
from orchestrate.model.scene_file import SCENES_DIR, apply_overrides, load_scene
from orchestrate.run import monolithic_of, prepare

pytestmark = pytest.mark.slow       # not in the everyday subset (make test-fast)

RADIUS, NU = 40.0, 0.3
STIFF = (1e4, 1e5)                  # the stiff indenters' moduli (E)


def _hertz_scene(size, a=1.0):
    """A rigid cylinder on an uncoated block ``size`` wide (half model) and high, under
    the force that gives the half-width a: F = pi E* a^2 / (4 R), E* = E / (1 - nu^2)."""
    modulus = 1.0 / (1.0 - NU ** 2)
    force = math.pi * modulus * a ** 2 / (4.0 * RADIUS)
    return Scene(indenter=Indenter(radius=RADIUS, width=size, height=size, rigid=True),
                 base=Base(shape="block", width=size, height=size, E=1.0, nu=NU),
                 coatings=(), load=Load(force=force), symmetric=True,
                 contact_zone=(0.0, 2.0)), force, 2.0 * force / (math.pi * a)


def test_a_rigid_cylinder_on_a_large_block_is_hertz():
    """W = 16 a: the finite body's error is about 0.36 (a/W)^2 (tests/studies/
    test_hertz.py), far below the 1 % asserted."""
    scene, force, p0 = _hertz_scene(16.0)
    result = orchestrate.solve(scene, Settings(eps_u=1e-8))
    summary = result.summary
    assert abs(summary["total_force"] / force - 1) < 1e-6
    assert abs(-summary["peak_contact_stress"] / p0 - 1) < 0.01
    assert abs(summary["contact_half_width"] - 1.0) < 0.01
    assert summary["stamp_reaction"] == pytest.approx(summary["contact_force"], rel=1e-6)
    assert summary["dofs"]["indenter"] == 1


@pytest.fixture(scope="module")
def rigid_and_stiff():
    """The monolithic solves of a coated block under a rigid cylinder and under ones of
    10^4 and 10^5 E, each pair at the same penalty (theta in the solver's units: a
    scene's theta is in b/E of its stiffer body) and interface elements."""
    scene, _ = load_scene(SCENES_DIR / "gallery" / "near_rigid_cylinder.toml")
    scene = apply_overrides(scene, {"coating.model": "elastic", "indenter.rigid": True})
    solved = {}
    for modulus in STIFF:
        stiff = apply_overrides(scene, {"indenter.rigid": False, "indenter.E": modulus})
        for name, case, theta in (("rigid", scene, 1.0 / modulus), ("stiff", stiff, 1.0)):
            plan = prepare(case, Settings(element_size=0.0625, theta=theta))
            solved[name, modulus] = (plan.problem, *monolithic_of(
                plan.problem, half_width=plan.strategy.first_contact))
    return solved


def _difference(rigid, stiff):
    """The largest difference of the interface stresses, relative to each interface's
    largest; and of the descent."""
    worst = 0.0
    for i, interface in enumerate(rigid[0].interfaces):
        ours, theirs = np.asarray(rigid[2][i]), np.asarray(stiff[2][i])
        if not np.any(theirs):               # a stretch of bare base out of contact
            assert not np.any(ours), interface.name
            continue
        worst = max(worst, float(np.max(np.abs(ours - theirs)) / np.max(np.abs(theirs))))
    return worst, abs(rigid[1]["descent"] / stiff[1]["descent"] - 1)


def test_the_rigid_indenter_is_the_limit_of_a_stiff_one(rigid_and_stiff):
    """The difference from a stiff indenter is that indenter's own compliance: it falls
    as 1/E (measured: 1.771e-3 of the interface stresses at 10^4 E, 1.78e-4 at 10^5 E,
    a ratio of 9.95; the descent's 6.56e-5 and 6.5e-6), so the rigid indenter is the
    limit, and an indenter of 10^6 E differs from it by about 1.8e-5. That last one is
    not measured here: a monolithic solve of the 10^6 E scene varies from run to run by
    6e-6 to 1.7e-5 of its stresses (its conditioning; measured on this and the previous
    version of the forms), as much as the difference itself, while at 10^5 E it varies
    by 0.2 % of the difference."""
    for modulus in STIFF:
        rigid, stiff = rigid_and_stiff["rigid", modulus], rigid_and_stiff["stiff", modulus]
        assert rigid[0].penalty == pytest.approx(stiff[0].penalty, rel=1e-12)
    (far, far_descent), (near, near_descent) = (
        _difference(rigid_and_stiff["rigid", m], rigid_and_stiff["stiff", m]) for m in STIFF)
    assert near < 2e-4 and near_descent < 1e-5, (near, near_descent)
    assert far / near == pytest.approx(10.0, rel=0.05), (far, near)
    assert far_descent / near_descent == pytest.approx(10.0, rel=0.05)


def test_the_rigid_indenter_has_no_mesh(rigid_and_stiff):
    rigid, stiff = rigid_and_stiff["rigid", STIFF[1]][0], rigid_and_stiff["stiff", STIFF[1]][0]
    assert rigid.subdomains["indenter"].kind == "rigid"
    assert rigid.subdomains["indenter"].plan is None
    assert stiff.subdomains["indenter"].kind == "body"


def test_a_rigid_indenters_scene_is_in_units_of_the_bases_modulus():
    scene, _ = load_scene(SCENES_DIR / "cylinder.toml")
    rigid = apply_overrides(scene, {"indenter.rigid": True, "indenter.E": 1e9})
    assert rigid.modulus == rigid.base.E      # its own E does not count
    plan = prepare(rigid, Settings())
    sides = {(s.subdomain, s.neighbour): s for s in plan.strategy.sides}
    # the base's side under a rigid neighbour is held as hard as the law allows
    assert sides["base", "indenter"].gamma == pytest.approx(1.0 / plan.problem.penalty)
    assert not sides["base", "indenter"].hold_inactive


def test_rigid_must_be_true_or_false():
    scene, _ = load_scene(SCENES_DIR / "cylinder.toml")
    with pytest.raises(ParameterError, match="indenter.rigid"):
        apply_overrides(scene, {"indenter.rigid": "yes"})
    with pytest.raises(ParameterError, match="indenter.rigid"):
        replace(scene, indenter=replace(scene.indenter, rigid=1)).check()
