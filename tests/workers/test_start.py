"""A run's workers start as their files are written (orchestrate/workers/subdomains.py):
the largest worker's mesh first, and each worker taken before the next mesh is made, so
that it assembles and factorises meanwhile. What is written is what write_inputs
writes at once."""

from types import SimpleNamespace

from orchestrate.mesh.discretization import discretize
from orchestrate.mesh.problem_size import estimated_dofs
from orchestrate.model.scene import Settings
from orchestrate.model.scene_file import SCENES_DIR, load_scene
from orchestrate.workers.subdomains import Subdomains, write_inputs, written_inputs

COATED_BASE = (("indenter", ("indenter",)), ("coated_base", ("base", "coating1")))


class _RecordingSession:
    """Takes no process: records when each worker is taken, and says it is ready."""

    def __init__(self, events):
        self.events = events

    def take(self, name, *_):
        self.events.append(("take", name))
        return SimpleNamespace(scenes=1, dofs=None, worker=None)

    def ready(self, entry):
        return 1


def _written(problem, workdir, workers, events):
    for worker, files in written_inputs(problem, workdir, workers):
        events.append(("written", worker))
        yield worker, files


def _problem():
    """The roller: its base the largest body, after the indenter in the problem's order."""
    scene, _ = load_scene(SCENES_DIR / "roller.toml")
    return discretize(scene, Settings())


def test_the_largest_worker_s_files_are_written_first_and_as_write_inputs_writes_them(tmp_path):
    problem = _problem()
    dofs = estimated_dofs(problem)
    for folder in ("one", "two", "three"):
        (tmp_path / folder).mkdir()
    order = [worker for worker, _ in written_inputs(problem, tmp_path / "one")]
    assert sorted(order) == sorted(problem.subdomains)
    assert [dofs[name] for name in order] == sorted(dofs.values(), reverse=True)
    assert order[0] != list(problem.subdomains)[0]     # not merely the problem's order

    collected = {}
    for _ in written_inputs(problem, tmp_path / "two", COATED_BASE, collected):
        pass
    at_once = write_inputs(problem, tmp_path / "three", COATED_BASE)
    assert collected.keys() == at_once.keys() == {"indenter", "base", "coating1", "coated_base"}
    for name in at_once:
        assert collected[name]["geometry"][0] == at_once[name]["geometry"][0]


def test_each_worker_is_taken_before_the_next_mesh_is_made(tmp_path):
    problem = _problem()
    events = []
    subdomains = Subdomains(problem, _written(problem, tmp_path, COATED_BASE, events),
                            _RecordingSession(events), COATED_BASE)
    assert events == [("written", "coated_base"), ("take", "coated_base"),
                      ("written", "indenter"), ("take", "indenter")]
    assert list(subdomains.entries) == ["indenter", "coated_base"]   # the workers' order
