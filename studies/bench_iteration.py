"""Benchmark: where the time of one Robin iteration goes (not a test).

Runs the default scene (shell model, h2 = b/8, E2 = E, mesh level 1) with each loop and
splits the wall time per iteration into the workers' solves (CPU seconds each worker
reports; the three run at once, on 2 cores here) and the driver (everything outside
the wait for the replies: Robin data, acceleration, bookkeeping), and compares an
iteration with one back-substitution of the largest subdomain (its factorised solve
alone). Iterations with a new contact set are counted apart: the paper's loop
refactorises Omega1's and the coating's matrices there, the active-set loop does not.

    python -m studies.bench_iteration            # prints a table, writes CSV
"""

import argparse
import os
import tempfile

import numpy as np
import pandas as pd

from studies.paths import RESULTS_DIR
from orchestrate.model import Settings
from orchestrate.model import paper_scene
from orchestrate.run import RunFailed, solve_into as solve


def measure(settings, label):
    with tempfile.TemporaryDirectory() as out:
        try:
            solve(paper_scene(), settings, out)
        except RunFailed:
            pass                      # the paper's loop does not converge: time it anyway
        history = pd.read_csv(os.path.join(out, "history.csv"))
    wall = np.diff(np.concatenate([[0.0], history["seconds"].to_numpy()]))
    rows = []
    for kind, mask in (("steady", ~history["active_set_changed"]),
                       ("new contact set", history["active_set_changed"])):
        part = history[mask]
        if len(part) == 0:
            continue
        iteration = wall[mask.to_numpy()].mean()
        wait = part["wait"].mean()
        rows.append({
            "loop": label, "iterations": kind, "count": len(part),
            "ms_per_iteration": 1e3 * iteration,
            "ms_omega1": 1e3 * part["cpu_indenter"].mean(),
            "ms_coating": 1e3 * part["cpu_coating1"].mean(),
            "ms_omega3": 1e3 * part["cpu_base"].mean(),
            "ms_waiting_for_workers": 1e3 * wait,
            "ms_python": 1e3 * (iteration - wait),
            "python_share": (iteration - wait) / iteration,
            "ms_backsubstitution_omega1": 1e3 * part["back_indenter"].mean(),
            "ms_backsubstitution_omega3": 1e3 * part["back_base"].mean(),
            "iteration_over_backsubstitution": iteration / max(part["back_indenter"].mean(),
                                                              part["back_base"].mean()),
        })
    return rows


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default=str(RESULTS_DIR / "bench_iteration.csv"))
    args = parser.parse_args(argv)
    rows = measure(Settings(), "active-set (default)")
    rows += measure(Settings(method="paper", max_iterations=400), "paper (400 iterations)")
    table = pd.DataFrame(rows)
    os.makedirs(os.path.dirname(args.out), exist_ok=True)
    table.to_csv(args.out, index=False)
    with pd.option_context("display.width", 200, "display.float_format", "{:.2f}".format):
        print(table.to_string(index=False))
    print(f"\nwritten to {args.out}")


if __name__ == "__main__":
    main()
