"""The active-set loop leaves a predicted contact set only on an iterate it knows well
enough, and updates a set whose points would return to where they were only on a
tighter tolerance (orchestrate/ddm/robin.py, _ActiveSetLoop).

A rigid sphere on a soft layer two contact radii thick (E2 = E3 / 10) over a cylinder
ten radii wide: the Robin iterations through the thick soft layer are slow, so an
iterate's change is small while it is still far from its set's answer. Updated on the
change alone, the predicted set (right from the start) was left for wrong ones: the set
shrank to 3 points, grew to over a hundred and came back in about fifteen updates
(451 iterations, measured). Gated on the displacements' estimated error too, the run keeps
the predicted set (53 iterations, measured)."""

from dataclasses import replace

import pytest

import orchestrate
from orchestrate.model.scene import Base, Coating, Indenter, Load, Scene, Settings
from orchestrate.model.scene_file import SCENES_DIR, load_scene, scene_and_settings

pytestmark = pytest.mark.slow       # not in the everyday subset (make test-fast)


def test_a_slow_map_does_not_lead_the_loop_away_from_the_predicted_set():
    size = 10.0
    scene = Scene(indenter=Indenter(radius=50.0, profile="parabola", width=size, height=size,
                                    rigid=True),
                  base=Base(width=size, height=size, E=1.0, nu=0.3),
                  coatings=(Coating(start=0.0, end=size, thickness=2.0, E=0.1, nu=0.3,
                                    model="elastic"),),
                  load=Load(force=0.003064), axisymmetric=True)   # a contact radius of ~1
    summary = orchestrate.solve(scene, Settings(inner_solve="iterate")).summary
    assert summary["converged"]
    assert summary["active_set_changes"] == 0
    assert summary["iterations"] < 100


@pytest.fixture(scope="module")
def pads():
    """The gallery's pads on one level as auto solves them, under their force and under
    the descent that force takes; and on two levels, the coarse level taking the face's
    elements for the pads' narrow cells (coarse.coarse_problem)."""
    scene, settings = load_scene(SCENES_DIR / "gallery" / "patches_and_bare_base.toml")
    one_level = orchestrate.solve(scene, settings).summary
    pressed = replace(scene, load=replace(scene.load, force=None,
                                          displacement=one_level["descent"]))
    return (scene, one_level,
            orchestrate.solve(scene, {**settings, "inner_solve": "two-level"}).summary,
            orchestrate.solve(pressed, settings).summary)


def test_a_zone_that_barely_touches_does_not_walk_the_contact_set(pads):
    """The gallery's pads: a cylinder across 1 um pads, touching the middle pad, the bare
    steel beside it and the next pad's edge, which it barely reaches. On inexact iterates
    that edge's points entered and left together, update after update: 28 set changes and
    221 iterations (measured). An update that would return a point to the state an earlier
    one took it from waits for a tolerance ten times tighter: 9 and 141 (measured). Under
    a force the first set is now the answer's (test below); under the descent that force
    takes the set is still walked from the points within the a priori half-width: 10 set
    changes with the wait, 16 without (measured, mesh level 1, one level as auto solves
    it)."""
    scene, forced, _, pressed = pads
    assert pressed["converged"] and pressed["inner_solve_used"] == "iterate"
    assert pressed["total_force"] == pytest.approx(scene.load.force, rel=1e-6)
    assert pressed["active_set_changes"] <= 12 and pressed["iterations"] < 100
    for summary in (forced, pressed):
        forces = {name: interface["force"] for name, interface in summary["interfaces"].items()}
        assert forces["contact-base1"] > 0.01 * forces["contact-coating1"]    # the bare steel
        assert forces["contact-coating2"] > 0.0                                # the next pad


def test_a_force_across_pads_and_bare_steel_starts_from_the_answers_contact_set(pads):
    """Under a force, the first set of a contact that spans several faces is the
    half-planes' contact across their actual gap (first_contact.profile_contact): the pads' answer
    has 73 points, the middle pad's 35, 9 in the middle of the bare steel beside it and 29
    of the next pad's; drawn to the layered contact's half-width the first set had 66 and
    the loop walked 5 set changes, 64 iterations (measured); now none."""
    scene, forced, _, _ = pads
    assert forced["converged"] and forced["inner_solve_used"] == "iterate"
    assert forced["total_force"] == pytest.approx(scene.load.force, rel=1e-6)
    assert forced["active_set_changes"] == 0


def test_two_levels_on_narrow_coating_cells_give_the_one_level_answer(pads):
    """Two levels on the pads, the coarse level's cells the face's elements where the
    fine level narrows them at the pads' ends: the one-level loop's answer, each run
    within eps_u = 1e-6 of the same fixed point (make gallery checks auto's against the
    monolithic solve: 1e-9 apart)."""
    _, one_level, two_levels, _ = pads
    assert two_levels["converged"] and two_levels["inner_solve_used"] == "two-level"
    answers = [(run["peak_contact_stress"], run["descent"],
                *[interface["force"] for interface in run["interfaces"].values()],
                *[interface["peak_normal_stress"] for interface in run["interfaces"].values()])
               for run in (one_level, two_levels)]
    scale = max(abs(value) for value in answers[0])
    for a, b in zip(*answers):
        assert b == pytest.approx(a, rel=2e-6, abs=2e-6 * scale)


def test_a_contact_zipping_open_is_not_held_to_the_tighter_tolerance():
    """A steel cylinder across 5 um copper pads on PEEK: the first sets' edge points return,
    then the contact opens a point an update. Held to the tighter tolerance for every
    update after a return, each of those took some 16 iterations: 400 in all (measured;
    94 without the wait). Held until an update returns no point: 157 (measured)."""
    copper_on_peek = {"base.E": "3.6 GPa", "base.nu": 0.4, "load.force": "20 N/mm"}
    for n in (1, 2, 3):
        copper_on_peek.update({f"coating[{n}].thickness": "5 um", f"coating[{n}].E": "120 GPa"})
    scene, settings = scene_and_settings(SCENES_DIR / "gallery" / "patches_and_bare_base.toml",
                                         copper_on_peek)
    summary = orchestrate.solve(scene, replace(settings, inner_solve="iterate")).summary
    assert summary["converged"] and summary["iterations"] < 200


@pytest.mark.parametrize("overrides, changes", [({"symmetric": False}, 1),
                                                ({"indenter.rigid": True}, 1),
                                                ({"load.force": "3000 N/mm"}, 3)],
                         ids=["full model", "rigid", "five times the force"])
def test_the_pads_first_set_across_their_gap_holds_beyond_the_gallery_scene(overrides,
                                                                            changes):
    """The pads as a user varies them: the whole model, a rigid cylinder, five times the
    force. The first set drawn across the faces' gap took 0, 0 and 2 set changes
    (measured; bounded here one above), against 4, 2 and 9 from the layered contact's
    half-width (60, 15 and 81 iterations against 26, 6 and 30)."""
    path = SCENES_DIR / "gallery" / "patches_and_bare_base.toml"
    summary = orchestrate.solve(path, {}, overrides=overrides).summary
    scene, _ = scene_and_settings(path, overrides)
    assert summary["converged"]
    assert summary["total_force"] == pytest.approx(scene.load.force, rel=1e-6)
    assert summary["active_set_changes"] <= changes
