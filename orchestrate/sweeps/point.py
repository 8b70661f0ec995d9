"""One point of a sweep, solved in an engine's worker process into its run folder (the
process keeps its FreeFEM workers from run to run: a Session, opened by worker_init in a
local pool's process and by the KeepWorkers plugin in a Dask worker's)."""

from pathlib import Path

from orchestrate.errors import ParameterError
from orchestrate.files.folders import RunFolder
from orchestrate.files.writing import write_json
from orchestrate.run.warm_start import nearest
from orchestrate.sweeps.manifest import (finished, point_inputs, point_stamp, read_manifest,
                                         run_status, why_stale)
from orchestrate.sweeps.sweep_file import point_scene
from orchestrate.workers.provenance import forms_digest


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


def write_report(folder, report):
    """A run folder holding only a summary: the report of a run that could not run (no
    scene or settings: the sweep's table fills them in from the point's values)."""
    with RunFolder(folder, overwrite=True, option="run folder") as run:
        write_json(run.scratch / "summary.json", {"scene": None, "settings": None, **report})
        run.commit()


# An engine's worker process keeps the FreeFEM workers of its last run for the next
# (orchestrate/workers/session.py); elsewhere (a direct call) each run has its own.
_process_session = None


def open_process_session():
    """The Session this process's runs share (one run at a time: its lock)."""
    from orchestrate.workers.session import Session

    global _process_session
    if _process_session is None:
        _process_session = Session()
    return _process_session


def close_process_session():
    """Stop the process's FreeFEM workers."""
    global _process_session
    if _process_session is not None:
        _process_session.close()
        _process_session = None


def worker_init(driver):
    """Local worker processes die with the driver (and their FreeFEM workers with them),
    and keep a Session, closed when the process ends."""
    from multiprocessing.util import Finalize

    from orchestrate.workers.children import die_with_parent

    die_with_parent(driver)
    Finalize(None, close_process_session, exitpriority=10)
    open_process_session()
