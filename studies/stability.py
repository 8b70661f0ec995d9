"""Maps of where each method converges, how fast and how accurately, from a finished
stability sweep (studies/sweeps/stability.toml). Reads the sweep's CSV files only,
except for the fine references (studies/reference.py), computed once if missing.

    python -m studies.stability results/stability

Writes results/stability/{loops,models}.png, findings.csv (runs.csv with each run's
errors against the fine reference), model_difference.csv and the report report.md: the
runs' outcomes, where each loop converges, the coating models' cost and accuracy over h2
and E2, what the mesh level buys, with the findings computed from them.
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
from studies.report import (Column, Report, command_line, fraction_of_b,  # noqa: E402
                            fraction_of_E, listing, percent, seconds, span)

MODEL_NAMES = {"shell": "shell", "elastic": "2D"}
CLOSE = 0.01          # shell and 2D "agree" when their contact stresses are this close (L2)

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


def _cell(runs, value="iterations"):
    """A map cell over both models: the value where converged, else the status; one
    entry when the models agree."""
    entries = {}
    for row in runs.itertuples():
        entries[row.model] = (f"{getattr(row, value):g}" if row.status == "converged"
                              else row.status.replace("_", " "))
    if len(set(entries.values())) == 1:
        return next(iter(entries.values()))
    return ", ".join(f"{entry} ({MODEL_NAMES[model]})" for model, entry in sorted(entries.items()))


def _map(runs, rows, columns, label):
    """Rows of a markdown map: one per value of ``rows``, a column per value of ``columns``."""
    table = []
    for r in sorted(runs[rows].unique(), reverse=True):
        line = {rows: r}
        for c in sorted(runs[columns].unique()):
            cell = runs[(runs[rows] == r) & (runs[columns] == c)]
            line[c] = _cell(cell) if len(cell) else ""
        table.append(line)
    return table, [Column(rows, rows, "{:g}")] + [
        Column(c, f"{label} = {c:g}", lambda v: v) for c in sorted(runs[columns].unique())]


def _run_summary(sweep_dir, run_id):
    import json
    with open(os.path.join(sweep_dir, "runs", run_id, "summary.json")) as f:
        return json.load(f)


def agreeing_from(differences, E2):
    """The largest h2 from which (it and every thinner h2) the shell and the 2D model
    agree within CLOSE, for E2; None if not even the thinnest."""
    part = differences[differences.E2 == E2].sort_values("h2")
    found = None
    for row in part.itertuples():
        if row.shell_vs_2d > CLOSE:
            break
        found = row.h2
    return found


def mesh_runs(table):
    """The mesh-level runs: every (model, h2, E2) solved at a level above 1 (default
    loop and penalty), with its level-1 run."""
    default = table.apply(default_penalty, axis=1) & table.robin.isna() & (
        table.method == "active-set")
    fine = table[default & (table.mesh_level > 1)]
    keys = set(zip(fine.model, fine.h2, fine.E2))
    listed = pd.Series([k in keys for k in zip(table.model, table.h2, table.E2)],
                       index=table.index)
    return table[default & listed]


def write_report(table, differences, sweep_dir, out, command):
    report = Report("Where each method converges: the stability map", command,
                    data=["runs.csv", "findings.csv", "model_difference.csv"])
    report.text("Every run of the stability sweep (studies/sweeps/stability.toml), one run "
                "each on a shared 2-core machine; errors are relative L2 errors of the "
                "contact stress against the fine reference (studies/reference.py, h2 >= "
                "b/16, default penalty), iterations are contact sets where a run solved "
                "them directly (`inner_solve_used`). Maps: loops.png, models.png.")
    converged = table[table.converged.astype(bool)]
    column = "error_estimate" if "error_estimate" in table else "final_relative_change"
    wrong = converged[~(converged[column] < converged.eps_u)]
    statuses = table.status.value_counts()
    report.finding(f"{len(table)} runs: " + listing(f"{n} {status.replace('_', ' ')}"
                                                     for status, n in statuses.items())
                   + f"; {len(wrong)} reported converged above its eps_u. The runs took "
                   f"{seconds(table.wall_time_s.sum())} in all (summed).")

    paper = table[table.method == "paper"]
    if len(paper):
        rows, columns = _map(paper, "theta", "rho", "rho")
        report.section("The paper's loop: theta against rho")
        report.text("Default scene, eps_u as the sweep's; each cell the iterations to "
                    "converge, or how the run stopped.")
        report.table(rows, columns)
        ok = paper[paper.status == "converged"]
        points = sorted({(r.theta, r.rho) for r in ok.itertuples()}, reverse=True)
        report.finding(f"The paper's loop converges at {len(points)} of the "
                       f"{paper.groupby(['theta', 'rho']).ngroups} points tried"
                       + (" (" + listing(f"theta = {t:g}, rho = {r:g}" for t, r in points)
                          + f"), in {span(ok.iterations, '{:g}'.format)} iterations"
                          if points else "") + ".")
    accelerated = table[(table.method == "active-set") & table.robin.notna()]
    if len(accelerated):
        rows, columns = _map(accelerated, "theta", "robin", "gamma")
        report.section("The accelerated loop: theta against the Robin parameter gamma")
        report.table(rows, columns)
        ok = accelerated[accelerated.status == "converged"]
        best = ok.groupby("robin").iterations.median()
        report.finding(f"The accelerated loop converges in {len(ok)} of {len(accelerated)} "
                       f"runs, in {span(ok.iterations, '{:g}'.format)} iterations; median by "
                       "gamma (E/b): " + ", ".join(f"{g:g}: {m:g}" for g, m in best.items())
                       + ".")
    grid = model_grid(table)
    if len(grid):
        report.section("The coating models over h2 and E2")
        wide = grid.pivot_table(index="h2", columns=["model", "E2"],
                                values=["iterations", "wall_time_s", "error_12_L2"],
                                aggfunc="first")
        rows = []
        for h2 in sorted(grid.h2.unique(), reverse=True):
            row = {"h2": h2}
            for (quantity, model, E2) in wide.columns:
                row[f"{quantity}|{model}|{E2}"] = wide.loc[h2, (quantity, model, E2)]
            rows.append(row)
        pairs = sorted({(m, E2) for _, m, E2 in wide.columns}, key=lambda p: (p[0], -p[1]))
        for quantity, show, what in (("iterations", "{:g}", "iterations"),
                                     ("wall_time_s", seconds, "wall time"),
                                     ("error_12_L2", percent, "L2 error of sigma_12n "
                                                              "against the fine reference")):
            report.text(f"{what.capitalize()}:")
            report.table(rows, [Column("h2", "h2", fraction_of_b)] + [
                Column(f"{quantity}|{m}|{E2}", f"{MODEL_NAMES[m]}, {fraction_of_E(E2)}", show)
                for m, E2 in pairs])
        if len(differences):
            report.text("The shell's contact stress against the 2D model's (relative L2 "
                        "distance):")
            diff = differences.pivot_table(index="h2", columns="E2", values="shell_vs_2d")
            report.table([{"h2": h2, **{E2: diff.loc[h2, E2] for E2 in diff.columns}}
                          for h2 in sorted(diff.index, reverse=True)],
                         [Column("h2", "h2", fraction_of_b)]
                         + [Column(E2, f"E2 = {fraction_of_E(E2)}", percent)
                            for E2 in diff.columns])
            report.finding(
                f"The shell agrees with the 2D model within {100 * CLOSE:g} % "
                + "; ".join(
                    f"for E2 = {fraction_of_E(E2)} " + (
                        f"from h2 = {fraction_of_b(h2)} down" if h2 is not None else
                        f"not even at h2 = {fraction_of_b(differences.h2.min())}")
                    for E2, h2 in ((E2, agreeing_from(differences, E2))
                                   for E2 in sorted(differences.E2.unique(), reverse=True)))
                + ": the paper's \"thin, stiff coatings\" made quantitative.")
        thin = grid[(grid.E2 == 1.0) & (grid.h2 <= 1 / 16) & (grid.status == "converged")]
        if len(thin):
            rows = []
            for h2 in sorted(thin.h2.unique(), reverse=True):
                row = {"h2": h2}
                for r in thin[thin.h2 == h2].itertuples():
                    summary = _run_summary(sweep_dir, r.id)
                    points = len(pd.read_csv(os.path.join(sweep_dir, "runs", r.id,
                                                          "contact.csv")))
                    name = MODEL_NAMES[r.model]
                    row.update({f"{name}_dofs": sum(summary["dofs"].values()),
                                f"{name}_elements": (points - 1) // 2,
                                f"{name}_iterations": r.iterations,
                                f"{name}_wall": r.wall_time_s,
                                f"{name}_peak": r.peak_contact_stress})
                rows.append(row)
            report.section("Thin coatings, E2 = E")
            report.text("The 2D coating's cells are at most twice as wide as high: below some "
                        "thickness its mesh refines the interface, and with it the bodies' "
                        "coated faces; the shell's cost does not depend on h2.")
            report.table(rows, [Column("h2", "h2", fraction_of_b)] + [
                Column(f"{name}_{key}", f"{name}: {label}", show, meaning if name == "2D" else "")
                for name in ("2D", "shell") for key, label, show, meaning in (
                    ("elements", "contact elements", "{:g}",
                     "interface elements on the contact face"),
                    ("dofs", "dofs", "{:g}", "unknowns of every subdomain"),
                    ("iterations", "iterations", "{:g}", ""),
                    ("wall", "wall time", seconds, ""),
                    ("peak", "peak (E)", "{:.4g}", "peak contact stress"))])
            last = rows[-1]
            if "2D_wall" in last and "shell_wall" in last and "2D_wall" in rows[0]:
                report.finding(
                    f"From h2 = {fraction_of_b(rows[0]['h2'])} to "
                    f"{fraction_of_b(last['h2'])} the 2D model's wall time grows "
                    f"{last['2D_wall'] / rows[0]['2D_wall']:.1f}x and the shell's "
                    f"{last['shell_wall'] / rows[0]['shell_wall']:.1f}x; at "
                    f"{fraction_of_b(last['h2'])} their peaks differ by "
                    f"{percent(abs(last['shell_peak'] / last['2D_peak'] - 1))}.")
    mesh = mesh_runs(table)
    if len(mesh):
        report.section("Mesh levels")
        rows = []
        mesh = mesh.drop_duplicates(["model", "h2", "E2", "mesh_level"])   # a point in two grids
        for (model, h2, E2), part in mesh.groupby(["model", "h2", "E2"]):
            for r in part.sort_values("mesh_level").itertuples():
                rows.append({"model": model, "h2": h2, "E2": E2, "level": r.mesh_level,
                             "status": r.status, "iterations": r.iterations,
                             "wall": r.wall_time_s, "error": r.error_12_L2})
        report.table(rows, [Column("model", "model", MODEL_NAMES.get),
                            Column("h2", "h2", fraction_of_b), Column("E2", "E2", fraction_of_E),
                            Column("level", "mesh level", "{:g}"), Column("status", "status"),
                            Column("iterations", "iterations", "{:g}"),
                            Column("wall", "wall time", seconds),
                            Column("error", "L2 error", percent, "of sigma_12n against the "
                                   "fine reference")])
        parts = []
        for (model, h2, E2), part in pd.DataFrame(rows).groupby(["model", "h2", "E2"]):
            errors = part.sort_values("level").error
            if errors.notna().sum() > 1:
                known = errors.dropna()
                parts.append(f"{MODEL_NAMES[model]} at h2 = {fraction_of_b(h2)}, E2 = "
                             f"{fraction_of_E(E2)}: " + " -> ".join(percent(e) for e in errors)
                             + f" (x{known.iloc[-1] / known.iloc[0]:.2f})")
        if parts:
            report.finding("The L2 error of sigma_12n by mesh level (in brackets: finest over "
                           "level 1): " + "; ".join(parts) + ".")
    return report.write(out)


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
    print(write_report(table, differences, args.sweep_dir,
                       os.path.join(args.sweep_dir, "report.md"),
                       command_line("studies.stability", argv)))


if __name__ == "__main__":
    main()
