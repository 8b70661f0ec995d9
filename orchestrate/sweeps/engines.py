"""The engines that run a sweep's pending points: local worker processes, or Dask
distributed; and the progress line."""

import concurrent.futures
import multiprocessing
import os
from pathlib import Path
import sys
import time

from orchestrate.files.folders import remove_dead_work_folders
from orchestrate.sweeps.manifest import run_status
from orchestrate.sweeps.point import (close_process_session, open_process_session, run_point,
                                      worker_init, write_report)

ATTEMPTS = 2           # a run whose worker process dies when alone is tried this often


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
                                                      initializer=worker_init,
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
                    progress.update(done=1, failed=failed(sweep_dir, name),
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


def keep_workers_plugin():
    """A Dask worker plugin: each Dask worker keeps a Session from run to run, as a local
    pool's process does, so that a cluster's marginal cost per scene is a local one's
    (the indenter's and the base's FreeFEM workers taken over where they are the same)."""
    from distributed.diagnostics.plugin import WorkerPlugin

    class KeepWorkers(WorkerPlugin):
        name = "orchestrate-keep-workers"

        def setup(self, worker):
            open_process_session()

        def teardown(self, worker):
            close_process_session()

    return KeepWorkers()


def run_dask(pending, sweep_dir, scene_dir, jobs, progress, scheduler=None, retry_failed=False,
             neighbours=None, run_done=lambda name=None: None, sweep_id=None):
    """Dask distributed: a local cluster of ``jobs`` workers, or a scheduler's, each
    keeping its FreeFEM workers from run to run (keep_workers_plugin). A task whose
    workers keep dying (Dask retries it) is recorded as failed."""
    from dask.distributed import Client, LocalCluster, as_completed
    from distributed import KilledWorker

    cluster = None if scheduler else LocalCluster(
        n_workers=jobs, threads_per_worker=1, processes=True, dashboard_address=None)
    client = Client(scheduler or cluster)
    client.register_plugin(keep_workers_plugin())
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
            progress.update(done=1, failed=failed(sweep_dir, name),
                            running=min(jobs, len(futures) - returned))
            run_done(name)
    finally:
        client.close()
        if cluster is not None:
            cluster.close()


def failed(sweep_dir, name):
    return int(run_status(Path(sweep_dir) / "runs" / name) != "converged")
