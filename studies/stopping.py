"""A run called converged is within its tolerance: every gallery scene at eps_u from the
paper's 1e-3 down to the default 1e-6, against the same scene run to 1e-9
(``python -m studies.stopping``, ``make stopping``).

The stopping test (orchestrate/ddm/robin.py, docs/method.md "Convergence") bounds each
part of the interface state apart: a contact's pressure, a bond's peel and shear stress,
each measured against its own size, or against component_floor (1e-3) times the largest
where it is smaller. This study measures the same parts in the stresses a user reads
(contact.csv and interface.csv: sigma_n and sigma_t of every interface, relative L2 along
s) and reports the largest error over them against eps_u. A row: the scene, mesh level
and eps_u, the iterations, the estimate the run reported, the largest true error, the
part it is in and their ratio to eps_u. A ratio above 1 is a run called converged
outside its tolerance.

Writes results/stopping.csv and results/stopping.md.
"""

import argparse
from dataclasses import replace
import os

import numpy as np
import pandas as pd

import orchestrate
from orchestrate.model import Settings, scene_and_settings
from orchestrate.run import RunFailed
from studies.paths import RESULTS_DIR, gallery_files
from studies.report import (Column, Report, command_line, print_table, progress_to_stderr,
                            report_beside, save_table, significant)

TOLERANCES = (1e-3, 1e-4, 1e-6)
REFERENCE_EPS_U = 1e-9
COMPONENT_FLOOR = Settings.component_floor


def _parts(result):
    """{(interface, column): (s, values)} of every interface's tractions."""
    parts = {}
    for table in (result.contact, result.interface):
        for name, rows in table.groupby("interface"):
            for column in ("sigma_n", "sigma_t"):
                parts[(name, column)] = (rows["s"].to_numpy(), rows[column].to_numpy())
    return parts


def _norm(s, values):
    return float(np.sqrt(np.trapezoid(values ** 2, s))) if len(s) > 1 else abs(values).max()


def largest_error(result, reference):
    """(the largest relative error of a part, the part): each part's L2 distance along s
    over its own norm, at least COMPONENT_FLOOR times the largest part's norm."""
    ours, theirs = _parts(result), _parts(reference)
    norms = {key: _norm(*value) for key, value in theirs.items()}
    floor = COMPONENT_FLOOR * max(norms.values())
    errors = {}
    for key, (s, values) in theirs.items():
        s_ours, values_ours = ours[key]
        if not np.allclose(s_ours, s):
            raise ValueError(f"{key}: the runs' points differ")
        errors[key] = _norm(s, values_ours - values) / max(norms[key], floor)
    key = max(errors, key=errors.get)
    return errors[key], f"{key[0]} {key[1]}"


def measure(path, level, progress=print):
    scene, settings = scene_and_settings(path)
    settings = replace(settings, mesh_level=level)
    rows = []
    try:
        reference = orchestrate.solve(scene, replace(settings, eps_u=REFERENCE_EPS_U))
    except RunFailed as failed:
        progress(f"{path.stem} level {level}: reference {failed.summary.get('status')}")
        return [{"scene": path.stem, "mesh_level": level, "status": "no reference"}]
    for eps in TOLERANCES:
        row = {"scene": path.stem, "mesh_level": level, "eps_u": eps}
        try:
            result = orchestrate.solve(scene, replace(settings, eps_u=eps))
        except RunFailed as failed:
            rows.append({**row, "status": failed.summary.get("status")})
            continue
        error, part = largest_error(result, reference)
        rows.append({**row, "status": "converged", "iterations": result.summary["iterations"],
                     "estimate": result.summary["error_estimate"], "error": error,
                     "part": part, "ratio": error / eps})
        progress(f"{path.stem} level {level} eps_u {eps:g}: error {error:.2g} ({part})")
    return rows


def study(out, levels=(1, 2), names=None, progress=print):
    rows = []
    for path in gallery_files(names):
        for level in levels:
            rows += measure(path, level, progress)
    table = pd.DataFrame(rows)
    save_table(table, out)
    return table


def write_report(table, out, command="python -m studies.stopping"):
    report = Report("A converged run against its tolerance", command,
                    data=[os.path.basename(os.path.splitext(out)[0]) + ".csv"])
    report.text("Each gallery scene with default settings at each eps_u, against the same "
                f"scene run to {REFERENCE_EPS_U:g}: the largest relative error (L2 along s) "
                "of a traction component of an interface (sigma_n, sigma_t of every "
                f"contact and bond), each against its own norm or {COMPONENT_FLOOR:g} times "
                "the largest component's, as the stopping test measures them; from a cold "
                "start on this machine, one run each.")
    report.table(table, [
        Column("scene", "scene", "{}"), Column("mesh_level", "level", "{:.0f}"),
        Column("eps_u", "eps_u", "{:g}"), Column("status", "outcome"),
        Column("iterations", "iterations", "{:.0f}", "all Robin iterations"),
        Column("estimate", "estimate", "{:.2g}", "the error the run reported"),
        Column("error", "error", "{:.2g}", "the largest relative error of a traction "
               "component against the reference"),
        Column("part", "part", "{}", "where it is"),
        Column("ratio", "error / eps_u", "{:.3g}", "above 1: called converged outside its "
               "tolerance")])
    converged = table[table.status == "converged"]
    if len(converged):
        worst = converged.loc[converged.ratio.idxmax()]
        outside = converged[converged.ratio > 1]
        report.finding(
            f"{len(converged)} converged runs; the largest error is "
            f"{significant(worst.ratio, 2)} times eps_u ({worst.scene}, level "
            f"{worst.mesh_level:.0f}, eps_u {worst.eps_u:g}, {worst.part}); "
            + (f"{len(outside)} outside their tolerance: " + ", ".join(
                f"{row.scene} level {row.mesh_level:.0f} eps_u {row.eps_u:g}"
                for row in outside.itertuples()) if len(outside) else
               "none outside its tolerance") + ".")
    failed = table[table.status != "converged"]
    if len(failed):
        report.finding("Not converged or no reference: " + ", ".join(
            f"{row.scene} level {row.mesh_level:.0f} ({row.status})"
            for row in failed.itertuples()) + ".")
    return report.write(out)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default=str(RESULTS_DIR / "stopping.csv"),
                        help="the table; the report goes beside it (stopping.md)")
    parser.add_argument("--levels", type=int, nargs="+", default=[1, 2])
    parser.add_argument("names", nargs="*", help="scenes of the gallery (default: all)")
    args = parser.parse_args(argv)
    table = study(args.out, args.levels, args.names,
                  progress=progress_to_stderr)
    print_table(table)
    print(write_report(table, report_beside(args.out),
                       command_line("studies.stopping", argv)))


if __name__ == "__main__":
    main()
