"""The paper's claims about its figures 3-5 (METHOD.md, "What the figures show"),
measured on finished runs. tests/studies/test_paper_claims.py turns each into a test;
``python -m studies.claims RUN ...`` prints the measurements.

Distances between two stress curves on an interface are relative L2 distances over
the coating, ||a - b|| / ||b||, with the nodal (Simpson) weights of the interface points.
"""

import argparse
import json
import os

import numpy as np
import pandas as pd

from studies.figures import load_runs
from orchestrate.mesh import simpson


class Runs:
    """Finished runs indexed by (model, h2, E2)."""

    def __init__(self, folders):
        table = load_runs(folders)
        self.folders = {(r.model, r.h2, r.E2): r.folder for r in table.itertuples()}
        self.height = float(table.height.iloc[0])

    def curve(self, file, model, h2, E2):
        table = pd.read_csv(os.path.join(self.folders[(model, h2, E2)], file))
        return table.x1.to_numpy(), table.sigma_n.to_numpy()

    def summary(self, model, h2, E2):
        with open(os.path.join(self.folders[(model, h2, E2)], "summary.json")) as f:
            return json.load(f)

    def coating(self, h2, E2):
        return pd.read_csv(os.path.join(self.folders[("elastic", h2, E2)], "coating1.csv"))


def distance(a, b):
    """||a - b|| / ||b|| for two curves given at the same interface points."""
    (xa, ya), (xb, yb) = a, b
    assert np.allclose(xa, xb), "curves on different interface points"
    weight = simpson(xb[::2])[1]       # the element ends are every other point
    return float(np.sqrt(np.dot(weight, (ya - yb) ** 2) / np.dot(weight, yb ** 2)))


def left_edge(coating, height):
    """sigma_eq along the coating's left edge x1 = 0, by height above S23."""
    edge = coating[coating.x1 == 0.0].sort_values("x2")
    return (edge.x2 - height).to_numpy(), edge.sigma_eq.to_numpy()


def maximum(coating, height, h2):
    """Value of the largest sigma_eq and its place: x1 and relative height (x2 - h)/h2."""
    peak = coating.sigma_eq.idxmax()
    return (float(coating.sigma_eq[peak]), float(coating.x1[peak]),
            float((coating.x2[peak] - height) / h2))


def local_maxima(values):
    """Indices of the local maxima of a sequence (ends count when above their neighbour)."""
    padded = np.concatenate([[-np.inf], values, [-np.inf]])
    return [i for i in range(len(values))
            if padded[i + 1] > padded[i] and padded[i + 1] >= padded[i + 2]]


def measurements(runs):
    """Every number the claims are judged on, as (name, value) rows."""
    rows = []
    for E2 in (5.0, 1.0):
        for h2 in (1.0, 0.125):
            rows.append((f"fig3 model distance, h2={h2:g}, E2={E2:g}", distance(
                runs.curve("contact.csv", "shell", h2, E2),
                runs.curve("contact.csv", "elastic", h2, E2))))
    for model in ("shell", "elastic"):
        for h2 in (1.0, 0.125):
            rows.append((f"fig3 E2 distance, {model}, h2={h2:g}", distance(
                runs.curve("contact.csv", model, h2, 5.0), runs.curve("contact.csv", model, h2, 1.0))))
            for E2 in (5.0, 1.0):
                summary = runs.summary(model, h2, E2)
                rows.append((f"fig3 peak |sigma12n|, {model}, h2={h2:g}, E2={E2:g}",
                             -summary["peak_contact_stress"]))
                rows.append((f"fig3 half-width, {model}, h2={h2:g}, E2={E2:g}",
                             summary["contact_half_width"]))
    for h2 in (1.0, 0.5, 0.25, 0.125, 0.0625):
        for E2 in (5.0, 1.0):
            rows.append((f"fig4 model distance, h2={h2:g}, E2={E2:g}", distance(
                runs.curve("interface.csv", "shell", h2, E2),
                runs.curve("interface.csv", "elastic", h2, E2))))
        for model in ("shell", "elastic"):
            rows.append((f"fig4 E2 distance, {model}, h2={h2:g}", distance(
                runs.curve("interface.csv", model, h2, 5.0),
                runs.curve("interface.csv", model, h2, 1.0))))
            for E2 in (5.0, 1.0):
                rows.append((f"fig4 sigma23-sigma12 distance, {model}, h2={h2:g}, E2={E2:g}",
                             distance(runs.curve("interface.csv", model, h2, E2),
                                      runs.curve("contact.csv", model, h2, E2))))
    for E2 in (0.2, 1.0, 5.0):
        for h2 in (1.0, 0.5, 0.25, 0.125):
            value, x1, height = maximum(runs.coating(h2, E2), runs.height, h2)
            rows.append((f"fig5 max sigma_eq, h2={h2:g}, E2={E2:g}", value))
            rows.append((f"fig5 max x1, h2={h2:g}, E2={E2:g}", x1))
            rows.append((f"fig5 max relative height, h2={h2:g}, E2={E2:g}", height))
            heights, values = left_edge(runs.coating(h2, E2), runs.height)
            for i in local_maxima(values):
                rows.append((f"fig5 left-edge local max, h2={h2:g}, E2={E2:g}, "
                             f"height={heights[i] / h2:.2f}", values[i]))
    return rows


def main(argv=None):
    parser = argparse.ArgumentParser(description="Measure the paper's claims on runs.")
    parser.add_argument("runs", nargs="+")
    args = parser.parse_args(argv)
    for name, value in measurements(Runs(args.runs)):
        print(f"{name:60s} {value:.4g}")


if __name__ == "__main__":
    main()
