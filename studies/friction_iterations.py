"""Iterations of a frictional scene against the frictionless one, from a cold start (not
a test: a table for the eye; the loop's correctness under friction is
tests/ddm/test_monolithic.py's).

Full models of the cylinder scene (orchestrate/scenes/cylinder.toml: R = 20 b on a
block 8 b wide and 8 b high, under a force), its patch [-2 b, 2 b] a 2D coating, a
shell or a stretch shell, the indenter of the base's modulus, three times stiffer or
rigid, and the bare block; each solved with default settings at mu = 0 (no friction),
0.1, 0.3 and 0.5, the indenter sliding towards +x1. Reported: Robin iterations,
contact sets, the wall time, and the iterations over the frictionless run's.

Writes results/friction_iterations.csv and its report results/friction_iterations.md.

    python -m studies.friction_iterations
"""

import argparse
from dataclasses import replace
import os

import pandas as pd

from orchestrate import solve
from orchestrate.model import apply_overrides, load_scene
from orchestrate.paths import SCENES_DIR
from studies.paths import RESULTS_DIR
from studies.report import Column, Report, command_line, seconds

FRICTIONS = (0.0, 0.1, 0.3, 0.5)
SCENES = {           # name: overrides of cylinder.toml (None: no coating)
    "bare block": None,
    "2D coating": {"coating[1].model": "elastic"},
    "shell": {"coating[1].model": "shell"},
    "stretch shell, indenter 3 E": {"coating[1].model": "stretch_shell", "indenter.E": 3.0},
    "2D coating, rigid indenter": {"coating[1].model": "elastic", "indenter.rigid": True},
}


def sliding_scene(overrides, friction):
    """The cylinder scene as a full model sliding under ``friction``."""
    scene, _ = load_scene(SCENES_DIR / "cylinder.toml")
    if overrides is not None:
        scene = apply_overrides(scene, overrides)
    coatings = () if overrides is None else (replace(scene.coatings[0], start=-2.0),)
    return replace(scene, symmetric=False, coatings=coatings, friction=friction,
                   sliding=friction > 0)


def run(name, friction):
    result = solve(sliding_scene(SCENES[name], friction))
    summary = result.summary
    return {"scene": name, "mu": friction, "iterations": summary["iterations"],
            "contact_sets": summary["active_set_changes"] + 1,
            "seconds": summary["wall_time_s"]}


def write_report(table, out, command="python -m studies.friction_iterations"):
    frictionless = table[table.mu == 0].set_index("scene").iterations
    table = table.assign(ratio=table.iterations / table.scene.map(frictionless))
    report = Report("Iterations with friction against without", command,
                    data=["friction_iterations.csv"])
    report.text("Full models of the cylinder scene (R = 20 b, a block 8 b wide and high, "
                "a patch [-2 b, 2 b] of 5 E, 0.125 b thick), default settings, a cold start "
                "each; mu = 0 is the scene without friction; one run each.")
    report.table(table, [
        Column("scene", "scene", "{}"), Column("mu", "mu", "{:g}"),
        Column("iterations", "iterations", "{:g}", "Robin iterations"),
        Column("contact_sets", "contact sets", "{:g}"),
        Column("ratio", "over mu = 0", "{:.2f}", "iterations over the frictionless run's"),
        Column("seconds", "time", seconds)])
    frictional = table[table.mu > 0]
    report.finding(f"With friction the loop takes {frictional.ratio.min():.2f} to "
                   f"{frictional.ratio.max():.2f} times the frictionless run's iterations "
                   f"(median {frictional.ratio.median():.2f}).")
    return report.write(out)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default=str(RESULTS_DIR))
    args = parser.parse_args(argv)
    table = pd.DataFrame([run(name, mu) for name in SCENES for mu in FRICTIONS])
    print(table.to_string(index=False, float_format=lambda v: f"{v:.4g}"))
    os.makedirs(args.out, exist_ok=True)
    table.to_csv(os.path.join(args.out, "friction_iterations.csv"), index=False)
    print(write_report(table, os.path.join(args.out, "friction_iterations.md"),
                       command_line("studies.friction_iterations", argv)))


if __name__ == "__main__":
    main()
