"""Workers that outlive a scene (orchestrate/workers/session.py) and their Robin-to-trace maps
(orchestrate/workers/robin_map.py).

Two scenes that differ only in the coating's thickness share the base, and the indenter
up to a shift by the change of h2: in one session the second scene takes both workers
over, evaluates their maps instead of solving, and must give the answer of a run of its
own to rounding, its indenter's fields at the indenter's new place.
"""

import dataclasses
import gc
import json
import os
import threading

import meshio
import numpy as np
import pandas as pd
import pytest

from orchestrate.workers.exchange import RobinRequest
from orchestrate.workers.robin_map import RobinMap, check
from orchestrate.model.scene import Settings
from orchestrate.model.scene_file import SCENES_DIR, load_scene, paper_scene
from orchestrate.workers.session import Session, body_fingerprint
from orchestrate.run.solve import solve
from orchestrate.workers.worker import WorkerError

pytestmark = pytest.mark.slow       # not in the everyday subset (make test-fast)

SAME = 1e-10      # two solves of one factorisation agree to rounding


def _freefem_processes():
    """Pids of the FreeFEM processes that are children of this test process."""
    mine = str(os.getpid())
    found = []
    for pid in os.listdir("/proc"):
        try:
            with open(f"/proc/{pid}/stat") as stat:
                fields = stat.read().rsplit(")", 1)[1].split()
            with open(f"/proc/{pid}/cmdline", "rb") as cmd:
                command = cmd.read()
        except OSError:
            continue
        if fields[1] == mine and b"FreeFem" in command:
            found.append(int(pid))
    return found


@pytest.fixture(scope="module")
def kept_runs(tmp_path_factory):
    """(the second scene's run alone, the same in a session after the first scene,
    the session's worker folder, FreeFEM processes while the session lived)."""
    base = tmp_path_factory.mktemp("session")
    first = paper_scene(h2=0.125, E2=5.0, model="elastic")
    second = paper_scene(h2=0.25, E2=5.0, model="elastic")
    alone = solve(second, Settings(), str(base / "alone"))
    with Session() as session:
        solve(first, Settings(), str(base / "first"), session=session)
        kept = solve(second, Settings(), str(base / "kept"), session=session)
        folder, living = session.folder, _freefem_processes()
    return base, alone, kept, folder, living


def test_a_second_scene_takes_over_the_workers_of_its_unchanged_bodies(kept_runs):
    _, alone, kept, _, _ = kept_runs
    assert alone["workers_kept"] == []
    assert sorted(kept["workers_kept"]) == ["base", "indenter"]   # the coating changed


def test_kept_workers_give_the_answer_of_a_run_of_its_own(kept_runs):
    _, alone, kept, _, _ = kept_runs
    for key in ("peak_contact_stress", "peak_interface_stress", "total_force",
                "contact_half_width", "stamp_reaction"):
        assert kept[key] == pytest.approx(alone[key], rel=SAME, abs=1e-300), key
    assert kept["iterations"] == alone["iterations"]    # the same loop, maps for solves


@pytest.mark.parametrize("body", ["indenter", "base", "coating1"])
def test_kept_workers_write_their_fields_at_the_scene_s_place(kept_runs, body):
    """The indenter's worker read the first scene's mesh, b/8 lower: its nodes are
    written where this scene has them, and its fields are this scene's."""
    base, _, _, _, _ = kept_runs
    alone, kept = (_by_place(pd.read_csv(base / run / f"{body}.csv")) for run in ("alone", "kept"))
    assert len(alone) == len(kept)
    # gmsh places the nodes of a shifted outline to rounding of the coordinates (~16 b)
    assert np.allclose(kept[["x1", "x2"]].to_numpy(), alone[["x1", "x2"]].to_numpy(),
                       rtol=0, atol=1e-10)
    scale = alone.sigma_eq.abs().max()
    assert np.max(np.abs(kept.sigma_eq.to_numpy() - alone.sigma_eq.to_numpy())) < SAME * scale


def _by_place(nodes):
    """The nodes in the order of their places (rounded: the shift leaves 1e-15 behind)."""
    key = np.round(nodes[["x1", "x2"]].to_numpy(), 9)
    return nodes.iloc[np.lexsort((key[:, 1], key[:, 0]))]


def test_a_closed_session_leaves_no_process_and_no_folder(kept_runs):
    _, _, _, folder, living = kept_runs
    assert len(living) == 3                     # the last scene's three workers, kept
    assert not any(os.path.exists(f"/proc/{pid}") and _is_running(pid) for pid in living)
    assert not os.path.exists(folder)


def _is_running(pid):
    try:
        with open(f"/proc/{pid}/stat") as stat:
            return stat.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


def test_a_force_load_is_carried_by_the_indenter_s_map(tmp_path):
    """A stamp under a force: its descent follows from the data, so the map carries a
    descent row. The same scene twice in a session: the second, on maps, gives the
    first's answer and descent (both iterated: the first run alone would probe no maps)."""
    scene, values = load_scene(SCENES_DIR / "cylinder.toml")
    settings = Settings(**values, inner_solve="iterate")
    with Session() as session:
        first = solve(scene, settings, str(tmp_path / "first"), session=session)
        again = solve(scene, settings, str(tmp_path / "again"), session=session)
    assert len(again["workers_kept"]) == len(first["dofs"])
    assert again["descent"] == pytest.approx(first["descent"], rel=SAME)
    assert again["peak_contact_stress"] == pytest.approx(first["peak_contact_stress"], rel=SAME)


def test_a_shifted_body_has_the_same_fingerprint_and_its_shift_as_origin():
    rng = np.random.default_rng(1)
    points = rng.random((20, 2))
    triangles = np.array([[0, 1, 2], [2, 3, 4], [5, 6, 7]])
    lines = np.array([[0, 1], [3, 4]])
    refs = {"medit:ref": [np.array([3, 4]), np.array([1, 1, 1])]}
    mesh = meshio.Mesh(points, [("line", lines), ("triangle", triangles)], cell_data=refs)
    order = rng.permutation(20)                 # renumbered, as gmsh does a shifted outline
    inverse = np.argsort(order)
    shifted = meshio.Mesh(points[order] + [0.5, 3.25],
                          [("line", inverse[lines]), ("triangle", inverse[triangles])],
                          cell_data=refs)
    key, origin = body_fingerprint(mesh, [])
    key_shifted, origin_shifted = body_fingerprint(shifted, [])
    assert key_shifted == key
    assert np.allclose(origin_shifted - origin, [0.5, 3.25])
    relabelled = meshio.Mesh(points, [("line", lines), ("triangle", triangles)],
                             cell_data={"medit:ref": [np.array([3, 5]), np.array([1, 1, 1])]})
    assert body_fingerprint(relabelled, [])[0] != key
    moved = points.copy()
    moved[7] += 1e-6                            # one vertex elsewhere: another body
    assert body_fingerprint(meshio.Mesh(moved, mesh.cells, cell_data=refs), [])[0] != key


def test_a_map_that_disagrees_with_a_solve_is_refused():
    """The last solve of a run on maps is a real one; a map it does not confirm (a stale
    one) fails the run rather than its answer."""
    matrix = np.array([[2.0, 0.5], [0.25, 1.0]])
    robin_map = RobinMap([np.ones(2)], [1], matrix, np.array([0.1, 0.2]), np.zeros(2), 0.0)
    request = RobinRequest((np.ones(2),), (np.array([[1.0, -1.0]]),))
    solved = robin_map.reply(request)
    check("w", robin_map, request, solved)                          # agrees
    solved = dataclasses.replace(solved, traces=(solved.traces[0] * (1 + 1e-6),))
    with pytest.raises(WorkerError, match="map and its solve differ"):
        check("w", robin_map, request, solved)
    assert not robin_map.serves(RobinRequest((np.full(2, 2.0),), (np.zeros((1, 2)),)))  # another alpha


def test_equal_patches_of_one_scene_each_have_a_worker(tmp_path):
    """A shell's files hold no place in the plane: the discrete coating's equal patches
    have one fingerprint, yet each needs a worker of its own (one worker for two would
    wait for ever on the second request)."""
    scene, values = load_scene(SCENES_DIR / "discrete.toml")
    settings = Settings(**values)
    with Session() as session:
        summary = solve(scene, settings, str(tmp_path / "run"), session=session)
        assert len(session.workers) == len(summary["dofs"])


def test_one_session_from_two_threads_solves_one_scene_at_a_time(kept_runs, tmp_path):
    """Two threads solving with one Session: its lock serialises the runs (no request of
    one interleaves with the other's on a worker), each with the answer it has alone."""
    base, alone, _, _, _ = kept_runs
    scenes = [paper_scene(h2=0.25, E2=5.0, model="elastic"),
              paper_scene(h2=0.125, E2=5.0, model="elastic")]
    found, failed = {}, []

    def run(number):
        try:
            found[number] = solve(scenes[number], Settings(), str(tmp_path / f"t{number}"),
                                  session=session)
        except BaseException as error:          # reported by the main thread
            failed.append(error)
    with Session() as session:
        threads = [threading.Thread(target=run, args=(n,)) for n in (0, 1)]
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join(timeout=300)
    assert not failed and not any(thread.is_alive() for thread in threads)
    first = json.loads((base / "first" / "summary.json").read_text())
    for summary, expected in ((found[0], alone), (found[1], first)):
        for key in ("peak_contact_stress", "peak_interface_stress", "total_force"):
            assert summary[key] == pytest.approx(expected[key], rel=1e-9), key


def test_a_session_never_closed_stops_its_workers_when_collected(tmp_path):
    session = Session()
    solve(paper_scene(h2=0.25), Settings(), str(tmp_path / "run"), session=session)
    processes = [worker.process for worker in session.workers]
    folder = session.folder
    assert processes and all(process.poll() is None for process in processes)
    del session
    gc.collect()
    assert all(process.poll() is not None for process in processes)
    assert not os.path.exists(folder)
