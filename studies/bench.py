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
L2 (orchestrate/claims.distance). sigma_23n is compared on x1 < 0.9 l2: at the coating's
end the bonded-edge stress is singular and no mesh converges there.

Writes results/bench.csv (one row per run) and results/speed_accuracy.png.

    python -m studies.bench [--scenes h2:E2 ...]
"""

import argparse
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
    summary = table.groupby(["model", "method", "mesh_level"]).agg(
        runs=("converged", "size"), converged=("converged", "sum"),
        iterations=("iterations", "median"), wall_time_s=("wall_time_s", "median"),
        error_12_L2=("error_12_L2", "median"), error_23_L2=("error_23_L2", "median"),
        error_peak=("error_peak", lambda e: e.abs().max()))
    with pd.option_context("display.width", 200):
        print(summary.to_string())
    print(f"\nwritten to {args.out}/bench.csv and {args.out}/speed_accuracy.png")


if __name__ == "__main__":
    main()
