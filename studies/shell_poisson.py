"""Why the shells' bond shear differs from the 2D coating's (not a test): the coating's
Poisson ratio.

The hypothesis (issue 28): under the contact pressure p the 2D coating is compressed
through its thickness and, through nu2, pushed to expand in-plane; held by the base, it
carries an in-plane stress of about nu2 / (1 - nu2) p that the paper's shell (its
membrane force from the bond's shear alone) leaves out, so its bond shear is off by an
amount that does not vanish as the coating thins. If so, the shells' error in bond
shear should change with nu2 and, at nu2 = 0, shrink as h2 -> 0.

On the paper's scene (E2 = E), for nu2 = 0.3 and 0, h2 = b/8 ... b/64, mesh levels 1 and
2: the 2D coating, the Timoshenko shell and the stretch shell, each at the default
settings; per run the bond's largest shear away from the patch's end zones (where it
is, near the contact's edge), the peak contact pressure and the bond's largest
compression, and each shell's difference from the 2D coating at the same mesh level.

Writes results/shell_poisson.csv and the report results/shell_poisson.md.

    python -m studies.shell_poisson
    python -m studies.shell_poisson --levels 1 --heights 0.125 0.0625     # shorter
"""

import argparse
import os

import pandas as pd

import orchestrate
from orchestrate.model import Settings, apply_overrides
from studies.paths import RESULTS_DIR
from studies.report import Column, Report, command_line, fraction_of_b, signed_percent

POISSON = (0.3, 0.0)
HEIGHTS = (0.125, 0.0625, 0.03125, 0.015625)
LEVELS = (1, 2)
MODELS = ("elastic", "shell", "stretch_shell")


def solve(nu2, h2, level, model, session):
    scene = apply_overrides(orchestrate.paper_scene(h2=h2, model=model), {"coating.nu": nu2})
    summary = orchestrate.solve(scene, Settings(mesh_level=level), session=session).summary
    bond = summary["answers"]["bonds"]["bond-coating1"]
    return {"nu2": nu2, "h2": h2, "mesh_level": level, "model": model,
            "bond_shear": bond["shear"]["value"], "bond_shear_x1": bond["shear"]["x1"],
            "bond_compression": -bond["compression"]["value"],
            "peak_pressure": -summary["peak_contact_stress"]}


def study(poisson=POISSON, heights=HEIGHTS, levels=LEVELS, progress=print):
    rows = []
    with orchestrate.Session() as session:
        for nu2 in poisson:
            for level in levels:
                for h2 in heights:
                    for model in MODELS:
                        rows.append(solve(nu2, h2, level, model, session))
                    progress(f"nu2 = {nu2:g}, mesh level {level}, h2 = {h2:g} b: done")
    table = pd.DataFrame(rows)
    key = ["nu2", "h2", "mesh_level"]
    reference = table[table.model == "elastic"].set_index(key)
    for quantity in ("bond_shear", "bond_compression", "peak_pressure"):
        table[f"{quantity}_error"] = [
            row[quantity] / reference.loc[tuple(row[k] for k in key), quantity] - 1.0
            for _, row in table.iterrows()]
    return table


def _errors(table, model, nu2, level):
    rows = table[(table.model == model) & (table.nu2 == nu2) & (table.mesh_level == level)]
    return ", ".join(f"{signed_percent(e, 1)}" for e in rows.sort_values("h2", ascending=False)
                     .bond_shear_error)


def write_report(table, out, command="python -m studies.shell_poisson"):
    report = Report("The shells' bond shear and the coating's Poisson ratio", command,
                    data=[os.path.basename(os.path.splitext(out)[0]) + ".csv"])
    report.text("The paper's scene (E2 = E) with the coating's nu2 = 0.3 and 0: the shells' "
                "bond shear (its largest away from the patch's end zones) against the 2D "
                "coating's at the same mesh level, h2 from b/8 down.")
    for model, name in (("shell", "Timoshenko shell"), ("stretch_shell", "stretch shell")):
        for level in sorted(table.mesh_level.unique()):
            report.finding(f"{name}, mesh level {level}, bond shear against the 2D coating "
                           f"as h2 halves: nu2 = 0.3: {_errors(table, model, 0.3, level)}; "
                           f"nu2 = 0: {_errors(table, model, 0.0, level)}.")
    shells = table[table.model != "elastic"]
    report.table(shells, [
        Column("model", "model"), Column("nu2", "nu2", "{:g}"),
        Column("mesh_level", "level", "{:g}"), Column("h2", "h2", fraction_of_b),
        Column("bond_shear_error", "bond shear", signed_percent,
               "largest bond shear away from the end zones, against the 2D coating's"),
        Column("bond_shear_x1", "at x1", "{:.3g}", "where it is (b)"),
        Column("bond_compression_error", "bond compression", signed_percent),
        Column("peak_pressure_error", "peak pressure", signed_percent)])
    return report.write(out)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default=str(RESULTS_DIR / "shell_poisson.csv"))
    parser.add_argument("--heights", type=float, nargs="+", default=list(HEIGHTS))
    parser.add_argument("--levels", type=int, nargs="+", default=list(LEVELS))
    args = parser.parse_args(argv)
    table = study(POISSON, args.heights, args.levels)
    os.makedirs(os.path.dirname(args.out) or ".", exist_ok=True)
    table.to_csv(args.out, index=False)
    print(table.to_string(index=False, float_format=lambda v: f"{v:.4g}"))
    print(write_report(table, os.path.splitext(args.out)[0] + ".md",
                       command_line("studies.shell_poisson", argv)))


if __name__ == "__main__":
    main()
