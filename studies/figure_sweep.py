"""`make fig3 fig4 fig5` (``python -m studies.figure_sweep [--out DIR] [--jobs N]``): the
sweep of the figures' scenes into results/figures/, each figure drawn as soon as the runs
it draws have converged, by a drawing process beside the sweep. Exit status as a sweep's
(`python -m orchestrate sweep`): 0 every run converged, 1 some did not (their figures are
not drawn), 2 refused, 130/143 interrupted.

The sweep file (studies/sweeps/figures.toml) lists fig. 5's scenes first: it takes
the longest to draw (twice figs. 3 and 4 together), so it is drawn while the other runs
go on; figs. 3 and 4 follow the last run. The sweep's own process imports no plotting
library: it only waits for the runs.

The figures are drawn into a staging folder beside them and put in place together once
all are drawn: a rebuild interrupted leaves the earlier set whole, never a mix of old
and new; a figure that could not be drawn (a run of it did not converge) leaves no
earlier version of itself behind.
"""

import argparse
from concurrent.futures import ProcessPoolExecutor
import importlib
import multiprocessing
import os
from pathlib import Path
import shutil
import sys

from orchestrate.cli import interrupted, stop_on_signals
from orchestrate.errors import EXIT_CONVERGED, EXIT_NOT_CONVERGED, EXIT_REFUSED, ParameterError
from studies.figure_scenes import DRAWS
from studies.paths import FIGURE_SWEEP
from orchestrate.workers import forms_digest
from orchestrate.sweeps import (run_sweep, kill_pool, load_sweep, named_points, point_stamp, read_manifest,
                    run_status, why_stale)


STAGING = ".figures-staging"
FIGURE_FILES = (".png", ".pdf", "_data.csv")    # what studies/figures.py writes of each


def figure_runs(sweep_file, sweep_dir):
    """{figure: the run folders it draws} of the sweep file run into ``sweep_dir``."""
    points = named_points(load_sweep(sweep_file)[1])
    return {figure: [Path(sweep_dir) / "runs" / name for name, values in points
                     if all(values[key] in allowed for key, allowed in draws.items())]
            for figure, draws in DRAWS.items()}


def ready_figures(runs, drawn):
    """The figures of ``runs`` (figure_runs) not in ``drawn`` whose runs have all
    converged as the sweep's points from its inputs now (a run solved before the scene
    or the forms were edited is not ready: it is run again)."""
    forms, manifests = forms_digest(), {}

    def current(folder):
        sweep_dir = folder.parent.parent
        if sweep_dir not in manifests:
            manifests[sweep_dir] = read_manifest(sweep_dir)
        stamp = point_stamp(sweep_dir, folder.name, manifests[sweep_dir])
        return (run_status(folder) == "converged" and stamp is not None
                and why_stale(folder, stamp, forms) is None)
    return [figure for figure, folders in runs.items()
            if figure not in drawn and all(current(folder) for folder in folders)]


def _start_drawing(driver):
    """The drawing process: dies with the driver; imports the plotting modules while the
    first runs run."""
    from orchestrate.workers import die_with_parent
    die_with_parent(driver)
    importlib.import_module("studies.figures")


def _draw(names, folders, out_dir):
    from studies.figures import draw
    return draw(names, folders, out_dir)


class FigureDrawing:
    """Draws the figures of the sweep file ``sweep_file``, run into ``sweep_dir``, into
    ``out_dir``, in a drawing process of its own: ``run_done`` after every run (and once
    before the first) hands it the figures whose runs have all converged, ``finish``
    waits for the drawings and returns the PNG paths; ``close`` kills the process. The
    process draws one batch at a time, the figures of a batch side by side
    (studies/figures.py's draw): those that become ready while it draws wait, and go
    together in the next."""

    def __init__(self, sweep_file, sweep_dir, out_dir):
        self.runs = figure_runs(sweep_file, sweep_dir)
        self.out_dir = Path(out_dir)
        self.staging = self.out_dir / STAGING     # what an interrupted rebuild left goes
        shutil.rmtree(self.staging, ignore_errors=True)
        self.staging.mkdir(parents=True)
        self.pool = ProcessPoolExecutor(1, mp_context=multiprocessing.get_context("spawn"),
                                        initializer=_start_drawing, initargs=(os.getpid(),))
        self.pool.submit(int)              # the process starts now, not at the first figure
        self.drawings = {}                 # figure: the future of its batch, or None: waiting
        self.batches = []
        self.solved = set()                # the runs reported done

    def run_done(self, name=None):
        if name in self.solved:            # solved again (forms edited during the sweep):
            for figure, folders in self.runs.items():    # its figures are drawn again
                if any(Path(folder).name == name for folder in folders):
                    self.drawings.pop(figure, None)
        self.solved.add(name)
        ready = ready_figures(self.runs, self.drawings)
        self.drawings.update((figure, None) for figure in ready)
        if not self.batches or self.batches[-1].done():
            self._draw_waiting()

    def _draw_waiting(self):
        waiting = [figure for figure, future in self.drawings.items() if future is None]
        if waiting:
            folders = sorted({str(folder) for figure in waiting
                              for folder in self.runs[figure]})
            self.batches.append(self.pool.submit(_draw, waiting, folders, str(self.staging)))
            self.drawings.update((figure, self.batches[-1]) for figure in waiting)

    def finish(self):
        """Once every figure is drawn, put them in place together; return the PNG paths
        of those drawn. Raises if a drawing failed (the earlier set then stays whole)."""
        while self.batches:
            self.batches.pop(0).result()
            if not self.batches:
                self._draw_waiting()
        drawn = [figure for figure, batch in self.drawings.items() if batch is not None]
        for figure in self.runs:
            for suffix in FIGURE_FILES:
                staged = self.staging / f"{figure}{suffix}"
                target = self.out_dir / f"{figure}{suffix}"
                if figure in drawn:
                    os.replace(staged, target)
                else:
                    target.unlink(missing_ok=True)      # drawn from runs no longer there
        return [str(self.out_dir / f"{figure}.png") for figure in drawn]

    def close(self):
        """Kill the drawing process, busy or not (an idle one takes half a second to
        exit), and remove the staging folder: what it held was not put in place."""
        kill_pool(self.pool)
        shutil.rmtree(self.staging, ignore_errors=True)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--jobs", type=int, help="runs at once (default: one per core)")
    parser.add_argument("--out", default="results",
                        help="folder of the figures and of their runs (default: results/)")
    args = parser.parse_args(argv)
    stop_on_signals()
    out = Path(args.out)
    runs = out / "figures"
    try:
        with FigureDrawing(FIGURE_SWEEP, runs, out) as drawing:
            table = run_sweep(FIGURE_SWEEP, runs, jobs=args.jobs, run_done=drawing.run_done)
            counts = table["status"].value_counts().to_dict()
            print(f"{len(table)} runs: " + ", ".join(f"{n} {s}"
                                                     for s, n in sorted(counts.items())))
            for path in drawing.finish():
                print(path)
    except ParameterError as error:
        print(f"error: {error}", file=sys.stderr)
        return EXIT_REFUSED
    except KeyboardInterrupt as error:
        print("finished runs are kept; run it again to resume", file=sys.stderr)
        return interrupted(error)
    return EXIT_CONVERGED if set(counts) <= {"converged"} else EXIT_NOT_CONVERGED


if __name__ == "__main__":
    sys.exit(main())
