"""Speed against accuracy (not a test): ``make bench``.

For every figure scene, each method is run and timed, and its interface stresses are
compared with the fine reference (studies/reference.py, computed once per scene):
  - the Robin loop, accelerated (active-set, Anderson), shell and 2D coating models,
    mesh levels 1 and 2;
  - the paper's loop with its fixed relaxation rho = 0.5 and its stopping test
    eps_u = 1e-3, mesh level 1;
  - the monolithic solve of the same discrete problem, levels 1 and 2;
  - on the default scene, the naive baseline: a fresh FreeFEM process per subdomain solve.
Errors are relative to the reference: max-norm (over the largest reference value) and
L2 (studies/claims.py's distance). sigma_23n is compared on x1 < 0.9 l2: at the coating's
end the bonded-edge stress is singular and no mesh converges there.

Writes results/bench.csv (one row per run), results/speed_accuracy.png and
results/bench.md (the medians per method, every accelerated run, the fine references'
last refinement, and the findings computed from them).

    python -m studies.bench [--scenes h2:E2 ...]
"""

import argparse
import glob
import os
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

from studies.claims import distance  # noqa: E402
from studies.figure_scenes import FIGURE_SCENES  # noqa: E402
from orchestrate.run import monolithic_curves  # noqa: E402
from studies.paths import RESULTS_DIR  # noqa: E402
from studies.reference import reference  # noqa: E402
from orchestrate.model import Settings  # noqa: E402
from orchestrate.model import paper_scene  # noqa: E402
from orchestrate.run import RunFailed, solve_into as solve  # noqa: E402
from studies.report import (Column, Report, command_line, fraction_of_b,  # noqa: E402
                            fraction_of_E, listing, percent, percent_g, seconds,
                            signed_percent, span)

SCENES = sorted({(h2, E2) for _, h2, E2 in FIGURE_SCENES})
ACCELERATED, PAPER, MONOLITHIC, FRESH = ("DDM accelerated", "DDM paper (fixed rho, eps_u 1e-3)",
                                         "monolithic", "DDM fresh process per solve")


def errors(x, sigma_12n, sigma_23n, ref, coating_length):
    """Relative max-norm and L2 errors of both stresses against the reference, and the
    error of the peak contact stress."""
    out = {"error_peak": float(np.min(sigma_12n) / np.min(ref.sigma_12n) - 1.0)}
    for name, values, keep in (("12", sigma_12n, np.ones_like(x, dtype=bool)),
                               ("23", sigma_23n, x < 0.9 * coating_length)):
        exact = np.interp(x, ref.x1, ref[f"sigma_{name}n"])
        out[f"error_{name}_max"] = float(np.max(np.abs(values - exact)[keep])
                                         / np.max(np.abs(exact[keep])))
        xs = x[keep][: 2 * ((keep.sum() - 1) // 2) + 1]   # whole Simpson elements
        out[f"error_{name}_L2"] = distance((xs, values[:len(xs)]), (xs, exact[:len(xs)]))
    return out


def _ddm_row(scene, settings, method, ref, out_dir):
    try:
        summary = solve(scene, settings, out_dir, overwrite=True)   # its own earlier run
    except RunFailed as failure:
        return {"method": method, "iterations": failure.summary["iterations"],
                "wall_time_s": failure.summary["wall_time_s"], "converged": False}
    contact = pd.read_csv(os.path.join(out_dir, "contact.csv"))
    interface = pd.read_csv(os.path.join(out_dir, "interface.csv"))
    return {"method": method, "iterations": summary["iterations"],
            "wall_time_s": summary["wall_time_s"],
            "time_per_iteration_s": summary["time_per_iteration_s"], "converged": True,
            **errors(contact.x1.to_numpy(), contact.sigma_n.to_numpy(),
                     interface.sigma_n.to_numpy(), ref, coating_length(scene))}


def coating_length(scene):
    return scene.coatings[0].end - scene.coatings[0].start


def _monolithic_row(scene, settings, ref):
    start = time.perf_counter()
    x1, sigma_12n, sigma_23n, solves = monolithic_curves(scene, settings)
    return {"method": MONOLITHIC, "iterations": solves,
            "wall_time_s": time.perf_counter() - start, "converged": True,
            **errors(x1, sigma_12n, sigma_23n, ref, coating_length(scene))}



def benchmark(scenes, out_dir):
    rows = []
    for h2, E2 in scenes:
        ref = reference(h2, E2, progress=lambda row: print("  reference", row, flush=True))
        models = ("shell", "elastic") if E2 != 0.2 else ("elastic",)
        for model in models:
            scene = paper_scene(h2=h2, E2=E2, model=model)
            runs = [(Settings(mesh_level=level), ACCELERATED) for level in (1, 2)]
            runs.append((Settings(method="paper", eps_u=1e-3), PAPER))
            if (h2, E2) == (0.125, 1.0):
                runs.append((Settings(workers="fresh"), FRESH))
            for settings, method in runs:
                name = f"{model}-h2_{h2:g}-E2_{E2:g}-{method.split()[1]}-L{settings.mesh_level}"
                row = _ddm_row(scene, settings, method, ref, os.path.join(out_dir, "runs", name))
                rows.append({"model": model, "h2": h2, "E2": E2, "mesh_level": settings.mesh_level,
                             **row})
                print(rows[-1], flush=True)
            for level in (1, 2):
                settings = Settings(mesh_level=level)
                rows.append({"model": model, "h2": h2, "E2": E2, "mesh_level": level,
                             **_monolithic_row(scene, settings, ref)})
                print(rows[-1], flush=True)
    return pd.DataFrame(rows)


MARKERS = {ACCELERATED: "o", PAPER: "x", MONOLITHIC: "s", FRESH: "^"}
COLOURS = {"shell": "tab:blue", "elastic": "tab:orange"}


def chart(table, path):
    figure, axes = plt.subplots(figsize=(7.5, 5.2))
    for (method, model), group in table.groupby(["method", "model"]):
        done = group[group.converged]
        axes.scatter(done.wall_time_s, done.error_12_L2, marker=MARKERS[method],
                     color=COLOURS[model], alpha=0.75,
                     label=f"{method}, {'shell' if model == 'shell' else '2D coating'}")
    axes.set_xscale("log")
    axes.set_yscale("log")
    axes.set_xlabel("wall time of the run [s]")
    axes.set_ylabel(r"relative L2 error of $\sigma_{12n}$ against the fine reference")
    axes.set_title("Speed against accuracy, figure scenes (one point per run)")
    axes.legend(fontsize=7)
    axes.grid(True, which="both", linewidth=0.3)
    figure.tight_layout()
    figure.savefig(path, dpi=150)
    plt.close(figure)


MODEL_NAMES = {"shell": "shell", "elastic": "2D coating"}


def medians(table):
    """Per model, method and mesh level: runs, converged, medians of iterations, wall
    time and L2 errors, and the largest peak error."""
    return table.groupby(["model", "method", "mesh_level"]).agg(
        runs=("converged", "size"), converged=("converged", "sum"),
        iterations=("iterations", "median"), wall_time_s=("wall_time_s", "median"),
        error_12_L2=("error_12_L2", "median"), error_23_L2=("error_23_L2", "median"),
        error_peak=("error_peak", lambda e: e.abs().max())).reset_index()


def refinements(reference_root):
    """The last refinement step of every fine reference: a row per scene."""
    rows = []
    for folder in sorted(glob.glob(os.path.join(reference_root, "h2_*-E2_*"))):
        path = os.path.join(folder, "refinement.csv")
        if not os.path.exists(path):
            continue
        steps = pd.read_csv(path)
        last = steps.iloc[-1]
        h2, E2 = (float(part.split("_")[1]) for part in os.path.basename(folder).split("-"))
        rows.append({"h2": h2, "E2": E2, "levels": int(last.level),
                     "peak_change": last.get("peak_change"),
                     "sigma_12n_L2_change": last.get("sigma_12n_L2_change"),
                     "sigma_23n_L2_change": last.get("sigma_23n_L2_change")})
    return pd.DataFrame(rows)


def _ratios(table, method, over, level):
    """Per scene and model: wall time of ``method`` over ``over``'s at ``level``."""
    a = table[(table.method == method) & (table.mesh_level == level) & table.converged]
    b = table[(table.method == over) & (table.mesh_level == level) & table.converged]
    both = a.merge(b, on=["model", "h2", "E2"], suffixes=("", "_over"))
    return both.wall_time_s / both.wall_time_s_over


def findings(table):
    """The sentences the data give (only those whose runs are in the table)."""
    out = []
    accelerated = table[(table.method == ACCELERATED) & table.converged]
    for model in ("elastic", "shell"):
        one = accelerated[(accelerated.model == model) & (accelerated.mesh_level == 1)]
        two = accelerated[(accelerated.model == model) & (accelerated.mesh_level == 2)]
        if one.empty:
            continue
        text = (f"The {MODEL_NAMES[model]} model on the paper's mesh (accelerated loop, "
                f"{len(one)} scenes): peak contact stress within "
                f"{percent_g(one.error_peak.abs().max())} of the fine reference, sigma_12n "
                f"within {percent(one.error_12_L2.max())} in L2 (median "
                f"{percent(one.error_12_L2.median())}), median wall time "
                f"{seconds(one.wall_time_s.median())}")
        if not two.empty:
            gain = one.merge(two, on=["h2", "E2"], suffixes=("", "_2"))
            factor = gain.error_12_L2 / gain.error_12_L2_2
            text += (f"; mesh level 2 (median {seconds(two.wall_time_s.median())}) divides "
                     f"its L2 error by {span(factor, lambda v: f'{v:.2g}')}")
        out.append(text + ".")
        if model == "shell":
            by_h2 = {E2: part.sort_values("h2") for E2, part in one.groupby("E2")}
            grows = all(part.error_peak.abs().is_monotonic_increasing and len(part) > 1
                        for part in by_h2.values())
            both = one.pivot_table(index="h2", columns="E2", values="error_peak").abs()
            stiffer = (len(both.columns) > 1 and (both.notna().all(axis=1).any())
                       and bool((both[both.columns.max()] < both[both.columns.min()])
                                [both.notna().all(axis=1)].all()))
            traits = (["growing with h2" if grows else ""]
                      + ["smaller for the stiffer coating" if stiffer else ""])
            if not two.empty:
                kept = one.merge(two, on=["h2", "E2"], suffixes=("", "_2"))
                ratio = (kept.error_peak_2.abs() / kept.error_peak.abs()).median()
                if ratio > 0.8:
                    traits.insert(0, f"not shrinking with the mesh (level 2 over level 1: "
                                     f"median {ratio:.2f})")
            traits = [t for t in traits if t]
            out.append("The shell's peak error against the fine reference, by h2: "
                       + "; ".join(f"E2 = {fraction_of_E(E2)}: " + ", ".join(
                           f"{signed_percent(r.error_peak, 1)} at {fraction_of_b(r.h2)}"
                           for r in part.itertuples()) for E2, part in by_h2.items())
                       + (": a model error, " + listing(traits) if traits else "") + ".")
    for level in sorted(table.mesh_level.unique()):
        ratio = _ratios(table, ACCELERATED, MONOLITHIC, level)
        if len(ratio):
            out.append(f"At mesh level {level:g} the accelerated Robin loop takes "
                       f"{ratio.median():.2g} of the monolithic solve's time (median over "
                       f"{len(ratio)} runs, {span(ratio, lambda v: f'{v:.2g}')}).")
    fresh = table[(table.method == FRESH) & table.converged]
    if len(fresh):
        persistent = accelerated[accelerated.mesh_level == 1].set_index(["model", "h2", "E2"])
        parts = [f"{seconds(r.wall_time_s)} against "
                 f"{seconds(persistent.wall_time_s[(r.model, r.h2, r.E2)])} for the "
                 f"{MODEL_NAMES[r.model]} model" for r in fresh.itertuples()
                 if (r.model, r.h2, r.E2) in persistent.index]
        factors = [r.wall_time_s / persistent.wall_time_s[(r.model, r.h2, r.E2)]
                   for r in fresh.itertuples() if (r.model, r.h2, r.E2) in persistent.index]
        if parts:
            out.append("A fresh FreeFEM process per subdomain solve takes "
                       f"{span(factors, lambda v: f'{v:.0f}')} times as long as persistent "
                       "workers: " + listing(parts) + ".")
    paper = table[table.method == PAPER]
    if len(paper):
        out.append(f"The paper's loop (rho = 0.5, eps_u = 1e-3) converged on "
                   f"{int(paper.converged.sum())} of {len(paper)} runs.")
    return out


def write_report(table, out, reference_root=RESULTS_DIR / "reference",
                 command="python -m studies.bench"):
    report = Report("Speed against accuracy on the figure scenes", command,
                    data=[os.path.basename(os.path.splitext(out)[0]) + ".csv",
                          "reference/*/refinement.csv"])
    report.text("Every figure scene solved by each method, its interface stresses compared "
                "with the fine reference (studies/reference.py: the monolithic solve of the "
                "2D coating model, refined until its peak changes by less than "
                "0.2 %). Errors are relative; sigma_23n on x1 < 0.9 l2 (the bonded end is "
                "singular). Wall times are of one run each on a shared machine.")
    for sentence in findings(table):
        report.finding(sentence)
    report.section("Medians per method")
    report.table(medians(table), [
        Column("model", "model", MODEL_NAMES.get), Column("method", "method"),
        Column("mesh_level", "mesh level", "{:g}"), Column("runs", "runs", "{:g}"),
        Column("converged", "converged", "{:g}"),
        Column("iterations", "iterations", "{:g}", "median; contact sets where solved "
               "directly, solves for the monolithic"),
        Column("wall_time_s", "wall time", seconds, "median"),
        Column("error_12_L2", "sigma_12n L2", percent, "median relative L2 error"),
        Column("error_23_L2", "sigma_23n L2", percent, "median, on x1 < 0.9 l2"),
        Column("error_peak", "peak, worst", percent_g,
               "the largest |error| of the peak contact stress")])
    report.section("Every run of the accelerated loop")
    runs = table[table.method == ACCELERATED].sort_values(["model", "mesh_level", "E2", "h2"],
                                                          ascending=[True, True, False, False])
    report.table(runs, [
        Column("model", "model", MODEL_NAMES.get), Column("mesh_level", "mesh level", "{:g}"),
        Column("h2", "h2", fraction_of_b), Column("E2", "E2", fraction_of_E),
        Column("error_peak", "peak", signed_percent, "the peak contact stress's error"),
        Column("error_12_L2", "sigma_12n L2", percent),
        Column("error_23_L2", "sigma_23n L2", percent),
        Column("iterations", "iterations", "{:g}"), Column("wall_time_s", "wall time", seconds)])
    steps = refinements(reference_root)
    if len(steps):
        report.section("The fine references' last refinement")
        report.table(steps, [
            Column("h2", "h2", fraction_of_b), Column("E2", "E2", fraction_of_E),
            Column("levels", "finest level", "{:g}", "mesh level of the reference "
                   "(theta = 1e-3 b/E over the level)"),
            Column("peak_change", "peak change", percent_g,
                   "the peak contact stress's change from the level below"),
            Column("sigma_12n_L2_change", "sigma_12n L2 change", percent_g),
            Column("sigma_23n_L2_change", "sigma_23n L2 change", percent_g,
                   "over the whole bond, its singular end included")])
        report.finding(f"The references' peaks changed by at most "
                       f"{percent_g(steps.peak_change.max())} at their last refinement; "
                       f"sigma_12n by {span(steps.sigma_12n_L2_change, percent_g)} in L2, "
                       f"sigma_23n by {span(steps.sigma_23n_L2_change, percent_g)}: the bonded "
                       "edge's stress is singular, whence sigma_23n's errors on x1 < 0.9 l2.")
    return report.write(out)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scenes", nargs="*", help="h2:E2 pairs (default: the figure scenes)")
    parser.add_argument("--out", default=str(RESULTS_DIR))
    args = parser.parse_args(argv)
    scenes = ([tuple(map(float, s.split(":"))) for s in args.scenes] if args.scenes
              else SCENES)
    table = benchmark(scenes, os.path.join(args.out, "bench"))
    table.to_csv(os.path.join(args.out, "bench.csv"), index=False)
    chart(table, os.path.join(args.out, "speed_accuracy.png"))
    with pd.option_context("display.width", 200):
        print(medians(table).to_string())
    report = write_report(table, os.path.join(args.out, "bench.md"),
                          command=command_line("studies.bench", argv))
    print(f"\nwritten to {args.out}/bench.csv, speed_accuracy.png and {report}")


if __name__ == "__main__":
    main()
