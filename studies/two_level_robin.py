"""The Robin parameter with two levels, against the mesh level (``python -m
studies.two_level_robin``, ``make two-level-robin``).

With two levels the fine loop's gamma is robin_two_level_per_length over the element
length at mesh level 1 (Settings.robin_choice): the stiffness of the shortest waves the
coarse level sees, the same at every mesh level. The coarse level removes the waves
longer than its element H; the fine loop's Robin exchange is left the band from H down
to the fine element h, and a one-sided Robin coefficient contracts a band fastest at
the geometric mean of its ends' stiffnesses, gamma ~ E / sqrt(h H), which grows as the
mesh refines (the one-level rule's square root of the mesh level, for the same reason).
This study measures both rules: "element", the default, and "band", the default's value
at mesh level 1 scaled by sqrt(h1 H1 / (h H)) (h1, H1: the fine and coarse elements at
mesh level 1, where the coarse elements are coarse_element_factor times longer).

Scenes: the gallery's pads (auto takes two levels there at every mesh level), the
paper's scene (2D coating b/8 of 5 E; the Timoshenko shell b/8 of E) and the discrete
example, whose coarse levels pay (auto takes two levels on them from mesh level 2).
Each at mesh levels 1 to 3 (``--levels``) with two levels, the bonds as auto takes them
under two levels (exchanged) and inside the base's worker; from a cold start, one run
each. A row: the Robin iterations of the final contact set, the contact sets, all
iterations, the time to answer. And the paper's 24 figure scenes at mesh levels 2 and 3
(``--figure-levels``), where auto takes two levels, under each rule, one Session per
level and rule (workers kept from scene to scene, as a sweep keeps them): their
iterations and wall time. The findings: per scene, way of the bonds and rule, the final
set's iterations level by level, their growth and time; the figure scenes' iterations
and time under each rule.

Writes results/two_level_robin.csv, two_level_robin_figures.csv and
results/two_level_robin.md.
"""

import argparse
from dataclasses import replace
import math
import os

import pandas as pd

from orchestrate.ddm import coarse_element_size
from orchestrate.model import Settings, load_scene, paper_scene, scene_and_settings
from orchestrate.paths import SCENES_DIR
from studies.bench_direct import figure_scenes
from studies.iterations import counted_run
from studies.paths import RESULTS_DIR, gallery_files
from studies.report import (Column, Report, command_line, print_table, progress_to_stderr,
                            save_table, seconds, significant)

RULES = ("element", "band")
BONDS = ("exchanged", "inside")


def scenes():
    """{name: (scene, settings)} of the study."""
    pads = scene_and_settings(gallery_files(["patches_and_bare_base"])[0])
    discrete, values = load_scene(SCENES_DIR / "discrete.toml")
    return {"pads (gallery)": pads,
            "paper, 2D coating b/8 5E": (paper_scene(h2=0.125, E2=5.0, model="elastic"),
                                         Settings()),
            "paper, shell b/8 E": (paper_scene(h2=0.125, E2=1.0, model="shell"), Settings()),
            "discrete example": (discrete, Settings(**values))}


def band_factor(settings):
    """sqrt(h1 H1 / (h H)): the band rule's gamma over the element rule's at the
    settings' mesh level (h, H: the fine and coarse interface elements)."""
    def product(level):
        at = replace(settings, mesh_level=level)
        return (at.element_length / level) * coarse_element_size(at)
    return math.sqrt(product(1) / product(settings.mesh_level))


def two_level_settings(settings, level, rule, bonds):
    at = replace(settings, mesh_level=level, inner_solve="two-level", bonds=bonds)
    if rule == "band":
        at = replace(at, robin_two_level_per_length=at.robin_two_level_per_length
                     * band_factor(at))
    return at


def figure_study(out, levels=(2, 3), progress=print):
    """The figure scenes at each of ``levels`` with two levels under each rule, one after
    the other in one Session per level and rule (studies.bench_direct.figure_scenes)."""
    tables = []
    for level in levels:
        for rule in RULES:
            per_length = two_level_settings(Settings(), level, rule,
                                            "auto").robin_two_level_per_length
            tables.append(figure_scenes(level, "two-level",
                                        robin_two_level_per_length=per_length)
                          .assign(rule=rule))
            progress(f"figure scenes level {level} {rule}")
    table = pd.concat(tables, ignore_index=True)
    save_table(table, out)
    return table


def study(out, levels=(1, 2, 3), progress=print):
    rows = []
    for name, (scene, settings) in scenes().items():
        for bonds in BONDS:
            for level in levels:
                for rule in RULES:
                    if rule == "band" and level == 1:
                        continue            # the same gamma as the element rule's
                    at = two_level_settings(settings, level, rule, bonds)
                    row = {"scene": name, "bonds": bonds, "mesh_level": level, "rule": rule,
                           "per_length": at.robin_two_level_per_length,
                           **counted_run(scene, at)}
                    progress(f"{name} bonds {bonds} level {level} {rule}: {row['status']}")
                    rows.append(row)
    table = pd.DataFrame(rows)
    # the band rule at mesh level 1 is the element rule's run
    first = table[(table.mesh_level == min(levels)) & (table.rule == "element")]
    if min(levels) == 1:
        table = pd.concat([table, first.assign(rule="band")], ignore_index=True)
    save_table(table, out)
    return table


def write_report(table, figures, out, command="python -m studies.two_level_robin"):
    stem = os.path.basename(os.path.splitext(out)[0])
    report = Report("The Robin parameter with two levels, against the mesh level", command,
                    data=[f"{stem}.csv"] + ([f"{stem}_figures.csv"] if figures is not None
                                            else []))
    report.text("Each scene with two levels (inner_solve = two-level), its bonds exchanged "
                "(as auto takes them under two levels) and inside the base's worker, under "
                "two rules for the fine loop's gamma: 'element', the default "
                "(robin_two_level_per_length over the element length at mesh level 1, at "
                "every level), and 'band', the default's value at mesh level 1 times "
                "sqrt(h1 H1 / (h H)), h and H the fine and coarse interface elements (the "
                "geometric mean of the band the coarse level leaves to the fine loop). At "
                "mesh level 1 both rules are one run. From a cold start on this machine, "
                "one run each.")
    report.table(table.sort_values(["scene", "bonds", "rule", "mesh_level"]), [
        Column("scene", "scene"), Column("bonds", "bonds"), Column("rule", "rule"),
        Column("mesh_level", "level", "{:.0f}"),
        Column("per_length", "gamma x element", "{:.3g}", "robin_two_level_per_length, E: "
               "the fine loop's gamma times the element length at mesh level 1 (the "
               "scene's mesh sized to its contact)"),
        Column("status", "outcome"),
        Column("final_set", "final set", "{:.0f}", "Robin iterations of the final contact set"),
        Column("sets", "sets", "{:.0f}", "contact sets"),
        Column("iterations", "iterations", "{:.0f}", "all Robin iterations"),
        Column("time_s", "time", seconds, "time to answer, workers started for it")])
    converged = table[table.status == "converged"]
    for (scene, bonds), runs in converged.groupby(["scene", "bonds"], sort=False):
        parts = []
        for rule in RULES:
            own = runs[runs.rule == rule].sort_values("mesh_level")
            if own.empty:
                continue
            counts = "/".join(f"{n:.0f}" for n in own.final_set)
            growth = own.final_set.iloc[-1] / own.final_set.iloc[0] - 1
            parts.append(f"{rule} {counts} ({growth:+.0%} from level "
                         f"{own.mesh_level.iloc[0]:.0f} to {own.mesh_level.iloc[-1]:.0f}, "
                         f"{significant(own.time_s.sum())} s in all)")
        report.finding(f"{scene}, bonds {bonds}: final contact set at each level, "
                       + "; ".join(parts) + ".")
    failed = table[table.status != "converged"]
    if len(failed):
        report.finding("Not converged: " + ", ".join(
            f"{row.scene} bonds {row.bonds} level {row.mesh_level} {row.rule} ({row.status})"
            for row in failed.itertuples()) + ".")
    if figures is not None and len(figures):
        report.section("The figure scenes")
        report.text("The paper's 24 figure scenes (studies/sweeps/figures.toml) with two "
                    "levels, one after the other in one Session per mesh level and rule.")
        counts = figures.groupby(["mesh_level", "rule"]).agg(
            median=("iterations", "median"), maximum=("iterations", "max"),
            total=("iterations", "sum"), wall_s=("wall_s", "sum"),
            scenes=("scene", "size")).reset_index()
        report.table(counts, [
            Column("mesh_level", "level", "{:.0f}"), Column("rule", "rule"),
            Column("median", "median", "{:g}", "Robin iterations per scene"),
            Column("maximum", "most", "{:.0f}"), Column("total", "all", "{:.0f}"),
            Column("wall_s", "wall, all scenes", seconds), Column("scenes", "scenes", "{:.0f}")])
        for level, runs in counts.groupby("mesh_level"):
            by_rule = runs.set_index("rule")
            if set(RULES) <= set(by_rule.index):
                element, band = by_rule.loc["element"], by_rule.loc["band"]
                report.finding(
                    f"Figure scenes at mesh level {level:.0f}: median {element['median']:g} "
                    f"iterations under the element rule, {band['median']:g} under the band "
                    f"rule; all scenes {significant(element.wall_s)} s against "
                    f"{significant(band.wall_s)} s.")
    return report.write(out)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default=str(RESULTS_DIR / "two_level_robin.csv"),
                        help="the table; the report goes beside it (two_level_robin.md)")
    parser.add_argument("--levels", type=int, nargs="+", default=[1, 2, 3])
    parser.add_argument("--figure-levels", type=int, nargs="*", default=[2, 3],
                        help="the figure scenes' mesh levels (none: leave them out)")
    args = parser.parse_args(argv)
    table = study(args.out, args.levels, progress=progress_to_stderr)
    stem = os.path.splitext(args.out)[0]
    figures = (figure_study(f"{stem}_figures.csv", args.figure_levels,
                            progress=progress_to_stderr) if args.figure_levels else None)
    print_table(table)
    print(write_report(table, figures, stem + ".md",
                       command_line("studies.two_level_robin", argv)))


if __name__ == "__main__":
    main()
