"""How many interface elements a contact needs: the answers' error against the elements
across the contact zone, the study behind the resolution limits of
orchestrate/run/validity.py (``python -m studies.resolution``, results/resolution.csv).

Each scene is solved with interface elements of decreasing length (element_size), so
that its a priori contact width 2a (orchestrate/model/estimate.py's estimate, mirrored in
a half model) spans from 2 to 48 elements; the answers (peak contact pressure, the
bond's peak compression and shear away from the patch ends, the coating's largest
stress) are compared with those of the finest run, 96 elements across. The scenes: the
paper's (a parabolic indenter on a 2 b patch, both coating models) and a cylinder of
radius 20 b on a stiff patch under a force (orchestrate/scenes/cylinder.toml).

Writes results/resolution.csv and results/resolution.md: the worst error over the scenes
per resolution, and the resolution from which the peak pressure and the coating's
largest stress stay within the accuracies TARGETS asks, the number the warnings' limit
(ELEMENTS_ACROSS) rests on.
"""

import argparse
import math
import os
import sys

import pandas as pd

from orchestrate.model import Settings, contact_half_width, load_scene, paper_scene
from orchestrate.paths import SCENES_DIR
from studies.paths import RESULTS_DIR
from studies.report import Column, Report, command_line, listing, percent, save_table

ACROSS = (2, 3, 4, 6, 8, 10, 12, 16, 24, 32, 48)
REFERENCE_ACROSS = 96
ANSWERS = {"peak_pressure": ("contact", None, "peak_pressure"),
           "bond_compression": ("bonds", "bond-coating1", "compression"),
           "bond_shear": ("bonds", "bond-coating1", "shear")}
# The accuracy a run on the warnings' limit is to give (chosen): the peak pressure within
# 0.2 %, the coating's largest stress within 1 % of the converged answer
TARGETS = {"peak_pressure_error": 0.002, "coating_stress_error": 0.01}
SHEAR_WITHIN = 0.02      # where the bond's peak shear settles, for the report
QUANTITIES = {"peak_pressure_error": "peak pressure",
              "bond_compression_error": "bond's peak compression",
              "bond_shear_error": "bond's peak shear",
              "coating_stress_error": "coating's largest stress"}


def scenes():
    cylinder, _ = load_scene(SCENES_DIR / "cylinder.toml")
    return {"paper, shell": paper_scene(model="shell"),
            "paper, 2D coating": paper_scene(model="elastic"),
            "cylinder R = 20 b, shell": cylinder}


def _value(answers, group, owner, quantity):
    found = answers[group] if owner is None else answers[group][owner]
    extreme = found.get(quantity)
    return abs(extreme["value"]) if extreme else math.nan


def _coating_stress(answers):
    values = [abs(e["value"]) for q, e in answers["coatings"]["coating1"].items()
              if q != "at_patch_ends" and e]
    return max(values) if values else math.nan


def study(out, progress=print):
    import orchestrate

    rows = []
    for name, scene in scenes().items():
        width = 2.0 * contact_half_width(scene)         # the whole contact (mirrored)
        found = {}
        for across in (REFERENCE_ACROSS,) + ACROSS:
            settings = Settings(element_size=width / across)
            result = orchestrate.solve(scene, settings)
            answers = result.answers
            found[across] = {key: _value(answers, *where) for key, where in ANSWERS.items()}
            found[across]["coating_stress"] = _coating_stress(answers)
            found[across]["measured_across"] = (2.0 * result.summary["contact_half_width"]
                                                / (width / across))
            progress(f"{name}: {across} elements across, {result.summary['iterations']} "
                     f"iterations")
        reference = found.pop(REFERENCE_ACROSS)
        for across, values in found.items():
            row = {"scene": name, "elements_across": across,
                   "measured_elements_across": values["measured_across"]}
            for key in (*ANSWERS, "coating_stress"):
                row[f"{key}_error"] = abs(values[key] / reference[key] - 1.0)
            rows.append(row)
    table = pd.DataFrame(rows)
    save_table(table, out)
    return table


def from_where(table, targets=TARGETS):
    """The fewest elements across from which, at every finer resolution of the table,
    every scene meets every target (None if none does)."""
    worst = table.groupby("elements_across")[list(targets)].max().sort_index()
    meets = (worst <= pd.Series(targets)).all(axis=1)
    found = None
    for across in reversed(meets.index):
        if not meets[across]:
            break
        found = across
    return found


def write_report(table, out, command="python -m studies.resolution"):
    report = Report("How many interface elements a contact needs", command,
                    data=[os.path.basename(os.path.splitext(out)[0]) + ".csv"])
    names = listing(f"“{name}”" for name in table.scene.unique())
    report.text(f"Each scene ({names}) solved with interface "
                "elements such that its a priori contact width 2a spans the number of "
                "elements of the first column; every error is relative to the same scene "
                f"at {REFERENCE_ACROSS} elements across (absolute values).")
    worst = table.groupby("elements_across")[list(QUANTITIES)].max().reset_index()
    report.section("The worst of the scenes")
    report.table(worst, [Column("elements_across", "elements across 2a", "{:g}",
                                "the a priori contact width over the element length")]
                 + [Column(key, name, percent, "" if i else
                           "the largest error over the scenes, per quantity")
                    for i, (key, name) in enumerate(QUANTITIES.items())])
    report.section("Per scene")
    report.table(table, [Column("scene", "scene"),
                         Column("elements_across", "elements across 2a", "{:g}"),
                         Column("measured_elements_across", "measured", "{:.3g}",
                                "elements across the contact width the run found")]
                 + [Column(key, name, percent) for key, name in QUANTITIES.items()])
    limit = from_where(table)
    asked = " and ".join(f"the {QUANTITIES[key]} within {100 * value:g} %"
                         for key, value in TARGETS.items())
    if limit is None:
        report.finding(f"No resolution of the table gives {asked} in every scene.")
    else:
        report.finding(f"From {limit:g} elements across the contact width on, every scene "
                       f"has {asked}: the least the warnings `coarse_mesh` and "
                       "`coarse_contact` may ask (their limit, ELEMENTS_ACROSS in "
                       "orchestrate/run/validity.py).")
        finer = table[table.elements_across >= limit]
        shear = finer.groupby("scene").bond_shear_error.max()
        settles = {scene: from_where(part, {"bond_shear_error": SHEAR_WITHIN})
                   for scene, part in table.groupby("scene")}
        report.finding("The bond's peak shear converges more slowly: from there on it moves "
                       "by up to " + listing(f"{percent(value, 1)} ({scene})"
                                             for scene, value in shear.items())
                       + f" from the finest run's, and stays within "
                       f"{100 * SHEAR_WITHIN:g} % from "
                       + listing(f"{across:g} elements across ({scene})"
                                 if across is not None else f"no resolution tried ({scene})"
                                 for scene, across in settles.items()) + ".")
    return report.write(out)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default=str(RESULTS_DIR / "resolution.csv"),
                        help="the table; the report goes beside it (resolution.md)")
    args = parser.parse_args(argv)
    table = study(args.out, progress=lambda text: print(text, file=sys.stderr))
    with pd.option_context("display.width", 200, "display.float_format", "{:.2e}".format):
        print(table.to_string(index=False))
    print(args.out)
    print(write_report(table, os.path.splitext(args.out)[0] + ".md",
                       command_line("studies.resolution", argv)))


if __name__ == "__main__":
    main()
