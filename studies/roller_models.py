"""A coated roller: the shell model against the 2D coating model as the coating thins
(not a test; tests/studies/test_roller_models.py checks two thicknesses).

The scene is orchestrate/scenes/roller.toml: a roller of radius R = 16 b on a rigid
shaft (bore 8 b), coated from its top x1 = 0 to x1 = 3 b (half model), pressed by a flat
block (half width 4 b) with a force of 0.02 E b per unit width. For each coating
modulus E2 and thickness h2 = R/16, R/32, ... the scene is solved twice, the patch a
shell (P4 on its mid-line) and a 2D P2 body, and the two answers are compared:

    peak_diff        sigma_12n's peak, shell / 2D - 1
    contact_l2       relative L2 distance ||shell - 2D|| / ||2D|| of sigma_12n over the
                     contact faces (the coating's top and the bare roller beyond it)
    bond_l2          the same for sigma_23n, over the bond S23 (the whole patch)
    *_core           the same over the core of the contact, s < 0.6 a (a the smaller
                     contact half-width): the full-face distances are dominated, once the
                     coating is thin, by the contact's edge, where the pressure falls to
                     zero between two interface points and a shift of the edge by a
                     fraction of an element changes the last loaded point's stress a lot
    half_width_*     the contact half-widths (x1 of the zone's end)
    *_rate           per halving of h2, log2 of the ratio of a difference at the thicker
                     h2 to that at this one: 1 means the difference halves with h2
    wall time, iterations, dofs (all bodies) of each model

Both models see the coating's thickness in the geometry: the contact face is the circle
of radius R + h2. The curves are compared at the interface points, which both models
share while the 2D coating keeps the shell's interface elements (b/16 long at mesh
level 1). Its cells, at most twice as wide as high, refine its interface once 2 h2 is
below that: 49 elements instead of 48 at R/512, 2x at R/1024, 4x at R/2048, and the
base's coated face with them. Then the curve with more points is interpolated linearly
in s (arc length along the roller's surface) onto the points of the other, with those
points' Simpson weights; ``interp_floor`` (``_core``) is what interpolation alone makes
of the finer curve (it against its interpolant through the coarser points and back).

The Robin loop is stopped at eps_u = 1e-9, not the default 1e-6: the stresses are
penalty forces, displacement / theta, and at 1e-6 the loop leaves errors that gather
at the symmetry axis and grow with the interface's refinement (node-to-node wiggles of
+-0.5 % at R/1024, +-1 % at R/2048, +-4 % at R/2048 on mesh level 2 for the 2D model),
as large as the model difference there and picked up by the peak. At 1e-9 the curves
are smooth, for 1.3-1.6 times the iterations.

Writes results/roller_models.csv and the report results/roller_models.md.

    python -m studies.roller_models                  # E2 = E, 5E, E/5; R/16 ... R/2048
    python -m studies.roller_models --E2 1 --divisors 16 32 64 --eps-u 1e-6
"""

import argparse
import math
import os
import tempfile

import numpy as np
import pandas as pd

from orchestrate.mesh import simpson
from studies.paths import RESULTS_DIR
from studies.report import (Column, Report, command_line, fraction_of_E, percent,
                            seconds, signed_percent)
from orchestrate.model import Settings
from orchestrate.paths import SCENES_DIR
from orchestrate.model import apply_overrides, load_scene
from orchestrate.run import RunFailed, solve_into as solve

ROLLER_SCENE_FILE = SCENES_DIR / "roller.toml"
DIVISORS = (16, 32, 64, 128, 256, 512, 1024, 2048)    # h2 = R / divisor
MODULI = (1.0, 5.0, 0.2)                   # E2 / E
EPS_U = 1e-9                               # the Robin loop's stopping test (docstring)


def roller_scene(h2, E2, model):
    """The roller scene with every patch of thickness h2, modulus E2, model."""
    scene, _ = load_scene(ROLLER_SCENE_FILE)
    return apply_overrides(scene, {"h2": h2, "E2": E2, "model": model})


def radius():
    scene, _ = load_scene(ROLLER_SCENE_FILE)
    return scene.base.radius


def run(scene, settings, out_dir):
    """solve()'s summary, or the failure's summary (with converged false)."""
    try:
        return solve(scene, settings, out_dir, overwrite=True)   # its own earlier run
    except RunFailed as failure:
        return failure.summary


def curves(folder, file, column="sigma_n"):
    """{interface: (s, values)} of a run's contact.csv or interface.csv."""
    table = pd.read_csv(os.path.join(folder, file))
    return {name: (part.s.to_numpy(), part[column].to_numpy())
            for name, part in table.groupby("interface", sort=False)}


def _weights(s, stretch):
    """Simpson's weights of P2 interface points (element ends every other point)."""
    return simpson(s[::2], stretch)[1]


def _on_common_points(a, b):
    """(s, a, b) on common points: as they are when both have the same points, else the
    curve with more points interpolated linearly in s onto the points of the other."""
    (sa, ya), (sb, yb) = a, b
    if _same_points(sa, sb):
        return sb, ya, yb
    if len(sa) > len(sb):
        return sb, np.interp(sb, sa, ya), yb
    return sa, ya, np.interp(sa, sb, yb)


def _same_points(sa, sb):
    return len(sa) == len(sb) and np.allclose(sa, sb, rtol=0, atol=1e-9)


def distance(a, b, stretches, upto=math.inf):
    """||a - b|| / ||b|| over every interface of b (dicts of (s, values)) where s < upto,
    with the Simpson weights of the common points times each interface's ``stretches``
    (the length of its face per unit s)."""
    numerator = denominator = 0.0
    for name in b:
        s, ya, yb = _on_common_points(a[name], b[name])
        weight = _weights(s, stretches.get(name, 1.0)) * (s < upto)
        numerator += float(np.dot(weight, (ya - yb) ** 2))
        denominator += float(np.dot(weight, yb ** 2))
    return math.sqrt(numerator / denominator)


def interpolation_floor(a, b, stretches, upto=math.inf):
    """What interpolation alone adds to ``distance``: on every interface whose points
    differ, the curve with more points against its linear interpolant through the
    other's points (0 when all points coincide)."""
    numerator = denominator = 0.0
    for name in b:
        (sa, ya), (sb, yb) = a[name], b[name]
        if _same_points(sa, sb):
            continue
        (sf, yf), sc = ((sa, ya), sb) if len(sa) > len(sb) else ((sb, yb), sa)
        back = np.interp(sf, sc, np.interp(sc, sf, yf))
        weight = _weights(sf, stretches.get(name, 1.0)) * (sf < upto)
        numerator += float(np.dot(weight, (back - yf) ** 2))
        denominator += float(np.dot(weight, yf ** 2))
    return math.sqrt(numerator / denominator) if denominator > 0 else 0.0


CORE = 0.6     # the core of the contact: s < CORE times the smaller contact half-width


def compare(scene, shell_dir, elastic_dir, half_width):
    """The distances between a finished shell run and a 2D run of one scene, over the
    whole faces and over the core of the contact, s < CORE * half_width (away from its
    edge, where the pressure falls to zero between two interface points)."""
    R = scene.base.radius
    stretches = {f"contact-coating{n}": (R + c.thickness) / R
                 for n, c in enumerate(scene.coatings, start=1)}
    contact = [curves(d, "contact.csv") for d in (shell_dir, elastic_dir)]
    bond = [curves(d, "interface.csv") for d in (shell_dir, elastic_dir)]
    core = CORE * half_width
    return {
        "contact_l2": distance(*contact, stretches),
        "bond_l2": distance(*bond, {}),
        "contact_l2_core": distance(*contact, stretches, core),
        "bond_l2_core": distance(*bond, {}, core),
        "interp_floor": max(interpolation_floor(*contact, stretches),
                            interpolation_floor(*bond, {})),
        "interp_floor_core": max(interpolation_floor(*contact, stretches, core),
                                 interpolation_floor(*bond, {}, core)),
        "bond_points_shell": sum(len(s) for s, _ in bond[0].values()),
        "bond_points_2d": sum(len(s) for s, _ in bond[1].values()),
    }


def study_row(h2, E2, settings=None, keep=None):
    """Solve both models at (h2, E2) and compare them: one row of the table."""
    settings = settings or Settings(eps_u=EPS_U)
    summaries, folders = {}, {}
    with tempfile.TemporaryDirectory() as scratch:
        for model in ("shell", "elastic"):
            scene = roller_scene(h2, E2, model)
            folder = os.path.join(keep or scratch, f"{model}-h2_{h2:g}-E2_{E2:g}")
            os.makedirs(folder, exist_ok=True)
            summaries[model], folders[model] = run(scene, settings, folder), folder
        shell, elastic = summaries["shell"], summaries["elastic"]
        row = {"h2": h2, "R_over_h2": scene.base.radius / h2, "E2": E2,
               "converged": bool(shell.get("converged")) and bool(elastic.get("converged"))}
        if row["converged"]:
            row["peak_shell"] = shell["peak_contact_stress"]
            row["peak_2d"] = elastic["peak_contact_stress"]
            row["peak_diff"] = shell["peak_contact_stress"] / elastic["peak_contact_stress"] - 1.0
            row.update(compare(scene, folders["shell"], folders["elastic"],
                               min(shell["contact_half_width"], elastic["contact_half_width"])))
            row["bond_peak_shell"] = shell["peak_interface_stress"]
            row["bond_peak_2d"] = elastic["peak_interface_stress"]
            row["half_width_shell"] = shell["contact_half_width"]
            row["half_width_2d"] = elastic["contact_half_width"]
            row["half_width_diff"] = (shell["contact_half_width"]
                                      / elastic["contact_half_width"] - 1.0)
        for model, name in (("shell", "shell"), ("elastic", "2d")):
            summary = summaries[model]
            row[f"time_{name}"] = summary.get("wall_time_s")
            row[f"iterations_{name}"] = summary.get("iterations")
            dofs = summary.get("dofs") or {}
            row[f"dofs_{name}"] = sum(dofs.values()) if dofs else None
            row[f"coating_dofs_{name}"] = dofs.get("coating1")
            if not summary.get("converged"):
                row[f"failure_{name}"] = f"{summary.get('status')}: {summary.get('reason')}"
    return row


def rates(table):
    """Per halving of h2, log2 of the ratio of each difference at the next thicker h2 of
    the table to this one, per E2 (1: the difference halves as h2 halves)."""
    table = table.sort_values(["E2", "h2"], ascending=[True, False]).reset_index(drop=True)
    halvings = np.log2(table.h2.groupby(table.E2).shift(1) / table.h2)
    for key in ("peak_diff", "contact_l2", "bond_l2", "contact_l2_core", "bond_l2_core"):
        values = table[key].abs() if key in table else pd.Series(np.nan, index=table.index)
        previous = values.groupby(table.E2).shift(1)
        table[f"{key}_rate"] = np.log2(previous / values) / halvings
    return table


COLUMNS = ["E2", "R_over_h2", "h2", "peak_2d", "peak_diff", "peak_diff_rate", "contact_l2",
           "contact_l2_rate", "bond_l2", "bond_l2_rate", "contact_l2_core",
           "contact_l2_core_rate", "bond_l2_core", "bond_l2_core_rate", "interp_floor",
           "interp_floor_core", "half_width_shell",
           "half_width_2d", "time_shell", "time_2d", "dofs_shell", "dofs_2d",
           "coating_dofs_shell", "coating_dofs_2d", "iterations_shell", "iterations_2d"]


def write_report(table, out, command="python -m studies.roller_models"):
    report = Report("A coated roller: the shell against the 2D coating", command,
                    data=[os.path.basename(os.path.splitext(out)[0]) + ".csv"])
    report.text("orchestrate/scenes/roller.toml (R = 16 b), each coating thickness h2 and "
                "modulus E2 solved with the patch a shell and a 2D body; the two answers "
                "compared (relative differences, shell against 2D). Rates: per halving of "
                "h2, log2 of the ratio of a difference at the thicker h2 to this one "
                "(1: the difference halves with h2).")
    ordered = table.sort_values(["E2", "h2"], ascending=[True, False])
    report.table(ordered, [
        Column("E2", "E2", fraction_of_E), Column("R_over_h2", "R/h2", "{:g}"),
        Column("peak_2d", "2D peak (E)", "{:.4g}", "the 2D model's peak contact stress"),
        Column("peak_diff", "peak", signed_percent, "shell's peak / 2D's - 1"),
        Column("peak_diff_rate", "rate", "{:.2f}"),
        Column("contact_l2", "contact L2", percent, "relative L2 distance of sigma_12n "
               "over the contact faces"),
        Column("contact_l2_core", "contact L2, core", percent, "the same on s < "
               f"{CORE:g} a, away from the contact's edge"),
        Column("bond_l2", "bond L2", percent, "the same for sigma_23n over the bond"),
        Column("interp_floor", "interp. floor", percent, "what interpolation between "
               "unlike interface points alone makes of a distance"),
        Column("time_shell", "shell", seconds, "wall time"),
        Column("time_2d", "2D", seconds, "wall time"),
        Column("dofs_2d", "2D dofs", "{:g}", "unknowns of all bodies, 2D model")])
    for E2, part in ordered.groupby("E2", sort=False):
        done = part[part.converged.astype(bool)] if "converged" in part else part
        if len(done) < 2:
            continue
        rates = done.peak_diff_rate.dropna()
        report.finding(
            f"E2 = {fraction_of_E(E2)}: the peaks differ by "
            + ", ".join(f"{percent(abs(r.peak_diff))} (R/{r.R_over_h2:g})"
                        for r in done.itertuples())
            + f"; the contact-stress curves by {percent(done.contact_l2.iloc[0], 1)} -> "
            f"{percent(done.contact_l2.iloc[-1], 1)} in L2. Median rate per halving "
            f"{rates.median():.2f}" + (" (the difference halves with h2, as on the "
                                       "paper's flat coating)" if 0.8 <= rates.median() <= 1.2
                                       else "") + ".")
    failed = table[~table.converged.astype(bool)] if "converged" in table else table.iloc[:0]
    if len(failed):
        report.finding(f"{len(failed)} thicknesses did not converge with both models: "
                       + ", ".join(f"E2 = {fraction_of_E(r.E2)}, R/{r.R_over_h2:g}"
                                   for r in failed.itertuples()) + ".")
    return report.write(out)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--E2", type=float, nargs="+", default=list(MODULI),
                        help="coating moduli, in E (default: 1 5 0.2)")
    parser.add_argument("--divisors", type=int, nargs="+", default=list(DIVISORS),
                        help="h2 = R / divisor (default: 16 ... 2048)")
    parser.add_argument("--eps-u", type=float, default=EPS_U,
                        help=f"the Robin loop's stopping test (default {EPS_U:g}, see above)")
    parser.add_argument("--mesh-level", type=int, default=1)
    parser.add_argument("--keep", default=None, help="keep every run in this folder")
    parser.add_argument("--out", default=str(RESULTS_DIR / "roller_models.csv"),
                        help="the table; the report goes beside it (roller_models.md)")
    args = parser.parse_args(argv)
    R = radius()
    settings = Settings(eps_u=args.eps_u, mesh_level=args.mesh_level)
    rows = []
    for E2 in args.E2:
        for divisor in args.divisors:
            rows.append(study_row(R / divisor, E2, settings, keep=args.keep))
            print({k: rows[-1].get(k) for k in ("E2", "R_over_h2", "peak_diff", "contact_l2",
                                                 "bond_l2", "time_shell", "time_2d")},
                  flush=True)
    table = rates(pd.DataFrame(rows))
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    table.to_csv(args.out, index=False)
    shown = [c for c in COLUMNS if c in table] + [c for c in table if c.startswith("failure")]
    with pd.option_context("display.width", 250, "display.max_columns", 40,
                           "display.float_format", "{:.4g}".format):
        print(table[shown].to_string(index=False))
    report = write_report(table, os.path.splitext(args.out)[0] + ".md",
                          command_line("studies.roller_models", argv))
    print(f"\nwritten to {args.out} and {report}")


if __name__ == "__main__":
    main()
