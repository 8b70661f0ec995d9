"""Friction under full sliding, as a user meets it (the Robin loop against the monolithic
solve is tests/ddm/test_monolithic.py's; McEwen's field tests/studies/
test_line_contact_field.py's): mu = 0 is today's frictionless run; the friction
traction is mu p on the contact and in the files; a frictional run starts from a
frictionless neighbour (to the same answer, in fewer iterations); auto models a patch under friction by the 2D coating, and a
shell chosen by hand is said to be outside the estimate."""

from dataclasses import replace

import numpy as np
import pandas as pd
import pytest

from orchestrate import solve
from orchestrate.model.scene import Settings
from orchestrate.model.scene_file import SCENES_DIR, apply_overrides, load_scene

pytestmark = pytest.mark.slow       # a few runs of a second each

SETTINGS = Settings(eps_u=1e-8)


def _sliding(friction, model="elastic"):
    """The cylinder on its coated block as a full model, the patch [-2 b, 2 b]."""
    scene, _ = load_scene(SCENES_DIR / "cylinder.toml")
    scene = apply_overrides(scene, {"coating[1].model": model})
    return replace(scene, symmetric=False, friction=friction, sliding=True,
                   coatings=(replace(scene.coatings[0], start=-2.0),))


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    out = tmp_path_factory.mktemp("friction")
    frictionless = solve(replace(_sliding(0.0), sliding=False), SETTINGS)
    return {"frictionless": frictionless,
            "mu 0 sliding": solve(_sliding(0.0), SETTINGS),
            "mu 0.3": solve(_sliding(0.3), SETTINGS),
            "mu 0.3 warm": solve(_sliding(0.3), SETTINGS, start_from=frictionless),
            "out": out}


def test_mu_zero_is_the_frictionless_run(runs):
    """No friction interface is made: the same problem, the same answers to the digit."""
    a, b = runs["frictionless"], runs["mu 0 sliding"]
    pd.testing.assert_frame_equal(a.contact, b.contact)
    pd.testing.assert_frame_equal(a.interface, b.interface)
    assert a.summary["iterations"] == b.summary["iterations"]
    assert (a.contact.sigma_t == 0).all()
    assert b.summary["tangential_force"] == 0.0


def test_the_friction_traction_is_mu_p_where_the_bodies_touch(runs):
    contact = runs["mu 0.3"].contact
    np.testing.assert_allclose(contact.sigma_t, -0.3 * contact.sigma_n,
                               rtol=0, atol=1e-9 * contact.sigma_n.abs().max())
    assert (contact.sigma_t > 0).sum() > 10         # the base dragged towards +x1
    summary = runs["mu 0.3"].summary
    assert summary["tangential_force"] == pytest.approx(0.3 * summary["total_force"], rel=1e-6)
    traces = runs["mu 0.3"].traces
    touching = traces[traces.interface.str.startswith("contact")]
    assert np.isfinite(touching[["a_t", "b_t"]].to_numpy()).all()


def test_friction_shifts_the_pressure_of_dissimilar_bodies(runs):
    """The coated base is stiffer than the indenter (Dundurs' beta is not 0): friction
    couples into the normal problem, and the pressure leaves its mirror symmetry."""
    def skew(result):
        c = result.contact.sort_values("x1")
        p = -c.sigma_n.to_numpy()
        return float(np.sum(p * c.x1.to_numpy()) / np.sum(p))    # its centre
    assert abs(skew(runs["frictionless"])) < 1e-6
    assert abs(skew(runs["mu 0.3"])) > 1e-3


def test_a_frictional_run_starts_from_a_frictionless_one(runs):
    cold, warm = runs["mu 0.3"], runs["mu 0.3 warm"]
    scale = cold.contact.sigma_n.abs().max()
    np.testing.assert_allclose(warm.contact.sigma_n, cold.contact.sigma_n, rtol=0,
                               atol=1e-6 * scale)
    np.testing.assert_allclose(warm.contact.sigma_t, cold.contact.sigma_t, rtol=0,
                               atol=1e-6 * scale)
    # fewer: its first contact set is held until the displacements' estimated error is
    # within the tolerance (measured 52 against 75 cold; updated at once, 129)
    assert warm.summary["iterations"] < cold.summary["iterations"]


def _codes(warnings):
    """The warnings' codes, coarse_bond aside (these scenes' coatings are thinner than
    four interface elements at the contact's edge: tests/run/test_validity.py's)."""
    return [w["code"] for w in warnings if w["code"] != "coarse_bond"]


def test_auto_models_a_patch_under_friction_by_the_2d_coating():
    from orchestrate.run.plan import prepare
    plan = prepare(_sliding(0.3, "auto"), SETTINGS)
    patch = plan.model_choice["patches"][0]
    assert patch["model"] == "elastic"
    assert "friction" in patch["not_estimated"]
    shell = prepare(_sliding(0.3, "shell"), SETTINGS)
    assert _codes(shell.warnings) == ["model_uncalibrated"]
    assert "friction" in shell.warnings[0]["message"]


def test_a_patch_may_have_its_own_friction():
    """Two patches side by side under the contact, mu 0.2 and 0.5 on their tops, the
    scene's 0.3 on the bare base: each contact's friction traction is its own mu p."""
    scene = _sliding(0.3)
    left = replace(scene.coatings[0], start=-2.0, end=0.0, friction=0.2)
    right = replace(scene.coatings[0], start=0.0, end=2.0, friction=0.5)
    result = solve(replace(scene, coatings=(left, right)), SETTINGS)
    contact = result.contact
    for name, mu in (("contact-coating1", 0.2), ("contact-coating2", 0.5)):
        rows = contact[contact.interface == name]
        assert (rows.sigma_n < 0).sum() > 5, name
        np.testing.assert_allclose(rows.sigma_t, -mu * rows.sigma_n, rtol=0,
                                   atol=1e-9 * contact.sigma_n.abs().max())
    from orchestrate.run.plan import prepare
    problem = prepare(replace(scene, coatings=(left, right)), SETTINGS).problem
    assert {f.name: f.friction[0] for f in problem.frictions} == {
        "friction-base1": 0.3, "friction-coating1": 0.2, "friction-coating2": 0.5,
        "friction-base2": 0.3}


def test_partial_slip_between_unlike_bodies_says_it_is_proportional_loading():
    """Pressing alone slips where Dundurs' beta is not 0: the one-step answer is not
    pressing-then-pulling's, and the run says so; between bodies of one material not."""
    from orchestrate.run.plan import prepare
    coated = _sliding(0.5)
    coated = replace(coated, sliding=False,
                     load=replace(coated.load, tangential_force=0.2 * 0.5 * coated.load.force))
    assert _codes(prepare(coated, SETTINGS).warnings) == ["partial_slip_path"]
    bare = replace(coated, coatings=())
    assert prepare(bare, SETTINGS).warnings == ()


def test_pressing_then_pulling_is_pulling_at_once_between_bodies_of_one_material():
    """With Dundurs' beta = 0 pressing makes no slip, so the load path's answer is the
    one-step answer: measured within 1e-5 of the peak pressure (the two bodies' meshes
    differ, and pressing leaves slips of that order at the contact's edges); between
    unlike bodies it is not (the stick zone's trailing end moved by 0.025 b under a
    cylinder of 3 E on the 2D coating), and a run at once says so."""
    def pulled(coatings, path):
        scene = _sliding(0.5)
        load = replace(scene.load, tangential_force=0.5 * 0.5 * scene.load.force, path=path)
        return solve(replace(scene, sliding=False, coatings=coatings, load=load), SETTINGS)
    once, path = pulled((), "at_once"), pulled((), "pressed_first")
    scale = once.contact.sigma_n.abs().max()
    for column in ("sigma_n", "sigma_t"):
        np.testing.assert_allclose(path.contact[column], once.contact[column], rtol=0,
                                   atol=1e-4 * scale)
    assert path.summary["stamp_shift"] == pytest.approx(once.summary["stamp_shift"], rel=1e-4)
    assert path.summary["load_steps"][0]["iterations"] > 0
    # unlike bodies: warned at once, not on the path (the loop against the monolithic
    # solve's two steps there: test_monolithic_partial_slip.py)
    from orchestrate.run.plan import prepare
    coated = _sliding(0.5)
    load = replace(coated.load, tangential_force=0.25 * coated.load.force)
    for path_name, codes in (("at_once", ["partial_slip_path"]), ("pressed_first", [])):
        scene = replace(coated, sliding=False, load=replace(load, path=path_name))
        assert _codes(prepare(scene, SETTINGS).warnings) == codes


def test_a_given_shift_is_the_force_it_carries_and_beyond_the_stick_limit_sliding():
    """Displacement control along x1 (load.tangential_displacement) against the two
    other ways the solver has: the shift the tangential force Q = mu P / 2 needs gives
    back Q (to 1e-9 mu P) and its traction (measured 2e-9 of the peak pressure; the
    force control solves a 2x2 system for the descent and the shift, this one gives the
    shift); three times that shift slips everywhere, and the answer is full sliding's
    (the sliding law, not the stick and slip states: measured 5e-9)."""
    scene = replace(_sliding(0.5), coatings=())
    mu_p = 0.5 * scene.load.force

    def loaded(**tangential):
        return solve(replace(scene, sliding=False,
                             load=replace(scene.load, **tangential)), SETTINGS)
    pulled = loaded(tangential_force=0.5 * mu_p)
    shift = pulled.summary["stamp_shift"]
    assert shift > 0

    given = loaded(tangential_displacement=shift)
    scale = pulled.contact.sigma_n.abs().max()
    assert given.summary["tangential_force"] == pytest.approx(0.5 * mu_p, rel=1e-9)
    assert given.summary["stamp_shift"] == shift
    np.testing.assert_allclose(given.contact.sigma_t, pulled.contact.sigma_t, rtol=0,
                               atol=1e-7 * scale)
    np.testing.assert_allclose(given.summary["stick_zones"], pulled.summary["stick_zones"],
                               rtol=0, atol=1e-6)
    sliding, beyond = solve(scene, SETTINGS), loaded(tangential_displacement=3 * shift)
    assert beyond.summary["stick_zones"] == []
    assert beyond.summary["tangential_force"] == pytest.approx(mu_p, rel=1e-8)
    for column in ("sigma_n", "sigma_t"):
        np.testing.assert_allclose(beyond.contact[column], sliding.contact[column], rtol=0,
                                   atol=1e-7 * scale)


def test_the_fretting_example_converges_to_the_monolithic_answer():
    """orchestrate/scenes/fretting_mm.toml (pressed, pulled to 200 N/mm, turned to
    -100 N/mm): an edge point of its pull flipped for ever between sticking, with a
    tension that released it, and released, penetrating; the run stagnated. Kept in
    contact and slipping at such a cycle (robin.slipping_at_flips) it converges to the
    monolithic solve's answer of the same path: the stamp's shift -0.0071678422659 mm and
    descent 0.0231861763602 mm (computed once with orchestrate/run/monolithic.py's
    monolithic_solution at eps_u 1e-8, 11 Newton solves over the three steps, on the mesh
    whose far elements are the contact range's reach over FAR_ELEMENTS; the loop at that
    tolerance agreed to 3e-12)."""
    scene, settings = load_scene(SCENES_DIR / "fretting_mm.toml")
    summary = solve(scene, settings).summary
    assert summary["converged"]
    assert summary["stamp_shift"] == pytest.approx(-0.0071678422659, rel=1e-6)
    assert summary["descent"] == pytest.approx(0.0231861763602, rel=1e-6)
    assert [step["tangential_force"] for step in summary["load_steps"]] == pytest.approx(
        [0.0, 200.0], abs=1e-6)
