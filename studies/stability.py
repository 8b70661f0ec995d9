"""Maps of where each method converges, how fast and how accurately, from a finished
stability sweep (studies/sweeps/stability.toml). Reads the sweep's CSV files only,
except for the fine references (studies/reference.py), computed once if missing.

    python -m studies.stability results/stability

Writes results/stability/{loops,models}.png and findings.csv, and prints the tables the
docs/findings.md quotes.
"""

import argparse
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

from studies.bench import errors  # noqa: E402
from studies.claims import distance  # noqa: E402
from studies.reference import reference  # noqa: E402
from orchestrate.model import Settings  # noqa: E402

STATUS_COLOURS = {"converged": "#4caf50", "max_iterations": "#ffb300", "stagnated": "#fb8c00",
                  "diverged": "#e53935", "error": "#6d4c41", "invalid": "#9e9e9e"}
REFERENCE_H2 = (1.0, 0.5, 0.25, 0.125, 0.0625)     # fine references exist down to b/16


def _curves(folder):
    contact = pd.read_csv(os.path.join(folder, "contact.csv"))
    interface = pd.read_csv(os.path.join(folder, "interface.csv"))
    return contact.x1.to_numpy(), contact.sigma_n.to_numpy(), interface.sigma_n.to_numpy()


def default_penalty(row):
    """Whether a run's theta is the default of its loop and mesh (Settings)."""
    try:
        default = Settings(method=row.method, mesh_level=int(row.mesh_level),
                           element_size=float(row.element_size)).theta
    except (TypeError, ValueError):      # a run that could not run: no settings
        return False
    return bool(row.theta == default)


def add_accuracy(table, sweep_dir):
    """Errors against the fine reference (h2 >= b/16, default penalty, converged runs)."""
    table = table.copy()
    for column in ("error_12_L2", "error_23_L2", "error_peak"):
        table[column] = np.nan
    for i, row in table.iterrows():
        if (row.status != "converged" or row.h2 not in REFERENCE_H2
                or not default_penalty(row) or row.E2 not in (0.2, 1.0, 5.0)):
            continue
        x, sigma_12n, sigma_23n = _curves(os.path.join(sweep_dir, "runs", row.id))
        found = errors(x, sigma_12n, sigma_23n, reference(row.h2, row.E2, progress=print),
                       row.coating_length)
        for column in ("error_12_L2", "error_23_L2", "error_peak"):
            table.loc[i, column] = found[column]
    return table


def model_grid(table):
    """The runs of the models grid: accelerated, default penalty, Robin and mesh."""
    return table[(table.method == "active-set") & table.apply(default_penalty, axis=1)
                 & table.robin.isna() & (table.mesh_level == 1)]


def model_difference(table, sweep_dir):
    """Relative L2 distance between the shell's and the 2D model's contact stress."""
    grid = model_grid(table)
    rows = []
    for (h2, E2), group in grid.groupby(["h2", "E2"]):
        runs = {r.model: r for r in group.itertuples() if r.status == "converged"}
        if set(runs) == {"shell", "elastic"}:
            shell, elastic = (_curves(os.path.join(sweep_dir, "runs", runs[m].id))
                              for m in ("shell", "elastic"))
            if len(shell[0]) == len(elastic[0]):
                difference = distance((shell[0], shell[1]), (elastic[0], elastic[1]))
            else:          # the thin 2D coating refined its interface: compare on the shell's
                difference = distance((shell[0], shell[1]),
                                      (shell[0], np.interp(shell[0], elastic[0], elastic[1])))
            rows.append({"h2": h2, "E2": E2, "shell_vs_2d": difference})
    return pd.DataFrame(rows)


def _status_map(axis, runs, x, y, title):
    xs, ys = sorted(runs[x].unique()), sorted(runs[y].unique())
    for row in runs.itertuples():
        i, j = xs.index(getattr(row, x)), ys.index(getattr(row, y))
        axis.add_patch(plt.Rectangle((i - 0.5, j - 0.5), 1, 1,
                                     color=STATUS_COLOURS.get(row.status, "white")))
        label = f"{row.iterations:g}" if row.status == "converged" else row.status.replace("_", " ")
        axis.text(i, j, label, ha="center", va="center", fontsize=7)
    axis.set_xticks(range(len(xs)), [f"{v:g}" for v in xs])
    axis.set_yticks(range(len(ys)), [f"{v:g}" for v in ys])
    axis.set_xlim(-0.5, len(xs) - 0.5)
    axis.set_ylim(-0.5, len(ys) - 0.5)
    axis.set_xlabel(x)
    axis.set_ylabel(y)
    axis.set_title(title, fontsize=9)


def loops_chart(table, path):
    figure, axes = plt.subplots(2, 2, figsize=(10, 7.5))
    for column, model in enumerate(("shell", "elastic")):
        paper = table[(table.method == "paper") & (table.model == model)]
        _status_map(axes[0][column], paper, "rho", "theta",
                    f"paper's loop, {model}: iterations to eps_u = 1e-6, or why not")
        accelerated = table[(table.method == "active-set") & (table.model == model)
                            & table.robin.notna()]
        _status_map(axes[1][column], accelerated, "robin", "theta",
                    f"active-set loop, {model}: iterations (gamma against theta)")
    figure.tight_layout()
    figure.savefig(path, dpi=140)
    plt.close(figure)


def models_chart(table, differences, path):
    grid = model_grid(table)
    figure, axes = plt.subplots(1, 3, figsize=(15, 4.6))
    markers = {0.2: "v", 1.0: "o", 5.0: "^"}
    colours = {"shell": "tab:blue", "elastic": "tab:orange"}
    for (model, E2), group in grid.groupby(["model", "E2"]):
        group = group.sort_values("h2")
        ok = group[group.status == "converged"]
        label = f"{'shell' if model == 'shell' else '2D'}, E2 = {E2:g} E"
        axes[0].plot(ok.h2, ok.iterations, marker=markers[E2], color=colours[model], label=label)
        axes[1].plot(ok.h2, ok.wall_time_s, marker=markers[E2], color=colours[model], label=label)
        axes[2].plot(ok.h2, ok.error_12_L2, marker=markers[E2], color=colours[model], label=label)
    for E2, group in differences.groupby("E2"):
        group = group.sort_values("h2")
        axes[2].plot(group.h2, group.shell_vs_2d, ":", marker=markers[E2], color="0.4",
                     label=f"shell vs 2D, E2 = {E2:g} E")
    for axis, title in zip(axes, ("iterations to eps_u = 1e-6", "wall time of a run [s]",
                                  "L2 error of sigma_12n (solid: vs fine reference)")):
        axis.set_xscale("log", base=2)
        axis.set_xlabel("h2 / b")
        axis.set_title(title, fontsize=9)
        axis.grid(True, which="both", linewidth=0.3)
    axes[2].set_yscale("log")
    axes[2].legend(fontsize=6)
    axes[0].legend(fontsize=6)
    figure.tight_layout()
    figure.savefig(path, dpi=140)
    plt.close(figure)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("sweep_dir")
    args = parser.parse_args(argv)
    table = pd.read_csv(os.path.join(args.sweep_dir, "runs.csv"))
    table = add_accuracy(table, args.sweep_dir)
    differences = model_difference(table, args.sweep_dir)
    table.to_csv(os.path.join(args.sweep_dir, "findings.csv"), index=False)
    differences.to_csv(os.path.join(args.sweep_dir, "model_difference.csv"), index=False)
    loops_chart(table, os.path.join(args.sweep_dir, "loops.png"))
    models_chart(table, differences, os.path.join(args.sweep_dir, "models.png"))
    pd.set_option("display.width", 220)
    converged = table[table.converged.astype(bool)]
    wrong = converged[~(converged.final_relative_change < converged.eps_u)]
    print(f"{len(table)} runs; converged runs above eps_u: {len(wrong)}")
    print(table.status.value_counts().to_string())
    print(table[table.method == "paper"].pivot_table(
        index=["model", "theta"], columns="rho", values="iterations", aggfunc="first").to_string())
    print(table[table.method == "paper"].pivot_table(
        index=["model", "theta"], columns="rho", values="status", aggfunc="first").to_string())
    print(table[(table.method == "active-set") & table.robin.notna()].pivot_table(
        index=["model", "theta"], columns="robin", values="iterations", aggfunc="first").to_string())
    grid = model_grid(table)
    print(grid.pivot_table(index="h2", columns=["model", "E2"], values="iterations").to_string())
    print(grid.pivot_table(index="h2", columns=["model", "E2"], values="wall_time_s").round(2).to_string())
    print(grid.pivot_table(index="h2", columns=["model", "E2"], values="error_12_L2").round(4).to_string())
    print(differences.pivot_table(index="h2", columns="E2", values="shell_vs_2d").round(4).to_string())
    mesh = table[(table.mesh_level > 1) | ((table.mesh_level == 1) & table.h2.isin([1.0, 0.125])
                                           & (table.E2 == 1.0) & table.robin.isna()
                                           & (table.method == "active-set")
                                           & table.apply(default_penalty, axis=1))]
    print(mesh.pivot_table(index=["model", "h2"], columns="mesh_level",
                           values=["iterations", "wall_time_s", "error_12_L2"]).round(4).to_string())


if __name__ == "__main__":
    main()
