"""The penalty's error against the mesh's, at mesh levels 1-3 (`make bench`).

The penalised contact law t = (d - u_A - u_B)/theta lets the bodies overlap by theta |t|;
its error in the peak contact stress and the total force is, to first order,
proportional to theta. For each benchmark scene, each mesh level and each way of
choosing theta, the monolithic solve (the Robin loop's answer, orchestrate/run/monolithic.py)
is run at theta and at theta/4: the penalty's error at theta is estimated as
4/3 (P(theta) - P(theta/4)) (Richardson), the discretisation's as the change of the
quantity from the level below (same rule). Two rules:

    fixed   theta = 1e-3 b/E at every level (the paper's; its loop's default)
    mesh    the accelerated loop's default (Settings): 4e-3 E times the interface
            element's length, 2.5e-4 b/E on the paper's mesh, divided by the mesh level

    python -m studies.penalty          # prints the table, writes results/penalty.csv
"""

import argparse

import numpy as np
import pandas as pd

from orchestrate.run import monolithic_solution
from orchestrate.files import write_csv
from studies.paths import RESULTS_DIR
from orchestrate.model import Settings
from orchestrate.model import paper_scene

SCENES = ((0.125, 1.0), (1.0, 5.0))       # (h2, E2): the benchmark's reference scenes
LEVELS = (1, 2, 3)
BASE_THETA = 1e-3
RULES = {"fixed": lambda level: BASE_THETA,
         "mesh": lambda level: Settings(mesh_level=level).theta}


def peak_and_force(h2, E2, level, theta):
    """The monolithic solve's peak contact stress and total force (both halves)."""
    problem, _, stresses = monolithic_solution(paper_scene(h2=h2, E2=E2, model="elastic"),
                                               Settings(mesh_level=level, theta=theta))
    contact = problem.contacts[0]
    sigma = stresses[problem.interfaces.index(contact)]
    force = -2.0 * contact.integrate(sigma * contact.normal[:, 1])
    return float(np.min(sigma)), float(force)


def penalty_table(scenes=SCENES, levels=LEVELS, progress=print):
    rows = []
    for h2, E2 in scenes:
        for rule, theta_of in RULES.items():
            previous = None
            for level in levels:
                theta = theta_of(level)
                peak, force = peak_and_force(h2, E2, level, theta)
                peak4, force4 = peak_and_force(h2, E2, level, theta / 4)
                row = {"h2": h2, "E2": E2, "rule": rule, "level": level, "theta": theta,
                       "peak": peak, "force": force,
                       "penalty_error_peak": abs(4 / 3 * (peak - peak4) / peak),
                       "penalty_error_force": abs(4 / 3 * (force - force4) / force),
                       "mesh_change_peak": (abs(peak / previous[0] - 1) if previous else None),
                       "mesh_change_force": (abs(force / previous[1] - 1) if previous else None)}
                rows.append(row)
                progress(row)
                previous = (peak, force)
    return pd.DataFrame(rows)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", default=str(RESULTS_DIR / "penalty.csv"))
    args = parser.parse_args(argv)
    table = penalty_table(progress=lambda row: None)
    write_csv(args.out, {name: table[name].to_numpy() for name in table.columns})
    shown = table.copy()
    for name in ("penalty_error_peak", "penalty_error_force", "mesh_change_peak",
                 "mesh_change_force"):
        shown[name] = [f"{100 * v:.4f} %" if v == v and v is not None else "" for v in shown[name]]
    print(shown.drop(columns=["peak", "force"]).to_string(index=False))
    print(f"written: {args.out}")


if __name__ == "__main__":
    main()
