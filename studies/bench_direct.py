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

Writes results/direct.csv, direct_figure_scenes.csv and the report results/direct.md.

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
from studies.report import Column, Report, command_line, listing, seconds
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


def figure_scenes(level, inner_solve="auto", **settings):
    """A row per figure scene, solved one after the other in one Session at ``level``
    (and any other ``settings``)."""
    points = [(name, {**values, "mesh_level": level, "inner_solve": inner_solve, **settings})
              for name, values in named_points(load_sweep(SWEEP)[1])]
    with Session() as session:
        return one_by_one(points, session).assign(mesh_level=level, inner_solve=inner_solve)


def iteration_counts(figures):
    """Per inner solve asked and mesh level: the figure scenes' iterations (median,
    maximum), how each was solved, and the summed wall time."""
    return figures.groupby(["inner_solve", "mesh_level"]).agg(
        median=("iterations", "median"), maximum=("iterations", "max"),
        direct=("inner_solve_used", lambda used: int((used == "direct").sum())),
        two_level=("inner_solve_used", lambda used: int((used == "two-level").sum())),
        scenes=("scene", "size"), wall_s=("wall_s", "sum")).reset_index()


def _way(row, way, count="it."):
    wall, iterations = row.get(f"wall_s_{way}"), row.get(f"iterations_{way}")
    return "" if wall is None or wall != wall else f"{wall:.2f} s ({iterations:g} {count})"


def write_report(table, figures, out, command="python -m studies.bench_direct"):
    report = Report("Each contact set solved directly, iterated, or with two levels", command,
                    data=["direct.csv", "direct_figure_scenes.csv"])
    report.section("Time to an answer")
    report.text("Each scene solved with each inner solve (one run each, a shared 2-core "
                "machine); the paper's scene (2D coating, b/8, 5E) also by the monolithic "
                "solve.")
    report.table(table, [
        Column("scene", "scene"), Column("mesh_level", "mesh level", "{:g}"),
        Column(lambda r: _way(r, "iterate"), "plainly iterated",
               meaning="wall time (Robin iterations)"),
        Column(lambda r: _way(r, "direct", "contact sets"), "direct",
               meaning="wall time (contact sets, each solved directly)"),
        Column(lambda r: _way(r, "two-level"), "two levels", meaning="wall time (Robin "
               "iterations with the coarse-mesh correction)"),
        Column("wall_s_monolithic", "monolithic", seconds),
        Column("auto_chooses", "auto chooses"),
        Column("peak_difference", "peaks apart", "{:.1e}", "the largest relative "
               "difference of a way's peak contact stress from the plainly iterated one's")])
    paper = table[table.scene.str.startswith("paper 2D")].sort_values("mesh_level")
    if len(paper):
        fastest = [min(("iterate", "direct", "two-level"), key=lambda w: r[f"wall_s_{w}"])
                   for _, r in paper.iterrows()]
        finest = paper.iloc[-1]
        report.finding(
            "On the paper's scene the fastest way is "
            + listing(f"{way} at level {level:g}" for way, level in zip(fastest, paper.mesh_level))
            + f"; at level {finest.mesh_level:g} two levels take "
            f"{finest['wall_s_two-level'] / finest.wall_s_monolithic:.2f} of the monolithic "
            f"solve's time. `auto` chose " + listing(
                f"{r.auto_chooses} at level {r.mesh_level:g}" for r in paper.itertuples())
            + f". Every way's peak is the plain loop's within "
            f"{table.peak_difference.max():.1e}.")
    if len(figures):
        counts = iteration_counts(figures)
        report.section("The figure scenes, level by level")
        report.text("The figure scenes one after another in one Session (workers kept, no "
                    "warm start), default settings (`auto`), and two levels at level 1 too, "
                    "like for like.")
        report.table(counts, [
            Column("inner_solve", "inner solve asked"), Column("mesh_level", "mesh level", "{:g}"),
            Column("median", "median", "{:g}", "iterations per scene: contact sets where "
                   "solved directly, Robin iterations with two levels"),
            Column("maximum", "maximum", "{:g}"),
            Column("direct", "direct", "{:g}", "scenes solved directly"),
            Column("two_level", "two levels", "{:g}", "scenes solved with two levels"),
            Column("scenes", "scenes", "{:g}"), Column("wall_s", "wall, all scenes", seconds)])
        two = figures[figures.inner_solve_used == "two-level"].groupby("mesh_level").iterations
        if len(two.median()) > 1:
            report.finding(
                "Counted like for like, two levels at every level, the figure scenes' Robin "
                "iterations have medians " + listing(f"{m:g}" for m in two.median())
                + f" at levels {listing(f'{l:g}' for l in two.median().index)}, at most "
                + listing(f"{m:g}" for m in two.max()) + ": "
                + ("they do not grow with the mesh." if two.median().iloc[-1]
                   <= 1.25 * two.median().iloc[0] else "they grow with the mesh."))
        one = figures[figures.mesh_level == 1]
        pair = one[one.inner_solve == "two-level"].merge(
            one[one.inner_solve == "auto"], on="scene", suffixes=("_two", "_auto"))
        if len(pair):
            apart = (pair.peak_contact_stress_two / pair.peak_contact_stress_auto - 1).abs()
            report.finding(f"On the paper's mesh the two-level peaks are the default run's "
                           f"within {apart.max():.1e} (relative).")
    return report.write(out)


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
    print("\nfigure scenes in one session, iterations per scene:\n"
          + iteration_counts(figures).to_string())
    os.makedirs(args.out, exist_ok=True)
    table.to_csv(os.path.join(args.out, "direct.csv"), index=False)
    figures.to_csv(os.path.join(args.out, "direct_figure_scenes.csv"), index=False)
    print(write_report(table, figures, os.path.join(args.out, "direct.md"),
                       command_line("studies.bench_direct", argv)))


if __name__ == "__main__":
    main()
