"""Iterations per contact set on the gallery's scenes, against the mesh level: what the
Robin loop's inner solve costs where it iterates, on one level with the coatings inside
the base's worker at the default split of the sides (Settings.bonds "inside",
contact_split and bond_split: the defaults where the loop iterates), at the earlier
defaults (the coatings exchanged across their bonds, the sides split by 4), exchanged
with a contact's and a bond's sides unsplit (1), and with two levels (inner_solve
"two-level", the coatings inside the base's worker; ``python -m studies.iterations``,
``make iterations``).

Every scene of orchestrate/scenes/gallery/ whose mesh the machine takes is solved in
each variant at mesh levels 1 to 3 (``--levels``), from a cold start, one run each. A
row: the Robin iterations of the final contact set (the linear iterations that set's
fixed point took) and the most any set took, the contact sets, all iterations, the time
to answer and the unknowns. The table's findings: the largest final-set count at each
level and its growth from the first level to the last, per variant, and each variant's
time against the one-level default's.

Writes results/iterations.csv and results/iterations.md.
"""

import argparse
from dataclasses import replace
import os
import time

import pandas as pd

import orchestrate
from orchestrate.errors import ParameterError
from orchestrate.model import scene_and_settings
from orchestrate.run import RunFailed
from studies.paths import RESULTS_DIR, gallery_files
from studies.report import (Column, Report, command_line, print_table, progress_to_stderr,
                            report_beside, save_table, seconds, significant)

# Each variant's settings: on one level the default split with the coatings inside, the
# earlier defaults (split 4, exchanged), and exchanged unsplit; two levels, the coatings
# inside (their sides held, unsplit)
ONE_LEVEL = "inside"
VARIANTS = {
    ONE_LEVEL: {"inner_solve": "iterate", "bonds": "inside"},
    "split 4, exchanged": {"inner_solve": "iterate", "bonds": "exchanged",
                           "contact_split": 4.0, "bond_split": 4.0},
    "exchanged, unsplit": {"inner_solve": "iterate", "bonds": "exchanged",
                           "contact_split": 1.0, "bond_split": 1.0},
    "two levels": {"inner_solve": "two-level", "bonds": "inside"},
}


def counted_run(scene, settings):
    """A run's row of counts: status, time to answer, and where it converged the final
    contact set's iterations, the most of any set, the sets, all iterations, the inner
    solve used, the unknowns and whether its bonds ran inside a worker. A mesh the
    machine does not take is a row too ("refused: KEY")."""
    started = time.perf_counter()
    try:
        result = orchestrate.solve(scene, settings)
    except RunFailed as failed:
        return {"status": failed.summary.get("status"), "time_s": time.perf_counter() - started}
    except ParameterError as refused:
        return {"status": f"refused: {refused.key}"}
    per_set = result.history.groupby("active_set_update").size().tolist()
    summary = result.summary
    return {"status": "converged", "time_s": time.perf_counter() - started,
            "final_set": per_set[-1], "largest_set": max(per_set), "sets": len(per_set),
            "iterations": summary["iterations"], "inner_solve": summary["inner_solve_used"],
            "unknowns": sum(summary["dofs"].values()),
            "inside": bool(summary["strategy"]["bonds_inside"])}


def measure(path, level, variant):
    """One scene's run at one mesh level, one variant: its row."""
    scene, settings = scene_and_settings(path)
    row = {"scene": path.stem, "mesh_level": level, "variant": variant}
    return {**row, **counted_run(scene, replace(settings, mesh_level=level,
                                                **VARIANTS[variant]))}


def study(out, names=None, levels=(1, 2, 3), progress=print):
    rows = []
    for path in gallery_files(names):
        for level in levels:
            for variant in VARIANTS:
                row = measure(path, level, variant)
                progress(f"{path.stem} level {level} {variant}: {row['status']}")
                rows.append(row)
    table = pd.DataFrame(rows)
    save_table(table, out)
    return table


def write_report(table, out, command="python -m studies.iterations"):
    report = Report("Iterations per contact set against the mesh level", command,
                    data=[os.path.basename(os.path.splitext(out)[0]) + ".csv"])
    report.text("Each gallery scene iterated on one level (inner_solve = iterate), its "
                "coatings inside the base's worker (bonds = inside; a scene whose patch is "
                "thicker than the contact keeps them exchanged: 'inside' says which ran) "
                "at the default split of the sides; at the earlier defaults, exchanged "
                "across their bonds with the sides split by 4 (contact_split = bond_split "
                "= 4); exchanged with a contact's two sides "
                "given the neighbour rule's coefficients unsplit and a bond's split by the "
                "coating's response alone (contact_split = bond_split = 1: "
                "docs/method.md, Robin parameters); and with two levels "
                "(inner_solve = two-level, bonds = inside: every side held and unsplit, "
                "docs/method.md, Two levels); from a cold start on this machine, one run "
                "each.")
    report.table(table, [
        Column("scene", "scene"), Column("mesh_level", "level", "{:.0f}"),
        Column("variant", "variant"), Column("status", "outcome"),
        Column("final_set", "final set", "{:.0f}", "Robin iterations of the final contact set"),
        Column("largest_set", "largest set", "{:.0f}", "the most of any contact set"),
        Column("sets", "sets", "{:.0f}", "contact sets"),
        Column("iterations", "iterations", "{:.0f}", "all Robin iterations"),
        Column("time_s", "time", seconds, "time to answer, workers started for it"),
        Column("unknowns", "unknowns", "{:.0f}", "the workers' unknowns"),
        Column("inside", "inside", "{}", "whether the run solved its bonds inside")])
    converged = table[table.status == "converged"]
    baseline = converged[converged.variant == ONE_LEVEL].set_index(["scene", "mesh_level"])
    for variant in VARIANTS:
        runs = converged[converged.variant == variant]
        if runs.empty:
            continue
        worst = runs.groupby("mesh_level").final_set.max()
        levels = list(worst.index)
        growth = worst.iloc[-1] / worst.iloc[0] - 1
        text = (f"{variant}: the final contact set took at most "
                + ", ".join(f"{worst[level]:.0f} (level {level})" for level in levels)
                + f" iterations; {significant(100 * growth, 2)} % more from level "
                f"{levels[0]} to {levels[-1]}. Median time at level {levels[0]}: "
                f"{significant(runs[runs.mesh_level == levels[0]].time_s.median())} s.")
        # issue 28's bound: at most 30 iterations, and less than 20 % growth from the
        # first level
        per_scene = runs.pivot_table(index="scene", columns="mesh_level", values="final_set")
        outside = [f"{scene} ({'/'.join(f'{n:.0f}' for n in row.dropna())})"
                   for scene, row in per_scene.iterrows()
                   if row.max() > 30 or row.max() > 1.2 * row.iloc[0]]
        text += (f" Scenes whose final set exceeds 30 or grows by 20 % or more from the "
                 f"first level: {', '.join(outside) if outside else 'none'}.")
        if variant != ONE_LEVEL:
            ratios = (runs.set_index(["scene", "mesh_level"]).time_s
                      / baseline.time_s).dropna().groupby("mesh_level")
            text += (" Its time over the one-level run's (inside), per level, median "
                     "(least-most): " + ", ".join(
                         f"level {level} {significant(r.median())} "
                         f"({significant(r.min())}-{significant(r.max())})"
                         for level, r in ratios) + ".")
        report.finding(text)
    failed = table[table.status != "converged"]
    if len(failed):
        report.finding("Not converged or refused: " + ", ".join(
            f"{row.scene} level {row.mesh_level} {row.variant} ({row.status})"
            for row in failed.itertuples()) + ".")
    return report.write(out)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default=str(RESULTS_DIR / "iterations.csv"),
                        help="the table; the report goes beside it (iterations.md)")
    parser.add_argument("--levels", type=int, nargs="+", default=[1, 2, 3])
    parser.add_argument("names", nargs="*", help="scenes of the gallery (default: all)")
    args = parser.parse_args(argv)
    table = study(args.out, args.names, args.levels,
                  progress=progress_to_stderr)
    print_table(table)
    print(write_report(table, report_beside(args.out),
                       command_line("studies.iterations", argv)))


if __name__ == "__main__":
    main()
