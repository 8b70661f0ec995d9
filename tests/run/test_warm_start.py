"""A run started from a finished neighbour (orchestrate/run/warm_start.py).

The state read back from a run's files is the state it converged to: started from its
own files, a run stops within a few iterations at the same answer. Started from a
neighbour (another E2), it reaches the cold run's answer within its tolerance in fewer
iterations (measured: 74 against 113). A sweep with warm_start = true starts its runs
from their nearest converged neighbour and says which.
"""

import json
from dataclasses import replace

import pandas as pd
import pytest

import orchestrate
from orchestrate.errors import ParameterError
from orchestrate.model import scene_and_settings
from orchestrate.model.scene import Settings
from orchestrate.model.scene_file import paper_scene
from orchestrate.paths import SCENES_DIR
from orchestrate.run.solve import solve
from orchestrate.run.warm_start import nearest
from orchestrate.sweeps import load_sweep, run_sweep
from orchestrate.workers.session import Session

TOLERANCE = Settings().eps_u


@pytest.fixture(scope="module")
def neighbour(tmp_path_factory):
    folder = tmp_path_factory.mktemp("warm") / "E2_1"
    solve(paper_scene(h2=0.125, E2=1.0, model="elastic"), Settings(), str(folder))
    return folder


def _summary(folder):
    return json.loads((folder / "summary.json").read_text())


def test_a_run_started_from_its_own_answer_stops_at_once_with_it(coating_2d_run, tmp_path):
    scene, cold = coating_2d_run
    again = solve(scene, Settings(), str(tmp_path / "again"), start_from=cold)
    assert again["started_from"] == str(cold)
    assert again["iterations"] <= 6      # the stopping test's secant pairs (robin.py), no more
    assert again["peak_contact_stress"] == pytest.approx(
        _summary(cold)["peak_contact_stress"], rel=TOLERANCE)


def test_a_neighbours_start_saves_iterations_and_changes_no_answer(coating_2d_run, neighbour,
                                                                   tmp_path):
    scene, cold_folder = coating_2d_run
    cold = _summary(cold_folder)
    warm = solve(scene, Settings(), str(tmp_path / "warm"), start_from=neighbour)
    assert warm["iterations"] < 0.8 * cold["iterations"]
    for key in ("peak_contact_stress", "total_force", "peak_interface_stress"):
        assert warm[key] == pytest.approx(cold[key], rel=TOLERANCE), key
    a, b = (pd.read_csv(folder / "interface.csv") for folder in (cold_folder, tmp_path / "warm"))
    scale = a.sigma_n.abs().max()
    assert (a.sigma_n - b.sigma_n).abs().max() < TOLERANCE * scale


@pytest.mark.slow
def test_a_warm_start_draws_its_first_set_to_the_estimate_its_neighbour_calibrated():
    """The near-rigid cylinder from its answer at half the force: the neighbour's own
    contact set, grown from, took 30 iterations (and, corrected by the low-rank identity
    before the workers factorised again where points are held, 260, stalled, then solved
    directly), where a cold start from its layered estimate takes 10. Drawn to this
    run's estimate times the neighbour's answer over its own (warm_start.
    calibrated_half_width), the warm start takes 10 too; from its own answer, 4."""
    path = SCENES_DIR / "gallery" / "near_rigid_cylinder.toml"
    scene, settings = scene_and_settings(path)
    settings = replace(settings, mesh_level=1)
    with Session() as session:
        lighter = orchestrate.solve(scene, settings, session=session,
                                    overrides={"load.force": scene.load.force / 2})
        warm = orchestrate.solve(scene, settings, session=session, start_from=lighter)
        cold = orchestrate.solve(scene, settings, session=session)
        again = orchestrate.solve(scene, settings, session=session, start_from=cold)
    assert warm.summary["strategy"]["first_contact_over_start"]
    assert warm.summary["iterations"] <= cold.summary["iterations"] + 2
    assert again.summary["iterations"] <= 6        # the stopping test's secant pairs
    for key in ("peak_contact_stress", "total_force", "peak_interface_stress"):
        assert warm.summary[key] == pytest.approx(cold.summary[key], rel=TOLERANCE), key


@pytest.mark.slow
def test_kept_workers_whose_points_are_held_afresh_converge_as_fresh_ones():
    """The near-rigid cylinder under a descent, in one session: from its answer at half
    the descent, and then again cold on the workers that answer left. Corrected by the
    low-rank identity, the warm run took 477 iterations (stalled, then solved directly);
    with its solves refined to a residual of 5e-14, 119, and the cold run after it 76,
    where fresh workers take 18: an accurate residual did not make an accurate solve.
    Factorised again where points are held, 20 and 18."""
    path = SCENES_DIR / "gallery" / "near_rigid_cylinder.toml"
    scene, settings = scene_and_settings(path)
    settings = replace(settings, mesh_level=1)
    descent = orchestrate.solve(scene, settings).summary["descent"]
    under = {"load.force": None, "load.displacement": descent}
    fresh = orchestrate.solve(scene, settings, overrides=under)
    with Session() as session:
        half = orchestrate.solve(scene, settings, session=session,
                                 overrides={**under, "load.displacement": descent / 2})
        warm = orchestrate.solve(scene, settings, session=session, overrides=under,
                                 start_from=half)
        kept = orchestrate.solve(scene, settings, session=session, overrides=under)
    assert warm.summary["inner_solve_fallback"] is None
    assert warm.summary["iterations"] < 1.5 * fresh.summary["iterations"]
    assert kept.summary["iterations"] <= fresh.summary["iterations"] + 2


def test_the_nearest_neighbour_differs_in_the_fewest_values_then_the_least():
    candidates = [("a", {"h2": 1.0, "E2": 5.0}), ("b", {"h2": 0.25, "E2": 1.0}),
                  ("c", {"h2": 0.5, "E2": 1.0}), ("d", {"h2": 0.125, "E2": 0.2})]
    assert nearest({"h2": 0.125, "E2": 1.0}, candidates)[0] == "b"   # 1 key, log 2 < log 4
    assert nearest({"h2": 0.125, "E2": 5.0}, candidates)[0] == "a"   # 1 key beats 2 keys
    assert nearest({"h2": 0.5, "E2": 2.0}, [("x", {"h2": 0.5, "E2": 1.0}),
                                            ("y", {"h2": 0.5, "E2": 4.0})])[0] == "x"  # tie
    assert nearest({"h2": 1.0}, []) is None


def test_a_warm_sweep_says_where_each_run_started(tmp_path):
    path = tmp_path / "warm.toml"
    path.write_text('warm_start = true\n[fixed]\nmodel = "elastic"\neps_u = 1e-6\n'
                    '[grid]\nh2 = [0.25, 0.125]\n')
    table = run_sweep(path, tmp_path / "sweep", jobs=1, stream=open("/dev/null", "w"))
    assert table.converged.all()
    assert pd.isna(table.started_from[0]) and table.started_from[1] == table.id[0]
    assert table.iterations[1] < table.iterations[0]


def test_warm_start_must_be_true_or_false(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text('warm_start = "yes"\n[grid]\nh2 = [0.25]\n')
    with pytest.raises(ParameterError, match="warm_start = 'yes' must be true or false"):
        load_sweep(path)
