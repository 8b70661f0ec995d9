"""The fine reference: the accuracy yardstick of the speed-accuracy benchmark.

For a scene (h2, E2), the monolithic solve of the 2D coating model (freefem/
monolithic.edp, which the Robin loop reproduces) on meshes 1, 2, 3, ... with the penalty
scaled like the mesh (theta = 1e-3 / level, so that its error shrinks with the
discretisation's), until the peak contact stress changes by less than 0.2 % and at
least MIN_LEVEL is reached. The finest solution is the reference; the refinement table
records every level.

    python -m studies.reference --h2 0.125 --E2 1   # results/reference/h2_0.125-E2_1/
"""

import argparse
import os
import time

import numpy as np
import pandas as pd

from studies.claims import distance
from orchestrate.run import monolithic_curves
from orchestrate.files import write_csv
from studies.paths import RESULTS_DIR
from orchestrate.model import Settings
from orchestrate.model import paper_scene

PEAK_TOLERANCE = 0.002
MIN_LEVEL = 3          # one level above the finest benchmarked mesh (2)
MAX_LEVEL = 5
BASE_THETA = 1e-3


def refinement_settings(level):
    """Mesh level ``level`` with the penalty scaled like the mesh."""
    return Settings(mesh_level=level, theta=BASE_THETA / level)


def reference_dir(h2, E2):
    return RESULTS_DIR / "reference" / f"h2_{h2:g}-E2_{E2:g}"


def compute_reference(scene, out_dir, progress=print):
    """Refine until converged; write refinement.csv and reference.csv; return both."""
    rows, previous = [], None
    for level in range(1, MAX_LEVEL + 1):
        start = time.perf_counter()
        settings = refinement_settings(level)
        x1, sigma_12n, sigma_23n, _ = monolithic_curves(scene, settings)
        contact, interface = (x1, sigma_12n), (x1, sigma_23n)
        row = {"level": level, "theta": settings.theta, "points": len(x1),
               "peak_sigma_12n": float(np.min(contact[1])),
               "seconds": time.perf_counter() - start}
        if previous is not None:
            row["peak_change"] = abs(row["peak_sigma_12n"] / rows[-1]["peak_sigma_12n"] - 1)
            # change of the whole curves, the coarser one as the yardstick
            row["sigma_12n_L2_change"] = distance(
                (previous[0][0], np.interp(previous[0][0], *contact)), previous[0])
            row["sigma_23n_L2_change"] = distance(
                (previous[1][0], np.interp(previous[1][0], *interface)), previous[1])
        rows.append(row)
        progress(row)
        previous = (contact, interface)
        if level >= MIN_LEVEL and row["peak_change"] < PEAK_TOLERANCE:
            break
    os.makedirs(out_dir, exist_ok=True)
    table = pd.DataFrame(rows)
    table.to_csv(os.path.join(out_dir, "refinement.csv"), index=False)
    write_csv(os.path.join(out_dir, "reference.csv"), {
        "x1": contact[0], "sigma_12n": contact[1], "sigma_23n": interface[1]})
    return table, load_reference(out_dir)


def load_reference(out_dir):
    return pd.read_csv(os.path.join(out_dir, "reference.csv"))


def reference(h2, E2, progress=print):
    """The reference of a scene, computed once and then read from results/reference."""
    out_dir = reference_dir(h2, E2)
    if os.path.exists(os.path.join(out_dir, "reference.csv")):
        return load_reference(out_dir)
    return compute_reference(paper_scene(h2=h2, E2=E2, model="elastic"), out_dir, progress)[1]


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--h2", type=float, default=0.125)
    parser.add_argument("--E2", type=float, default=1.0)
    args = parser.parse_args(argv)
    table, _ = compute_reference(paper_scene(h2=args.h2, E2=args.E2, model="elastic"),
                                 reference_dir(args.h2, args.E2))
    print(table.to_string(index=False))


if __name__ == "__main__":
    main()
