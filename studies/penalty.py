"""The penalty's error against the mesh's, at mesh levels 1-3 (`make bench`).

The penalised contact law t = (d - u_A - u_B)/theta lets the bodies overlap by theta |t|;
its error in the peak contact stress and the total force is, to first order,
proportional to theta. For each benchmark scene, each mesh level and each way of
choosing theta, the monolithic solve (the Robin loop's answer, orchestrate/run/monolithic.py)
is run at theta and at theta/4: the penalty's error at theta is estimated as
4/3 (P(theta) - P(theta/4)) (Richardson), the discretisation's as the change of the
quantity from the level below (same rule). Two rules:

    fixed   theta = 1e-3 b/E at every level (the paper's; its loop's default)
    mesh    the accelerated loop's default (Settings): 4e-3 E times the interface
            element's length, 2.5e-4 b/E on the paper's mesh, divided by the mesh level

Two more tables: the default scene's peak contact stress and half-width as theta is
halved (HALVING), and what a stiffer penalty costs the iterated active-set loop
(iterations at COST_THETAS; Anderson acceleration, inner_solve = "iterate").

Writes results/penalty.csv, penalty_halving.csv, penalty_iterations.csv and the report
results/penalty.md.

    python -m studies.penalty          # prints the table, writes the files
    python -m studies.penalty --scenes 0.125:1 --levels 1 2     # shorter
"""

import argparse
import os
import tempfile

import numpy as np
import pandas as pd

from orchestrate.run import monolithic_solution, solve_into
from orchestrate.files import write_csv
from studies.paths import RESULTS_DIR
from studies.report import (Column, Report, command_line, fraction_of_b, fraction_of_E,
                            listing, percent_g, span)
from orchestrate.model import Settings
from orchestrate.model import paper_scene

SCENES = ((0.125, 1.0), (1.0, 5.0))       # (h2, E2): the benchmark's reference scenes
LEVELS = (1, 2, 3)
BASE_THETA = 1e-3
RULES = {"fixed": lambda level: BASE_THETA,
         "mesh": lambda level: Settings(mesh_level=level).theta}
HALVING = (1e-2, 2e-3, 1e-3, 5e-4, 2.5e-4)     # theta (b/E) on the default scene
COST_SCENE = (0.125, 5.0)                      # (h2, E2) of the iteration counts
COST_THETAS = (1e-3, 2.5e-4, 1e-4)


def peak_and_force(h2, E2, level, theta):
    """The monolithic solve's peak contact stress and total force (both halves)."""
    problem, _, stresses = monolithic_solution(paper_scene(h2=h2, E2=E2, model="elastic"),
                                               Settings(mesh_level=level, theta=theta))
    contact = problem.contacts[0]
    sigma = stresses[problem.interfaces.index(contact)]
    force = -2.0 * contact.integrate(sigma * contact.normal[:, 1])
    return float(np.min(sigma)), float(force)


def penalty_table(scenes=SCENES, levels=LEVELS, progress=print):
    rows = []
    for h2, E2 in scenes:
        for rule, theta_of in RULES.items():
            previous = None
            for level in levels:
                theta = theta_of(level)
                peak, force = peak_and_force(h2, E2, level, theta)
                peak4, force4 = peak_and_force(h2, E2, level, theta / 4)
                row = {"h2": h2, "E2": E2, "rule": rule, "level": level, "theta": theta,
                       "peak": peak, "force": force,
                       "penalty_error_peak": abs(4 / 3 * (peak - peak4) / peak),
                       "penalty_error_force": abs(4 / 3 * (force - force4) / force),
                       "mesh_change_peak": (abs(peak / previous[0] - 1) if previous else None),
                       "mesh_change_force": (abs(force / previous[1] - 1) if previous else None)}
                rows.append(row)
                progress(row)
                previous = (peak, force)
    return pd.DataFrame(rows)


def _solve(scene, settings):
    with tempfile.TemporaryDirectory() as out:
        return solve_into(scene, settings, out)


def halving_table(thetas=HALVING):
    """The default scene (its run's answer, the monolithic solve's to rounding on this
    mesh) at each theta: peak contact stress, half-width, the peak's change from the
    theta before."""
    rows = []
    for theta in thetas:
        summary = _solve(paper_scene(), Settings(theta=theta))
        rows.append({"theta": theta, "peak": summary["peak_contact_stress"],
                     "half_width": summary["contact_half_width"]})
    table = pd.DataFrame(rows)
    table["peak_change"] = (table.peak / table.peak.shift(1) - 1).abs()
    table["theta_ratio"] = table.theta.shift(1) / table.theta
    return table


def iterations_table(thetas=COST_THETAS, scene=COST_SCENE):
    """Iterations of the iterated active-set loop at each theta, both coating models."""
    h2, E2 = scene
    rows = []
    for model in ("elastic", "shell"):
        for theta in thetas:
            summary = _solve(paper_scene(h2=h2, E2=E2, model=model),
                             Settings(theta=theta, inner_solve="iterate"))
            rows.append({"model": model, "h2": h2, "E2": E2, "theta": theta,
                         "iterations": summary["iterations"]})
    return pd.DataFrame(rows)


def _levels(part, column):
    return ", ".join(percent_g(v) for v in part.sort_values("level")[column])


def write_report(table, halving, iterations, out, command="python -m studies.penalty"):
    report = Report("The penalty's error", command,
                    data=[f"penalty{suffix}.csv" for suffix in ("", "_halving", "_iterations")])
    if len(halving):
        report.section("Halving theta (the default scene)")
        report.text("The default scene (shell model, h2 = b/8, E2 = E), default settings but "
                    "theta; peak in E, half-width in b.")
        report.table(halving, [
            Column("theta", "theta (b/E)", "{:g}"), Column("peak", "peak sigma_12n (E)", "{:.5g}"),
            Column("half_width", "half-width (b)", "{:.3f}"),
            Column("peak_change", "peak change", percent_g,
                   "from the theta of the row above")])
        halved = halving[np.isclose(halving.theta_ratio, 2.0)]
        if len(halved):
            report.finding("Halving theta changes the peak contact stress by "
                           + listing(f"{percent_g(r.peak_change)} (to {r.theta:g})"
                                     for r in halved.itertuples())
                           + ": the change halves with theta, the penalty's first-order "
                           "error.")
    report.section("The penalty's error against the mesh's")
    report.text("The monolithic solve of the 2D coating model at theta and theta/4: the "
                "penalty's error at theta is 4/3 of the difference (Richardson); the mesh's, "
                "the change from the level below. Rules: `fixed`, theta = "
                f"{BASE_THETA:g} b/E at every level; `mesh`, the accelerated loop's default "
                "(tied to the interface element's length).")
    report.table(table, [
        Column("h2", "h2", fraction_of_b), Column("E2", "E2", fraction_of_E),
        Column("rule", "rule"), Column("level", "mesh level", "{:g}"),
        Column("theta", "theta (b/E)", "{:g}"),
        Column("penalty_error_peak", "penalty error, peak", percent_g,
               "of the peak contact stress"),
        Column("penalty_error_force", "penalty error, force", percent_g,
               "of the total contact force"),
        Column("mesh_change_peak", "mesh change, peak", percent_g,
               "the peak's change from the level below"),
        Column("mesh_change_force", "mesh change, force", percent_g)])
    fixed, mesh = table[table.rule == "fixed"], table[table.rule == "mesh"]
    if len(fixed):
        changes = table.mesh_change_peak.dropna()
        floor = fixed.penalty_error_peak.min()
        report.finding(
            f"At a fixed theta = {BASE_THETA:g} the penalty's error is "
            f"{span(fixed.penalty_error_peak, percent_g)} of the peak contact stress and "
            f"{span(fixed.penalty_error_force, percent_g)} of the force at every level, "
            + (f"against a level-to-level change of the peak of {span(changes, percent_g)}: "
               + ("above it, so the penalty, not the mesh, sets the error floor."
                  if floor > changes.max() else "not above it everywhere.")
               if len(changes) else "(one mesh level: no change to compare with)."))
    if len(mesh):
        report.finding(
            "With the default (mesh) rule it is "
            + "; ".join(f"h2 = {fraction_of_b(h2)}, E2 = {fraction_of_E(E2)}: "
                        f"{_levels(part, 'penalty_error_peak')} of the peak and "
                        f"{_levels(part, 'penalty_error_force')} of the force"
                        for (h2, E2), part in mesh.groupby(["h2", "E2"]))
            + f" at levels {listing(sorted(mesh.level.unique()))}: at most "
            f"{percent_g(mesh[['penalty_error_peak', 'penalty_error_force']].max().max())}.")
    if len(iterations):
        report.section("What a stiffer penalty costs the iterated loop")
        report.table(iterations, [
            Column("model", "model", {"shell": "shell", "elastic": "2D coating"}.get),
            Column("h2", "h2", fraction_of_b), Column("E2", "E2", fraction_of_E),
            Column("theta", "theta (b/E)", "{:g}"),
            Column("iterations", "iterations", "{:g}", "active-set loop, Anderson "
                   "acceleration (inner_solve = iterate), to eps_u = 1e-6")])
        spread = iterations.groupby("model").iterations.agg(lambda v: v.max() / v.min() - 1)
        report.finding(f"Over theta = {span(iterations.theta, '{:g}'.format)} b/E the iterated "
                       "loop's iterations vary by at most "
                       f"{percent_g(spread.max())} (unlike the paper's loop, whose Robin "
                       "parameter is 1/theta).")
    return report.write(out)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", default=str(RESULTS_DIR / "penalty.csv"),
                        help="the main table; the others and penalty.md go beside it")
    parser.add_argument("--scenes", nargs="*", help="h2:E2 pairs (default: 0.125:1 1:5)")
    parser.add_argument("--levels", nargs="*", type=int, default=list(LEVELS))
    args = parser.parse_args(argv)
    scenes = ([tuple(map(float, s.split(":"))) for s in args.scenes] if args.scenes
              else SCENES)
    table = penalty_table(scenes, args.levels, progress=lambda row: None)
    write_csv(args.out, {name: table[name].to_numpy() for name in table.columns})
    stem = os.path.splitext(args.out)[0]
    halving, iterations = halving_table(), iterations_table()
    halving.to_csv(stem + "_halving.csv", index=False)
    iterations.to_csv(stem + "_iterations.csv", index=False)
    shown = table.copy()
    for name in ("penalty_error_peak", "penalty_error_force", "mesh_change_peak",
                 "mesh_change_force"):
        shown[name] = [f"{100 * v:.4f} %" if v == v and v is not None else "" for v in shown[name]]
    print(shown.drop(columns=["peak", "force"]).to_string(index=False))
    report = write_report(table, halving, iterations, stem + ".md",
                          command_line("studies.penalty", argv))
    print(f"written: {args.out}, {report}")


if __name__ == "__main__":
    main()
