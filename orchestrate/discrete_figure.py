"""The discrete-coating figure (``make discrete``): a cylinder over a coating in patches
(orchestrate/scenes/discrete.toml), both coating models, from finished runs (reads
CSV, computes nothing).

    python -m orchestrate.discrete_figure SHELL_RUN ELASTIC_RUN   # results/discrete.png, .pdf, _data.csv

Three panels along the surface, x1/b: the contact pressure -sigma_n on the patches'
tops and the bare base, and the bond's normal and shear stress under the patches;
solid: shell model, dashed: 2D coating model; patches shaded. A bonded end of a patch
off the symmetry axis is a re-entrant corner of two bonded materials: the 2D model's
stresses there are singular (they grow without bound as the mesh is refined) and the
shell's are the mesh-dependent values of a model without that corner; the figure marks
those ends and their values are not stresses to design with.
"""

import argparse
import json
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pandas as pd  # noqa: E402

from .paths import RESULTS_DIR  # noqa: E402

LINESTYLE = {"shell": "-", "elastic": "--"}
MODEL_NAME = {"shell": "shell", "elastic": "2D coating"}


def load(folder):
    """(model, summary, contact table, bond table) of a finished run."""
    with open(os.path.join(folder, "summary.json")) as f:
        summary = json.load(f)
    if not summary["converged"]:
        raise SystemExit(f"{folder} did not converge: {summary['reason']}")
    models = {c["model"] for c in summary["scene"]["coatings"]}
    if len(models) != 1:
        raise SystemExit(f"{folder}: the figure compares runs with one model for every patch")
    contact = pd.read_csv(os.path.join(folder, "contact.csv"))
    bond = pd.read_csv(os.path.join(folder, "interface.csv"))
    return models.pop(), summary, contact, bond


def singular_ends(scene):
    """x1 of every bonded patch end off the symmetry axis of a half model."""
    ends = []
    for coating in scene["coatings"]:
        for x1 in (coating["start"], coating["end"]):
            if not (scene["symmetric"] and x1 == 0.0):
                ends.append(x1)
    return ends


def figure(folders, out_dir):
    runs = [load(folder) for folder in folders]
    scene = runs[0][1]["scene"]
    panels = [("contact", "sigma_n", r"contact pressure $-\sigma_n/E$", -1.0),
              ("bond", "sigma_n", r"bond normal stress $\sigma_{23n}/E$", 1.0),
              ("bond", "sigma_t", r"bond shear stress $\sigma_{23t}/E$", 1.0)]
    plot, axes = plt.subplots(len(panels), 1, figsize=(8.0, 9.0), sharex=True)
    data = []
    for axis, (table, column, label, sign) in zip(axes, panels):
        for coating in scene["coatings"]:
            axis.axvspan(coating["start"], coating["end"], color="0.92", zorder=0)
        for model, summary, contact, bond in runs:
            frame = contact if table == "contact" else bond
            for k, (name, part) in enumerate(frame.groupby("interface", sort=False)):
                axis.plot(part.x1, sign * part[column], LINESTYLE[model], color="C0" if
                          model == "shell" else "C1", linewidth=1.2,
                          label=MODEL_NAME[model] if k == 0 else None)
                data.append(pd.DataFrame({"model": model, "quantity": f"{table} {column}",
                                          "interface": name, "x1": part.x1,
                                          "value": sign * part[column]}))
        for x1 in singular_ends(scene):
            axis.axvline(x1, color="tab:red", linewidth=0.6, linestyle=":")
        axis.axhline(0.0, color="0.6", linewidth=0.6)
        axis.set_ylabel(label)
    top = axes[0]
    for x1 in singular_ends(scene):
        top.annotate("singular\n(bonded end)", (x1, 1.0), xycoords=("data", "axes fraction"),
                     ha="center", va="bottom", fontsize=7, color="tab:red")
    axes[0].legend(loc="upper right", fontsize=8)
    axes[-1].set_xlabel(r"$x_1/b$ (half model: symmetry at $x_1 = 0$; grey: coating patches)")
    reach = max(c["end"] for c in scene["coatings"])
    axes[-1].set_xlim(0.0 if scene["symmetric"] else -reach - 0.25, reach + 0.25)
    force = runs[0][1]["total_force"]
    radius = scene["indenter"]["radius"]
    plot.suptitle(f"Cylinder R = {radius:g} b over {len(scene['coatings'])} coating patches, "
                  f"force {force:.3g} Eb per unit width (dotted red: singular bonded ends)",
                  fontsize=10)
    plot.tight_layout()
    os.makedirs(out_dir, exist_ok=True)
    for extension in ("png", "pdf"):
        plot.savefig(os.path.join(out_dir, f"discrete.{extension}"), dpi=150)
    plt.close(plot)
    pd.concat(data, ignore_index=True).to_csv(os.path.join(out_dir, "discrete_data.csv"),
                                              index=False)
    return os.path.join(out_dir, "discrete.png")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("runs", nargs="+", help="run folders of the discrete scene, one per model")
    parser.add_argument("--out", default=str(RESULTS_DIR))
    args = parser.parse_args(argv)
    print(figure([r[:-len("summary.json")] if r.endswith("summary.json") else r
                  for r in args.runs], args.out))


if __name__ == "__main__":
    main()
