"""When a kept worker gives its Robin-to-trace map (orchestrate/workers/subdomains.py):
once the real solves it answered, over the scenes it served, have cost what probing
the map costs (KEPT_MAP_SOLVES_PER_UNKNOWN of them per interface unknown). Probed at
its second scene regardless, the thick ceramic's coating took 5.7 s to save 1.1 s a
scene. A run that may solve each contact set directly maps every worker or none (the
direct solve's coefficients are not the iterated loop's); a run that iterates maps
each kept worker once it has paid."""

from types import SimpleNamespace

import pytest

from orchestrate.mesh.discretization import discretize
from orchestrate.model.scene import Settings
from orchestrate.model.scene_file import SCENES_DIR, load_scene
from orchestrate.workers.subdomains import (KEPT_MAP_SOLVES_PER_UNKNOWN, Subdomains,
                                            write_inputs)


class _KeptSession:
    """Takes no process: every worker comes kept from ``scenes - 1`` earlier scenes with
    ``solves[name]`` real solves answered and no map."""

    map_kept = True

    def __init__(self, scenes, solves):
        self.scenes, self.solves = scenes, solves

    def take(self, name, *_):
        return SimpleNamespace(scenes=self.scenes, dofs=None, worker=None, robin_map=None,
                               solves=self.solves.get(name, 0))

    def ready(self, entry):
        return 1000


@pytest.fixture(scope="module")
def problem_and_files(tmp_path_factory):
    scene, _ = load_scene(SCENES_DIR / "cylinder.toml")
    problem = discretize(scene, Settings())
    return problem, write_inputs(problem, tmp_path_factory.mktemp("inputs"))


def _subdomains(problem_and_files, paid, iterate=False, scenes=2):
    """Subdomains whose workers in ``paid`` have answered just enough solves to have
    paid for their maps, the others one fewer."""
    problem, files = problem_and_files
    probe = Subdomains(problem, files, _KeptSession(1, {}))
    needed = {name: int(-(-KEPT_MAP_SOLVES_PER_UNKNOWN * probe.unknowns[name] // 1))
              for name in probe.entries}
    solves = {name: needed[name] - (name not in paid) for name in needed}
    assert all(n > 0 for n in solves.values())
    return Subdomains(problem, files, _KeptSession(scenes, solves), iterate=iterate)


def test_a_run_that_may_solve_directly_maps_every_kept_worker_once_all_have_paid(
        problem_and_files):
    names = list(_subdomains(problem_and_files, ()).entries)
    for unpaid in names:
        all_but_one = _subdomains(problem_and_files, [n for n in names if n != unpaid])
        assert not all_but_one.solves_directly, unpaid
        assert not any(all_but_one._to_map(name) for name in names)     # none probed
    every = _subdomains(problem_and_files, names)
    assert every.solves_directly and all(every._to_map(name) for name in names)


def test_an_iterated_run_maps_each_kept_worker_once_it_has_paid(problem_and_files):
    names = list(_subdomains(problem_and_files, ()).entries)
    one = _subdomains(problem_and_files, names[:1], iterate=True)
    assert not one.solves_directly
    assert [one._to_map(name) for name in names] == [True] + [False] * (len(names) - 1)


def test_new_workers_are_mapped_where_the_maps_pay_whatever_they_solved(problem_and_files):
    new = _subdomains(problem_and_files, (), scenes=1)
    assert new.solves_directly == new._maps_pay()
    assert _subdomains(problem_and_files, (), iterate=True, scenes=1).solves_directly is False
