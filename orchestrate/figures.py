"""The paper's figures 3, 4 and 5 from finished runs (reads CSV, computes nothing).

    python -m orchestrate.figures fig3 RUN ...    # writes results/fig3.png, .pdf, _data.csv

The runs are given by the Makefile, one folder per scene; each figure takes what it
needs from the runs' summaries (model, h2, E2), so the run lists live in one place.
  fig3: sigma_12n/E on S12; panels h2 = b, b/8; curves E2 = 5E (1), E (2);
        solid: shell model, dashed: 2D coating model.
  fig4: sigma_23n/E on S23; panels E2 = 5E, E; curves h2 = b ... b/16; both models.
  fig5: isolines of sigma_eq/E in the 2D coating; panels E2 = E/5, E, 5E; h2 = b ... b/8.
"""

import argparse
import json
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pandas as pd  # noqa: E402

from .paths import RESULTS_DIR  # noqa: E402
from .scene import scene_from_dict  # noqa: E402
from .scene_file import shorthand_values  # noqa: E402

# Every scene the three figures need, (model, h2, E2): the same list as the Makefile's
# FIG3_RUNS, FIG4_RUNS and FIG5_RUNS together (tests/test_paper_claims.py checks it).
FIGURE_HEIGHTS = (1.0, 0.5, 0.25, 0.125, 0.0625)
FIGURE_SCENES = sorted(
    {(model, h2, E2) for model in ("shell", "elastic") for h2 in FIGURE_HEIGHTS for E2 in (5.0, 1.0)}
    | {("elastic", h2, E2) for h2 in FIGURE_HEIGHTS[:4] for E2 in (0.2, 1.0, 5.0)})

LINESTYLE = {"shell": "-", "elastic": "--"}
MODEL_NAME = {"shell": "shell", "elastic": "2D coating"}


def load_runs(folders):
    """One row per run: model, h2, E2 and the folder."""
    rows = []
    for folder in folders:
        folder = folder[:-len("summary.json")] if folder.endswith("summary.json") else folder
        with open(os.path.join(folder, "summary.json")) as f:
            summary = json.load(f)
        values = shorthand_values(scene_from_dict(summary["scene"]))
        rows.append({"model": values["model"], "h2": values["h2"], "E2": values["E2"],
                     "height": values["height"], "folder": folder,
                     "converged": summary["converged"]})
    runs = pd.DataFrame(rows)
    if not runs["converged"].all():
        raise SystemExit("some runs did not converge: " + ", ".join(runs[~runs.converged].folder))
    return runs


def _fraction(value):
    """h2 or E2 as the paper writes it: b, b/8, 5E, E/5."""
    if value >= 1:
        return f"{value:g}" if value != 1 else ""
    return f"/{1 / value:g}"


def _label_h2(h2):
    return "b" + _fraction(h2) if h2 < 1 else f"{_fraction(h2)}b"


def _label_E2(E2):
    return "E" + _fraction(E2) if E2 < 1 else f"{_fraction(E2)}E"


def _save(figure, name, data, out_dir):
    os.makedirs(out_dir, exist_ok=True)
    for extension in ("png", "pdf"):
        figure.savefig(os.path.join(out_dir, f"{name}.{extension}"), dpi=150)
    plt.close(figure)
    data.to_csv(os.path.join(out_dir, f"{name}_data.csv"), index=False)


def _stress_curves(runs, file, panel_key, panel_values, curve_key, curve_values, ylabel,
                   title_of):
    figure, axes = plt.subplots(1, len(panel_values), figsize=(5.2 * len(panel_values), 4.2),
                                sharey=True)
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    data = []
    for axis, panel in zip(axes, panel_values):
        for number, curve in enumerate(curve_values, start=1):
            for model in ("shell", "elastic"):
                match = runs[(runs[panel_key] == panel) & (runs[curve_key] == curve)
                             & (runs.model == model)]
                if match.empty:
                    continue
                table = pd.read_csv(os.path.join(match.folder.iloc[0], file))
                axis.plot(table.x1, table.sigma_n, LINESTYLE[model], color=colours[number - 1],
                          label=f"{number}: {title_of(curve)}, {MODEL_NAME[model]}")
                data.append(pd.DataFrame({panel_key: panel, curve_key: curve, "curve": number,
                                          "model": model, "x1": table.x1,
                                          "sigma_n": table.sigma_n}))
        axis.set_title(f"{panel_key} = {(_label_h2 if panel_key == 'h2' else _label_E2)(panel)}")
        axis.set_xlabel(r"$x_1/b$")
        axis.axhline(0.0, color="0.8", linewidth=0.8)
        axis.set_xlim(0, 2)
    axes[0].set_ylabel(ylabel)
    axes[-1].legend(fontsize=7)
    figure.tight_layout()
    return figure, pd.concat(data, ignore_index=True)


def fig3(runs, out_dir):
    figure, data = _stress_curves(runs, "contact.csv", "h2", [1.0, 0.125], "E2", [5.0, 1.0],
                                  r"$\sigma_{12n}/E$ on $S_{12}$", _label_E2)
    _save(figure, "fig3", data, out_dir)


def fig4(runs, out_dir):
    figure, data = _stress_curves(runs, "interface.csv", "E2", [5.0, 1.0], "h2",
                                  [1.0, 0.5, 0.25, 0.125, 0.0625],
                                  r"$\sigma_{23n}/E$ on $S_{23}$", _label_h2)
    _save(figure, "fig4", data, out_dir)


def coating_field(folder):
    """Nodal sigma_eq of the 2D coating: x1, x2 and sigma_eq (coating1.csv)."""
    return pd.read_csv(os.path.join(folder, "coating1.csv"))


def fig5(runs, out_dir):
    moduli, heights = [0.2, 1.0, 5.0], [1.0, 0.5, 0.25, 0.125]
    figure, axes = plt.subplots(len(heights), len(moduli), figsize=(13, 8), squeeze=False)
    data = []
    for column, E2 in enumerate(moduli):
        for row, h2 in enumerate(heights):
            axis = axes[row][column]
            match = runs[(runs.model == "elastic") & (runs.E2 == E2) & (runs.h2 == h2)]
            if match.empty:
                axis.set_visible(False)
                continue
            field = coating_field(match.folder.iloc[0])
            height = match.height.iloc[0]
            local = field.x2 - height
            contours = axis.tricontour(field.x1, local, field.sigma_eq, levels=10,
                                       linewidths=0.8, cmap="viridis")
            axis.clabel(contours, fontsize=5, fmt="%.1e")
            peak = field.sigma_eq.idxmax()
            axis.plot(field.x1[peak], local[peak], "r*", markersize=8)
            axis.set_xlim(0, 2)
            axis.set_title(f"$E_2$ = {_label_E2(E2)}, $h_2$ = {_label_h2(h2)}: max "
                           f"{field.sigma_eq.max():.2e}", fontsize=8)
            if column == 0:
                axis.set_ylabel(r"$(x_2 - h)/b$")
            if row == len(heights) - 1:
                axis.set_xlabel(r"$x_1/b$")
            data.append(field.assign(E2=E2, h2=h2)[["E2", "h2", "x1", "x2", "sigma_eq"]])
    figure.suptitle(r"$\sigma_{eq}/E$ in the 2D coating (red star: maximum)")
    figure.tight_layout()
    _save(figure, "fig5", pd.concat(data, ignore_index=True), out_dir)


FIGURES = {"fig3": fig3, "fig4": fig4, "fig5": fig5}


def main(argv=None):
    parser = argparse.ArgumentParser(description="Draw one of the paper's figures.")
    parser.add_argument("figure", choices=sorted(FIGURES))
    parser.add_argument("runs", nargs="+", help="run folders (or their summary.json)")
    parser.add_argument("--out", default=str(RESULTS_DIR))
    args = parser.parse_args(argv)
    FIGURES[args.figure](load_runs(args.runs), args.out)
    print(os.path.join(args.out, f"{args.figure}.png"))


if __name__ == "__main__":
    main()
