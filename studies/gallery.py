"""The gallery: the scenes coating engineers pose (orchestrate/scenes/gallery/), each
solved with default settings and by the monolithic solve of the same discrete problem
(``python -m studies.gallery``, ``make gallery``).

Every scene is solved twice, each from a cold start (workers started for it): by the
Robin loop as a user runs it (orchestrate.solve, default settings), and by the
monolithic solve (orchestrate/run/monolithic.py: every subdomain in one matrix, its
contact set iterated) of the problem the run's plan made (the same mesh and interface
points, the same coating models). The table says, per scene, what it spans (the
indenter's and the coating's modulus over the base's, h2 and the body's width over the
a priori contact half-width), the time to answer of each and their ratio, the loop's
iterations and contact sets, the unknowns, and how far the loop's answer is from the
monolithic one: peak pressure, total force, contact half-width, the bonds' peak normal
and shear stresses (relative to the largest of each).

Writes results/gallery.csv and results/gallery.md.
"""

import argparse
from dataclasses import replace
import math
import os
import time

import numpy as np
import pandas as pd

import orchestrate
from orchestrate.ddm import contact_half_width
from orchestrate.model import contact_half_width as a_priori_half_width
from orchestrate.model import scene_and_settings
from orchestrate.run import RunFailed, monolithic_of, prepare
from studies.paths import RESULTS_DIR, gallery_files
from studies.report import (Column, Report, command_line, listing, percent_g, print_table,
                            progress_to_stderr, report_beside, save_table, seconds,
                            significant)

def _describe(scene, solved):
    """What the scene spans, from its dimensionless form ``solved`` (b and E)."""
    a = a_priori_half_width(solved)
    base = solved.base
    width = base.width if base.shape == "block" else base.radius
    coating = max(solved.coatings, key=lambda c: c.E / base.E) if solved.coatings else None
    return {"indenter_over_base": (math.inf if solved.indenter.rigid
                                   else solved.indenter.E / base.E),
            "coating_over_base": coating.E / base.E if coating else math.nan,
            "h2_over_a": coating.thickness / a if coating and a else math.nan,
            "width_over_a": width / a if a else math.nan,
            "load": "force" if scene.load.force is not None else "displacement"}


def _monolithic_answers(problem, stresses):
    """Peak pressure, total force, half-width and the bonds' peak stresses of the
    monolithic solution, in b and E."""
    x, sigma, force = [], [], 0.0
    bond_n, bond_t = [0.0], [0.0]
    for i, interface in enumerate(problem.interfaces):
        if interface.kind == "contact":
            x.append(interface.position[:, 0])
            sigma.append(stresses[i])
            force -= interface.integrate(stresses[i] * interface.normal[:, 1])
        else:
            bond_t.append(float(np.max(np.abs(stresses[i][0]))))
            bond_n.append(float(np.max(np.abs(stresses[i][1]))))
    x, sigma = np.concatenate(x), np.concatenate(sigma)
    symmetric = problem.scene.symmetric
    # a body of revolution's weights carry 2 pi r: the force is already the whole ring's
    halves = 2.0 if symmetric and not problem.scene.axisymmetric else 1.0
    return {"peak_pressure": float(-np.min(sigma)),
            "total_force": halves * force,
            "half_width": contact_half_width(x, sigma) if symmetric else math.nan,
            "bond_normal": max(bond_n), "bond_shear": max(bond_t)}


def _loop_answers(result, scales):
    """The same of the loop's run, from its summary and tables, in b and E."""
    summary, stress = result.summary, scales.stress
    bonds = result.interface
    return {"peak_pressure": -summary["peak_contact_stress"] / stress,
            "total_force": summary["total_force"] / (stress * scales.length ** (
                2 if summary["scene"]["axisymmetric"] else 1)),
            "half_width": (summary["contact_half_width"] / scales.length
                           if result.summary["scene"]["symmetric"] else math.nan),
            "bond_normal": (float(bonds.sigma_n.abs().max()) / stress if len(bonds) else 0.0),
            "bond_shear": (float(bonds.sigma_t.abs().max()) / stress if len(bonds) else 0.0)}


def _difference(loop, reference):
    if math.isnan(reference) or reference == 0:
        return math.nan if math.isnan(reference) else abs(loop)
    return abs(loop / reference - 1.0)


def measure(path, progress=print, mesh_level=None):
    """One scene's row; ``mesh_level``: the scene's own (its file's settings) if None."""
    scene, settings = scene_and_settings(path)
    if mesh_level is not None:
        settings = replace(settings, mesh_level=mesh_level)
    plan = prepare(scene, settings)
    row = {"scene": path.stem, "mesh_level": settings.mesh_level,
           **_describe(scene, plan.problem.scene),
           "models": ", ".join(sorted({c.model for c in plan.scene.coatings}))}
    started = time.perf_counter()
    try:
        result = orchestrate.solve(scene, settings)
    except RunFailed as failed:
        row.update(converged=False, status=failed.summary.get("status"),
                   time_s=time.perf_counter() - started,
                   iterations=failed.summary.get("iterations"))
        result = None
    else:
        summary = result.summary
        row.update(converged=True, status="converged", time_s=time.perf_counter() - started,
                   iterations=summary["iterations"],
                   contact_sets=summary["active_set_changes"] + 1,
                   inner_solve=summary["inner_solve_used"],
                   final_set=int(result.history.groupby("active_set_update").size().iloc[-1]),
                   setup_s=summary["setup_time_s"], loop_only_s=summary["loop_time_s"],
                   outputs_s=summary["outputs_time_s"],
                   unknowns=sum(summary["dofs"].values()),
                   warnings=", ".join(w["code"] for w in summary["warnings"]))
    progress(f"{path.stem}: loop {row['status']} in {row['time_s']:.1f} s")
    started = time.perf_counter()
    traces, stresses = monolithic_of(plan.problem)
    row["monolithic_time_s"] = time.perf_counter() - started
    row["monolithic_solves"] = traces["solves"]
    row["time_ratio"] = row["time_s"] / row["monolithic_time_s"]
    progress(f"{path.stem}: monolithic in {row['monolithic_time_s']:.1f} s")
    # the yardstick starts its contact set from the first point touched; started
    # from the loop's own a priori set it is the stronger one
    started = time.perf_counter()
    primed, _ = monolithic_of(plan.problem, half_width=plan.strategy.first_contact)
    row["primed_time_s"] = time.perf_counter() - started
    row["primed_solves"] = primed["solves"]
    row["primed_ratio"] = row["time_s"] / row["primed_time_s"]
    progress(f"{path.stem}: monolithic from the a priori set in {row['primed_time_s']:.1f} s")
    reference = _monolithic_answers(plan.problem, stresses)
    row["peak_pressure"] = reference["peak_pressure"] * plan.scales.stress
    row["units"] = f"{scene.units.stress}, {scene.units.length}"
    if result is not None:
        loop = _loop_answers(result, plan.scales)
        for key in reference:
            row[f"{key}_difference"] = _difference(loop[key], reference[key])
    return row


def study(out, names=None, progress=print, mesh_level=None):
    rows = [measure(path, progress, mesh_level) for path in gallery_files(names)]
    table = pd.DataFrame(rows)
    save_table(table, out)
    return table


DIFFERENCES = {"peak_pressure_difference": "peak pressure",
               "total_force_difference": "total force",
               "half_width_difference": "half-width",
               "bond_normal_difference": "bond normal",
               "bond_shear_difference": "bond shear"}


def write_report(table, out, command="python -m studies.gallery"):
    report = Report("The gallery: engineers' scenes against the monolithic solve", command,
                    data=[os.path.basename(os.path.splitext(out)[0]) + ".csv"])
    levels = sorted(set(table.mesh_level)) if "mesh_level" in table else [1]
    report.text("Each scene of orchestrate/scenes/gallery/ solved with default settings "
                f"(mesh level {', '.join(str(int(level)) for level in levels)}) "
                "by the Robin loop, and by the monolithic solve of the same discrete "
                "problem (same mesh, interface points and coating models), each from a "
                "cold start on this machine; one run each. The monolithic solve's contact "
                "set starts from the first point touched (its Newton solves grow it), and "
                "again from the loop's own a priori set (the points within the estimated "
                "contact half-width).")
    report.section("What each scene spans")
    report.table(table, [
        Column("scene", "scene"),
        Column("indenter_over_base", "E1/E3", significant, "the indenter's modulus over the base's"),
        Column("coating_over_base", "E2/E3", significant, "the stiffest patch's over the base's"),
        Column("h2_over_a", "h2/a", significant, "its thickness over the a priori contact half-width"),
        Column("width_over_a", "W/a", significant, "the base's half width (a roller's radius) over it"),
        Column("load", "load"),
        Column("models", "models", "{}", "the coating models the run solved (auto's choice)"),
        Column("unknowns", "unknowns", "{:.0f}", "the subdomains' unknowns")])
    report.section("Time to answer and accuracy")
    report.table(table, [
        Column("scene", "scene"),
        Column("status", "outcome"),
        Column("iterations", "iterations", "{:.0f}", "Robin iterations"),
        Column("contact_sets", "sets", "{:.0f}", "contact sets the loop went through"),
        Column("inner_solve", "inner solve"),
        Column("time_s", "loop", seconds, "the run's wall time, workers started for it"),
        Column("monolithic_time_s", "monolithic", seconds, "the monolithic solve's, "
               "from the first point touched"),
        Column("monolithic_solves", "solves", "{:.0f}", "its Newton solves"),
        Column("time_ratio", "ratio", significant, "loop over monolithic"),
        Column("primed_time_s", "from a priori set", seconds, "the monolithic solve's, "
               "from the a priori set"),
        Column("primed_solves", "solves", "{:.0f}", ""),
        Column("primed_ratio", "ratio", significant, "loop over it")]
        + [Column(key, name, percent_g, "" if i else
                  "the loop's answer against the monolithic one, relative")
           for i, (key, name) in enumerate(DIFFERENCES.items())])
    converged = table[table.converged]
    if len(converged):
        worst = converged[list(DIFFERENCES)].max().max()
        report.finding(f"{len(converged)} of {len(table)} scenes converge with default "
                       f"settings; their answers are within {percent_g(worst)} of the "
                       f"monolithic solve's. The loop takes {significant(converged.time_s.median())} s "
                       f"at the median (at most {significant(converged.time_s.max())} s), "
                       f"{significant(converged.time_ratio.median())} times the monolithic "
                       "solve's time at the median (at most "
                       f"{significant(converged.time_ratio.max())}), and "
                       f"{significant(converged.primed_ratio.median())} times its time from "
                       "the a priori set (at most "
                       f"{significant(converged.primed_ratio.max())}).")
    report.section("Where the time goes")
    report.table(converged, [
        Column("scene", "scene"),
        Column("time_s", "run", seconds, "the run's wall time, as above"),
        Column("setup_s", "setup", seconds, "meshes and the workers' start (assembly)"),
        Column("loop_only_s", "loop", seconds, "the Robin loop, its first solves "
               "factorising"),
        Column("outputs_s", "outputs", seconds, "the stresses and the files"),
        Column("final_set", "final set", "{:.0f}", "the iterations of the final contact "
               "set (its linear iterations where iterated)")])
    if len(converged):
        shares = converged[["setup_s", "loop_only_s", "outputs_s"]].div(converged.time_s, axis=0)
        report.finding(f"At the median, setup takes {percent_g(shares.setup_s.median())}, "
                       f"the loop {percent_g(shares.loop_only_s.median())} and the outputs "
                       f"{percent_g(shares.outputs_s.median())} of a run; the final contact "
                       f"set took at most {converged.final_set.max():.0f} iterations "
                       f"({converged.loc[converged.final_set.idxmax(), 'scene']}).")
    failed = table[~table.converged]
    if len(failed):
        report.finding("Not converged: " + listing(f"{row.scene} ({row.status})"
                                                  for row in failed.itertuples()) + ".")
    return report.write(out)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default=str(RESULTS_DIR / "gallery.csv"),
                        help="the table; the report goes beside it (gallery.md)")
    parser.add_argument("--mesh-level", type=int, default=None,
                        help="every scene at this mesh level (default: each file's own)")
    parser.add_argument("names", nargs="*", help="scenes of the gallery (default: all)")
    args = parser.parse_args(argv)
    table = study(args.out, args.names, progress=progress_to_stderr,
                  mesh_level=args.mesh_level)
    print_table(table)
    print(args.out)
    print(write_report(table, report_beside(args.out),
                       command_line("studies.gallery", argv)))


if __name__ == "__main__":
    main()
