"""Benchmark: each contact set solved directly from the subdomains' maps, or iterated
with a coarse-mesh correction, against the plain iterated loop and the monolithic solve
(not a test).

1. Scenes: the paper's (2D coating, b/8, 5E) at mesh levels 1-3 and the example scenes,
   each solved with inner_solve = "iterate", "direct" and "two-level" (Settings), with
   what "auto" chooses, and the paper's scene by the monolithic solve: wall time,
   iterations, the peak contact stress's largest difference from the plain loop's, the
   time to an answer against the monolithic solve's.
2. The figure scenes one after another in one Session (workers kept; no warm start), at
   mesh levels 1-3, default settings: iterations (contact sets, where solved directly,
   as at level 1; Robin iterations with two levels, as finer) per scene, their median
   and maximum; and like for like, two levels at level 1 too (its coarse interfaces'
   elements twice as long): the growth of the Robin iterations from level to level.

    python -m studies.bench_direct     # prints the tables, writes results/direct*.csv
"""

import argparse
import dataclasses
import os
import tempfile
import time

import pandas as pd

from studies.bench_session import SWEEP, one_by_one
from orchestrate.run import monolithic_solution
from studies.paths import RESULTS_DIR
from orchestrate.model import Settings
from orchestrate.paths import SCENES_DIR
from orchestrate.model import load_scene, paper_scene
from orchestrate.workers import Session
from orchestrate.run import solve_into as solve
from orchestrate.sweeps import load_sweep, named_points

LEVELS = (1, 2, 3)
WAYS = ("iterate", "direct", "two-level")


def scenes():
    """(name, scene, settings) of part 1."""
    paper = paper_scene(h2=0.125, E2=5.0, model="elastic")
    cases = [(f"paper 2D b/8 5E, level {level}", paper, Settings(mesh_level=level))
             for level in LEVELS]
    cases.append(("paper shell b/8 E", paper_scene(h2=0.125, E2=1.0, model="shell"),
                  Settings()))
    for name in ("cylinder", "roller", "discrete"):
        scene, values = load_scene(SCENES_DIR / f"{name}.toml")
        cases.append((name, scene, Settings(**values)))
    return cases


def both_ways(out):
    rows = []
    for name, scene, settings in scenes():
        row = {"scene": name, "mesh_level": settings.mesh_level}
        ways = WAYS
        for way in ways + ("auto",):
            summary = solve(scene, dataclasses.replace(settings, inner_solve=way),
                            os.path.join(out, f"{name}-{way}"))
            if way == "auto":
                row["auto_chooses"] = summary["inner_solve_used"]
                continue
            row[f"wall_s_{way}"] = summary["wall_time_s"]
            row[f"iterations_{way}"] = summary["iterations"]
            row[f"peak_{way}"] = summary["peak_contact_stress"]
        best = min(row[f"wall_s_{way}"] for way in ways)
        row["peak_difference"] = max(abs(row[f"peak_{way}"] / row["peak_iterate"] - 1)
                                     for way in ways)
        if name.startswith("paper 2D"):
            start = time.perf_counter()
            monolithic_solution(scene, settings)
            row["wall_s_monolithic"] = time.perf_counter() - start
            row["best_over_monolithic"] = best / row["wall_s_monolithic"]
        rows.append(row)
        print(rows[-1], flush=True)
    return pd.DataFrame(rows)


def figure_scenes(level, inner_solve="auto"):
    """A row per figure scene, solved one after the other in one Session at ``level``."""
    points = [(name, {**values, "mesh_level": level, "inner_solve": inner_solve})
              for name, values in named_points(load_sweep(SWEEP)[1])]
    with Session() as session:
        return one_by_one(points, session).assign(mesh_level=level, inner_solve=inner_solve)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=str(RESULTS_DIR))
    args = parser.parse_args(argv)
    with tempfile.TemporaryDirectory() as out:
        table = both_ways(out)
        figures = pd.concat([figure_scenes(level) for level in LEVELS]
                            + [figure_scenes(1, "two-level")], ignore_index=True)
    with pd.option_context("display.width", 220):
        print(table.to_string(index=False, float_format=lambda v: f"{v:.3g}"))
    counts = figures.groupby(["inner_solve", "mesh_level"]).agg(
        median=("iterations", "median"), maximum=("iterations", "max"),
        direct=("inner_solve_used", lambda used: int((used == "direct").sum())),
        two_level=("inner_solve_used", lambda used: int((used == "two-level").sum())),
        scenes=("scene", "size"), wall_s=("wall_s", "sum"))
    # like for like: two levels' Robin iterations at every level, against level 1's
    two_level = figures[figures.inner_solve_used == "two-level"].groupby("mesh_level")
    growth = two_level["iterations"].median() / two_level["iterations"].median().loc[1] - 1
    counts["two_level_median_growth_from_level_1"] = [
        growth.get(level) if used == "two-level" or level > 1 else None
        for used, level in counts.index]
    print("\nfigure scenes in one session, iterations per scene:\n" + counts.to_string())
    os.makedirs(args.out, exist_ok=True)
    table.to_csv(os.path.join(args.out, "direct.csv"), index=False)
    figures.to_csv(os.path.join(args.out, "direct_figure_scenes.csv"), index=False)


if __name__ == "__main__":
    main()
