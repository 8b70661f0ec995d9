"""`make fig3 fig4 fig5` (``python -m orchestrate figures``): the sweep of the figures'
scenes into results/figures/, each figure drawn as soon as the runs it draws have
converged, by a drawing process beside the sweep.

The sweep file (orchestrate/sweeps/figures.toml) lists the 2D coating's scenes first:
fig. 5 draws them alone, and takes the longest to draw (twice figs. 3 and 4 together),
so it is drawn while the shell's runs go on; figs. 3 and 4 follow the last run. The
sweep's own process imports no plotting library: it only waits for the runs.
"""

from concurrent.futures import ProcessPoolExecutor
import importlib
import multiprocessing
import os
from pathlib import Path

from .sweep import kill_pool, load_sweep, named_points, run_status

# The coating models whose runs each figure draws (orchestrate/figures.py).
DRAWS = {"fig3": ("shell", "elastic"), "fig4": ("shell", "elastic"), "fig5": ("elastic",)}


def figure_runs(sweep_file, sweep_dir):
    """{figure: the run folders it draws} of the sweep file run into ``sweep_dir``."""
    points = named_points(load_sweep(sweep_file)[1])
    return {figure: [Path(sweep_dir) / "runs" / name for name, values in points
                     if values["model"] in models]
            for figure, models in DRAWS.items()}


def ready_figures(runs, drawn):
    """The figures of ``runs`` (figure_runs) not in ``drawn`` whose runs have all
    converged."""
    return [figure for figure, folders in runs.items() if figure not in drawn
            and all(run_status(folder) == "converged" for folder in folders)]


def _start_drawing(driver):
    """The drawing process: dies with the driver; imports the plotting modules while the
    first runs run."""
    from .worker import die_with_parent
    die_with_parent(driver)
    importlib.import_module("orchestrate.figures")


def _draw(names, folders, out_dir):
    from .figures import draw
    return draw(names, folders, out_dir)


class FigureDrawing:
    """Draws the figures of the sweep file ``sweep_file``, run into ``sweep_dir``, into
    ``out_dir``: ``run_done`` after every run (and once before the first) submits each
    figure whose runs have all converged; ``finish`` waits for the drawings and returns
    the PNG paths. A drawing process of its own, killed on ``close`` if still busy."""

    def __init__(self, sweep_file, sweep_dir, out_dir):
        self.runs = figure_runs(sweep_file, sweep_dir)
        self.out_dir = str(out_dir)
        self.pool = ProcessPoolExecutor(1, mp_context=multiprocessing.get_context("spawn"),
                                        initializer=_start_drawing, initargs=(os.getpid(),))
        self.pool.submit(int)              # the process starts now, not at the first figure
        self.drawings = {}

    def run_done(self, name=None):
        ready = ready_figures(self.runs, self.drawings)
        if ready:              # figures ready together are drawn together, side by side
            future = self.pool.submit(_draw, ready, sorted({str(folder) for figure in ready
                                                            for folder in self.runs[figure]}),
                                      self.out_dir)
            self.drawings.update((figure, future) for figure in ready)

    def finish(self):
        """The PNG paths of the figures drawn, once all are; raises if a drawing failed."""
        return [path for future in dict.fromkeys(self.drawings.values())
                for path in future.result()]

    def close(self):
        if all(future.done() for future in self.drawings.values()):
            self.pool.shutdown()
        else:
            kill_pool(self.pool)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
