"""Iterations per contact set across the indenter's modulus: the near-rigid cylinder's
scene (orchestrate/scenes/gallery/near_rigid_cylinder.toml: R = 100 b on a block 20 b
wide and high, a coating of 4 E3 half a b thick) with the indenter's modulus from a
hundredth of the base's to a thousand times it, and rigid (``python -m
studies.indenter_contrast``, ``make contrast``).

The force is scaled with the bodies' contact modulus (1/E* = 1/E1* + 1/E3*) so that the
contact keeps the half-width of the scene's own (about 1.5 b): only the contrast
changes. Each scene is solved with default settings (auto's inner solve and coating
model) and with the sides unsplit (contact_split = bond_split = 1, against the defaults':
docs/method.md, Robin parameters; under an indenter more than hold_contrast times as
stiff as the base the contact's split is at most 4), at mesh levels 1 and 2
(``--levels``), from a cold start, one run each. A row: the Robin iterations of the final contact set (the
linear iterations its fixed point took; 1 where it was solved directly), the contact
sets, all iterations, the time to answer and the inner solve used. The findings: the
range of the final set's iterations over the moduli, per level and variant.

Writes results/indenter_contrast.csv and results/indenter_contrast.md.
"""

import argparse
from dataclasses import replace
import os

import pandas as pd

from orchestrate.model import Settings, scene_and_settings
from orchestrate.paths import SCENES_DIR
from studies.iterations import counted_run
from studies.paths import RESULTS_DIR
from studies.report import (Column, Report, command_line, print_table, progress_to_stderr,
                            report_beside, save_table, seconds, significant)

SCENE = SCENES_DIR / "gallery" / "near_rigid_cylinder.toml"
# the indenter's modulus over the base's; None: rigid
MODULI = (0.01, 0.1, 1.0, 10.0, 100.0, 1000.0, None)
# (contact_split, bond_split): the defaults, and unsplit
SPLITS = ((Settings.contact_split, Settings.bond_split), (1.0, 1.0))


def _plane_strain(E, nu):
    return E / (1.0 - nu ** 2)


def scene_with(modulus):
    """The scene with the indenter's modulus ``modulus`` times the base's (None: rigid),
    its force scaled by the contact modulus against the scene's own."""
    scene, _ = scene_and_settings(SCENE)
    indenter, base = scene.indenter, scene.base

    def contact_modulus(E1):
        return 1.0 / ((0.0 if E1 is None else 1.0 / _plane_strain(E1, indenter.nu))
                      + 1.0 / _plane_strain(base.E, base.nu))

    force = scene.load.force * contact_modulus(
        None if modulus is None else modulus * base.E) / contact_modulus(indenter.E)
    overrides = ({"indenter.rigid": True} if modulus is None
                 else {"indenter.E": modulus * base.E})
    return scene_and_settings(SCENE, {**overrides, "load.force": force})


def measure(modulus, level, split):
    scene, settings = scene_with(modulus)
    contact_split, bond_split = split
    row = {"indenter_over_base": "rigid" if modulus is None else modulus, "mesh_level": level,
           "contact_split": contact_split, "bond_split": bond_split}
    return {**row, **counted_run(scene, replace(settings, mesh_level=level,
                                                contact_split=contact_split,
                                                bond_split=bond_split))}


def study(out, levels=(1, 2), progress=print):
    rows = []
    for level in levels:
        for split in SPLITS:
            for modulus in MODULI:
                row = measure(modulus, level, split)
                progress(f"E1/E3 {row['indenter_over_base']} level {level} split "
                         f"{split[0]:g}: {row['status']}")
                rows.append(row)
    table = pd.DataFrame(rows)
    save_table(table, out)
    return table


def write_report(table, out, command="python -m studies.indenter_contrast"):
    report = Report("Iterations per contact set across the indenter's modulus", command,
                    data=[os.path.basename(os.path.splitext(out)[0]) + ".csv"])
    report.text("The near-rigid cylinder's scene of the gallery with the indenter's modulus "
                "E1 from a hundredth of the base's E3 to a thousand times it, and rigid; the "
                "force scaled with the contact modulus, so that the contact keeps its "
                "half-width. Default settings, and the sides unsplit "
                "(contact_split = bond_split = 1); from a cold start on this machine, one run each.")
    report.table(table, [
        Column("indenter_over_base", "E1/E3", "{}"), Column("mesh_level", "level", "{:.0f}"),
        Column("contact_split", "split", "{:g}", "contact_split (bond_split with it: the "
               "default's, or 1)"), Column("status", "outcome"),
        Column("final_set", "final set", "{:.0f}", "Robin iterations of the final contact "
               "set (1: solved directly)"),
        Column("sets", "sets", "{:.0f}", "contact sets"),
        Column("iterations", "iterations", "{:.0f}", "all Robin iterations"),
        Column("inner_solve", "inner solve", "{}", "how each contact set was solved"),
        Column("time_s", "time", seconds, "time to answer, workers started for it"),
        Column("unknowns", "unknowns", "{:.0f}", "the workers' unknowns")])
    converged = table[table.status == "converged"]
    for (level, split), runs in converged.groupby(["mesh_level", "contact_split"]):
        iterated = runs[runs.inner_solve != "direct"]
        if iterated.empty:
            continue
        low, high = iterated.final_set.min(), iterated.final_set.max()
        report.finding(
            f"Mesh level {level:.0f}, split {split:g}: over the {len(iterated)} "
            f"iterated moduli the final contact set took {low:.0f} to {high:.0f} "
            f"iterations (the most {significant(high / low, 2)} times the least; largest at "
            f"E1/E3 = "
            f"{iterated.loc[iterated.final_set.idxmax(), 'indenter_over_base']}); all "
            f"iterations {iterated.iterations.min():.0f} to {iterated.iterations.max():.0f}, "
            f"time {significant(iterated.time_s.min())} to "
            f"{significant(iterated.time_s.max())} s.")
    failed = table[table.status != "converged"]
    if len(failed):
        report.finding("Not converged: " + ", ".join(
            f"E1/E3 {row.indenter_over_base} level {row.mesh_level} split "
            f"{row.contact_split:g} ({row.status})" for row in failed.itertuples()) + ".")
    return report.write(out)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default=str(RESULTS_DIR / "indenter_contrast.csv"),
                        help="the table; the report goes beside it (indenter_contrast.md)")
    parser.add_argument("--levels", type=int, nargs="+", default=[1, 2])
    args = parser.parse_args(argv)
    table = study(args.out, args.levels, progress=progress_to_stderr)
    print_table(table)
    print(write_report(table, report_beside(args.out),
                       command_line("studies.indenter_contrast", argv)))


if __name__ == "__main__":
    main()
