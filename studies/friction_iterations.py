"""Iterations of a frictional scene against the frictionless one, from a cold start (not
a test: a table for the eye; the loop's correctness under friction is
tests/ddm/test_monolithic.py's).

Full models of the cylinder scene (orchestrate/scenes/cylinder.toml: R = 20 b on a
block 8 b wide and 8 b high, under a force), its patch [-2 b, 2 b] a 2D coating, a
shell or a stretch shell, the indenter of the base's modulus, three times stiffer or
rigid, and the bare block; each solved with default settings at mu = 0 (no friction),
0.1, 0.3 and 0.5, the indenter sliding towards +x1, and under partial slip (mu = 0.5,
pulled by half of mu P; not under the rigid indenter, whose shift is not modelled).
Reported: Robin iterations, contact sets, the wall time, and the iterations over the
frictionless run's.

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


def sliding_scene(overrides, friction, pulled=False):
    """The cylinder scene as a full model sliding under ``friction``, or (``pulled``)
    pulled by half of the friction's limit."""
    scene, _ = load_scene(SCENES_DIR / "cylinder.toml")
    if overrides is not None:
        scene = apply_overrides(scene, overrides)
    coatings = () if overrides is None else (replace(scene.coatings[0], start=-2.0),)
    load = (replace(scene.load, tangential_force=0.5 * friction * scene.load.force)
            if pulled else scene.load)
    return replace(scene, symmetric=False, coatings=coatings, friction=friction,
                   sliding=friction > 0 and not pulled, load=load)


def run(name, friction, pulled=False):
    result = solve(sliding_scene(SCENES[name], friction, pulled))
    summary = result.summary
    return {"scene": name, "mu": friction,
            "load": "partial slip, Q = mu P / 2" if pulled else "sliding" if friction else "",
            "iterations": summary["iterations"],
            "contact_sets": summary["active_set_changes"] + 1,
            "seconds": summary["wall_time_s"]}


def write_report(table, out, command="python -m studies.friction_iterations"):
    frictionless = table[table.mu == 0].set_index("scene").iterations.to_dict()
    table = table.assign(ratio=table.iterations / table.scene.map(frictionless))
    report = Report("Iterations with friction against without", command,
                    data=["friction_iterations.csv"])
    report.text("Full models of the cylinder scene (R = 20 b, a block 8 b wide and high, "
                "a patch [-2 b, 2 b] of 5 E, 0.125 b thick), default settings, a cold start "
                "each; mu = 0 is the scene without friction; one run each.")
    report.table(table, [
        Column("scene", "scene", "{}"), Column("mu", "mu", "{:g}"), Column("load", "load", "{}"),
        Column("iterations", "iterations", "{:g}", "Robin iterations"),
        Column("contact_sets", "contact sets", "{:g}"),
        Column("ratio", "over mu = 0", "{:.2f}", "iterations over the frictionless run's"),
        Column("seconds", "time", seconds)])
    for load, rows in table[table.mu > 0].groupby("load"):
        elastic = rows[~rows.scene.str.contains("rigid")]
        rigid = rows[rows.scene.str.contains("rigid")]
        report.finding(
            f"{load.capitalize()}: under an elastic indenter the loop takes "
            f"{elastic.ratio.min():.2f} to {elastic.ratio.max():.2f} times the frictionless "
            "run's iterations" + (f", under the rigid one {rigid.ratio.min():.2f} to "
                                  f"{rigid.ratio.max():.2f} times" if len(rigid) else "") + ".")
    return report.write(out)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default=str(RESULTS_DIR))
    args = parser.parse_args(argv)
    table = pd.DataFrame([row for name in SCENES for row in
                          [run(name, mu) for mu in FRICTIONS]
                          + ([] if "rigid" in name else [run(name, 0.5, pulled=True)])])
    print(table.to_string(index=False, float_format=lambda v: f"{v:.4g}"))
    os.makedirs(args.out, exist_ok=True)
    table.to_csv(os.path.join(args.out, "friction_iterations.csv"), index=False)
    print(write_report(table, os.path.join(args.out, "friction_iterations.md"),
                       command_line("studies.friction_iterations", argv)))


if __name__ == "__main__":
    main()
