"""The contact pressure of each coating model against the penalty, under a stiff
indenter (``python -m studies.shell_edge_penalty``, ``make shell-edge``).

The gallery's rigid and near-rigid cylinders (R = 100 b on a block 20 b wide, a coating
of 4 E3 half a b thick; orchestrate/scenes/gallery/) solved with each coating model at
the default penalty theta and at multiples of it (``--factors``), mesh level 1. A row:
the peak contact stress, where it is, the contact's half-width, and the pressure's
alternation from node to node: the largest |p_i - (p_(i-1) + p_(i+1)) / 2| over the
contact zone's inner nodes (its first and last two left out), over the peak. The
findings: per scene and model, how far the peak moves over the penalties, and the
alternation at the default's.

A penalty's error should stay below the mesh's (docs/method.md, "Penalty"): the answers
should not depend on it. docs/findings.md ("The contact's edges under a stiff indenter")
explains what this measures.

Writes results/shell_edge_penalty.csv and results/shell_edge_penalty.md.
"""

import argparse
from dataclasses import replace
import os

import numpy as np
import pandas as pd

import orchestrate
from orchestrate.model import scene_and_settings
from studies.paths import RESULTS_DIR, gallery_files
from studies.report import (Column, Report, command_line, print_table, progress_to_stderr,
                            report_beside, save_table, significant)

SCENES = ("rigid_cylinder", "near_rigid_cylinder")
MODELS = ("shell", "stretch_shell", "elastic")
FACTORS = (10.0, 1.0, 0.1)          # theta over the default's


def alternation(contact):
    """The pressure's largest second difference over the contact zone's inner nodes (its
    first and last two left out), over its peak: 0 for a pressure linear between nodes."""
    g = contact[contact.interface.str.startswith("contact-coating")].sort_values("s")
    p = -g.sigma_n.to_numpy()
    inner = np.flatnonzero(p > 0)[1:-2]
    if len(inner) == 0:
        return float("nan")
    return float(np.max(np.abs(p[inner] - 0.5 * (p[inner - 1] + p[inner + 1]))) / p.max())


def measure(name, model, factor):
    scene, settings = scene_and_settings(gallery_files([name])[0])
    scene = replace(scene, coatings=tuple(replace(c, model=model) for c in scene.coatings))
    theta = settings.default_theta()[0] * factor
    result = orchestrate.solve(scene, replace(settings, theta=theta))
    summary = result.summary
    contact = result.contact
    touching = contact[contact.interface.str.startswith("contact")]
    at = touching.loc[touching.sigma_n.idxmin()]
    return {"scene": name, "model": model, "theta_factor": factor, "theta": theta,
            "status": summary["status"], "peak": -summary["peak_contact_stress"],
            "peak_at": float(at.x1), "half_width": summary["contact_half_width"],
            "alternation": alternation(contact)}


def study(out, factors=FACTORS, progress=print):
    rows = []
    for name in SCENES:
        for model in MODELS:
            for factor in factors:
                rows.append(measure(name, model, factor))
                progress(f"{name} {model} theta x{factor:g}: {rows[-1]['status']}")
    table = pd.DataFrame(rows)
    save_table(table, out)
    return table


def write_report(table, out, command="python -m studies.shell_edge_penalty"):
    report = Report("The contact pressure against the penalty, under a stiff indenter",
                    command, data=[os.path.basename(os.path.splitext(out)[0]) + ".csv"])
    report.text("The gallery's rigid and near-rigid cylinders with each coating model, at "
                "the default penalty theta and multiples of it, mesh level 1; one run each.")
    report.table(table, [
        Column("scene", "scene"), Column("model", "model"),
        Column("theta_factor", "theta / default", "{:g}"),
        Column("peak", "peak pressure", "{:.5g}", "the largest contact pressure, E"),
        Column("peak_at", "at x1", "{:.3g}", "b"),
        Column("half_width", "half-width", "{:.4g}", "b"),
        Column("alternation", "alternation", "{:.3f}", "the largest second difference "
               "of the pressure over its inner nodes, over the peak")])
    for (name, model), runs in table.groupby(["scene", "model"], sort=False):
        default = runs[runs.theta_factor == 1.0]
        moved = runs.peak.max() / runs.peak.min() - 1
        text = (f"{name}, {model}: the peak pressure moves {significant(100 * moved, 2)} % "
                f"over theta x{runs.theta_factor.min():g} to x{runs.theta_factor.max():g}")
        if len(default):
            text += f"; alternation {default.alternation.iloc[0]:.3f} at the default theta"
        report.finding(text + ".")
    return report.write(out)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default=str(RESULTS_DIR / "shell_edge_penalty.csv"),
                        help="the table; the report goes beside it (shell_edge_penalty.md)")
    parser.add_argument("--factors", type=float, nargs="+", default=list(FACTORS))
    args = parser.parse_args(argv)

    table = study(args.out, args.factors, progress=progress_to_stderr)
    print_table(table)
    print(write_report(table, report_beside(args.out),
                       command_line("studies.shell_edge_penalty", argv)))


if __name__ == "__main__":
    main()
