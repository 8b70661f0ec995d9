"""Parameter sweeps (orchestrate/sweeps/sweep.py): a row for every run, failures included;
resuming after Ctrl-C or a killed driver redoes only the missing runs and ends with the
table of an uninterrupted sweep; the Dask engine gives the same table; no FreeFEM process
outlives a sweep. Tables are compared in every column but the timings (``*_s``), numbers
to 1e-9 relative: repeated runs agree to round-off (~1e-13), not bit for bit. The loop's
last relative change, a small difference of large numbers below eps_u = 1e-6, agrees to
round-off in absolute terms (1e-12), not relative; its error estimate, that residual
times the amplification the history showed (up to 10^3-10^4) and a margin, to 1e-4
relative (measured: 4e-6)."""

import io
import json
import math
import os
import shutil
import signal
import subprocess
import sys
import time
from xml.etree import ElementTree

import meshio
import numpy as np
import pandas as pd
import pytest

from orchestrate.errors import ParameterError
from orchestrate.model.scene_file import SCENES_DIR
from orchestrate.sweeps import load_sweep, named_points, run_sweep
from tests.conftest import PROJECT_DIR, processes_mentioning

pytestmark = pytest.mark.slow       # not in the everyday subset (make test-fast)

SWEEP = """
name = "small"
[fixed]
eps_u = 1e-6
[grid]
model = ["shell", "elastic"]
h2 = [0.25, 0.125]
E2 = [1.0, 5.0]
[[runs]]
model = "shell"
method = "paper"
max_iterations = 30
[[runs]]
model = "auto"
model_answers = "normal"
h2 = 0.015625
E2 = 1.0
"""
RUNS = 10


@pytest.fixture(scope="module")
def sweep_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("sweep") / "small.toml"
    path.write_text(SWEEP)
    return path


@pytest.fixture(scope="module")
def uninterrupted(sweep_file, tmp_path_factory):
    out = tmp_path_factory.mktemp("uninterrupted")
    return run_sweep(sweep_file, out, jobs=2, stream=open(os.devnull, "w")), out


# A run that solved its contact sets directly has an error estimate of rounding size,
# which differs between a map probed in the run and one kept from the run before.
ROUNDING = 1e-10


def _same_table(a, b):
    assert list(a.columns) == list(b.columns)
    rounding = (a.error_estimate < ROUNDING) & (b.error_estimate < ROUNDING)
    for column in a.columns:
        if column.endswith("_s"):
            continue
        if column == "final_relative_change":
            np.testing.assert_allclose(a[column], b[column], rtol=0, atol=1e-12, err_msg=column)
        elif column == "error_estimate":
            np.testing.assert_allclose(a[column][~rounding], b[column][~rounding], rtol=1e-4,
                                       atol=0, err_msg=column)
        elif column == "reason":       # it quotes the estimate
            assert a[column][~rounding].tolist() == b[column][~rounding].tolist(), column
        elif pd.api.types.is_float_dtype(a[column]) and pd.api.types.is_float_dtype(b[column]):
            np.testing.assert_allclose(a[column], b[column], rtol=1e-9, atol=0, err_msg=column)
        else:
            assert a[column].tolist() == b[column].tolist(), column


def test_every_run_is_a_row_failures_with_their_reason(sweep_file, uninterrupted):
    table, out = uninterrupted
    assert len(table) == RUNS and len(pd.read_csv(out / "runs.csv")) == RUNS
    assert (table.status == "converged").sum() == 9
    stopped = table[table.status == "max_iterations"]
    assert len(stopped) == 1 and not stopped.converged.iloc[0]
    assert sorted(os.listdir(out / "runs")) == sorted(table.id)
    _, points = load_sweep(sweep_file)           # rows in the file's order, not the names'
    assert table.id.tolist() == [name for name, _ in named_points(points)]
    assert table.id.iloc[0] == "eps_u=1e-06_model=shell_h2=0.25_E2=1"
    converged = table[table.converged.astype(bool)]
    assert (converged.final_relative_change < converged.eps_u).all()
    assert not table[~table.converged.astype(bool)].status.isin(["converged"]).any()


def test_an_auto_run_is_a_row_with_the_model_chosen_and_its_estimate(uninterrupted):
    table, _ = uninterrupted
    auto = table[table.model_chosen.notna()]
    assert len(auto) == 1        # b/64: the 2D coating would need twice the unknowns (the
                                 # shells' bond shear left out of the answers judged)
    assert auto.model_chosen.iloc[0] == auto.model.iloc[0] == "stretch_shell"
    assert 0 <= auto.model_error_estimate.iloc[0] <= 0.01


def _runs_that_kept_the_bodies(out):
    kept = [json.loads(path.read_text()).get("workers_kept")
            for path in (out / "runs").glob("*/summary.json")]
    assert len(kept) == RUNS
    return sum("indenter" in (names or []) and "base" in names for names in kept)


def test_a_local_sweep_s_runs_take_over_the_workers_of_the_run_before(uninterrupted):
    """Each worker process keeps its last run's workers (orchestrate/workers/session.py): the
    points share the indenter (shifted) and the base, so every run after a process's
    first takes those over. Their answers are those of runs alone (the table of the Dask
    engine's sweep, whose workers keep theirs too, is this one)."""
    assert _runs_that_kept_the_bodies(uninterrupted[1]) >= RUNS - 4


def test_a_dask_sweep_s_runs_take_over_the_workers_of_the_run_before(dask_sweep):
    """A Dask worker keeps a Session too (engines.keep_workers_plugin)."""
    assert _runs_that_kept_the_bodies(dask_sweep[1]) >= RUNS - 4


def test_a_finished_sweep_is_not_run_again(sweep_file, uninterrupted):
    _, out = uninterrupted
    before = {name: os.stat(out / "runs" / name).st_mtime_ns for name in os.listdir(out / "runs")}
    start = time.monotonic()
    run_sweep(sweep_file, out, jobs=2, stream=open(os.devnull, "w"))
    assert time.monotonic() - start < 5
    after = {name: os.stat(out / "runs" / name).st_mtime_ns for name in os.listdir(out / "runs")}
    assert before == after


def _finished(out):
    runs = out / "runs"
    return {name for name in os.listdir(runs) if not name.startswith(".")} if runs.exists() else set()


@pytest.mark.parametrize("how", [signal.SIGINT, signal.SIGKILL], ids=["Ctrl-C", "SIGKILL"])
def test_an_interrupted_sweep_resumes_with_the_missing_runs_only(sweep_file, uninterrupted,
                                                                   tmp_path, how):
    out = tmp_path / "sweep"
    command = [sys.executable, "-m", "orchestrate", "sweep", str(sweep_file), "--out", str(out),
               "--jobs", "1"]
    process = subprocess.Popen(command, cwd=PROJECT_DIR, stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 120
    while len(_finished(out)) < 3 and time.monotonic() < deadline:
        time.sleep(0.05)
    process.send_signal(how)
    _, stderr = process.communicate(timeout=60)
    if how == signal.SIGINT:
        assert process.returncode == 130 and "interrupted" in stderr
    else:
        assert process.returncode == -signal.SIGKILL
    time.sleep(0.5)                     # the killed driver's processes follow it
    assert processes_mentioning(str(out)) == []
    kept = _finished(out)
    assert 3 <= len(kept) < RUNS
    assert all((out / "runs" / name / "summary.json").exists() for name in kept)
    stamps = {name: os.stat(out / "runs" / name).st_mtime_ns for name in kept}

    resumed = subprocess.run(command, cwd=PROJECT_DIR, capture_output=True, text=True,
                             timeout=300)
    assert resumed.returncode == 1, resumed.stderr     # a run did not converge (by design)
    assert {name: os.stat(out / "runs" / name).st_mtime_ns for name in kept} == stamps
    assert sorted(os.listdir(out)) == ["runs", "runs.csv", "sweep.json", "sweep.pvd"]  # no lock
    assert not [name for name in os.listdir(out / "runs") if name.startswith(".")]
    _same_table(pd.read_csv(out / "runs.csv"), pd.read_csv(uninterrupted[1] / "runs.csv"))


@pytest.fixture(scope="module")
def dask_sweep(sweep_file, tmp_path_factory):
    out = tmp_path_factory.mktemp("dask") / "dask"
    said = io.StringIO()
    return run_sweep(sweep_file, out, engine="dask", jobs=2, stream=said), out, said


def test_the_dask_engine_runs_the_same_sweep(dask_sweep, uninterrupted):
    table, out, said = dask_sweep
    _same_table(table, uninterrupted[0])
    assert processes_mentioning(str(out)) == []      # its workers' FreeFEM workers stopped
    last = said.getvalue().strip().splitlines()[-1]          # the progress at the end
    assert last.startswith(f"{RUNS}/{RUNS} done, 0 running"), last


def test_checking_a_large_sweep_says_how_far_it_is(monkeypatch):
    from orchestrate.sweeps import sweep_file
    monkeypatch.setattr(sweep_file, "CHECK_REPORT_SECONDS", 0.0)
    said = io.StringIO()
    sweep_file.check_points([{"h2": 0.1 + 1e-3 * n} for n in range(5)], stream=said)
    assert said.getvalue().splitlines()[-1] == "checking the sweep's points: 4 of 5"


def test_a_bad_point_refuses_the_sweep_before_any_run(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text('[grid]\nh2 = [0.1, 9.0]\n[[runs]]\nrobin = 5000.0\n')
    result = subprocess.run([sys.executable, "-m", "orchestrate", "sweep", str(path),
                             "--out", str(tmp_path / "out")], cwd=PROJECT_DIR,
                            capture_output=True, text=True, timeout=60)
    assert result.returncode == 2
    assert "2 of 3 points refused" in result.stderr
    assert "coating[1].thickness = 9.0" in result.stderr and "robin = 5000.0" in result.stderr
    assert not (tmp_path / "out").exists()


def test_one_run_written_two_ways_is_refused_and_a_default_set_elsewhere_is_not():
    """A grid listing one value in two units ("2 um" and 0.002 in a mm scene) would run
    the same scene twice into two folders: refused, naming both points. A default set
    explicitly in another grid (mesh_level = 1 beside E2 = 1, as make stability's
    grids do) is a point of its own."""
    from orchestrate.sweeps.sweep_file import check_points
    ball = {"scene": str(SCENES_DIR / "ball_mm.toml")}
    with pytest.raises(ParameterError) as refused:
        check_points([{**ball, "coating.thickness": "2 um"},
                      {**ball, "coating.thickness": 0.002},
                      {**ball, "coating.thickness": "3 um"}], stream=io.StringIO())
    assert "1 of 3 points refused" in str(refused.value)
    assert ("point 2" in str(refused.value) and "the same run as point 1" in str(refused.value)
            and "'2 um'" in str(refused.value))
    check_points([{"h2": 0.5, "E2": 1.0}, {"h2": 0.5, "mesh_level": 1}], stream=io.StringIO())


def test_a_bad_sweep_file_is_refused_naming_the_parameter(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text('[grid]\nh2 = [0.1]\nyoung = [1.0]\n')
    result = subprocess.run([sys.executable, "-m", "orchestrate", "sweep", str(path),
                             "--out", str(tmp_path / "out")], cwd=PROJECT_DIR,
                            capture_output=True, text=True, timeout=60)
    assert result.returncode == 2 and "young" in result.stderr
    assert not (tmp_path / "out").exists()


def test_points_keep_their_names_when_a_sweep_grows(tmp_path):
    small, large = tmp_path / "a.toml", tmp_path / "b.toml"
    small.write_text('[grid]\nh2 = [0.5]\nE2 = [1.0]\n')
    large.write_text('[grid]\nh2 = [0.25, 0.5]\nE2 = [1.0, 5.0]\n')
    (_, first), (_, second) = load_sweep(small), load_sweep(large)
    names = [{name for name, _ in named_points(points)} for points in (first, second)]
    assert names[0] == {"h2=0.5_E2=1"} and names[0] < names[1]


def test_a_sweep_takes_a_scene_file_and_dotted_keys(tmp_path):
    from orchestrate.sweeps import point_scene
    path = tmp_path / "scenes.toml"
    path.write_text('[fixed]\nscene = "discrete.toml"\n"load.force" = 0.01\n'
                    '[grid]\n"coating[2].E" = [2.0, 5.0]\nh2 = [0.25]\n')
    (tmp_path / "discrete.toml").write_text(
        (PROJECT_DIR / "orchestrate" / "scenes" / "discrete.toml").read_text())
    _, points = load_sweep(path)
    scenes = [point_scene(p, tmp_path)[0] for p in points]
    assert [s.coatings[1].E for s in scenes] == [2.0, 5.0]
    assert all(s.load.force == 0.01 and s.load.displacement is None for s in scenes)
    assert all(c.thickness == 0.25 for s in scenes for c in s.coatings)


def test_a_bad_dotted_key_is_refused_before_any_run(tmp_path):
    from orchestrate.model.scene import ParameterError
    path = tmp_path / "bad.toml"
    path.write_text('[grid]\n"indenter.colour" = [1.0]\n')
    with pytest.raises(ParameterError, match="indenter.colour"):
        load_sweep(path)


# ---- a sweep owns its folder; dying workers cost only their run -----------------------

FOUR = '[grid]\nh2 = [0.25, 0.125]\nE2 = [1.0, 5.0]\n[fixed]\neps_u = 1e-4\n'


def _sweep_command(path, out, *extra):
    return [sys.executable, "-m", "orchestrate", "sweep", str(path), "--out", str(out), *extra]


@pytest.mark.parametrize("name", ["../outside", "/absolute", "", ".hidden", "a/b"])
def test_a_name_that_leaves_results_is_refused(tmp_path, name):
    path = tmp_path / "named.toml"
    path.write_text(f'name = "{name}"\n[grid]\nh2 = [0.5]\n')
    with pytest.raises(Exception, match="must be a plain folder name"):
        load_sweep(path)


def test_a_second_sweep_of_one_folder_is_refused_and_foreign_files_stay(tmp_path):
    path, out = tmp_path / "four.toml", tmp_path / "sweep"
    path.write_text(FOUR)
    for name in ("tmp", "scratch"):
        (out / name).mkdir(parents=True)
        (out / name / "keep.txt").write_text("mine")
    (out / "notes.txt").write_text("mine")
    first = subprocess.Popen(_sweep_command(path, out, "--jobs", "1"), cwd=PROJECT_DIR,
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 60
    while not (out / ".sweep.lock").exists() and time.monotonic() < deadline:
        time.sleep(0.05)
    second = subprocess.run(_sweep_command(path, out), cwd=PROJECT_DIR, capture_output=True,
                            text=True, timeout=60)
    assert second.returncode == 2 and "another sweep is running in it" in second.stderr
    _, stderr = first.communicate(timeout=300)
    assert first.returncode == 0, stderr
    assert sorted(os.listdir(out)) == ["notes.txt", "runs", "runs.csv", "scratch", "sweep.json",
                                       "sweep.pvd", "tmp"]
    for name in ("tmp", "scratch"):
        assert (out / name / "keep.txt").read_text() == "mine"


def _children(parent):
    """PIDs of the live processes whose parent is ``parent``."""
    children = []
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            try:
                with open(f"/proc/{entry}/stat") as f:
                    if int(f.read().rsplit(")", 1)[1].split()[1]) == parent:
                        children.append(int(entry))
            except OSError:
                continue
    return children


@pytest.mark.parametrize("kills", [1, 2])
def test_a_killed_pool_worker_costs_only_its_run(tmp_path, kills):
    """Each kill hits a worker running FreeFEM: the runs in flight are tried again alone,
    and a run killed once is tried again: none is lost, none is blamed for another's
    death (the second kill may hit a run running alone)."""
    path, out = tmp_path / "four.toml", tmp_path / "sweep"
    path.write_text(FOUR)
    driver = subprocess.Popen(_sweep_command(path, out, "--jobs", "2"), cwd=PROJECT_DIR,
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    killed = []
    for kill in range(1, kills + 1):
        deadline = time.monotonic() + 60
        while len(killed) < kill and time.monotonic() < deadline:
            busy = [worker for worker in _children(driver.pid)    # running FreeFEM
                    if _children(worker) and worker not in killed]
            try:
                os.kill(busy[0], signal.SIGKILL)
                killed.append(busy[0])
            except (IndexError, ProcessLookupError):    # none yet, or one of a broken
                time.sleep(0.05)                         # pool, ended by the executor
    assert len(killed) == kills, "no pool worker ran FreeFEM to be killed"
    _, stderr = driver.communicate(timeout=300)
    assert driver.returncode == 0, stderr                # the lost runs were run again
    table = pd.read_csv(out / "runs.csv")
    assert len(table) == 4 and (table.status == "converged").all()
    assert processes_mentioning(str(out)) == []


def test_a_killed_dask_worker_costs_only_its_run(tmp_path):
    path, out = tmp_path / "four.toml", tmp_path / "sweep"
    path.write_text(FOUR)
    driver = subprocess.Popen(_sweep_command(path, out, "--engine", "dask", "--jobs", "2"),
                              cwd=PROJECT_DIR, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                              text=True)
    deadline, busy = time.monotonic() + 120, []
    while not busy and time.monotonic() < deadline:    # a Dask worker running FreeFEM
        busy = [pid for pid in processes_mentioning("body.edp")
                if _is_descendant(pid, driver.pid)]
        time.sleep(0.05)
    os.kill(_parent(busy[0]), signal.SIGKILL)           # the worker process holding it
    _, stderr = driver.communicate(timeout=300)
    assert driver.returncode == 0, stderr
    table = pd.read_csv(out / "runs.csv")
    assert len(table) == 4 and (table.status == "converged").all()
    time.sleep(0.5)
    assert processes_mentioning(str(out)) == []


def _parent(pid):
    with open(f"/proc/{pid}/stat") as f:
        return int(f.read().rsplit(")", 1)[1].split()[1])


def _is_descendant(pid, ancestor):
    try:
        while pid > 1:
            pid = _parent(pid)
            if pid == ancestor:
                return True
    except OSError:
        pass
    return False


def test_every_row_has_the_runs_answers(uninterrupted):
    """runs.csv carries summary.json's answers (orchestrate/run/answers.py), away from the
    patches' ends: the peak pressure is the peak contact stress's magnitude."""
    table, _ = uninterrupted
    done = table[table.converged.astype(bool)]
    assert len(done)
    np.testing.assert_allclose(done.peak_pressure, -done.peak_contact_stress, rtol=1e-12)
    assert done["bond-coating1.compression"].lt(0).all()
    assert done["bond-coating1.shear"].gt(0).all()


def test_the_sweep_pvd_opens_every_converged_run_one_time_step_each(uninterrupted):
    """sweep.pvd: run k of runs.csv's converged rows (in the file's order) is time step k,
    its parts that run's VTU files, all of which exist and read back."""
    table, out = uninterrupted
    datasets = list(ElementTree.parse(out / "sweep.pvd").getroot().iter("DataSet"))
    steps = {}
    for dataset in datasets:
        path = out / dataset.get("file")
        assert path.is_file() and path.suffix == ".vtu"
        steps.setdefault(int(dataset.get("timestep")), set()).add(path.parent.name)
    done = table[table.converged.astype(bool)]
    assert [steps[k] for k in sorted(steps)] == [{name} for name in done.id]
    assert len(meshio.read(out / datasets[0].get("file")).points) > 0


def test_a_run_solved_from_other_inputs_is_run_again(tmp_path):
    """A sweep resumed after its scene file was edited runs the points that file changed
    again, naming them and why, and keeps the others; a default changed since (its
    recorded inputs are not the point's now) likewise."""
    scene = tmp_path / "scene.toml"
    scene.write_text((PROJECT_DIR / "orchestrate" / "scenes" / "paper.toml").read_text())
    path, out = tmp_path / "one.toml", tmp_path / "sweep"
    path.write_text('[fixed]\nscene = "scene.toml"\neps_u = 1e-4\nmodel = "elastic"\n'
                    '[grid]\nh2 = [0.25, 0.125]\n')
    first = run_sweep(path, out, jobs=1, stream=open(os.devnull, "w"))
    summaries = [out / "runs" / name / "summary.json" for name in first.id]
    stamps = [summary.stat().st_mtime_ns for summary in summaries]
    again = run_sweep(path, out, jobs=1, stream=open(os.devnull, "w"))
    assert [summary.stat().st_mtime_ns for summary in summaries] == stamps   # kept
    scene.write_text(scene.read_text().replace("E = 1.0\nnu = 0.3\nmodel", 
                                               "E = 2.0\nnu = 0.3\nmodel"))
    said = io.StringIO()
    edited = run_sweep(path, out, jobs=1, stream=said)
    assert "2 point(s) since they ran: its inputs changed" in said.getvalue()
    assert set(edited["E2"]) == {2.0} and set(again["E2"]) == {1.0}
    assert (edited.peak_contact_stress != again.peak_contact_stress).all()
    summary = json.loads(summaries[0].read_text())
    summary["sweep_point"]["inputs"] = "solved under another default"
    summaries[0].write_text(json.dumps(summary))
    stamps = [path.stat().st_mtime_ns for path in summaries]
    run_sweep(path, out, jobs=1, stream=open(os.devnull, "w"))
    assert [path.stat().st_mtime_ns != stamp for path, stamp in zip(summaries, stamps)] == [
        True, False]


def test_a_run_folder_copied_from_another_sweep_is_not_taken_for_a_point(tmp_path):
    """Two sweeps of the same point: a run folder copied from one into the other is not
    that sweep's (its manifest does not say so): it is run again."""
    path = tmp_path / "one.toml"
    path.write_text('[fixed]\neps_u = 1e-4\nmodel = "elastic"\n[grid]\nh2 = [0.25]\n')
    first = run_sweep(path, tmp_path / "a", jobs=1, stream=open(os.devnull, "w"))
    run_sweep(path, tmp_path / "b", jobs=1, stream=open(os.devnull, "w"))
    name = first.id[0]
    shutil.rmtree(tmp_path / "b" / "runs" / name)
    shutil.copytree(tmp_path / "a" / "runs" / name, tmp_path / "b" / "runs" / name)
    said = io.StringIO()
    run_sweep(path, tmp_path / "b", jobs=1, stream=said)
    assert "1 point(s) since they ran: not a run of this sweep" in said.getvalue()
    own = json.loads((tmp_path / "b" / "runs" / name / "summary.json").read_text())
    manifest = json.loads((tmp_path / "b" / "sweep.json").read_text())
    assert own["sweep_point"]["sweep_id"] == manifest["sweep_id"] != json.loads(
        (tmp_path / "a" / "sweep.json").read_text())["sweep_id"]


def test_a_sweep_writes_into_the_current_folder_and_says_where(tmp_path):
    """Without --out, results/<name> relative to the folder it is run from, not the
    project's; the table's path is printed."""
    path = tmp_path / "here.toml"
    path.write_text('name = "here"\n[[runs]]\nh2 = 0.25\n')
    result = subprocess.run([sys.executable, "-m", "orchestrate", "sweep", str(path)],
                            cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, result.stderr
    table = tmp_path / "results" / "here" / "runs.csv"
    assert table.is_file() and f"table: {os.path.join('results', 'here', 'runs.csv')}" in \
        result.stdout
    assert not (PROJECT_DIR / "results" / "here").exists()


def test_a_scene_file_edited_while_a_sweep_runs_leaves_no_stale_point(tmp_path):
    """The scene file edited once the first point is solved: the later points read the
    edited file, and the first is solved again once the pass is over (named); every row
    is the edited scene's."""
    scene = tmp_path / "scene.toml"
    scene.write_text((PROJECT_DIR / "orchestrate" / "scenes" / "paper.toml").read_text())
    path = tmp_path / "mid.toml"
    path.write_text('[fixed]\nscene = "scene.toml"\neps_u = 1e-4\nmodel = "elastic"\n'
                    '[grid]\nh2 = [0.25, 0.125]\n')
    solved = []

    def edit_after_the_first(name=None):
        if name is not None:
            solved.append(name)
            if len(solved) == 1:
                scene.write_text(scene.read_text().replace("E = 1.0\nnu = 0.3\nmodel",
                                                           "E = 2.0\nnu = 0.3\nmodel"))
    said = io.StringIO()
    table = run_sweep(path, tmp_path / "out", jobs=1, stream=said, run_done=edit_after_the_first)
    assert len(solved) == 3 and solved[2] == solved[0]
    assert "1 point(s) during the sweep: its inputs changed" in said.getvalue()
    assert set(table["E2"]) == {2.0} and table.converged.all()


CURVE_SCENE = """
axisymmetric = true
[indenter]
radius = 20.0
rigid = true
width = 4.0
height = 4.0
[base]
width = 20.0
height = 20.0
[load]
force = 0.07326
"""
CURVE = """
name = "curve"
warm_start = true
[fixed]
scene = "ball.toml"
element_size = 0.0625      # one mesh for every step: the workers are kept
[grid]
"load.force" = [0.0375, 0.07326, 0.1431]
"""


def test_an_indentation_curve_is_a_sweep_over_the_force(tmp_path):
    """A rigid sphere (R = 20 b) on a cylinder 20 b wide and deep, its force stepped so
    that Hertz's contact radius is 0.8, 1 and 1.25 b: each step from its neighbour, each
    within 1 % of Hertz in contact radius and peak pressure (tests/run/
    test_axisymmetric.py: 0.05 % at one force)."""
    (tmp_path / "ball.toml").write_text(CURVE_SCENE)
    (tmp_path / "curve.toml").write_text(CURVE)
    table = run_sweep(tmp_path / "curve.toml", tmp_path / "out", jobs=1,
                      stream=open(os.devnull, "w"))
    assert list(table.status) == ["converged"] * 3
    modulus = 1.0 / (1.0 - 0.3 ** 2)
    for _, row in table.iterrows():
        force = row["load.force"]
        a = (0.75 * force * 20.0 / modulus) ** (1.0 / 3.0)
        assert row["contact_half_width"] / a == pytest.approx(1.0, abs=0.01)
        assert row["peak_pressure"] / (1.5 * force / (math.pi * a ** 2)) == pytest.approx(
            1.0, abs=0.01)
    assert table.started_from.notna().sum() == 2
