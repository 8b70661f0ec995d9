"""Parameter sweeps: ``python -m orchestrate sweep SWEEP.toml``.

A sweep file names scene and settings values: any solver setting (orchestrate/scene.py's
Settings), the paper's parameters (h2, E2, model, ...; scene_file.SHORTHANDS), any scene
key in dotted form ("indenter.radius", "coating[2].E", "load.force"), and ``scene``, a
scene file (relative to the sweep file; default: the paper's scene):

    name = "example"                 # results/<name>/ (default: the file's stem)
    [fixed]                          # values shared by every run
    eps_u = 1e-6
    [grid]                           # the product of these lists
    model = ["shell", "elastic"]
    h2 = [1.0, 0.125]
    [[grids]]                        # more products, each merged with [fixed]
    method = ["paper"]
    rho = [0.3, 0.5]
    [[runs]]                         # and/or single points, each merged with [fixed]
    model = "shell"
    h2 = 0.0625

Every point is one run folder, results/<name>/runs/<id>/, written as `solve` writes it
(id: a hash of the point's values, so a point keeps its folder when the sweep grows).
A run is computed in a scratch folder and renamed into place once its summary.json is
written, so a folder that exists is finished: re-running a sweep skips it, and a sweep
interrupted by Ctrl-C, a killed driver or a full disk loses no finished run. Runs that
diverge, stagnate, fail or are invalid are rows with their reason. All summaries gather
into results/<name>/runs.csv, one row per point.

Engines: local processes (default, one run per core), or Dask distributed (``--engine
dask`` with ``--scheduler tcp://HOST:PORT`` for a cluster sharing the results folder, or
a local Dask cluster of ``--jobs`` workers), with the same sweep file.
"""

import concurrent.futures
import hashlib
import json
import multiprocessing
import os
import shutil
import sys
import time
import tomllib
from dataclasses import fields
from itertools import product
from pathlib import Path

import pandas as pd

from .outputs import write_json
from .paths import RESULTS_DIR
from .scene import ParameterError, Settings, scene_from_dict, to_dict
from .scene_file import is_scene_key, scene_and_settings, shorthand_values

SETTINGS_FIELDS = {f.name for f in fields(Settings)}
FAILED = ("diverged", "stagnated", "max_iterations", "contact_zone", "error", "invalid")


# ---- the sweep file ---------------------------------------------------------------------

def load_sweep(path):
    """(name, points): every point a dict of scene and settings values, in file order."""
    path = Path(path)
    with open(path, "rb") as f:
        data = tomllib.load(f)
    unknown_sections = set(data) - {"name", "fixed", "grid", "grids", "runs"}
    if unknown_sections:
        raise ParameterError(f"unknown sweep section(s): {sorted(unknown_sections)}")
    fixed = data.get("fixed", {})
    grids = ([data["grid"]] if "grid" in data else []) + data.get("grids", [])
    singles = data.get("runs", [])
    for table in (fixed, *grids, *singles):
        unknown = {key for key in table if key not in SETTINGS_FIELDS and key != "scene"
                   and not is_scene_key(key)}
        if unknown:
            raise ParameterError(f"unknown scene or settings parameter(s) in {path.name}: "
                                 f"{sorted(unknown)}")
    points = []
    for grid in grids:
        for key, values in grid.items():
            if not isinstance(values, list) or not values:
                raise ParameterError(f"grid value {key} must be a non-empty list")
        keys = list(grid)
        points += [{**fixed, **dict(zip(keys, combination))}
                   for combination in product(*(grid[k] for k in keys))]
    points += [{**fixed, **single} for single in singles]
    if not points:
        raise ParameterError(f"{path.name} defines no run: give a [grid], [[grids]] or [[runs]]")
    return data.get("name", path.stem), points


def point_scene(values, scene_dir="."):
    """The scene and settings of a point; its scene file is relative to ``scene_dir``."""
    overrides = {k: v for k, v in values.items() if is_scene_key(k)}
    settings = {k: v for k, v in values.items() if k in SETTINGS_FIELDS}
    scene_file = Path(scene_dir) / values["scene"] if "scene" in values else None
    return scene_and_settings(scene_file, overrides, settings)


def point_id(values):
    """A short stable name for a point: the hash of its values."""
    text = json.dumps({k: values[k] for k in sorted(values)}, sort_keys=True)
    return hashlib.sha1(text.encode()).hexdigest()[:12]


# ---- one run, in a worker process -----------------------------------------------------

def run_point(values, sweep_dir, scene_dir="."):
    """Solve one point into sweep_dir/runs/<id>/ unless it is there; return its id.

    Runs in an engine's worker process; never raises for a failed run: the reason goes
    into the run's summary.json."""
    from .solve import RunFailed, solve        # a worker process imports what it needs

    identifier = point_id(values)
    final = Path(sweep_dir) / "runs" / identifier
    if (final / "summary.json").exists():
        return identifier
    scratch = Path(sweep_dir) / "scratch" / identifier
    shutil.rmtree(scratch, ignore_errors=True)
    scratch.mkdir(parents=True)
    report = {"point": values}
    try:
        scene, settings = point_scene(values, scene_dir)
        solve(scene, settings, scratch / "run")
    except ParameterError as error:
        report.update(status="invalid", reason=str(error), converged=False)
    except RunFailed:
        pass                                   # solve wrote the report
    except Exception as error:                 # WorkerError, a full disk, ...: a row, not a crash
        report.update(status="error", reason=f"{type(error).__name__}: {error}",
                      converged=False)
    run_dir = scratch / "run"
    run_dir.mkdir(exist_ok=True)
    summary_path = run_dir / "summary.json"
    summary = json.loads(summary_path.read_text()) if summary_path.exists() else {}
    write_json(summary_path, {**summary, **report})
    shutil.rmtree(final, ignore_errors=True)   # a partial copy from an earlier crash
    final.parent.mkdir(parents=True, exist_ok=True)
    os.replace(run_dir, final)                 # a finished run appears at once, whole
    shutil.rmtree(scratch, ignore_errors=True)
    return identifier


def _worker_init(scratch_dir):
    """Local worker processes: temporary files under the sweep, death with the driver."""
    import tempfile

    from .worker import die_with_parent

    die_with_parent()
    os.makedirs(scratch_dir, exist_ok=True)
    tempfile.tempdir = scratch_dir


# ---- the table ------------------------------------------------------------------------

def gather(sweep_dir, points):
    """One row per point: its values, the scene and settings, outcome and figures."""
    rows = []
    for values in points:
        identifier = point_id(values)
        path = Path(sweep_dir) / "runs" / identifier / "summary.json"
        if not path.exists():
            continue
        summary = json.loads(path.read_text())
        row = {"id": identifier, **values}
        if summary.get("scene"):
            scene = scene_from_dict(summary["scene"])
            row.update(shorthand_values(scene))
            row.update(_flatten(to_dict(scene)))
        # an invalid point has no settings: its values over the defaults
        settings = summary.get("settings") or {f.name: values.get(f.name, f.default)
                                               for f in fields(Settings)}
        row.update({f.name: settings[f.name] for f in fields(Settings)})
        for key in ("status", "reason", "converged", "iterations", "final_relative_change",
                    "active_set_changes", "contact_force", "total_force", "descent",
                    "interface_force", "peak_contact_stress", "peak_interface_stress",
                    "contact_half_width", "wall_time_s", "setup_time_s",
                    "time_per_iteration_s"):
            row[key] = summary.get(key)
        rows.append(row)
    return pd.DataFrame(rows).sort_values("id").reset_index(drop=True) if rows else pd.DataFrame()


def _flatten(data, prefix=""):
    """A scene's dict as dotted keys: indenter.radius, coating[1].E, ..."""
    flat = {}
    for key, value in data.items():
        if isinstance(value, dict):
            flat.update(_flatten(value, f"{prefix}{key}."))
        elif key == "coatings":
            for number, coating in enumerate(value, start=1):
                flat.update(_flatten(coating, f"{prefix}coating[{number}]."))
        elif isinstance(value, list):
            flat[prefix + key] = str(value)
        else:
            flat[prefix + key] = value
    return flat


def write_table(sweep_dir, points):
    table = gather(sweep_dir, points)
    path = Path(sweep_dir) / "runs.csv"
    partial = path.with_name(".runs.csv.partial")
    table.to_csv(partial, index=False)
    os.replace(partial, path)
    return table


# ---- progress -------------------------------------------------------------------------

class Progress:
    """One line: done / running / failed of total, and the time left at the pace so far."""

    def __init__(self, total, stream=sys.stderr):
        self.total, self.stream, self.start = total, stream, time.monotonic()
        self.done = self.failed = self.running = 0
        self.tty = stream.isatty()
        self.last_print = 0.0

    def update(self, done=0, failed=0, running=None):
        self.done += done
        self.failed += failed
        if running is not None:
            self.running = running
        now = time.monotonic()
        if not self.tty and now - self.last_print < 10 and self.done < self.total:
            return
        self.last_print = now
        elapsed = now - self.start
        left = f"~{elapsed / self.done * (self.total - self.done):.0f} s left" if self.done else "time left unknown yet"
        line = (f"{self.done}/{self.total} done, {self.running} running, {self.failed} failed"
                f", {elapsed:.0f} s elapsed, {left}")
        self.stream.write(("\r" + line.ljust(78)) if self.tty else line + "\n")
        self.stream.flush()

    def close(self):
        if self.tty:
            self.stream.write("\n")


def _status(sweep_dir, identifier):
    path = Path(sweep_dir) / "runs" / identifier / "summary.json"
    return json.loads(path.read_text()).get("status") if path.exists() else "error"


# ---- engines --------------------------------------------------------------------------

def run_local(pending, sweep_dir, scene_dir, jobs, progress):
    context = multiprocessing.get_context("spawn")   # no inherited gmsh or threads
    pool = concurrent.futures.ProcessPoolExecutor(
        max_workers=jobs, mp_context=context, initializer=_worker_init,
        initargs=(str(Path(sweep_dir) / "tmp"),))
    try:
        futures = {pool.submit(run_point, values, str(sweep_dir), str(scene_dir))
                   for values in pending}
        _follow(futures, sweep_dir, jobs, progress, concurrent.futures.as_completed)
    except BaseException:
        for process in list(getattr(pool, "_processes", {}).values()):
            process.kill()                            # their FreeFEM workers die with them
        pool.shutdown(wait=False, cancel_futures=True)
        raise
    pool.shutdown()


def run_dask(pending, sweep_dir, scene_dir, jobs, progress, scheduler=None):
    from dask.distributed import Client, LocalCluster, as_completed

    cluster = None if scheduler else LocalCluster(
        n_workers=jobs, threads_per_worker=1, processes=True, dashboard_address=None)
    client = Client(scheduler or cluster)
    try:
        futures = [client.submit(run_point, values, str(sweep_dir), str(scene_dir), pure=False)
                   for values in pending]
        _follow(set(futures), sweep_dir, jobs, progress, as_completed)
    finally:
        client.close()
        if cluster is not None:
            cluster.close()


def _follow(futures, sweep_dir, jobs, progress, as_completed):
    remaining = len(futures)
    progress.update(running=min(jobs, remaining))
    for future in as_completed(futures):
        identifier = future.result()
        remaining -= 1
        progress.update(done=1, failed=int(_status(sweep_dir, identifier) in FAILED),
                        running=min(jobs, remaining))


ENGINES = ("local", "dask")


def run_sweep(path, out=None, engine="local", jobs=None, scheduler=None, stream=sys.stderr):
    """Run a sweep file; return its table. Finished runs are skipped."""
    name, points = load_sweep(path)
    scene_dir = Path(path).resolve().parent
    if engine not in ENGINES:
        raise ParameterError(f"engine = {engine!r} must be one of {ENGINES}")
    from . import freefem
    freefem.executable()                             # before any work
    sweep_dir = Path(out) if out else RESULTS_DIR / name
    for leftover in ("scratch", "tmp"):              # of an interrupted or killed sweep
        shutil.rmtree(sweep_dir / leftover, ignore_errors=True)
    (sweep_dir / "runs").mkdir(parents=True, exist_ok=True)
    unique = list({point_id(p): p for p in points}.values())
    pending = [p for p in unique
               if not (sweep_dir / "runs" / point_id(p) / "summary.json").exists()]
    jobs = jobs or os.cpu_count() or 1
    progress = Progress(len(unique), stream)
    progress.done = len(unique) - len(pending)
    progress.failed = sum(_status(sweep_dir, point_id(p)) in FAILED
                          for p in unique if p not in pending)
    try:
        if pending:
            if engine == "dask":
                run_dask(pending, sweep_dir, scene_dir, jobs, progress, scheduler)
            else:
                run_local(pending, sweep_dir, scene_dir, jobs, progress)
    finally:
        progress.close()
        table = write_table(sweep_dir, unique)
        for leftover in ("scratch", "tmp"):
            shutil.rmtree(sweep_dir / leftover, ignore_errors=True)
    return table
