"""The paper's figures 3, 4 and 5 from finished runs (reads CSV, computes nothing).

    python -m studies.figures fig3 RUN ...    # writes results/fig3.png, .pdf, _data.csv
    python -m studies.figures fig3 results/figures    # every run of a sweep

The scenes are listed once, in studies/sweeps/figures.toml, which `make` runs as a
sweep; each figure takes the runs studies/figure_scenes.py's DRAWS names for it, by
their summaries' values (model, h2, E2).
  fig3: sigma_12n/E on S12; panels h2 = b, b/8; curves E2 = 5E (1), E (2);
        solid: shell model, dashed: 2D coating model.
  fig4: sigma_23n/E on S23; panels E2 = 5E, E; curves h2 = b ... b/16; both models.
  fig5: isolines of sigma_eq/E in the 2D coating; panels E2 = E/5, E, 5E; h2 = b ... b/8.
Stresses are drawn in units of 1e-4 E (STRESS_UNIT); the data files keep them in E.
Fig. 5 contours the nodal values of coating1.csv (recovered by freefem/recovery.idp) on
the coating's own P2 triangles (coating1_cells.csv): on each, the quadratic its six
nodal values define (p2_triangulation). Every panel is stretched vertically by b/h2, so
that all are as high as h2 = b: the title of each stretched panel says by how much
("stretched x8": drawn 8 times taller than it is).
"""

import argparse
import json
import os
import signal
import sys
import traceback

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
# loaded here, once, rather than by each forked drawing of a PDF (0.1 s each)
import matplotlib.backends.backend_pdf  # noqa: E402,F401
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
from matplotlib.ticker import MaxNLocator  # noqa: E402
from matplotlib.tri import Triangulation  # noqa: E402

from studies.figure_scenes import DRAWS  # noqa: E402
from orchestrate.files import partial_path, written  # noqa: E402
from studies.paths import RESULTS_DIR  # noqa: E402
from orchestrate.model import scene_from_dict  # noqa: E402
from orchestrate.model import shorthand_values  # noqa: E402
from orchestrate.workers import die_with_parent  # noqa: E402

LINESTYLE = {"shell": "-", "elastic": "--"}
STRESS_UNIT = 1e-4          # stresses are drawn in units of 1e-4 E
UNIT_LABEL = r"$10^{-4}\,E$"
MODEL_NAME = {"shell": "shell", "elastic": "2D coating"}


def run_folders(paths):
    """Run folders from PATHS: a run folder (or its summary.json) as it is, a sweep's
    folder (it holds runs.csv) as every run in its table."""
    folders = []
    for path in paths:
        table = os.path.join(path, "runs.csv")
        if os.path.isfile(table):
            folders += [os.path.join(path, "runs", name) for name in pd.read_csv(table)["id"]]
        else:
            folders.append(path)
    return folders


def load_runs(paths):
    """One row per run (run folders, or sweep folders: run_folders): model, h2, E2 and
    the folder."""
    rows = []
    for folder in run_folders(paths):
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


def _save(figure, name, data, out_dir, pdf_aside=False):
    """PNG, PDF and the data, each under a temporary name first (a file that exists is
    whole). The figure is laid out already (a layout engine would lay it out at each
    savefig: as costly as drawing it). ``pdf_aside``: the PDF is drawn in a forked copy
    of this process, beside the PNG."""
    os.makedirs(out_dir, exist_ok=True)
    png, pdf = (os.path.join(out_dir, f"{name}.{extension}") for extension in ("png", "pdf"))
    if not pdf_aside:
        _save_as(figure, png, "png")
        _save_as(figure, pdf, "pdf")
    else:
        wait = _forked(lambda: _save_as(figure, pdf, "pdf"))
        try:
            _save_as(figure, png, "png")
        except BaseException:
            wait()                             # killed: what it was writing goes too
            partial_path(pdf).unlink(missing_ok=True)
            raise
        wait()
    plt.close(figure)
    path = os.path.join(out_dir, f"{name}_data.csv")
    written(path, lambda partial: data.to_csv(partial, index=False))


def _save_as(figure, path, extension):
    written(path, lambda partial: figure.savefig(partial, dpi=150, format=extension))


def _forked(task):
    """Run ``task()`` in a forked child (which has this process's figures as they are);
    return a function that waits for it and raises if it failed, or kills it first if
    this process is failing."""
    parent = os.getpid()
    pid = os.fork()
    if pid == 0:
        code = 1
        try:
            die_with_parent(parent)
            task()
            code = 0
        except BaseException:
            traceback.print_exc()
        finally:
            os._exit(code)

    def wait():
        if sys.exc_info()[0] is not None:
            os.kill(pid, signal.SIGKILL)
        _, status = os.waitpid(pid, 0)
        if sys.exc_info()[0] is None and os.waitstatus_to_exitcode(status) != 0:
            raise RuntimeError("drawing a figure in a forked process failed (see above)")
    return wait


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
                axis.plot(table.x1, table.sigma_n / STRESS_UNIT, LINESTYLE[model],
                          color=colours[number - 1],
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
    # laid out now: the place-holder engine tight_layout leaves would make every
    # savefig draw the figure twice
    figure.set_layout_engine("none")
    return figure, pd.concat(data, ignore_index=True)


def fig3(runs, out_dir):
    draws = DRAWS["fig3"]
    figure, data = _stress_curves(runs, "contact.csv", "h2", draws["h2"], "E2", draws["E2"],
                                  rf"$\sigma_{{12n}}$ / ({UNIT_LABEL}) on $S_{{12}}$", _label_E2)
    _save(figure, "fig3", data, out_dir)


def fig4(runs, out_dir):
    draws = DRAWS["fig4"]
    figure, data = _stress_curves(runs, "interface.csv", "E2", draws["E2"], "h2", draws["h2"],
                                  rf"$\sigma_{{23n}}$ / ({UNIT_LABEL}) on $S_{{23}}$", _label_h2)
    _save(figure, "fig4", data, out_dir)


def coating_field(folder):
    """The 2D coating's nodes (x1, x2, u1, u2, sigma_eq, s11, ...: coating1.csv) and its
    P2 triangles (six node rows each, VTK's triangle6 order: coating1_cells.csv)."""
    return (pd.read_csv(os.path.join(folder, "coating1.csv")),
            pd.read_csv(os.path.join(folder, "coating1_cells.csv")).to_numpy())


def p2_triangulation(x, y, cells, values, n=6):
    """The P2 field of nodal ``values`` on the P2 triangles ``cells`` (six node indices
    each, VTK's triangle6 order: vertices, then the midpoints of edges 01, 12, 20),
    sampled on n x n sub-triangles of each: (Triangulation, values at its points). With
    n = 2 the points are the nodes themselves (each triangle cut into four); larger n
    draws the quadratic between them, as ParaView draws a triangle6."""
    points = [(i, j) for i in range(n + 1) for j in range(n + 1 - i)]
    number = {point: k for k, point in enumerate(points)}
    lam = np.array([[1 - (i + j) / n, i / n, j / n] for i, j in points])
    l0, l1, l2 = lam.T
    basis = np.column_stack([l0 * (2 * l0 - 1), l1 * (2 * l1 - 1), l2 * (2 * l2 - 1),
                             4 * l0 * l1, 4 * l1 * l2, 4 * l2 * l0])
    sub = [(number[i, j], number[i + 1, j], number[i, j + 1])
           for i in range(n) for j in range(n - i)]
    sub += [(number[i + 1, j], number[i + 1, j + 1], number[i, j + 1])
            for i in range(n) for j in range(n - 1 - i)]
    triangles = (np.array(sub)[None] + len(points) * np.arange(len(cells))[:, None, None])
    px = (lam @ x[cells[:, :3]].T).T.ravel()          # straight-sided: linear in lam
    py = (lam @ y[cells[:, :3]].T).T.ravel()
    pv = (basis @ values[cells].T).T.ravel()
    size = max(np.ptp(x), np.ptp(y)) * 1e-9           # a point shared by triangles: once
    key = np.round(np.column_stack([px, py]) / size).astype(np.int64)
    _, first, inverse = np.unique(key, axis=0, return_index=True, return_inverse=True)
    return (Triangulation(px[first], py[first], inverse.ravel()[triangles.reshape(-1, 3)]),
            pv[first])


def fig5(runs, out_dir):
    moduli, heights = DRAWS["fig5"]["E2"], DRAWS["fig5"]["h2"]
    # a fixed layout: the panels are alike, and laying them out would cost a third draw;
    # titles at the axes' top (where matplotlib would put them: no decoration is above)
    with plt.rc_context({"axes.titley": 1.0}):
        figure, axes = plt.subplots(len(heights), len(moduli), figsize=(14, 10.5),
                                    squeeze=False,
                                    gridspec_kw=dict(left=0.05, right=0.99, bottom=0.06,
                                                     top=0.92, wspace=0.12, hspace=0.5))
    data = []
    for column, E2 in enumerate(moduli):
        for row, h2 in enumerate(heights):
            axis = axes[row][column]
            match = runs[(runs.model == "elastic") & (runs.E2 == E2) & (runs.h2 == h2)]
            if match.empty:
                axis.set_visible(False)
                continue
            field, cells = coating_field(match.folder.iloc[0])
            height = match.height.iloc[0]
            local = field.x2 - height
            values = field.sigma_eq.to_numpy() / STRESS_UNIT
            mesh, drawn = p2_triangulation(field.x1.to_numpy(), local.to_numpy(), cells, values)
            levels = MaxNLocator(9).tick_values(values.min(), values.max())
            filled = axis.tricontourf(mesh, drawn, levels=levels, cmap="viridis", alpha=0.85)
            lines = axis.tricontour(mesh, drawn, levels=levels, colors="k", linewidths=0.6)
            axis.clabel(lines, fontsize=7, fmt="%g", inline_spacing=2)
            colour_bar = figure.colorbar(filled, ax=axis, fraction=0.05, pad=0.01)
            colour_bar.ax.tick_params(labelsize=7)
            peak = field.sigma_eq.idxmax()
            axis.plot(field.x1[peak], local[peak], "r*", markersize=10, clip_on=False, zorder=5)
            stretch = 1.0 / h2
            axis.set_aspect(stretch)            # every panel as high as h2 = b
            axis.set_xlim(0, 2)
            axis.set_ylim(0, h2)
            axis.tick_params(labelsize=8)
            axis.set_title(f"$E_2$ = {_label_E2(E2)}, $h_2$ = {_label_h2(h2)}"
                           + (f" (stretched x{stretch:g})" if stretch != 1 else "")
                           + f": max {values.max():.2f}", fontsize=9)
            if column == 0:
                axis.set_ylabel(r"$(x_2 - h)/b$")
            if row == len(heights) - 1:
                axis.set_xlabel(r"$x_1/b$")
            data.append(field.assign(E2=E2, h2=h2)[["E2", "h2", "x1", "x2", "sigma_eq"]])
    _fix_empty_label_places(figure)
    figure.suptitle(rf"$\sigma_{{eq}}$ / ({UNIT_LABEL}) in the 2D coating (red star: maximum; "
                    r"each panel stretched vertically by $b/h_2$)")
    # the longest of the three to draw: its PDF on the other core
    _save(figure, "fig5", pd.concat(data, ignore_index=True), out_dir, pdf_aside=True)


def _fix_empty_label_places(figure):
    """Give every axis without a label (colour bars, inner panels) a fixed label place:
    else matplotlib places the empty label at each draw by measuring all tick labels
    (a fifth of fig. 5's drawing); the figure is the same."""
    for axes in figure.axes:
        for axis in (axes.xaxis, axes.yaxis):
            if not axis.get_label_text():
                axis.set_label_coords(0.5, 0.5)


FIGURES = {"fig3": fig3, "fig4": fig4, "fig5": fig5}


def draw(names, folders, out_dir):
    """Draw the figures ``names`` from the run folders (or sweep folders) ``folders`` into
    ``out_dir``, side by side: each but the last in a forked copy of this process;
    return the PNG paths."""
    runs = load_runs(folders)
    waits = []
    try:
        for name in names[:-1]:
            waits.append(_forked(lambda name=name: FIGURES[name](runs, out_dir)))
        FIGURES[names[-1]](runs, out_dir)
    except BaseException:
        for wait in waits:
            wait()                              # kills them: this process is failing
        raise
    failures = []
    for wait in waits:
        try:
            wait()
        except RuntimeError as error:
            failures.append(error)
    if failures:
        raise failures[0]
    return [os.path.join(out_dir, f"{name}.png") for name in names]


def main(argv=None):
    parser = argparse.ArgumentParser(description="Draw one of the paper's figures, or all.")
    parser.add_argument("figure", choices=sorted(FIGURES) + ["all"])
    parser.add_argument("runs", nargs="+",
                        help="run folders (or their summary.json), or a sweep's folder")
    parser.add_argument("--out", default=str(RESULTS_DIR))
    args = parser.parse_args(argv)
    names = sorted(FIGURES) if args.figure == "all" else [args.figure]
    for path in draw(names, args.runs, args.out):
        print(path)


if __name__ == "__main__":
    main()
