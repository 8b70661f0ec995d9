"""Plot of one run: the contact and interface stresses along the coating.

Reads only the run's CSV files, so a plot never recomputes anything."""

import json
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pandas as pd  # noqa: E402


def plot_run(run_dir, path=None):
    """Write ``run_dir/stresses.png``: sigma_12n and sigma_23n against x1/b."""
    contact = pd.read_csv(os.path.join(run_dir, "contact.csv"))
    interface = pd.read_csv(os.path.join(run_dir, "interface.csv"))
    with open(os.path.join(run_dir, "summary.json")) as f:
        summary = json.load(f)
    scene, settings = summary["scene"], summary["settings"]
    figure, axes = plt.subplots(figsize=(6.4, 4.0))
    axes.plot(contact["x1"], contact["sigma_n"], label=r"$\sigma_{12n}/E$ on $S_{12}$")
    axes.plot(interface["x1"], interface["sigma_n"], "--", label=r"$\sigma_{23n}/E$ on $S_{23}$")
    axes.axhline(0.0, color="0.7", linewidth=0.8)
    axes.set_xlabel(r"$x_1/b$")
    axes.set_ylabel(r"normal stress $/E$")
    axes.set_title(f"{settings['model']} model, $h_2$ = {scene['h2']:g} b, "
                   f"$E_2$ = {scene['E2']:g} E: {summary['iterations']} iterations")
    axes.legend()
    figure.tight_layout()
    path = path or os.path.join(run_dir, "stresses.png")
    figure.savefig(path, dpi=150)
    plt.close(figure)
    return path
