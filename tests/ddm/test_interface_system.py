"""Each contact set's fixed point solved directly from the subdomains' Robin maps
(orchestrate/ddm/interface_system.py).

The system is assembled from the same Robin laws the loop evaluates; its solution must
be a fixed point of the loop's own iteration (robin_data, the maps' replies,
state_after_solve), whatever the maps. On the paper's scene the direct solve must give
the iterated loop's answer within the loop's tolerance, with one iteration per contact
set.
"""

import math

import numpy as np
import pandas as pd
import pytest

from orchestrate.mesh.discretization import discretize
from orchestrate.errors import ParameterError
from orchestrate.workers.exchange import RobinRequest
from orchestrate.ddm.interface_system import InterfaceSystem
from orchestrate.ddm.robin import robin_data, robin_laws, state_after_solve
from orchestrate.ddm.robin_parameters import side_parameters
from orchestrate.workers.robin_map import RobinMap
from orchestrate.model.scene import Settings
from orchestrate.model.scene_file import SCENES_DIR, load_scene, paper_scene
from orchestrate.run.solve import solve
from orchestrate.ddm.state import StateLayout

pytestmark = pytest.mark.slow       # not in the everyday subset (make test-fast)

EPS_U = 1e-6


def _random_maps(problem, laws, rng):
    """Affine maps of random matrices for every subdomain, at the laws' alphas."""
    maps = {}
    for name in problem.subdomains:
        sides = problem.sides_of(name)
        components = [problem.interfaces[i].components for i, _ in sides]
        n = sum(problem.interfaces[i].size * c for (i, _), c in zip(sides, components))
        maps[name] = RobinMap([laws[key].alpha for key in sides], components,
                              rng.normal(size=(n, n)) / np.sqrt(n), rng.normal(size=n),
                              rng.normal(size=n), 0.3)
    return maps


def _loop_image(problem, layout, maps, laws, x):
    """One iteration of the loop from x, the maps standing in for the workers
    (as Subdomains.solve does)."""
    data = robin_data(layout, x, laws)
    traces = {}
    for name, robin_map in maps.items():
        sides = problem.sides_of(name)
        traces.update(robin_map.reply(RobinRequest.of(sides, data)).by_side(sides))
    return state_after_solve(layout, data, traces, x)


@pytest.mark.parametrize("hold_inactive", [True, False])
@pytest.mark.parametrize("rule, E1", [("equal", 1.0), ("neighbour", 100.0)])
def test_the_direct_solution_is_a_fixed_point_of_the_loops_own_iteration(hold_inactive, rule,
                                                                         E1):
    """With one gamma or each side's own (a stiff indenter: gamma differs by side)."""
    problem = discretize(paper_scene(h2=0.125, E2=5.0, E1=E1, model="elastic"), Settings())
    layout = StateLayout(problem.interfaces)
    rng = np.random.default_rng(7)
    psi = (rng.random(layout.gap.size) < 0.5).astype(float)
    # as a run that solves each set directly has them (strategy._solved_directly)
    sides = [side.solved_directly() for side in
             side_parameters(problem, problem.robin, rule, math.inf, hold_all=hold_inactive)]
    assert len({side.gamma for side in sides}) == (1 if rule == "equal" else 2)
    laws = robin_laws(problem, layout, psi, problem.penalty, sides)
    maps = _random_maps(problem, laws, rng)
    sides = {name: problem.sides_of(name) for name in maps}
    x, refined = InterfaceSystem(layout, sides, maps).fixed_point(laws)
    image = _loop_image(problem, layout, maps, laws, x)
    assert np.linalg.norm(image - x) < 1e-10 * np.linalg.norm(x)
    assert np.linalg.norm(refined - x) < 1e-10 * np.linalg.norm(x)


@pytest.fixture(scope="module")
def both_ways(tmp_path_factory):
    """The paper's scene (2D coating, b/8, 5E) solved directly and iterated."""
    base = tmp_path_factory.mktemp("inner")
    scene = paper_scene(h2=0.125, E2=5.0, model="elastic")
    runs = {}
    for way in ("direct", "iterate"):
        summary = solve(scene, Settings(eps_u=EPS_U, inner_solve=way), str(base / way))
        runs[way] = (summary, pd.read_csv(base / way / "contact.csv"),
                     pd.read_csv(base / way / "interface.csv"))
    return runs


def _relative_l2(a, b):
    return float(np.linalg.norm(a - b) / np.linalg.norm(b))


def test_a_direct_run_gives_the_iterated_answer_within_the_tolerance(both_ways):
    (direct, contact, bond), (iterated, contact_i, bond_i) = both_ways["direct"], both_ways["iterate"]
    assert direct["converged"] and iterated["converged"]
    assert direct["inner_solve_used"] == "direct" and iterated["inner_solve_used"] == "iterate"
    # each side is within eps_u of the penalised solution; the direct one to rounding
    assert direct["error_estimate"] < 1e-10
    assert _relative_l2(contact.sigma_n, contact_i.sigma_n) < 2 * EPS_U
    for component in ("sigma_n", "sigma_t"):
        assert _relative_l2(bond[component], bond_i[component]) < 2 * EPS_U


def test_a_direct_run_takes_one_iteration_per_contact_set(both_ways):
    direct, iterated = both_ways["direct"][0], both_ways["iterate"][0]
    assert direct["iterations"] == direct["active_set_changes"] + 1
    assert direct["iterations"] < iterated["iterations"] / 5


def test_auto_solves_directly_where_the_maps_cost_less(tmp_path):
    """At the paper's mesh probing the maps costs fewer back-substitutions than the
    loop's iterations; at mesh level 2 the base's interface unknowns double and it no
    longer does (Subdomains._maps_pay): the loop iterates there, corrected on the coarse
    mesh (tests/ddm/test_coarse.py)."""
    scene = paper_scene(h2=0.125, E2=5.0, model="shell")
    assert solve(scene, Settings(), str(tmp_path / "one"))["inner_solve_used"] == "direct"
    assert solve(scene, Settings(mesh_level=2),
                 str(tmp_path / "two"))["inner_solve_used"] == "two-level"


def test_a_force_load_is_solved_directly_through_the_maps_descent_row(tmp_path):
    scene, values = load_scene(SCENES_DIR / "cylinder.toml")     # a cylinder under a force
    assert scene.load.force is not None
    direct = solve(scene, Settings(**values, inner_solve="direct"), str(tmp_path / "direct"))
    iterated = solve(scene, Settings(**values, inner_solve="iterate"), str(tmp_path / "iterate"))
    assert direct["inner_solve_used"] == "direct"
    assert abs(direct["descent"] - iterated["descent"]) < 2 * EPS_U * abs(iterated["descent"])
    contact = pd.read_csv(tmp_path / "direct" / "contact.csv")
    contact_i = pd.read_csv(tmp_path / "iterate" / "contact.csv")
    assert _relative_l2(contact.sigma_n, contact_i.sigma_n) < 2 * EPS_U


@pytest.mark.parametrize("settings, message", [
    (dict(method="paper", inner_solve="direct"), "method = 'active-set'"),
    (dict(workers="fresh", inner_solve="direct"), "workers = 'persistent'"),
    (dict(inner_solve="exact"), "inner_solve"),
])
def test_a_direct_solve_the_settings_cannot_give_is_refused(settings, message):
    with pytest.raises(ParameterError, match=message):
        Settings(**settings)


def test_a_system_too_ill_conditioned_for_its_tolerance_hands_over_to_the_iterations(
        tmp_path, monkeypatch, both_ways):
    """Where one step of refinement moves the direct solution by more than eps_u, the
    loop goes on with Anderson iterations from it, and still reaches the iterated answer."""
    solve_directly = InterfaceSystem.fixed_point

    def rough(self, laws):                # a refinement step as large as 10 eps_u
        state, refined = solve_directly(self, laws)
        return state, refined * (1 + 10 * EPS_U)

    monkeypatch.setattr(InterfaceSystem, "fixed_point", rough)
    scene = paper_scene(h2=0.125, E2=5.0, model="elastic")
    summary = solve(scene, Settings(eps_u=EPS_U, inner_solve="direct"), str(tmp_path / "run"))
    assert summary["converged"] and summary["inner_solve_used"] == "direct, then iterate"
    contact = pd.read_csv(tmp_path / "run" / "contact.csv")
    assert _relative_l2(contact.sigma_n, both_ways["iterate"][1].sigma_n) < 2 * EPS_U
