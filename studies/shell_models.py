"""The coating on its mid-line against the full 2D coating (not a test): on the paper's
scene, for every figure height h2 and E2 = E/5, E, 5E, the Timoshenko shell (the
paper's model) and the shell with thickness stretch, each on the paper's mesh, against
the fine reference of the 2D coating model (studies/reference.py: the monolithic
solve refined until its peak converges). Errors as the benchmark's (studies/bench.py):
the peak contact stress, the contact stress in L2, and sigma_23n on the bond (its peak,
its L2 on x1 < 0.9 l2, away from the singular bonded end).

    python -m studies.shell_models          # prints a table, writes CSV
"""

import argparse
import os
import tempfile

import pandas as pd

from studies.bench import coating_length, errors
from studies.figure_scenes import FIGURE_HEIGHTS
from studies.paths import RESULTS_DIR
from studies.reference import reference
from orchestrate.model import Settings
from orchestrate.model import paper_scene
from orchestrate.run import solve_into as solve

MODELS = ("shell", "stretch_shell")
MODULI = (0.2, 1.0, 5.0)
TIGHT = Settings(eps_u=1e-9)     # the loop's error far below the models'


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


def markdown(table):
    """Per scene: each model's peak, L2 and bond errors, in per cent."""
    lines = ["| h2 | E2 | " + " | ".join(f"{m}: {q}" for m in MODELS
                                          for q in ("peak", "L2", "bond peak", "bond L2")) + " |",
             "|---|---|" + "---|" * (4 * len(MODELS))]
    for (h2, E2), group in table.groupby(["h2", "E2"], sort=False):
        cells = []
        for model in MODELS:
            row = group[group.model == model].iloc[0]
            cells += [f"{100 * row.error_peak:+.2f} %", f"{100 * row.error_12_L2:.2f} %",
                      f"{100 * row.error_bond_peak:+.2f} %", f"{100 * row.error_23_L2:.2f} %"]
        lines.append(f"| {h2:g} | {E2:g} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--heights", nargs="*", type=float, default=list(FIGURE_HEIGHTS))
    parser.add_argument("--moduli", nargs="*", type=float, default=list(MODULI))
    args = parser.parse_args(argv)
    table = study(args.heights, args.moduli)
    RESULTS_DIR.mkdir(parents=True, exist_ok=True)
    table.to_csv(RESULTS_DIR / "shell_models.csv", index=False)
    print(markdown(table))


if __name__ == "__main__":
    main()
