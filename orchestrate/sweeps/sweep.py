"""Parameter sweeps: ``python -m orchestrate sweep SWEEP.toml``.

A sweep file (orchestrate/sweeps/sweep_file.py) names scene and settings values, as a
product of lists ([grid], [[grids]]) and single points ([[runs]]).

Every point is one run folder, results/<name>/runs/<run>/, written as `solve` writes it
and named by the point's values (orchestrate/sweeps/run_names.py), e.g.
eps_u=1e-06_model=shell_h2=1, so a point keeps its folder when the sweep grows. A run
folder appears only once complete, so re-running a sweep skips it, and a sweep
interrupted by Ctrl-C, a killed driver or a full disk loses no finished run. A finished
run counts as its point only if it was solved by this sweep (its manifest, sweep.json,
says so), from the point's inputs now (its scene file and settings) and with the forms'
files now: other runs are run again, named with the reason (manifest.py). Every point is
checked before the first run (its scene, settings and size): a bad one refuses the
sweep, all bad points named. Runs
that diverge or stagnate are rows with their reason; runs that fail for a reason outside
their numbers (a worker killed, a full disk) are rows with the cause, and are run again
when the sweep is resumed (``--retry-failed``: those that did not converge too). All
summaries gather into results/<name>/runs.csv, one row per point in the file's order
(its column "id": the run folder's name). A lock in the sweep's folder keeps a second
sweep out; the sweep touches nothing in it but its runs, its table and its manifest.

Engines: local processes (default, one run per core), or Dask distributed (``--engine
dask`` with ``--scheduler tcp://HOST:PORT`` for a cluster sharing the results folder, or
a local Dask cluster of ``--jobs`` workers), with the same sweep file. A worker process
that dies (killed, out of memory) costs only the run it held: that run is tried once
more, then recorded as failed.
"""

import os
from pathlib import Path
import sys

from orchestrate.errors import ParameterError
from orchestrate.files.folders import (hold_lock, release_lock, remove_dead_run_leftovers,
                                       remove_dead_work_folders)
from orchestrate.sweeps.engines import Progress, failed, run_dask, run_local
from orchestrate.sweeps.manifest import (finished, point_inputs, point_stamp, read_manifest,
                                         solved, sweep_identity, why_stale)
from orchestrate.sweeps.sweep_file import check_points, load_sweep, named_points, point_scene, warm_start_of
from orchestrate.sweeps.table import write_table
from orchestrate.workers.provenance import forms_digest

EDITED_PASSES = 2      # passes over points whose scene file or forms were edited while
                       # the sweep ran
SWEEPS_DIR = Path("results")   # a sweep's folder: results/<name> in the current folder


ENGINES = ("local", "dask")


def _inputs(runs, scene_dir):
    """{name: the point's inputs (point_inputs)}; a point whose scene can no longer be
    built (its file edited into a bad one during the sweep) gets none, and is run into
    its report."""
    inputs = {}
    for name, values in runs:
        try:
            inputs[name] = point_inputs(*point_scene(values, scene_dir))
        except ParameterError:
            inputs[name] = None
    return inputs


def _pending(sweep_dir, runs, retry_failed, stream, when="since they ran"):
    """The points to run: those without a run that counts (finished); the finished
    runs that no longer count are named, by reason."""
    forms, manifest = forms_digest(), read_manifest(sweep_dir)
    pending, stale = [], {}
    for name, values in runs:
        folder = Path(sweep_dir) / "runs" / name
        stamp = point_stamp(sweep_dir, name, manifest)
        if stamp and stamp["inputs"] and finished(folder, stamp, forms, retry_failed):
            continue
        pending.append((name, values))
        if solved(folder) and stamp:
            reason = why_stale(folder, stamp, forms)
            if reason:
                stale.setdefault(reason, []).append(name)
    for reason, names in stale.items():
        print(f"{len(names)} point(s) {when}: {reason}; run again: {', '.join(names[:5])}"
              f"{', ...' if len(names) > 5 else ''}", file=stream)
    return pending


def run_sweep(path, out=None, engine="local", jobs=None, scheduler=None, stream=sys.stderr,
              retry_failed=False, run_done=lambda name=None: None):
    """Run a sweep file; return its table. Finished runs are skipped. ``run_done(name)``
    is called once before the first run and after each (the figures draw from finished
    runs while the others run: studies/figure_sweep.py)."""
    name, points = load_sweep(path)
    scene_dir = Path(path).resolve().parent
    if engine not in ENGINES:
        raise ParameterError(f"engine = {engine!r} must be one of {ENGINES}")
    if jobs is not None and jobs < 1:
        raise ParameterError(f"--jobs = {jobs} must be a positive number")
    from orchestrate.workers import freefem
    freefem.executable()                             # before any work
    check_points(points, scene_dir, stream)
    sweep_dir = Path(out) if out else SWEEPS_DIR / name
    try:
        (sweep_dir / "runs").mkdir(parents=True, exist_ok=True)
    except OSError as error:
        raise ParameterError(f"sweep folder {sweep_dir}: {error.strerror}") from None
    lock = hold_lock(sweep_dir / ".sweep.lock", f"sweep folder {sweep_dir}",
                     "another sweep is running in it")
    try:
        remove_dead_run_leftovers(sweep_dir / "runs")     # of a sweep killed before
        runs = named_points(points)
        identity = sweep_identity(sweep_dir, path, runs, _inputs(runs, scene_dir))
        pending = _pending(sweep_dir, runs, retry_failed, stream)
        jobs = jobs or os.cpu_count() or 1
        progress = Progress(len(runs), stream)
        progress.done = len(runs) - len(pending)
        waiting = {name for name, _ in pending}
        progress.failed = sum(failed(sweep_dir, name) for name, _ in runs
                              if name not in waiting)
        try:
            run_done()
            neighbours = runs if warm_start_of(path) else None
            for _ in range(1 + EDITED_PASSES):
                if not pending:
                    break
                if engine == "dask":
                    run_dask(pending, sweep_dir, scene_dir, jobs, progress, scheduler,
                             retry_failed, neighbours, run_done, identity)
                else:
                    run_local(pending, sweep_dir, scene_dir, jobs, progress, retry_failed,
                              neighbours, run_done, identity)
                # a scene file or a form edited while the sweep ran: the points solved
                # from the old one are run again
                sweep_identity(sweep_dir, path, runs, _inputs(runs, scene_dir))
                pending = [(name, values) for name, values in
                           _pending(sweep_dir, runs, retry_failed, stream, "during the sweep")
                           if solved(sweep_dir / "runs" / name)]
                progress.done -= len(pending)
        finally:
            progress.close()
            remove_dead_run_leftovers(sweep_dir / "runs")  # of runs whose process died
            remove_dead_work_folders()
            table = write_table(sweep_dir, runs)
    finally:
        release_lock(lock)
    return table
