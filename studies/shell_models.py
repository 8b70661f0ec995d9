"""The coating on its mid-line against the full 2D coating (not a test): on the paper's
scene, for every figure height h2 and E2 = E/5, E, 5E, the Timoshenko shell (the
paper's model) and the shell with thickness stretch, each on the paper's mesh, against
the fine reference of the 2D coating model (studies/reference.py: the monolithic
solve refined until its peak converges). Errors as the benchmark's (studies/bench.py):
the peak contact stress, the contact stress in L2, and sigma_23n on the bond (its peak,
its L2 on x1 < 0.9 l2, away from the singular bonded end).

Writes results/shell_models.csv and the report results/shell_models.md.

    python -m studies.shell_models          # prints a table, writes CSV and the report
    python -m studies.shell_models --heights 1 0.125 --moduli 1     # shorter
"""

import argparse
import os
import tempfile

import pandas as pd

from studies.bench import coating_length, errors
from studies.figure_scenes import FIGURE_HEIGHTS
from studies.paths import RESULTS_DIR
from studies.report import (Column, Report, command_line, fraction_of_b, fraction_of_E,
                            listing, percent, signed_percent)
from studies.reference import reference
from orchestrate.model import Settings
from orchestrate.model import paper_scene
from orchestrate.run import solve_into as solve

MODELS = ("shell", "stretch_shell")
MODULI = (0.2, 1.0, 5.0)
MODEL_NAMES = {"shell": "Timoshenko shell", "stretch_shell": "stretch shell"}
TIGHT = Settings(eps_u=1e-9)     # the loop's error far below the models'
THIN = 0.125                     # h2 <= b/8: the thin coatings the findings group


def compare(h2, E2, model, ref):
    scene = paper_scene(h2=h2, E2=E2, model=model)
    with tempfile.TemporaryDirectory() as out:
        summary = solve(scene, TIGHT, out)
        contact = pd.read_csv(os.path.join(out, "contact.csv"))
        bond = pd.read_csv(os.path.join(out, "interface.csv"))
    row = {"model": model, "h2": h2, "E2": E2, "wall_time_s": summary["wall_time_s"],
           **errors(contact.x1.to_numpy(), contact.sigma_n.to_numpy(),
                    bond.sigma_n.to_numpy(), ref, coating_length(scene))}
    keep = bond.x1 < 0.9 * coating_length(scene)
    reference_bond = ref[ref.x1 < 0.9 * coating_length(scene)].sigma_23n
    row["error_bond_peak"] = float(bond.sigma_n[keep].min() / reference_bond.min() - 1.0)
    return row


def study(heights=FIGURE_HEIGHTS, moduli=MODULI):
    rows = []
    for h2 in heights:
        for E2 in moduli:
            ref = reference(h2, E2, progress=lambda row: None)
            for model in MODELS:
                rows.append(compare(h2, E2, model, ref))
                print({k: (f"{v:+.4f}" if k.startswith("error") else v)
                       for k, v in rows[-1].items()}, flush=True)
    return pd.DataFrame(rows)


def worst(table):
    """Per model and h2, the largest |error| over the moduli of each quantity."""
    quantities = ["error_peak", "error_12_L2", "error_bond_peak", "error_23_L2"]
    return table.assign(**{q: table[q].abs() for q in quantities}).groupby(
        ["model", "h2"], sort=False)[quantities].max().reset_index()


def write_report(table, out, command="python -m studies.shell_models"):
    report = Report("The shell and the stretch shell against the fine 2D reference", command,
                    data=[os.path.basename(os.path.splitext(out)[0]) + ".csv"])
    report.text("The paper's scene and mesh, each shell model against the fine reference of "
                "the 2D coating model (studies/reference.py); relative errors: the peak "
                "contact stress (signed: + too stiff), the contact stress in L2, and on the "
                "bond (sigma_23n) its peak and L2 on x1 < 0.9 l2 (away from the singular "
                "bonded end). The Robin loop to eps_u = 1e-9.")
    columns = [Column("h2", "h2", fraction_of_b), Column("E2", "E2", fraction_of_E)]
    for model in MODELS:
        name = MODEL_NAMES[model]
        columns += [Column(f"{model}_error_peak", f"{name}: peak", signed_percent),
                    Column(f"{model}_error_12_L2", f"{name}: L2", percent),
                    Column(f"{model}_error_bond_peak", f"{name}: bond peak", signed_percent),
                    Column(f"{model}_error_23_L2", f"{name}: bond L2", percent)]
    wide = table.pivot_table(index=["h2", "E2"], columns="model", values=[
        "error_peak", "error_12_L2", "error_bond_peak", "error_23_L2"])
    wide.columns = [f"{model}_{quantity}" for quantity, model in wide.columns]
    wide = wide.reset_index().sort_values(["h2", "E2"], ascending=[False, True])
    report.table(wide, columns)
    thick = table[table.h2 == table.h2.max()].sort_values("E2")
    if len(thick):
        report.finding(
            f"At h2 = {fraction_of_b(thick.h2.iloc[0])} the peak contact stress is off by "
            + "; ".join(f"{MODEL_NAMES[model]} " + ", ".join(
                f"{signed_percent(r.error_peak)} ({fraction_of_E(r.E2)})"
                for r in thick[thick.model == model].itertuples()) for model in MODELS)
            + ".")
    thin = worst(table[table.h2 <= THIN])
    if len(thin):
        by_model = thin.groupby("model").max(numeric_only=True)
        report.finding(
            f"At h2 <= {fraction_of_b(THIN)} ("
            + listing(fraction_of_b(h) for h in sorted(table.h2[table.h2 <= THIN].unique(),
                                                       reverse=True))
            + "), "
            "over every modulus, the worst errors are: "
            + "; ".join(f"{MODEL_NAMES[model]} {percent(r.error_peak)} in peak, "
                        f"{percent(r.error_12_L2)} in L2, {percent(r.error_bond_peak)} in "
                        "the bond's peak" for model, r in by_model.iterrows()) + ".")
    per_h2 = worst(table)
    report.section("The worst over the moduli, per thickness")
    report.table(per_h2, [Column("model", "model", MODEL_NAMES.get),
                          Column("h2", "h2", fraction_of_b),
                          Column("error_peak", "peak", percent),
                          Column("error_12_L2", "L2", percent),
                          Column("error_bond_peak", "bond peak", percent),
                          Column("error_23_L2", "bond L2", percent)])
    return report.write(out)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--heights", nargs="*", type=float, default=list(FIGURE_HEIGHTS))
    parser.add_argument("--moduli", nargs="*", type=float, default=list(MODULI))
    parser.add_argument("--out", default=str(RESULTS_DIR / "shell_models.csv"),
                        help="the table; the report goes beside it (shell_models.md)")
    args = parser.parse_args(argv)
    table = study(args.heights, args.moduli)
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    table.to_csv(args.out, index=False)
    print(write_report(table, os.path.splitext(args.out)[0] + ".md",
                       command_line("studies.shell_models", argv)))


if __name__ == "__main__":
    main()
