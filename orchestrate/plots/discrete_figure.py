"""The discrete-coating figure (``make discrete``): a cylinder over a coating in patches
(orchestrate/scenes/discrete.toml), both coating models, from finished runs (reads
CSV, computes nothing).

    python -m orchestrate.plots.discrete_figure SHELL_RUN ELASTIC_RUN --out results/discrete.png
    # writes results/discrete.png, discrete.pdf and discrete_data.csv beside it

Without --out the figure is discrete.png in the current folder. The runs must be of one
scene in one set of units, apart from the coating model (refused otherwise).

Three panels along the surface, x1 in the runs' units: the contact pressure -sigma_n on
the patches' tops and the bare base, and the bond's normal and shear stress under the
patches; solid: shell model, dashed: 2D coating model; patches shaded. A bonded end of a
patch off the symmetry axis is a re-entrant corner of two bonded materials: the 2D
model's stresses there are singular (they grow without bound as the mesh is refined)
and the shell's are the mesh-dependent values of a model without that corner; the
figure marks those ends and their values are not stresses to design with.
"""

import argparse
import json
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pandas as pd  # noqa: E402

from orchestrate.model.units import force_label, force_name  # noqa: E402

LINESTYLE = {"shell": "-", "stretch_shell": "-.", "elastic": "--"}
COLOUR = {"shell": "C0", "stretch_shell": "C2", "elastic": "C1"}
MODEL_NAME = {"shell": "shell", "stretch_shell": "shell with stretch",
              "elastic": "2D coating"}
DEFAULT_OUT = "discrete.png"


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


def run_units(summary):
    """(length, stress, force) unit names of a run; a run older than units: b and E."""
    units = summary.get("units", {})
    length, stress = units.get("length", "b"), units.get("stress", "E")
    force = units.get("force", force_name(stress, length))
    return length, stress, force_label(force)


def _scene_but_models(summary):
    scene = dict(summary["scene"])
    scene["coatings"] = [{k: v for k, v in c.items() if k != "model"}
                         for c in scene["coatings"]]
    return scene


def check_comparable(folders, runs):
    """SystemExit naming the first run whose units or scene (but for the coating model)
    differ from the first run's: their curves would not share the axes."""
    first = runs[0][1]
    for folder, (_, summary, _, _) in zip(folders[1:], runs[1:]):
        if run_units(summary) != run_units(first):
            raise SystemExit(f"{folder} is in {'/'.join(run_units(summary)[:2])}, "
                             f"{folders[0]} in {'/'.join(run_units(first)[:2])}: the figure "
                             "compares runs in the same units")
        if _scene_but_models(summary) != _scene_but_models(first):
            raise SystemExit(f"{folder} and {folders[0]} are runs of different scenes: the "
                             "figure compares the coating models on one scene")


def singular_ends(scene):
    """x1 of every bonded patch end off the symmetry axis of a half model."""
    ends = []
    for coating in scene["coatings"]:
        for x1 in (coating["start"], coating["end"]):
            if not (scene["symmetric"] and x1 == 0.0):
                ends.append(x1)
    return ends


def output_paths(out):
    """(png, pdf, data csv) beside one another: discrete.png, discrete.pdf,
    discrete_data.csv; SystemExit unless ``out`` names a PNG file."""
    stem, extension = os.path.splitext(str(out))
    if extension.lower() != ".png" or not os.path.basename(stem):
        raise SystemExit(f"--out {out}: give the PNG file's path, e.g. results/discrete.png "
                         "(its .pdf and _data.csv are written beside it)")
    return str(out), stem + ".pdf", stem + "_data.csv"


def figure(folders, out=DEFAULT_OUT):
    """Draw the figure of the runs in ``folders`` into ``out`` (a PNG path), its PDF and
    data beside it; return the PNG's path."""
    png, pdf, data_csv = output_paths(out)
    runs = [load(folder) for folder in folders]
    check_comparable(folders, runs)
    plot, data = draw(runs)
    if os.path.dirname(png):
        os.makedirs(os.path.dirname(png), exist_ok=True)
    try:
        plot.savefig(png, dpi=150)
        plot.savefig(pdf)
    finally:
        plt.close(plot)
    data.to_csv(data_csv, index=False)
    return png


def draw(runs):
    """(the figure, its data) of ``runs``, load()'s tuples of one scene in one set of
    units."""
    scene = runs[0][1]["scene"]
    length, stress, force_unit = run_units(runs[0][1])
    panels = [("contact", "sigma_n", rf"contact pressure $-\sigma_n$ ({stress})", -1.0),
              ("bond", "sigma_n", rf"bond normal stress $\sigma_{{23n}}$ ({stress})", 1.0),
              ("bond", "sigma_t", rf"bond shear stress $\sigma_{{23t}}$ ({stress})", 1.0)]
    plot, axes = plt.subplots(len(panels), 1, figsize=(8.0, 9.0), sharex=True)
    data = []
    for axis, (table, column, label, sign) in zip(axes, panels):
        for coating in scene["coatings"]:
            axis.axvspan(coating["start"], coating["end"], color="0.92", zorder=0)
        for model, summary, contact, bond in runs:
            frame = contact if table == "contact" else bond
            for k, (name, part) in enumerate(frame.groupby("interface", sort=False)):
                axis.plot(part.x1, sign * part[column], LINESTYLE.get(model, ":"),
                          color=COLOUR.get(model, "C3"), linewidth=1.2,
                          label=MODEL_NAME.get(model, model) if k == 0 else None)
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
    axes[-1].set_xlabel(rf"$x_1$ ({length})" + (r" (half model: symmetry at $x_1 = 0$;"
                                                 if scene["symmetric"] else " (")
                        + " grey: coating patches)")
    reach = max(c["end"] for c in scene["coatings"])
    axes[-1].set_xlim(0.0 if scene["symmetric"] else -reach * 1.125, reach * 1.125)
    force = runs[0][1]["total_force"]
    radius = scene["indenter"]["radius"]
    indenter = f"Cylinder R = {radius:g} {length}" if radius is not None else "A flat indenter"
    patches = len(scene["coatings"])
    plot.suptitle(f"{indenter} over {patches} coating patch{'es' if patches > 1 else ''}, "
                  f"force {force:.4g} {force_unit}\n(dotted red: singular "
                  "bonded ends)", fontsize=10)
    plot.tight_layout()
    return plot, pd.concat(data, ignore_index=True)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("runs", nargs="+", help="run folders of the discrete scene, one per "
                        "model (a summary.json's path is taken as its folder)")
    parser.add_argument("--out", default=DEFAULT_OUT, metavar="PNG",
                        help="the PNG file; its .pdf and _data.csv are written beside it "
                             f"(default: {DEFAULT_OUT} in the current folder; `make "
                             "discrete` passes results/discrete.png)")
    args = parser.parse_args(argv)
    print(figure([r[:-len("summary.json")] if r.endswith("summary.json") else r
                  for r in args.runs], args.out))


if __name__ == "__main__":
    main()
