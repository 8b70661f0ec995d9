"""Parameter sweeps: ``python -m orchestrate sweep SWEEP.toml``.

A sweep file names scene and settings values: any solver setting (orchestrate/model/scene.py's
Settings), the paper's parameters (h2, E2, model, ...; scene_file.SHORTHANDS), any scene
key in dotted form ("indenter.radius", "coating[2].E", "load.force"), and ``scene``, a
scene file (relative to the sweep file; default: the paper's scene):

    name = "example"                 # results/<name>/ (default: the file's stem)
    warm_start = true                # each run starts from its nearest converged
                                     # neighbour (orchestrate/run/warm_start.py; default false)
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

Every point is one run folder, results/<name>/runs/<run>/, written as `solve` writes it
and named by the point's values (orchestrate/sweeps/run_names.py), e.g.
eps_u=1e-06_model=shell_h2=1, so a point keeps its folder when the sweep grows. A run
folder appears only once complete, so re-running a sweep skips it, and a sweep
interrupted by Ctrl-C, a killed driver or a full disk loses no finished run. A finished
run counts as its point only if it was solved by this sweep (its manifest, sweep.json,
says so), from the point's inputs now (its scene file and settings) and with the forms'
files now: other runs are run again, named with the reason (MANIFEST). Every point is checked before the first run
(its scene, settings and size): a bad one refuses the sweep, all bad points named. Runs
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

import concurrent.futures
import hashlib
import json
import multiprocessing
import os
import re
import sys
import time
import uuid
from dataclasses import fields
from itertools import product
from pathlib import Path

import pandas as pd

from orchestrate.errors import ParameterError
from orchestrate.files.folders import (RunFolder, hold_lock, release_lock, remove_dead_run_leftovers,
                      remove_dead_work_folders)
from orchestrate.files.outputs import write_json
from orchestrate.run.paraview import SWEEP_COLLECTION, write_sweep_collection
from orchestrate.workers.provenance import forms_digest
from orchestrate.sweeps.run_names import run_names, values_hash
from orchestrate.model.scene import Settings, scene_from_dict, to_dict
from orchestrate.model.scene_file import is_scene_key, read_toml, scene_and_settings, shorthand_values
from orchestrate.run.warm_start import nearest

SETTINGS_FIELDS = {f.name for f in fields(Settings)}
NOT_CONVERGED = ("diverged", "stagnated", "max_iterations", "contact_zone")
FAILED = NOT_CONVERGED + ("error",)
NAME = re.compile(r"[A-Za-z0-9][A-Za-z0-9_.-]*")      # fullmatch: no trailing newline
ATTEMPTS = 2           # a run whose worker process dies when alone is tried this often
EDITED_PASSES = 2      # passes over points whose scene file or forms were edited while
                       # the sweep ran
CHECK_REPORT_SECONDS = 5.0
SWEEPS_DIR = Path("results")   # a sweep's folder: results/<name> in the current folder


# ---- the sweep file ---------------------------------------------------------------------

def load_sweep(path):
    """(name, points): every point a dict of scene and settings values, in file order.
    A malformed file is refused naming what is wrong."""
    path = Path(path)
    data = read_toml(path, "sweep file")
    unknown_sections = set(data) - {"name", "warm_start", "fixed", "grid", "grids", "runs"}
    if unknown_sections:
        raise ParameterError(f"{path}: unknown sweep section(s) {sorted(unknown_sections)} "
                             "(allowed: name, warm_start, fixed, grid, grids, runs)")
    if not isinstance(data.get("warm_start", False), bool):
        raise ParameterError(f"{path}: warm_start = {data['warm_start']!r} must be true or "
                             "false")
    name = data.get("name", path.stem)
    if not isinstance(name, str) or not NAME.fullmatch(name):
        raise ParameterError(f"{path}: name = {name!r} must be a plain folder name (letters, "
                             "digits, _ . -, not starting with . or -): the sweep's folder is "
                             "results/<name>")
    fixed = data.get("fixed", {})
    grids = data.get("grids", [])
    singles = data.get("runs", [])
    for where, tables in (("fixed", [fixed]), ("grid", [data.get("grid", {})]),
                          ("grids", grids), ("runs", singles)):
        if not isinstance(tables, list) or not all(isinstance(t, dict) for t in tables):
            raise ParameterError(f"{path}: [{where}] must be a table (or [[{where}]] tables)")
    grids = ([data["grid"]] if "grid" in data else []) + grids
    for table in (fixed, *grids, *singles):
        unknown = {key for key in table if key not in SETTINGS_FIELDS and key != "scene"
                   and not is_scene_key(key)}
        if unknown:
            raise ParameterError(f"{path}: unknown scene or settings parameter(s) "
                                 f"{sorted(unknown)}")
    points = []
    for grid in grids:
        for key, values in grid.items():
            if not isinstance(values, list) or not values:
                raise ParameterError(f"{path}: grid value {key} = {values!r} must be a "
                                     "non-empty list")
        keys = list(grid)
        points += [{**fixed, **dict(zip(keys, combination))}
                   for combination in product(*(grid[k] for k in keys))]
    points += [{**fixed, **single} for single in singles]
    if not points:
        raise ParameterError(f"{path} defines no run: give a [grid], [[grids]] or [[runs]]")
    return name, points


def warm_start_of(path):
    """Whether a sweep file asks its runs to start from their nearest finished neighbour
    (``warm_start = true``; load_sweep has checked the value)."""
    return read_toml(path, "sweep file").get("warm_start", False)


def check_points(points, scene_dir=".", stream=sys.stderr):
    """Refuse the sweep, before any run, if any point's scene, settings or size is bad;
    the message names every bad point. A long check says how far it is, every
    CHECK_REPORT_SECONDS (about a millisecond a point)."""
    from orchestrate.run.solve import prepare

    problems = []
    last_report = time.monotonic()
    for number, values in enumerate(points, start=1):
        if time.monotonic() - last_report > CHECK_REPORT_SECONDS:
            stream.write(f"checking the sweep's points: {number - 1} of {len(points)}\n")
            stream.flush()
            last_report = time.monotonic()
        try:
            scene, settings = point_scene(values, scene_dir)
            prepare(scene, settings)
        except (ParameterError, TypeError, ValueError) as error:
            problems.append(f"point {number} {values}: {error}")
    if problems:
        shown = problems[:10] + ([f"... and {len(problems) - 10} more"] if len(problems) > 10 else [])
        raise ParameterError(f"{len(problems)} of {len(points)} points refused:\n  "
                             + "\n  ".join(shown))


def point_scene(values, scene_dir="."):
    """The scene and settings of a point; its scene file is relative to ``scene_dir``."""
    overrides = {k: v for k, v in values.items() if is_scene_key(k)}
    settings = {k: v for k, v in values.items() if k in SETTINGS_FIELDS}
    if not isinstance(values.get("scene", ""), str):
        raise ParameterError(f"scene = {values['scene']!r} must be the path of a scene file")
    scene_file = Path(scene_dir) / values["scene"] if "scene" in values else None
    return scene_and_settings(scene_file, overrides, settings)


def named_points(points):
    """(run folder name, values) of each distinct point, in the points' order."""
    distinct = list({values_hash(values): values for values in points}.values())
    return list(zip(run_names(distinct), distinct))


# ---- which sweep a run folder belongs to, and from what inputs ----------------------------

# A sweep's folder holds MANIFEST: the sweep's identity (made when it first runs), its
# file, and each point's values and inputs. Every run it solves records, in its
# summary.json, that identity and the hash of the inputs it was solved from (its scene as
# its file and values give it, units included, and its settings): a run folder is a
# finished point of this sweep only if both match, and its forms are the files'
# (orchestrate/workers/provenance.py). So a sweep resumed after its scene file or a default was
# edited runs the changed points again, and a run folder copied in from another sweep
# is not taken for one of its points.
MANIFEST = "sweep.json"


def point_inputs(scene, settings):
    """The hash of what a point is solved from: its scene and its settings."""
    text = json.dumps({"scene": to_dict(scene), "settings": to_dict(settings)},
                      sort_keys=True)
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def sweep_identity(sweep_dir, path, runs, inputs):
    """The sweep's identity, from its manifest (made now if it has none), rewritten with
    the points' values and inputs."""
    manifest_path = Path(sweep_dir) / MANIFEST
    try:
        identity = json.loads(manifest_path.read_text())["sweep_id"]
    except (OSError, ValueError, KeyError, TypeError):
        identity = uuid.uuid4().hex
    write_json(manifest_path, {"sweep_id": identity, "file": str(Path(path).resolve()),
                               "points": {name: {"values": values, "inputs": inputs[name]}
                                          for name, values in runs}})
    return identity


def read_manifest(sweep_dir):
    """The sweep's manifest, or None."""
    try:
        return json.loads((Path(sweep_dir) / MANIFEST).read_text())
    except (OSError, ValueError):
        return None


def point_stamp(sweep_dir, name, manifest=None):
    """What a point's run must have recorded to count (summary.json's "sweep_point"),
    from the manifest (read now unless given); None without one."""
    manifest = read_manifest(sweep_dir) if manifest is None else manifest
    try:
        return {"sweep_id": manifest["sweep_id"],
                "inputs": manifest["points"][name]["inputs"]}
    except (KeyError, TypeError):
        return None


def why_stale(folder, stamp, forms):
    """Why the run in ``folder``, which has an answer or a reason of its numbers, does
    not count as the point of ``stamp`` solved with forms ``forms``; None if it does."""
    try:
        summary = json.loads((Path(folder) / "summary.json").read_text())
    except (OSError, ValueError):
        return "no summary"
    recorded = summary.get("sweep_point") or {}
    if recorded.get("sweep_id") != stamp["sweep_id"]:
        return "not a run of this sweep (copied in, or older than its manifest)"
    if recorded.get("inputs") != stamp["inputs"]:
        return "its inputs changed (the scene file, a value or a default setting)"
    if (summary.get("provenance") or {}).get("forms_digest") != forms:
        return "solved with other FreeFEM forms than the files' now"
    return None


# ---- one run, in a worker process -----------------------------------------------------

def run_point(name, values, sweep_dir, scene_dir=".", retry_failed=False, neighbours=None,
              sweep_id=None):
    """Solve one point into sweep_dir/runs/<name>/ unless it is done; return its name.
    ``neighbours``: the sweep's (name, values) points; the run starts from the nearest
    of them that has converged by then (orchestrate/run/warm_start.py), if any.
    ``sweep_id``: the sweep's identity, recorded in the run with the hash of the inputs
    it is solved from (its scene file is read now: an edit since the sweep started
    shows in that hash).

    Runs in an engine's worker process; never raises for a failed run: the reason goes
    into the run's summary.json (a run that failed outside its numbers, "error", is
    run again; with ``retry_failed`` one that did not converge too)."""
    from orchestrate.errors import RunFailed, SystemFailure

    runs_dir = Path(sweep_dir) / "runs"
    folder = runs_dir / name
    try:
        scene, settings = point_scene(values, scene_dir)
        stamp = {"sweep_id": sweep_id, "inputs": point_inputs(scene, settings)}
    except ParameterError:
        scene = settings = stamp = None        # refused again below, into its report
    forms = forms_digest()
    if stamp is not None and finished(folder, stamp, forms, retry_failed):
        return name
    try:
        from orchestrate.run.solve import solve               # a worker process imports what it needs
        if settings is None:
            scene, settings = point_scene(values, scene_dir)
        manifest = read_manifest(sweep_dir)
        done = [(other, point) for other, point in neighbours or () if other != name
                and run_status(runs_dir / other) == "converged"
                and point_stamp(sweep_dir, other, manifest) is not None
                and why_stale(runs_dir / other, point_stamp(sweep_dir, other, manifest),
                              forms) is None]
        source = nearest(values, done)
        try:
            solve(scene, settings, folder, overwrite=True,
                  start_from=runs_dir / source[0] if source else None,
                  session=_process_session, sweep_point=stamp)
        except ParameterError as error:
            if error.key != "start_from":
                raise
            solve(scene, settings, folder, overwrite=True, session=_process_session,
                  sweep_point=stamp)              # a neighbour of another layout: cold
    except RunFailed:
        pass                                   # solve wrote the report
    except (SystemFailure, ParameterError) as error:
        write_report(folder, {"status": "error", "converged": False, "reason": str(error)})
    except MemoryError:
        write_report(folder, {"status": "error", "converged": False, "reason": "out of memory"})
    except Exception as error:                 # a bug: this run's row, not the sweep's end
        write_report(folder, {"status": "error", "converged": False,
                              "reason": f"internal error: {type(error).__name__}: {error}"})
    return name


def finished(folder, stamp, forms, retry_failed=False):
    """Whether a point's run is done: converged, or (unless retry_failed) not converged
    for reasons of its numbers; and solved as the point of ``stamp`` (this sweep, from
    these inputs) with the forms of digest ``forms`` (why_stale). A run that is not is
    run again rather than mixed with the new ones."""
    status = run_status(folder)
    done = status == "converged" or (status in NOT_CONVERGED and not retry_failed)
    return done and why_stale(folder, stamp, forms) is None


def _solved(folder):
    """Whether a point's folder holds a run that reached an answer or a reason of its
    numbers (not a report of a failure outside them)."""
    return run_status(folder) in ("converged",) + NOT_CONVERGED


def run_status(folder):
    try:
        return json.loads((Path(folder) / "summary.json").read_text()).get("status")
    except (OSError, ValueError):
        return None


def write_report(folder, report):
    """A run folder holding only a summary: the report of a run that could not run (no
    scene or settings: the sweep's table fills them in from the point's values)."""
    with RunFolder(folder, overwrite=True, option="run folder") as run:
        write_json(run.scratch / "summary.json", {"scene": None, "settings": None, **report})
        run.commit()


# A local engine's worker process keeps the FreeFEM workers of its last run for the next
# (orchestrate/workers/session.py); elsewhere (a direct call, Dask) each run has its own.
_process_session = None


def _worker_init(driver):
    """Local worker processes die with the driver (and their FreeFEM workers with them),
    and keep a Session, closed when the process ends."""
    from multiprocessing.util import Finalize

    from orchestrate.workers.session import Session
    from orchestrate.workers.worker import die_with_parent

    global _process_session
    die_with_parent(driver)
    _process_session = Session()
    Finalize(_process_session, _process_session.close, exitpriority=10)


# ---- the table ------------------------------------------------------------------------

# a run's outcome in its row, from its summary.json; the other columns say what was run
SUMMARY_COLUMNS = ("status", "reason", "converged", "iterations", "final_relative_change",
                   "error_estimate", "active_set_changes", "inner_solve_used", "contact_force",
                   "total_force",
                   "descent", "interface_force", "peak_contact_stress",
                   "peak_interface_stress", "contact_half_width", "wall_time_s",
                   "setup_time_s", "time_per_iteration_s")
OUTCOME_COLUMNS = SUMMARY_COLUMNS + ("model_chosen", "model_error_estimate", "warnings",
                                     "forms_digest")


def _model_choice_columns(choice):
    """A run with "auto" patches: the models chosen (one per auto patch, "/"-joined) and
    the largest estimated model error among them."""
    if not choice:
        return {"model_chosen": None, "model_error_estimate": None}
    return {"model_chosen": "/".join(p["model"] for p in choice["patches"]),
            "model_error_estimate": max(p["estimated_error"] for p in choice["patches"])}


def gather(sweep_dir, runs):
    """One row per (name, values) run, in their order: the run folder's name ("id"), the
    point's values, the scene and settings, outcome and figures."""
    rows = []
    for name, values in runs:
        path = Path(sweep_dir) / "runs" / name / "summary.json"
        if not path.exists():
            continue
        summary = json.loads(path.read_text())
        row = {"id": name, **values}
        if summary.get("scene"):
            scene = scene_from_dict(summary["scene"])
            row.update(shorthand_values(scene))
            row.update(_flatten(to_dict(scene)))
        # a run that could not run has no settings: its values over the defaults
        settings = summary.get("settings") or {f.name: values.get(f.name, f.default)
                                               for f in fields(Settings)}
        # a run older than a setting has no value for it: an empty cell
        row.update({f.name: settings.get(f.name) for f in fields(Settings)})
        row.update({key: summary.get(key) for key in SUMMARY_COLUMNS})
        row["started_from"] = Path(summary["started_from"]).name if summary.get(
            "started_from") else None
        row.update(_model_choice_columns(summary.get("model_choice")))
        row["warnings"] = "; ".join(w["code"] for w in summary.get("warnings") or ())
        row["forms_digest"] = (summary.get("provenance") or {}).get("forms_digest")
        row.update(_answer_columns(summary.get("answers")))
        rows.append(row)
    return pd.DataFrame(rows)


def _answer_columns(answers):
    """orchestrate/run/answers.py's values away from the patches' ends, a column for each
    value and its x1: peak_pressure, bond-coating1.peel, coating1.von_mises, ..."""
    if not answers:
        return {}
    columns = {}
    found = {"": answers["contact"], **answers["bonds"], **answers["coatings"]}
    for owner, values in found.items():
        for quantity, extreme in values.items():
            if quantity == "at_patch_ends":
                continue
            name = f"{owner}.{quantity}" if owner else quantity
            columns[name] = extreme["value"] if extreme else None
            columns[f"{name}_x1"] = extreme["x1"] if extreme else None
    return columns


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


def write_table(sweep_dir, runs):
    """runs.csv, and sweep.pvd: the finished runs' fields in ParaView, one time step per
    run in the file's order (its time slider steps through them)."""
    table = gather(sweep_dir, runs)
    path = Path(sweep_dir) / "runs.csv"
    partial = path.with_name(".runs.csv.partial")
    table.to_csv(partial, index=False)
    os.replace(partial, path)
    table.attrs["path"] = str(path)
    write_sweep_collection(Path(sweep_dir) / SWEEP_COLLECTION,
                           [Path(sweep_dir) / "runs" / name for name, _ in runs])
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


# ---- engines --------------------------------------------------------------------------

def run_local(pending, sweep_dir, scene_dir, jobs, progress, retry_failed=False,
              neighbours=None, run_done=lambda name=None: None, sweep_id=None):
    """Local worker processes, at most ``jobs`` runs at once; ``pending`` holds (name,
    values) pairs.

    A worker process that dies breaks its pool, and which of the runs in flight it held
    is unknown: each of them is tried again alone, in a new pool. A run whose worker
    dies while it runs alone is to blame: tried ATTEMPTS times so, then recorded as
    failed. So a dying worker costs only its own run."""
    context = multiprocessing.get_context("spawn")   # no inherited gmsh or threads
    queue, alone, deaths = list(pending), [], {}
    while queue or alone:
        pool = concurrent.futures.ProcessPoolExecutor(max_workers=jobs, mp_context=context,
                                                      initializer=_worker_init,
                                                      initargs=(os.getpid(),))
        running = {}

        def submit(source):                    # taken from its list once submitted
            future = pool.submit(run_point, *source[0], str(sweep_dir), str(scene_dir),
                                 retry_failed, neighbours, sweep_id)
            running[future] = source.pop(0)
        try:
            while queue or alone or running:
                if alone:                      # a suspect runs once the pool is empty
                    if not running:
                        submit(alone)
                else:
                    while queue and len(running) < jobs:
                        submit(queue)
                progress.update(running=len(running))
                done, _ = concurrent.futures.wait(running, return_when="FIRST_COMPLETED")
                for future in done:
                    future.result()            # BrokenProcessPool: a worker died
                    name, _ = running.pop(future)
                    progress.update(done=1, failed=_failed(sweep_dir, name),
                                    running=len(running) + min(len(queue), jobs - len(running)))
                    run_done(name)
        except concurrent.futures.process.BrokenProcessPool:
            kill_pool(pool)                  # the others too: their runs are tried again
            if len(running) != 1:
                alone = list(running.values()) + alone
            else:
                (run,) = running.values()
                name = run[0]
                deaths[name] = deaths.get(name, 0) + 1
                if deaths[name] < ATTEMPTS:
                    alone.insert(0, run)
                else:
                    write_report(Path(sweep_dir) / "runs" / name, {
                        "status": "error", "converged": False,
                        "reason": f"the worker process running it died {ATTEMPTS} times "
                                  "while it ran alone (killed, or out of memory)"})
                    progress.update(done=1, failed=1)
            running = {}
        finally:
            if running:
                kill_pool(pool)
            else:
                pool.shutdown()
        remove_dead_work_folders()


def kill_pool(pool):
    """Kill the pool's processes (their FreeFEM workers die with them) and wait for them:
    a dead process's locks are free, and what its run left can go."""
    processes = list((getattr(pool, "_processes", None) or {}).values())
    for process in processes:
        process.kill()
    for process in processes:
        process.join(timeout=10)
    pool.shutdown(wait=False, cancel_futures=True)


def run_dask(pending, sweep_dir, scene_dir, jobs, progress, scheduler=None, retry_failed=False,
             neighbours=None, run_done=lambda name=None: None, sweep_id=None):
    """Dask distributed: a local cluster of ``jobs`` workers, or a scheduler's. A task
    whose workers keep dying (Dask retries it) is recorded as failed."""
    from dask.distributed import Client, LocalCluster, as_completed
    from distributed import KilledWorker

    cluster = None if scheduler else LocalCluster(
        n_workers=jobs, threads_per_worker=1, processes=True, dashboard_address=None)
    client = Client(scheduler or cluster)
    try:
        futures = {client.submit(run_point, name, values, str(sweep_dir), str(scene_dir),
                                 retry_failed, neighbours, sweep_id, pure=False): name
                   for name, values in pending}
        progress.update(running=min(jobs, len(futures)))
        for returned, future in enumerate(as_completed(futures), start=1):
            name = futures[future]
            try:
                future.result()
            except KilledWorker:
                write_report(Path(sweep_dir) / "runs" / name, {
                    "status": "error", "converged": False,
                    "reason": "the Dask workers running it kept dying (killed, or out of memory)"})
            progress.update(done=1, failed=_failed(sweep_dir, name),
                            running=min(jobs, len(futures) - returned))
            run_done(name)
    finally:
        client.close()
        if cluster is not None:
            cluster.close()


def _failed(sweep_dir, name):
    return int(run_status(Path(sweep_dir) / "runs" / name) != "converged")


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
        if _solved(folder) and stamp:
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
        progress.failed = sum(_failed(sweep_dir, name) for name, _ in runs
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
                           if _solved(sweep_dir / "runs" / name)]
                progress.done -= len(pending)
        finally:
            progress.close()
            remove_dead_run_leftovers(sweep_dir / "runs")  # of runs whose process died
            remove_dead_work_folders()
            table = write_table(sweep_dir, runs)
    finally:
        release_lock(lock)
    return table
