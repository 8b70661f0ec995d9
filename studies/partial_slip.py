"""Partial slip against Cattaneo and Mindlin (not a test; tests/studies/
test_partial_slip.py checks one case).

A cylinder on a block of the same material (E = 1, nu = 0.3; Dundurs' beta = 0, so the
normal load makes no slip and the one-step solution is the loading path's), a full
model, pressed by the force that gives a = 1 b, then pulled towards +x1 by Q = share
times mu P with mu = 0.5. Cattaneo's closed form (studies/line_contact_stresses.py):
a stick zone of half-width c = a sqrt(1 - Q / (mu P)) in the middle, the traction mu p
in the slip zones and mu p0 (sqrt(1 - x^2/a^2) - (c/a) sqrt(1 - x^2/c^2)) inside.

Reported: the stick zone's half-width (summary.json's stick_zones, its ends estimated
between the nodes, orchestrate/ddm/contact.py) over the contact's (contact_zones),
against sqrt(1 - Q / (mu P)); the stick zone's centre; the largest difference between
the friction traction and Cattaneo's over mu p0; the stamp's shift.

Load paths (load.path): pressed, pulled to Q* and brought back to Q (towards -x1 where
Q < 0), each step from the one before; against Mindlin and Deresiewicz (studies/
line_contact_stresses.py's unloading_traction): the zone stuck through the turn,
c' / a = sqrt(1 - (Q* - Q) / (2 mu P)), and the traction; with each step's iterations.

Writes results/partial_slip.csv, results/partial_slip_paths.csv and their report
results/partial_slip.md.

    python -m studies.partial_slip
"""

import argparse
from dataclasses import replace
import math
import os

import numpy as np
import pandas as pd

from orchestrate import solve
from orchestrate.model import LoadStep, Settings
from studies.hertz import hertz, hertz_force, hertz_scene
from studies.line_contact_stresses import cattaneo_traction, unloading_traction
from studies.paths import RESULTS_DIR
from studies.report import Column, Report, command_line, seconds

MU = 0.5
CASES = ((16.0, 40.0, 1, 0.5), (16.0, 40.0, 2, 0.5), (128.0, 200.0, 2, 0.25),
         (128.0, 200.0, 2, 0.5), (128.0, 200.0, 2, 0.75))   # (W, R, level, Q / mu P)
# load paths: (W, R, level, Q* / mu P, Q / mu P), pressed first, then Q*, then Q
PATHS = ((16.0, 40.0, 1, 0.75, 0.25), (16.0, 40.0, 1, 0.5, -0.5), (16.0, 40.0, 2, 0.75, 0.25),
         (128.0, 200.0, 2, 0.75, 0.25))
EPS_U = 1e-8


def scene(size, radius, share):
    half = hertz_scene(size, radius=radius, force=hertz_force(radius=radius))
    zone = half.contact_zone[1]
    load = replace(half.load, tangential_force=share * MU * half.load.force)
    return replace(half, symmetric=False, contact_zone=(-zone, zone), friction=MU, load=load)


def run(size, radius, mesh_level, share):
    problem = scene(size, radius, share)
    a, p0 = hertz(problem.load.force, radius=radius)
    result = solve(problem, Settings(mesh_level=mesh_level, eps_u=EPS_U))
    summary = result.summary
    (start, end), = summary["stick_zones"]
    (low, high), = summary["contact_zones"]
    half_width = 0.5 * (high - low)
    expected = math.sqrt(1.0 - share)
    contact = result.contact
    x = contact.x1.to_numpy()
    reference = cattaneo_traction(x, a, p0, MU, share)
    return {"size": size, "radius": radius, "mesh_level": mesh_level, "share": share,
            "stick_half_width": 0.5 * (end - start) / half_width,
            "expected": expected,
            "stick_error": 0.5 * (end - start) / half_width / expected - 1,
            "stick_centre": 0.5 * (end + start) / a,
            "traction_error": float(np.max(np.abs(contact.sigma_t.to_numpy() - reference)))
            / (MU * p0),
            "shift": summary["stamp_shift"], "iterations": summary["iterations"],
            "seconds": summary["wall_time_s"]}


def run_path(size, radius, mesh_level, peak, share):
    """Pressed, pulled to Q* = peak mu P, then brought to Q = share mu P (a row)."""
    problem = scene(size, radius, share)
    force = problem.load.force
    path = (LoadStep(tangential_force=0.0), LoadStep(tangential_force=peak * MU * force))
    problem = replace(problem, load=replace(problem.load, path=path))
    a, p0 = hertz(force, radius=radius)
    result = solve(problem, Settings(mesh_level=mesh_level, eps_u=EPS_U))
    summary = result.summary
    (start, end), = summary["stick_zones"]
    (low, high), = summary["contact_zones"]
    expected = math.sqrt(1.0 - 0.5 * (peak - share))
    contact = result.contact
    reference = unloading_traction(contact.x1.to_numpy(), a, p0, MU, peak, share)
    steps = summary["load_steps"]
    return {"size": size, "radius": radius, "mesh_level": mesh_level, "peak": peak,
            "share": share, "stick_half_width": (end - start) / (high - low),
            "expected": expected,
            "stick_error": (end - start) / (high - low) / expected - 1,
            "stick_centre": 0.5 * (end + start) / a,
            "traction_error": float(np.max(np.abs(contact.sigma_t.to_numpy() - reference)))
            / (MU * p0),
            "tangential_force_error": (summary["tangential_force"] - share * MU * force)
            / (MU * force),
            "pressed_iterations": steps[0]["iterations"],
            "peak_iterations": steps[1]["iterations"], "iterations": summary["iterations"],
            "seconds": summary["wall_time_s"]}


def write_report(table, paths, out, command="python -m studies.partial_slip"):
    report = Report("Partial slip against Cattaneo and Mindlin", command,
                    data=["partial_slip.csv", "partial_slip_paths.csv"])
    report.text(f"A cylinder on a block of its own material (a full model), a = 1 b, "
                f"mu = {MU}, pulled by Q = share x mu P; the stick zone from summary.json's "
                "stick_zones against Cattaneo's c / a = sqrt(1 - Q / (mu P)); one run each.")
    report.table(table, [
        Column("size", "W (a)", "{:g}"), Column("mesh_level", "level", "{:g}"),
        Column("share", "Q / (mu P)", "{:g}"),
        Column("stick_half_width", "c / a", "{:.4f}", "half the stick zone over half the "
               "contact zone"),
        Column("expected", "Cattaneo's", "{:.4f}"),
        Column("stick_error", "error", "{:+.2%}"),
        Column("stick_centre", "stick centre (a)", "{:+.4f}"),
        Column("traction_error", "traction", "{:.4f}", "the largest difference from "
               "Cattaneo's traction over mu p0"),
        Column("iterations", "iterations", "{:g}"), Column("seconds", "time", seconds)])
    report.finding(f"The stick zone's half-width is within "
                   f"{100 * table.stick_error.abs().max():.2f} % of Cattaneo's in every case; "
                   f"the traction within {table.traction_error.max():.3f} mu p0 of his "
                   "(largest at the stick zone's ends, where it turns within an element).")
    report.text("Load paths (load.path): pressed, pulled to Q*, then brought back to Q, "
                "each step from the one before; the zone stuck through the turn against "
                "Mindlin and Deresiewicz's c' / a = sqrt(1 - (Q* - Q) / (2 mu P)), the "
                "traction against theirs.")
    report.table(paths, [
        Column("size", "W (a)", "{:g}"), Column("mesh_level", "level", "{:g}"),
        Column("peak", "Q* / (mu P)", "{:g}"), Column("share", "Q / (mu P)", "{:g}"),
        Column("stick_half_width", "c' / a", "{:.4f}"),
        Column("expected", "Mindlin's", "{:.4f}"),
        Column("stick_error", "error", "{:+.2%}"),
        Column("stick_centre", "stick centre (a)", "{:+.4f}"),
        Column("traction_error", "traction", "{:.4f}", "the largest difference from "
               "Mindlin and Deresiewicz's traction over mu p0"),
        Column("pressed_iterations", "pressed", "{:g}", "iterations of each step"),
        Column("peak_iterations", "to Q*", "{:g}"), Column("iterations", "to Q", "{:g}"),
        Column("seconds", "time", seconds, "the three steps")])
    report.finding(f"Through the turn the stuck zone's half-width is within "
                   f"{100 * paths.stick_error.abs().max():.2f} % of Mindlin and "
                   f"Deresiewicz's, the traction within {paths.traction_error.max():.3f} "
                   "mu p0 of theirs.")
    return report.write(out)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default=str(RESULTS_DIR))
    args = parser.parse_args(argv)
    table = pd.DataFrame([run(*case) for case in CASES])
    paths = pd.DataFrame([run_path(*case) for case in PATHS])
    for frame in (table, paths):
        print(frame.to_string(index=False, float_format=lambda v: f"{v:.4g}"))
    os.makedirs(args.out, exist_ok=True)
    table.to_csv(os.path.join(args.out, "partial_slip.csv"), index=False)
    paths.to_csv(os.path.join(args.out, "partial_slip_paths.csv"), index=False)
    print(write_report(table, paths, os.path.join(args.out, "partial_slip.md"),
                       command_line("studies.partial_slip", argv)))


if __name__ == "__main__":
    main()
