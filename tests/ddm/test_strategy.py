"""The strategy a run is solved by (orchestrate/ddm/strategy.py) and its knobs (Settings).

- Every knob is a setting: its default is the constant it replaced (so every answer and
  iteration count stays), a value out of its range is refused naming it, and it is a
  flag, a scene file's and a sweep's key and an API setting.
- The strategy is decided once, before any work (run/plan.py's prepare): the loop, the
  inner solve planned, theta and gamma resolved (equal to Settings.theta and
  Settings.robin_parameter), the coarse level; a run records it in summary.json, with
  the inner solve auto decided once the workers started.
- The loop reads its numbers from the strategy: changed, a knob changes what it should.
  The fast tests drive the loop with springs standing in for the workers (each side a
  bed of springs coupled to its neighbours, so that the fixed-point map has the spread
  of eigenvalues that makes Anderson's depth matter); the slow ones run FreeFEM.
"""

import json
import math
from dataclasses import fields, replace

import numpy as np
import pytest

import orchestrate
from orchestrate.cli import build_parser, main
from orchestrate.ddm.robin import ConvergenceMonitor, run_robin_loop
from orchestrate.ddm.robin_parameters import (CONTACT_SPLIT_BALANCED_UNDER_CONTRAST,
                                              CONTACT_SPLIT_UNDER_CONTRAST)
from orchestrate.ddm.strategy import (COATED_BASE, DIRECT, DIRECT_OR_ITERATE, ITERATE,
                                      NO_INNER_SOLVE, TWO_LEVEL, LoopKnobs)
from orchestrate.errors import ParameterError
from orchestrate.model.estimate import contact_half_width
from orchestrate.model.scene import KNOB_RANGES, Settings
from orchestrate.model.scene_file import SCENES_DIR, paper_scene, scene_and_settings
from orchestrate.run.plan import prepare
from orchestrate.run.solve import solve
from orchestrate.sweeps.sweep_file import point_scene
from tests.model.test_scene import PIN_EPS_U, PIN_THETA, PINNED

# The values the loop, the coarse level and auto used before they were settings (module
# constants of model/scene.py, ddm/robin.py, ddm/acceleration.py, ddm/coarse.py and
# workers/subdomains.py): the knobs' defaults, which every pinned number was computed with.
REPLACED_CONSTANTS = {
    "theta_per_length": 4e-3,
    "robin_one_level": 8.0,         # 2.0 until the meshes were sized to the contact
    "robin_two_level_per_length": 4.0,
    "auto_direct_unknowns": 250,
    "auto_two_level_mesh_level": 2,
    "active_set_tolerance": 1e-2,
    "predicted_set_tolerance": 1e-3,
    "estimate_margin": 5.0,
    "min_secants": 3,
    "traction_floor": 1e-6,
    "component_floor": 1e-3,
    "divergence_growth": 1e3,
    "stagnation_progress": 0.1,
    "stagnation_window": 200,
    "paper_stagnation_window": 500,
    "paper_contraction_window": 10,
    "paper_amplification_window": 50,
    "anderson_depth": 100,
    "anderson_filter": 1e-8,        # 1e-10 until the bonds went inside the base's worker:
                                    # its residual, on the contacts alone, made secants
                                    # between the two dependent enough to blow a step up
                                    # (gamma 0.01 E/b diverged; the gallery's iterations
                                    # are the same)
    "anderson_first_relaxation": 1.0,
    "coarse_element_factor": 2.0,
    "coarse_newton_steps": 50,
}
# (robin_one_level: 8 E/b took 20-50 % fewer iterations than 2 on the gallery's meshes,
# sized to the contact and finer than the figures' b/16, whose scenes the maps solve
# directly: docs/method.md.)
# Knobs added since: hold_contrast 4, a side holds its inactive points only on a body
# at least 4 times as stiff as its neighbour (the figures' scenes, solved directly,
# hold every side as before). contact_split 256: a frictionless contact's sides split
# about the neighbour rule on one level, nearly a Neumann and a Dirichlet side
# (robin_parameters.py; 4 when first added; the figures' scenes, solved directly, keep
# the rule's gamma). bond_split 16: a bond's split widened to its limit (4 when added).
ADDED_KNOBS = {"hold_contrast": 4.0, "auto_fallback_work": 5e8, "contact_split": 256.0,
               "bond_split": 16.0}
INTEGER_KNOBS = [key for key, value in REPLACED_CONSTANTS.items() if isinstance(value, int)]


# ---- the knobs as settings --------------------------------------------------------------

def test_the_knobs_default_to_the_constants_they_replaced():
    assert set(REPLACED_CONSTANTS) | set(ADDED_KNOBS) == set(KNOB_RANGES)
    settings = Settings()
    for key, value in {**REPLACED_CONSTANTS, **ADDED_KNOBS}.items():
        assert getattr(settings, key) == value and type(getattr(settings, key)) is type(value), key


def _out_of_range(key):
    low, high = KNOB_RANGES[key][:2]
    values = [low - max(abs(low), 1), high * 2 + 1, "many", True, None, math.nan]
    if key in INTEGER_KNOBS:
        values.append(low + 0.5)
    else:
        values.append(math.inf)
    return values


@pytest.mark.parametrize("key, value", [(key, value) for key in KNOB_RANGES
                                        for value in _out_of_range(key)])
def test_a_knob_out_of_range_is_refused_naming_it(key, value):
    with pytest.raises(ParameterError) as refused:
        Settings(**{key: value})
    assert refused.value.key == key and str(refused.value).startswith(f"{key} = ")


# each end accepted; the secant pairs the stopping test waits for fit the history kept
COMPANIONS = {("min_secants", 1000): {"anderson_depth": 1000},
              ("anderson_depth", 1): {"min_secants": 1},
              ("paper_amplification_window", 1): {"min_secants": 1}}


@pytest.mark.parametrize("key, value", [(key, end) for key in KNOB_RANGES
                                        for end in KNOB_RANGES[key][:2]])
def test_a_knob_at_an_end_of_its_range_is_accepted(key, value):
    settings = Settings(**{key: value, **COMPANIONS.get((key, value), {})})
    assert getattr(settings, key) == value


def test_more_secant_pairs_than_the_history_keeps_are_refused():
    with pytest.raises(ParameterError, match="min_secants = 3 must be at most anderson_depth"):
        Settings(anderson_depth=2)
    with pytest.raises(ParameterError, match="at most paper_amplification_window = 4") as refused:
        Settings(method="paper", min_secants=5, paper_amplification_window=4)
    assert refused.value.key == "min_secants"
    assert Settings(method="paper", anderson_depth=2, min_secants=1).anderson_depth == 2


def test_a_default_gamma_beyond_robins_range_is_refused_naming_its_knob():
    """With two levels the default gamma is robin_two_level_per_length over the element
    length, and the coarse level is given it as its robin."""
    with pytest.raises(ParameterError) as refused:
        Settings(mesh_level=2, robin_two_level_per_length=100.0)
    assert refused.value.key == "robin_two_level_per_length" and "1600" in str(refused.value)
    assert Settings(mesh_level=2, robin_two_level_per_length=100.0, robin=8.0).robin == 8.0


def test_every_knob_is_a_flag_a_scene_files_and_a_sweeps_key(tmp_path):
    values = {key: KNOB_RANGES[key][0] for key in KNOB_RANGES}
    values.update(min_secants=1)                     # within the history of depth 1
    options = [f"--{key.replace('_', '-')}={value}" for key, value in values.items()]
    arguments = build_parser().parse_args(["solve", "--out", str(tmp_path / "run"), *options])
    scene_file = tmp_path / "scene.toml"
    scene_file.write_text((SCENES_DIR / "paper.toml").read_text() + "\n[settings]\n"
                          + "".join(f"{key} = {value!r}\n" for key, value in values.items()))
    from_file = scene_and_settings(scene_file)[1]
    from_sweep = point_scene(values)[1]
    for key, value in values.items():
        assert getattr(arguments, key) == value, key
        assert getattr(from_file, key) == value == getattr(from_sweep, key), key


def test_a_knob_out_of_range_is_refused_by_the_command_line_and_the_api(tmp_path, capsys):
    status = main(["solve", "--out", str(tmp_path / "run"), "--estimate-margin", "0.5"])
    assert status == 2 and "estimate_margin = 0.5 must be" in capsys.readouterr().err
    with pytest.raises(ParameterError) as refused:
        orchestrate.solve(paper_scene(), {"anderson_depth": 0})
    assert refused.value.key == "anderson_depth"
    scene_file = tmp_path / "scene.toml"
    scene_file.write_text((SCENES_DIR / "paper.toml").read_text()
                          + "\n[settings]\ncoarse_newton_steps = 0\n")
    with pytest.raises(ParameterError, match=f"{scene_file}: settings.coarse_newton_steps"):
        scene_and_settings(scene_file)


# ---- the strategy decided once ------------------------------------------------------------

@pytest.mark.parametrize("values, planned, gamma, coarse_element", [
    ({}, DIRECT_OR_ITERATE, 8.0, None),
    ({"inner_solve": "direct"}, DIRECT, 8.0, None),
    ({"inner_solve": "iterate", "robin_one_level": 3.0}, ITERATE, 3.0, None),
    ({"workers": "fresh"}, ITERATE, 8.0, None),
    ({"mesh_level": 2}, TWO_LEVEL, 64.0, 0.0625),
    ({"mesh_level": 2, "robin_two_level_per_length": 2.0}, TWO_LEVEL, 32.0, 0.0625),
    # with the bonds inside where the loop iterates (auto's choice, or asked): the maps of
    # each worker apart would not pay on the finer mesh, so auto iterates, the coating
    # inside the base's worker
    ({"mesh_level": 2, "auto_two_level_mesh_level": 3}, ITERATE, 8.0 * 2 ** 0.5, None),
    ({"mesh_level": 2, "auto_two_level_mesh_level": 3, "bonds": "exchanged"},
     DIRECT_OR_ITERATE, 8.0 * 2 ** 0.5, None),
    ({"mesh_level": 2, "auto_two_level_mesh_level": 3, "bonds": "inside"}, ITERATE,
     8.0 * 2 ** 0.5, None),
    ({"inner_solve": "iterate", "bonds": "inside"}, ITERATE, 8.0, None),
    ({"auto_two_level_mesh_level": 1}, TWO_LEVEL, 64.0, 0.125),
    ({"inner_solve": "two-level", "coarse_element_factor": 4.0}, TWO_LEVEL, 64.0, 0.25),
    ({"theta_per_length": 8e-3}, DIRECT_OR_ITERATE, 8.0, None),
    ({"robin": 5.0}, DIRECT_OR_ITERATE, 5.0, None),
])
def test_the_plan_resolves_the_strategy_from_the_settings(values, planned, gamma,
                                                          coarse_element):
    settings = Settings(**values)
    plan = prepare(paper_scene(), settings)
    strategy = plan.strategy
    assert strategy.loop == "active-set"
    # the paper's bodies are equal: every contact side has the run's gamma, and so has
    # every bond side where each set is solved directly or under a coarse level;
    # iterated on one level, a bond's gamma is split by the coating's Dirichlet-to-Neumann
    # response against the base's at the contact's wavenumber (robin_parameters.
    # bond_ratio); iterated on one level it releases its inactive points, under a coarse
    # level it holds them
    assert len(strategy.sides) == 2 * len(plan.problem.interfaces)
    gamma_run = strategy.gamma.solver_value
    scene = plan.problem.scene
    coating, a = scene.coatings[0], contact_half_width(scene)
    ratio = (scene.base.E / (1 - scene.base.nu ** 2)) / (
        coating.E / (1 - coating.nu ** 2) * min(1.0, math.pi * coating.thickness / a))
    one_level = planned not in (DIRECT, TWO_LEVEL)
    # and further by bond_split 16 (frictionless), to 16 at the most
    split = min(16.0 * math.sqrt(min(max(ratio, 1.0), 256.0)), 16.0) if one_level else 1.0
    assert not one_level or ratio > 1    # the paper's coating is thin
    # a contact's sides split by 256 about gamma on one level, the indenter's the smaller:
    # the bodies are equal (Settings.contact_split); no side above 1/theta
    contact_split = 256.0 if one_level else 1.0
    for side in strategy.sides:
        bond = side.interface.startswith("bond")
        expected = min(gamma_run * ((split if side.side == 0 else 1 / split) if bond else
                                    (1 / contact_split if side.side == 0 else contact_split)),
                       1.0 / plan.problem.penalty)
        assert side.gamma == pytest.approx(expected, rel=1e-12), side
        assert side.direct_gamma == gamma_run, side
        assert side.hold_inactive == (planned == TWO_LEVEL) and not side.stiff_neighbour
    # iterated on one level, the coating is solved inside the base's worker, asked
    # ("inside") or by default ("auto"), not with a fresh process per solve
    if planned == ITERATE and settings.bonds != "exchanged" and settings.workers != "fresh":
        assert strategy.sweep == (("indenter", COATED_BASE),)
        assert strategy.workers == (("indenter", ("indenter",)),
                                    (COATED_BASE, ("base", "coating1")))
        assert strategy.bonds_inside == (1,) and plan.problem.interfaces[1].kind == "bond"
    else:
        assert strategy.sweep == (("indenter", "base"), ("coating1",))
        assert strategy.bonds_inside == ()
    assert strategy.inner_solve.asked == settings.inner_solve
    assert strategy.inner_solve.planned == planned
    assert strategy.inner_solve.pending == (planned == DIRECT_OR_ITERATE)
    assert (strategy.inner_solve.decided_on is not None) == (
        settings.inner_solve == "auto" and planned == ITERATE and settings.workers != "fresh")
    assert strategy.inner_solve.fallback == (DIRECT if settings.inner_solve == "auto"
                                             and settings.workers == "persistent" else None)
    assert strategy.theta.value == settings.theta == plan.problem.penalty
    assert strategy.theta.value == pytest.approx(
        values.get("theta_per_length", 4e-3) * 0.0625 / settings.mesh_level, rel=1e-12)
    assert strategy.gamma.value == settings.robin_parameter == plan.problem.robin
    assert strategy.gamma.value == pytest.approx(gamma, rel=1e-12)
    assert strategy.theta.solver_value == strategy.theta.value
    assert strategy.gamma.solver_value == strategy.gamma.value
    assert strategy.knobs == LoopKnobs.of(settings)
    if coarse_element is None:
        assert strategy.coarse is None and plan.coarse is None
    else:
        assert strategy.coarse.mesh_level == 1
        assert strategy.coarse.element_size == pytest.approx(coarse_element, rel=1e-12)
        assert plan.coarse.robin == strategy.gamma.value
        assert plan.coarse.penalty == strategy.theta.value


def test_the_papers_loop_has_no_inner_solve_and_solves_every_subdomain_at_once():
    plan = prepare(paper_scene(), Settings(method="paper"))
    strategy = plan.strategy
    assert strategy.loop == "paper"
    assert all(side.gamma == pytest.approx(1e3) and not side.hold_inactive
               for side in strategy.sides)
    assert strategy.inner_solve.planned == NO_INNER_SOLVE and strategy.inner_solve.fallback is None
    assert strategy.sweep == (tuple(plan.problem.subdomains),)
    assert set(strategy.sweep[0]) == {"indenter", "base", "coating1"}
    assert strategy.theta.value == 1e-3 and strategy.gamma.value == pytest.approx(1e3)
    assert strategy.stagnation_window == Settings().paper_stagnation_window


def test_the_record_says_theta_and_gamma_in_the_scenes_units_too():
    """cylinder_mm.toml: b = 1 mm, E = 210 GPa; never a null for a default."""
    scene, settings = scene_and_settings(SCENES_DIR / "cylinder_mm.toml")
    plan = prepare(scene, settings)
    record = json.loads(json.dumps(plan.strategy.record(plan.scales, scene.units)))
    b, modulus = plan.scales.length, plan.scales.stress
    settings = plan.problem.settings            # the mesh sized to the contact, and theta
    assert settings.theta < Settings().theta    # with it (Settings.sized_to)
    assert record["theta"]["value"] == settings.theta and record["theta"]["unit"] == "b/E"
    assert record["theta"]["scene_value"] == pytest.approx(settings.theta * b / modulus)
    assert record["theta"]["scene_unit"] == "mm/MPa"
    assert record["gamma"]["value"] == settings.robin_parameter is not None
    assert record["gamma"]["scene_value"] == pytest.approx(settings.robin_parameter * modulus / b)
    assert record["gamma"]["scene_unit"] == "MPa/mm"
    assert record["gamma_theta"] == pytest.approx(settings.robin_parameter * settings.theta)
    assert record["knobs"] == {f.name: getattr(settings, f.name) for f in fields(LoopKnobs)}


def test_the_record_in_a_scene_whose_stiffer_body_is_not_of_modulus_one():
    """gallery/near_rigid_cylinder.toml is in b and E with the indenter's E = 1000: the
    scene's gamma is 1000 times the value in the stiffer body's E/b."""
    scene, settings = scene_and_settings(SCENES_DIR / "gallery" / "near_rigid_cylinder.toml")
    plan = prepare(scene, settings)
    record = json.loads(json.dumps(plan.strategy.record(plan.scales, scene.units)))
    assert record["gamma"]["scene_value"] == pytest.approx(1000.0 * settings.robin_parameter)
    assert record["theta"]["scene_value"] == pytest.approx(settings.theta / 1000.0)
    # the base's side of the contact: the indenter's coefficient, times the contact's
    # split (the scene iterates on one level; under the indenter's contrast at most 16
    # where the base carries the stamp's force, as under this force, else 4)
    assert record["force_balance"] == COATED_BASE
    assert max(side["scene_gamma"] for side in record["sides"]) == pytest.approx(
        CONTACT_SPLIT_BALANCED_UNDER_CONTRAST * record["gamma"]["scene_value"])
    off = prepare(scene, replace(settings, force_balance="off"))
    record = json.loads(json.dumps(off.strategy.record(off.scales, scene.units)))
    assert max(side["scene_gamma"] for side in record["sides"]) == pytest.approx(
        CONTACT_SPLIT_UNDER_CONTRAST * record["gamma"]["scene_value"])


def test_a_pending_inner_solve_is_recorded_once_decided():
    strategy = prepare(paper_scene(), Settings()).strategy
    weighed = {"auto_direct_unknowns": 250, "weighted_unknowns": {"base": 300.0}}
    decided = strategy.decided(False, weighed)
    assert not decided.inner_solve.pending and decided.inner_solve.decided == ITERATE
    assert decided.inner_solve.decided_on == weighed and strategy.inner_solve.pending
    assert decided.decided(True, {}) is decided          # decided once
    assert strategy.decided(True, {}).inner_solve.decided == DIRECT
    # a contact set solved directly is solved at once: no partner balanced then
    balanced = replace(strategy, force_balance="base")
    assert balanced.decided(True, {}).force_balance is None
    assert balanced.decided(False, {}).force_balance == "base"


# ---- the loop reads its knobs: springs for workers ----------------------------------------

SPRING_STIFFNESS = {"indenter": 1.0, "base": 1.5, "coating1": 3.0}   # E/b per point
SPRING_COUPLING = 30.0          # neighbouring points' springs against the ground's


def spring_solve(problem):
    """Workers of springs: every side a chain of points held by springs K (each to the
    ground and to its neighbours), the indenter's pushed by the stamp's descent; its
    Robin solve is (alpha + K) u = alpha g + K descent."""
    descent = problem.scene.load.displacement

    def solve(data, names):
        traces = {}
        for name in names:
            load = descent if problem.subdomains[name].stamp else 0.0
            for i, side in problem.sides_of(name):
                alpha, g = data[i, side]
                n = problem.interfaces[i].size
                chain = 2 * np.eye(n) - np.eye(n, k=1) - np.eye(n, k=-1)
                K = SPRING_STIFFNESS[name] * (np.eye(n) + SPRING_COUPLING * chain)
                traces[i, side] = np.linalg.solve(np.diag(alpha) + K,
                                                  (alpha * g + K.sum(axis=1) * load).T).T
        seconds = {"wait": 0.0, **{key + name: 0.0 for name in names for key in ("", "back_")}}
        return traces, seconds, descent if "indenter" in names else None
    return solve


def spring_loop(solve=spring_solve, **values):
    """The active-set loop iterated on the paper's scene with springs for workers."""
    # the springs' stiffness is of the order of the figures' gamma, 2 E/b; they are each
    # subdomain's own worker; the sides split by 4 (the split these knobs' effects were
    # measured at: split far, the springs' exchange converges in a few iterations, too
    # few for a short Anderson history or a divergence test to tell apart)
    plan = prepare(paper_scene(), Settings(inner_solve="iterate", bonds="exchanged",
                                           **{"robin_one_level": 2.0, "contact_split": 4.0,
                                              "bond_split": 4.0, **values}))
    return run_robin_loop(solve(plan.problem), plan.problem, plan.strategy)


def _final_set(loop):
    """Iterations of the loop's last contact set."""
    updates = [row["active_set_update"] for row in loop.history]
    return updates.count(updates[-1])


def test_a_smaller_anderson_depth_takes_more_iterations_to_the_same_answer():
    deep, shallow = spring_loop(), spring_loop(anderson_depth=3)
    assert deep.converged and shallow.converged
    assert shallow.iterations > 1.5 * deep.iterations
    assert shallow.history[-1]["contact_force"] == pytest.approx(
        deep.history[-1]["contact_force"], rel=1e-5)


def test_a_larger_estimate_margin_stops_later_with_a_smaller_error():
    plain, careful = spring_loop(), spring_loop(estimate_margin=50.0)
    assert plain.converged and careful.converged
    assert careful.iterations > plain.iterations
    # the estimate is 10 times as large for the same iterates: where the plain loop
    # stopped, the careful one would not have
    assert 10 * plain.error_estimate > careful.error_estimate


def test_the_final_contact_set_waits_for_min_secants_pairs():
    loop = spring_loop(min_secants=80)
    assert loop.converged and _final_set(loop) >= 80 + 1 > _final_set(spring_loop())


def test_a_tighter_active_set_tolerance_spends_more_iterations_on_each_contact_set():
    assert spring_loop(active_set_tolerance=1e-5).iterations > spring_loop().iterations


def test_the_loop_stops_at_its_iteration_limit():
    loop = spring_loop(max_iterations=5)
    assert loop.status == "max_iterations" and loop.iterations == 5


def growing_solve(problem):
    """Workers whose every answer doubles: the loop diverges."""
    calls = []

    def solve(data, names):
        calls.append(names)
        traces, seconds, descent = spring_solve(problem)(data, names)
        return ({key: trace * 2.0 ** len(calls) for key, trace in traces.items()}, seconds,
                descent)
    return solve


def test_a_smaller_divergence_growth_stops_a_diverging_loop_sooner():
    early, late = (spring_loop(growing_solve, divergence_growth=growth) for growth in (10.0, 1e3))
    assert early.status == late.status == "diverged"
    assert early.iterations < late.iterations


def test_the_monitor_counts_progress_by_stagnation_progress():
    changes = [1.0, 0.8, 0.7, 0.65, 0.6, 0.58]
    outcomes = {}
    for progress in (0.1, 0.5):
        monitor = ConvergenceMonitor(1000, 1.0, window=3, progress=progress)
        outcomes[progress] = [monitor.check(k, np.zeros(1), change)
                              for k, change in enumerate(changes, start=1)]
    assert all(outcome is None for outcome in outcomes[0.1])
    assert outcomes[0.5][3][0] == "stagnated"


# ---- runs: the strategy recorded, the defaults' numbers, knobs that change them --------------

@pytest.mark.slow
def test_a_run_records_its_strategy_resolved(tmp_path):
    settings = Settings()
    summary = solve(paper_scene(), settings, tmp_path / "run")
    strategy = summary["strategy"]
    assert summary["settings"]["robin"] is None              # given: none
    assert strategy["gamma"]["value"] == settings.robin_parameter == 8.0
    assert strategy["theta"]["value"] == settings.theta == summary["settings"]["theta"]
    assert strategy["inner_solve"]["planned"] == DIRECT_OR_ITERATE
    assert strategy["inner_solve"]["decided"] == DIRECT == summary["inner_solve_used"]
    weighed = strategy["inner_solve"]["decided_on"]
    assert set(weighed["weighted_unknowns"]) == {"indenter", "base", "coating1"}
    assert max(weighed["weighted_unknowns"].values()) <= weighed["auto_direct_unknowns"]
    assert strategy["knobs"] == {f.name: getattr(settings, f.name) for f in fields(LoopKnobs)}
    written = json.loads((tmp_path / "run" / "summary.json").read_text())
    assert written["strategy"] == strategy


@pytest.mark.slow
def test_the_defaults_reproduce_the_pinned_default_scene(tmp_path):
    """tests/model/test_scene.py's pins, with every knob at its default and with every
    knob given the constant it replaced: the same numbers, the same iterations."""
    pinned = {"theta": PIN_THETA, "inner_solve": "iterate", "eps_u": PIN_EPS_U}
    defaults = solve(paper_scene(), Settings(**pinned), tmp_path / "defaults")
    given = solve(paper_scene(), Settings(**pinned, **REPLACED_CONSTANTS), tmp_path / "given")
    for name, value in PINNED.items():
        assert defaults[name] == pytest.approx(value, rel=1e-8), name
        assert given[name] == pytest.approx(value, rel=1e-8), name
    assert given["iterations"] == defaults["iterations"]
    assert given["strategy"] == defaults["strategy"]


@pytest.mark.slow
def test_smaller_anderson_depth_and_larger_margin_iterate_longer_to_the_same_answer(tmp_path):
    runs = {name: solve(paper_scene(), Settings(inner_solve="iterate", **values),
                        tmp_path / name)
            for name, values in {"default": {}, "shallow": {"anderson_depth": 5},
                                 "careful": {"estimate_margin": 50.0}}.items()}
    for name in ("shallow", "careful"):
        assert runs[name]["iterations"] > runs["default"]["iterations"], name
        assert runs[name]["peak_contact_stress"] == pytest.approx(
            runs["default"]["peak_contact_stress"], rel=1e-5), name
    assert runs["shallow"]["strategy"]["knobs"]["anderson_depth"] == 5


@pytest.mark.slow
def test_auto_decides_to_iterate_where_no_map_pays(tmp_path):
    """Decided before the workers start (the maps of each worker apart would not pay), with
    the coating inside the base's worker; or, with the bonds exchanged, once they
    started."""
    for bonds in ("inside", "exchanged", "auto"):     # auto: inside, where it iterates
        summary = solve(paper_scene(), Settings(auto_direct_unknowns=0, bonds=bonds),
                        tmp_path / bonds)
        inner_solve = summary["strategy"]["inner_solve"]
        assert inner_solve["decided"] == ITERATE == summary["inner_solve_used"]
        assert inner_solve["decided_on"]["auto_direct_unknowns"] == 0
        assert inner_solve["decided_on"].get("estimated", False) == (bonds != "exchanged")
        assert (summary["strategy"]["bonds_inside"] == [1]) == (bonds != "exchanged")


@pytest.mark.slow
def test_a_coarser_coarse_level_gives_the_same_answer(tmp_path):
    """Two levels on the paper's mesh, the coarse interface elements four times as long
    instead of twice."""
    twice = solve(paper_scene(), Settings(inner_solve="two-level"), tmp_path / "twice")
    four = solve(paper_scene(), Settings(inner_solve="two-level", coarse_element_factor=4.0),
                 tmp_path / "four")
    assert four["inner_solve_used"] == twice["inner_solve_used"] == TWO_LEVEL
    assert four["strategy"]["coarse"]["element_size"] == 0.25
    assert twice["strategy"]["coarse"]["element_size"] == 0.125
    assert four["peak_contact_stress"] == pytest.approx(twice["peak_contact_stress"], rel=1e-5)


def test_the_first_contact_set_is_the_predicted_one():
    """Strategy.first_contact: under a force on a coating, the contact of the coating as
    a layer on the base (estimate.first_contact_half_width: a stiff coating's, narrower
    than the base's Hertz); under a descent, the a priori half-width (from the force the
    descent takes); the paper's loop takes none. The first set is the contact points
    within it; under a descent it is narrower than the overlap the descent makes (the
    answer's half-width is about that over sqrt(2))."""
    from orchestrate.ddm.first_contact import predicted_contact
    from orchestrate.ddm.robin import first_contact_set
    from orchestrate.ddm.state import StateLayout
    from orchestrate.model.estimate import contact_half_width, first_contact_half_width
    scene, settings = scene_and_settings(SCENES_DIR / "gallery" / "near_rigid_cylinder.toml")
    plan = prepare(scene, settings)
    a = first_contact_half_width(plan.problem.scene, contact_half_width(plan.problem.scene))
    assert plan.strategy.first_contact == pytest.approx(a)
    assert a < 0.85 * contact_half_width(plan.problem.scene)
    layout = StateLayout(plan.problem.interfaces)
    predicted = predicted_contact(plan.problem, layout, plan.strategy.first_contact)
    psi = first_contact_set(plan.problem.scene, layout, layout.zeros(), predicted=predicted)
    x1 = np.concatenate([plan.problem.interfaces[i].position[:, 0]
                         for i in layout.contact_indices])
    assert np.array_equal(psi > 0, x1 <= a) and 5 < psi.sum() < len(psi)
    touched = first_contact_set(plan.problem.scene, layout, layout.zeros())
    assert touched.sum() == 1
    paper = prepare(paper_scene(), Settings())
    a = contact_half_width(paper.problem.scene)
    assert paper.strategy.first_contact == pytest.approx(a)
    overlap = math.sqrt(2.0 * paper.problem.scene.indenter.radius
                        * paper.problem.scene.load.displacement)
    assert 1.2 < overlap / a < 1.6
    assert prepare(paper_scene(), Settings(method="paper")).strategy.first_contact is None


def test_two_levels_take_the_coatings_inside_only_where_asked():
    """Asked, two levels model the base's worker with its coatings from its parts' maps
    (coarse.py); under auto's contrast, where one level takes them inside, two levels
    keep them exchanged (with one worker the rigid cylinder took 366 iterations at mesh
    level 2 against 212)."""
    scene, _ = scene_and_settings(SCENES_DIR / "gallery" / "near_rigid_cylinder.toml")
    asked = prepare(scene, Settings(mesh_level=2, inner_solve="two-level", bonds="inside"))
    assert asked.strategy.inner_solve.planned == TWO_LEVEL
    assert asked.strategy.bonds_inside and dict(asked.strategy.workers)[COATED_BASE]
    assert asked.strategy.sweep == (("indenter", COATED_BASE),)
    by_auto = prepare(scene, Settings(mesh_level=2, inner_solve="two-level"))
    assert by_auto.strategy.inner_solve.planned == TWO_LEVEL
    assert by_auto.strategy.bonds_inside == ()
    assert COATED_BASE not in dict(by_auto.strategy.workers)


def test_auto_leaves_the_coarse_level_out_under_contrast():
    """At mesh level 2 auto takes two levels, which hold every side; where a side
    releases its inactive points (the near-rigid cylinder: its base's side under a
    neighbour 1000 times as stiff) it iterates on one level with its gamma instead."""
    scene, _ = scene_and_settings(SCENES_DIR / "gallery" / "near_rigid_cylinder.toml")
    plan = prepare(scene, Settings(mesh_level=2))
    # its maps would not pay, and under the contrast auto takes the coating inside; not
    # with a fresh process per solve, nor below the tolerance it reaches
    assert plan.strategy.inner_solve.planned == ITERATE and plan.strategy.bonds_inside
    for values in ({"workers": "fresh"}, {"eps_u": 1e-9}, {"bonds": "exchanged"}):
        assert not prepare(scene, Settings(mesh_level=2, **values)).strategy.bonds_inside
    assert "no coarse level" in plan.strategy.inner_solve.rule
    assert plan.strategy.gamma.value == pytest.approx(Settings().robin_one_level * 2 ** 0.5)
    assert plan.coarse is None
    assert not plan.problem.settings.two_levels
    assert any(not side.hold_inactive for side in plan.strategy.sides)
    equal = prepare(paper_scene(), Settings(mesh_level=2)).strategy
    assert equal.inner_solve.planned == TWO_LEVEL
    asked = prepare(scene, Settings(mesh_level=2, inner_solve="two-level")).strategy
    assert asked.inner_solve.planned == TWO_LEVEL          # asked, it is kept


def test_auto_takes_the_bonds_inside_only_down_to_the_tolerance_it_reaches_there():
    """With the bond's penalty in the base's matrix, the near-rigid cylinder's loop at
    eps_u = 1e-8 stagnated, its estimate stuck near 1.7e-8, while exchanged it reached
    9e-9 (measured): auto takes the bonds inside down to 1e-7, asked down to 1e-8."""
    scene, _ = scene_and_settings(SCENES_DIR / "gallery" / "near_rigid_cylinder.toml")
    inside = {eps_u: bool(prepare(scene, Settings(eps_u=eps_u)).strategy.bonds_inside)
              for eps_u in (1e-7, 5e-8)}
    assert inside == {1e-7: True, 5e-8: False}
    asked = {eps_u: bool(prepare(scene, Settings(eps_u=eps_u, bonds="inside"))
                         .strategy.bonds_inside) for eps_u in (1e-8, 5e-9)}
    assert asked == {1e-8: True, 5e-9: False}


def test_auto_leaves_the_coarse_level_out_where_its_maps_would_not_pay():
    """At mesh level 2 auto takes two levels only where probing the coarse level's maps
    would pay by the measure it applies to a direct solve (auto_direct_unknowns): the
    paper's scene, not the gallery's large coated bodies (one level, with its split
    sides, took half the time: the coated roller 3.3 s against 6.8 s)."""
    assert prepare(paper_scene(), Settings(mesh_level=2)).strategy.two_levels
    for name in ("coated_roller", "tin_on_steel", "thick_ceramic_on_steel",
                 "steel_on_anodised_aluminium"):
        scene, _ = scene_and_settings(SCENES_DIR / "gallery" / f"{name}.toml")
        plan = prepare(scene, Settings(mesh_level=2))
        assert not plan.strategy.two_levels and plan.coarse is None, name
        assert "the coarse level's maps would not pay" in plan.strategy.inner_solve.rule
        # its sides split, as on one level
        assert any(side.gamma != side.direct_gamma for side in plan.strategy.sides), name
        # asked, two levels are kept
        asked = prepare(scene, Settings(mesh_level=2, inner_solve="two-level")).strategy
        assert asked.inner_solve.planned == TWO_LEVEL, name
    # a larger auto_direct_unknowns makes the coarse maps pay
    scene, _ = scene_and_settings(SCENES_DIR / "gallery" / "tin_on_steel.toml")
    assert prepare(scene, Settings(mesh_level=2, auto_direct_unknowns=1000)).strategy.two_levels


def test_auto_leaves_the_coarse_level_out_where_the_first_set_spans_several_faces():
    """Where the first contact set is the half-planes' contact across several contact
    faces' gap (first_contact.profile_contact), auto iterates on one level: the gallery's pads
    and the discrete example's shell patches at mesh levels 2/3 answered faster so (pads
    6.3/16.1 s against 7.6/18.8 s, patches 1.5/3.6 s against 2.0/3.8 s, run/plan.py),
    though their coarse level's maps would pay; asked, two levels are kept."""
    for path in (SCENES_DIR / "discrete.toml",
                 SCENES_DIR / "gallery" / "patches_and_bare_base.toml"):
        scene, _ = scene_and_settings(path)
        plan = prepare(scene, Settings(mesh_level=2))
        assert not plan.strategy.two_levels and plan.coarse is None, path.name
        assert "across the faces' gap" in plan.strategy.inner_solve.rule
        asked = prepare(scene, Settings(mesh_level=2, inner_solve="two-level")).strategy
        assert asked.inner_solve.planned == TWO_LEVEL
    # one face under the contact: the paper's scene keeps its coarse level
    assert prepare(paper_scene(), Settings(mesh_level=2)).strategy.two_levels


def test_auto_takes_no_coarse_level_below_its_mesh_level():
    """On mesh level 1 every gallery scene is planned on one level (the pads too: with
    the contact's sides split far and the pads inside the base's worker, one level
    answers them in the time two took, run/plan.py), and the paper's scene is solved
    directly or iterated as its workers decide."""
    for path in sorted((SCENES_DIR / "gallery").glob("*.toml")):
        scene, settings = scene_and_settings(path)
        plan = prepare(scene, settings)
        assert plan.coarse is None and plan.strategy.inner_solve.planned != TWO_LEVEL, \
            path.stem
    assert prepare(paper_scene(), Settings()).strategy.inner_solve.planned == DIRECT_OR_ITERATE


def test_auto_leaves_the_coarse_level_out_under_a_soft_coating():
    """At mesh level 2 a coating more than hold_contrast times softer than its base (E*)
    iterates on one level: the gallery's polymer coating (E/100) took 128 iterations in
    its final contact set with two levels, 19 without. A coating of the base's modulus, or
    a stiffer one, keeps two levels; a contrast below hold_contrast too."""
    scene, _ = scene_and_settings(SCENES_DIR / "gallery" / "polymer_coating_on_steel.toml")
    plan = prepare(scene, Settings(mesh_level=2))
    assert plan.coarse is None and not plan.problem.settings.two_levels
    assert "a coating more than hold_contrast 4 times softer" in plan.strategy.inner_solve.rule
    for E2 in (0.3, 1.0, 5.0):
        assert prepare(paper_scene(E2=E2), Settings(mesh_level=2)).strategy.two_levels, E2
    assert not prepare(paper_scene(E2=0.2), Settings(mesh_level=2)).strategy.two_levels
    assert prepare(paper_scene(E2=0.2), Settings(mesh_level=2, hold_contrast=6)).strategy.two_levels
    asked = prepare(scene, Settings(mesh_level=2, inner_solve="two-level")).strategy
    assert asked.inner_solve.planned == TWO_LEVEL          # asked, it is kept


def _contact_gammas(scene_path, overrides=None, **values):
    """(indenter side, partner side) gammas of the first contact, over what the neighbour
    rule alone gives them (the run's gamma times the neighbour's E* over the stiffer
    body's)."""
    scene, _ = scene_and_settings(scene_path, overrides or {})
    plan = prepare(scene, Settings(inner_solve="iterate", **values))
    sides = [side for side in plan.strategy.sides if side.interface.startswith("contact")][:2]
    return tuple(side.gamma / side.direct_gamma for side in sides)


def test_a_contacts_sides_are_split_about_the_neighbour_rule():
    """Iterated on one level, a frictionless contact's stiffer side takes a quarter of
    its neighbour-rule coefficient and the softer side four times its own
    (Settings.contact_split); faces within CONTACT_TIE count as equal and the
    indenter takes the smaller. The face of a coated base is the coating layered on the
    base at the contact's scale (robin_parameters.face_stiffness)."""
    gallery = SCENES_DIR / "gallery"
    # which side takes the smaller coefficient, at a split of 4: equal bodies, a thin
    # hard coating (its face 1.07 times the base's): the indenter's
    assert _contact_gammas(gallery / "tin_on_steel.toml", contact_split=4.0) == \
        pytest.approx((0.25, 4.0))
    # a roller of E/100 on steel: the base's, widening the rule's own asymmetry
    assert _contact_gammas(gallery / "polymer_roller_on_chromed_steel.toml",
                           contact_split=4.0) == pytest.approx((4.0, 0.25))
    # a coating of 2 E, h2/a = 0.4, on the base: its face 1.8 times the indenter's
    assert _contact_gammas(SCENES_DIR / "cylinder_mm.toml", contact_split=4.0) == \
        pytest.approx((4.0, 0.25))
    # the same scene with the coating's modulus the base's: equal faces
    assert _contact_gammas(SCENES_DIR / "cylinder_mm.toml", {"coating[1].E": 210000.0},
                           contact_split=4.0) == pytest.approx((0.25, 4.0))
    # not under a coarse level (whose sides are held), nor under friction
    scene, _ = scene_and_settings(gallery / "tin_on_steel.toml")
    two_levels = prepare(scene, Settings(inner_solve="two-level")).strategy.sides
    assert all(side.gamma == side.direct_gamma for side in two_levels
               if side.interface.startswith("contact"))
    assert _contact_gammas(SCENES_DIR / "partial_slip.toml") == pytest.approx((1.0, 1.0))
    assert _contact_gammas(gallery / "tin_on_steel.toml", contact_split=1.0) == (1.0, 1.0)
    assert _contact_gammas(gallery / "tin_on_steel.toml", contact_split=8.0) == \
        pytest.approx((0.125, 8.0))
    # by default split far, nearly a Neumann side and a Dirichlet one (the softer side's
    # at most 1/theta)
    assert Settings().contact_split == 256.0
    stiffer, softer = _contact_gammas(gallery / "tin_on_steel.toml")
    assert stiffer == pytest.approx(1.0 / 256.0) and 4.0 < softer <= 256.0
    softer, stiffer = _contact_gammas(gallery / "polymer_roller_on_chromed_steel.toml")
    assert stiffer == pytest.approx(1.0 / 256.0) and 4.0 < softer <= 256.0
    # but under an indenter more than hold_contrast times as stiff as the base (its side,
    # nearly free, lengthened the contact set's walk) by 16 at the most where the base
    # carries the stamp's force (force_balance), else by 4
    assert _contact_gammas(gallery / "near_rigid_cylinder.toml") == \
        pytest.approx((1 / 16.0, 16.0))
    assert _contact_gammas(gallery / "near_rigid_cylinder.toml",
                           force_balance="off") == pytest.approx((0.25, 4.0))


@pytest.mark.slow
def test_a_split_loop_updates_its_set_once_the_tractions_begin_to_settle(tmp_path):
    """The paper's scene iterated on one level at mesh level 3 (sides split): updated on
    the displacements' change alone, its contact set walked through 18 sets (226
    iterations); waiting for the tractions' change to fall within LAGGING_TRACTIONS times
    the update tolerance, 3 updates. Its answer is the two-level run's. At the split
    these were measured at (4, the bond exchanged); split far (the default), with the
    coating inside the base's worker, it walked 9 sets in 107 iterations (docs/method.md,
    "Robin parameters")."""
    iterated = solve(paper_scene(), Settings(mesh_level=3, inner_solve="iterate",
                                             contact_split=4.0, bond_split=4.0,
                                             bonds="exchanged"),
                     tmp_path / "iterated")
    assert iterated["converged"] and iterated["active_set_changes"] <= 4
    assert iterated["strategy"]["sides"][0]["gamma"] != iterated["strategy"]["gamma"]["value"]
    two_levels = solve(paper_scene(), Settings(mesh_level=3), tmp_path / "two_levels")
    assert two_levels["inner_solve_used"] == "two-level"
    assert iterated["peak_contact_stress"] == pytest.approx(two_levels["peak_contact_stress"],
                                                            rel=1e-5)


def test_a_bonds_sides_split_further_without_friction():
    """A bond's split by the coating's response against the base's (bond_ratio r) is
    widened by bond_split where r > 1 and the scene has no friction, up to the limit of
    r's own split (sqrt(BOND_RATIO_LIMIT), 16, on each side)."""
    def bond_split(path, **values):
        scene, _ = scene_and_settings(path)
        plan = prepare(scene, Settings(inner_solve="iterate", **values))
        coating, base = [side for side in plan.strategy.sides
                         if side.interface.startswith("bond")][:2]
        return coating.gamma / coating.direct_gamma, base.gamma / base.direct_gamma

    tin = SCENES_DIR / "gallery" / "tin_on_steel.toml"
    plain = bond_split(tin, bond_split=1.0)
    assert 1 < plain[0] < 4 and plain[0] * plain[1] == pytest.approx(1.0)
    assert bond_split(tin, bond_split=4.0) == pytest.approx((4 * plain[0], plain[1] / 4))
    # by default (16) to the limit
    assert bond_split(tin) == pytest.approx((16.0, 1 / 16.0))
    # a 1 um film (r at its limit 256): sqrt(256) = 16 at the most
    dlc = bond_split(SCENES_DIR / "gallery" / "dlc_on_large_steel_part.toml")
    assert dlc == pytest.approx((16.0, 1 / 16.0))
    # a coating stiffer than the base at the contact's scale (r = 1): unsplit
    near_rigid = SCENES_DIR / "gallery" / "near_rigid_cylinder.toml"
    assert bond_split(near_rigid, bonds="exchanged") == pytest.approx((1.0, 1.0))
    # under friction, r's split alone
    scene, _ = scene_and_settings(SCENES_DIR / "partial_slip.toml")
    assert scene.coatings
    frictional = bond_split(SCENES_DIR / "partial_slip.toml")
    assert frictional == pytest.approx(bond_split(SCENES_DIR / "partial_slip.toml",
                                                  bond_split=1.0))


def test_a_stalled_iteration_falls_back_only_where_the_maps_are_affordable():
    """auto's direct fallback probes every worker's map: where that costs more than
    auto_fallback_work dof-columns (interface unknowns times estimated dofs, summed) it
    is not planned, and the rule says why. A b/512 2D coating on the paper's uniform face
    (its cells held at twice their height along the patch) at mesh level 2: 2.1e9
    dof-columns and a dense system of 9 GiB; the paper's scene at level 2 keeps it, at
    9e6. (A graded face refines a thin coating at its ends only: a 1 um film on the
    gallery's roller at mesh level 2 now keeps it, at 1.1e8.)"""
    big = prepare(paper_scene(model="elastic", h2=1 / 512),
                  Settings(mesh_level=2)).strategy.inner_solve
    # two levels there (the coarse level takes the face's elements for the film's cells)
    assert big.planned == TWO_LEVEL and big.fallback is None
    assert "no direct fallback" in big.rule and "auto_fallback_work" in big.rule
    small = prepare(paper_scene(model="elastic"), Settings(mesh_level=2)).strategy.inner_solve
    assert small.fallback == DIRECT and "no direct fallback" not in small.rule
    none = prepare(paper_scene(model="elastic"),
                   Settings(mesh_level=2, auto_fallback_work=0.0)).strategy.inner_solve
    assert none.fallback is None


def test_a_direct_solve_whose_interface_system_outgrows_the_memory_is_refused():
    """Asked for, the direct solve of a b/512 2D coating on the paper's uniform face (6150
    interface unknowns: its dense interface system about 2.3 GiB) under a 2 GiB
    memory_limit, which the workers' own estimate (about 1.2 GiB) meets: refused before
    any work, naming inner_solve; iterated, it is planned; auto plans no direct fallback
    there."""
    scene = paper_scene(model="elastic", h2=1 / 512)
    with pytest.raises(ParameterError) as refused:
        prepare(scene, Settings(inner_solve="direct", memory_limit=2.0))
    assert refused.value.key == "inner_solve" and "GiB" in str(refused.value)
    assert prepare(scene, Settings(inner_solve="iterate", memory_limit=2.0))
    auto = prepare(scene, Settings(memory_limit=2.0)).strategy.inner_solve
    assert auto.fallback is None and "dense interface system" in auto.rule
    assert prepare(scene, Settings(memory_limit=8.0)).strategy.inner_solve.fallback == DIRECT


def test_under_a_force_the_stamps_partner_carries_it_where_the_loop_iterates_on_one_level():
    """The stamp's partner is balanced (ddm/force_balance.py) under a force where the
    active-set loop iterates on one level without friction and one worker holds every
    contact's side B; the stamp's sides then release their inactive points, which under
    a neighbour 1000 times softer they held."""
    scene, _ = scene_and_settings(SCENES_DIR / "gallery" / "near_rigid_cylinder.toml")
    plan = prepare(scene, Settings(mesh_level=2))
    assert plan.strategy.force_balance == COATED_BASE
    stamp = [side for side in plan.strategy.sides if side.subdomain == "indenter"]
    assert stamp and not any(side.hold_inactive for side in stamp)
    off = prepare(scene, Settings(mesh_level=2, force_balance="off")).strategy
    assert off.force_balance is None
    assert all(side.hold_inactive for side in off.sides if side.subdomain == "indenter")
    # each contact set solved directly, two levels, bonds exchanged (the contact's sides
    # B in two workers): none
    for values in ({"inner_solve": "direct"}, {"inner_solve": "two-level"},
                   {"bonds": "exchanged"}):
        assert prepare(scene, Settings(mesh_level=2, **values)).strategy.force_balance is None
    # a rigid stamp's partner is the bare block's coated base too
    rigid, _ = scene_and_settings(SCENES_DIR / "gallery" / "rigid_cylinder.toml")
    assert prepare(rigid, Settings(mesh_level=2)).strategy.force_balance == COATED_BASE
    # under a descent, and with friction, none
    assert prepare(paper_scene(), Settings(inner_solve="iterate")).strategy.force_balance is None
    friction, _ = scene_and_settings(SCENES_DIR / "partial_slip.toml")
    assert prepare(friction, Settings()).strategy.force_balance is None
