"""Benchmark: a sweep on Dask against the same sweep on local processes (not a test).

The first SCENES scenes of studies/sweeps/figures.toml as one sweep (warm starts, 2
jobs), run on the local engine (2 processes) and on a local Dask cluster of 2 workers,
each from an empty results folder; each engine's workers keep their FreeFEM workers
from run to run (a local process's Session; on Dask the keep_workers_plugin of
orchestrate/sweeps/engines.py). Per engine: the wall time, how many runs took over the
indenter's and the base's workers, the answers' largest difference from the local
sweep's, and the marginal cost of a scene (the same sweep of its first FEW scenes too:
the difference in time over the difference in scenes), which leaves out what starting
the engine costs (a Dask cluster's scheduler and workers).

Writes results/dask.csv and the report results/dask.md.

    python -m studies.bench_dask
"""

import argparse
import json
import os
import tempfile
from pathlib import Path

import pandas as pd

from orchestrate.sweeps import load_sweep, named_points
from studies.bench_session import SWEEP, sweep_seconds
from studies.paths import RESULTS_DIR
from studies.report import Column, Report, command_line, seconds

SCENES = 20
FEW = 4
ENGINES = ("local", "dask")


def _runs(folder):
    """{run name: summary} of a sweep's runs."""
    return {path.parent.name: json.loads(path.read_text())
            for path in (Path(folder) / "sweep" / "runs").glob("*/summary.json")}


def measure(points):
    rows, answers = [], {}
    for engine in ENGINES:
        with tempfile.TemporaryDirectory() as out, tempfile.TemporaryDirectory() as few:
            wall = sweep_seconds(points, out, engine)
            runs = _runs(out)
            wall_few = sweep_seconds(points[:FEW], few, engine)
        answers[engine] = {name: s.get("peak_contact_stress") for name, s in runs.items()}
        rows.append({"engine": engine, "scenes": len(points), "wall_s": wall,
                     "few_wall_s": wall_few,
                     "marginal_s": (wall - wall_few) / (len(points) - FEW),
                     "converged": sum(bool(s.get("converged")) for s in runs.values()),
                     "kept_bodies": sum({"indenter", "base"} <= set(s.get("workers_kept") or ())
                                        for s in runs.values())})
    table = pd.DataFrame(rows)
    local = answers["local"]
    table["peak_difference"] = [max(abs(answers[e][n] / local[n] - 1) for n in local)
                                for e in ENGINES]
    table["ratio"] = table.wall_s / table.wall_s.iloc[0]
    table["marginal_ratio"] = table.marginal_s / table.marginal_s.iloc[0]
    return table


def write_report(table, out, command="python -m studies.bench_dask"):
    report = Report("Sweeps on Dask against local processes", command, data=["dask.csv"])
    report.text(f"The first {SCENES} figure scenes as one sweep (warm starts, 2 jobs) on "
                "each engine, from an empty folder; one run each on a shared 2-core machine.")
    report.table(table, [
        Column("engine", "engine"), Column("scenes", "scenes", "{:g}"),
        Column("wall_s", "wall", seconds),
        Column("ratio", "ratio", "{:.2f}", "wall time over the local engine's"),
        Column("few_wall_s", f"wall, {FEW} scenes", seconds),
        Column("marginal_s", "per scene more", seconds,
               f"(wall - wall of {FEW} scenes) / (scenes - {FEW})"),
        Column("marginal_ratio", "ratio", "{:.2f}", "over the local engine's"),
        Column("kept_bodies", "kept", "{:g}",
               "runs that took over the indenter's and the base's workers"),
        Column("peak_difference", "peak difference", "{:.1e}",
               "largest relative difference of a run's peak contact stress from the local "
               "sweep's")])
    dask = table[table.engine == "dask"].iloc[0]
    report.finding(f"The Dask sweep takes {dask.ratio:.2f} times the local one's time, a "
                   f"scene more {dask.marginal_ratio:.2f} times; {dask.kept_bodies:g} of its "
                   f"{dask.scenes:g} runs took over the bodies' workers.")
    return report.write(out)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=str(RESULTS_DIR))
    args = parser.parse_args(argv)
    points = named_points(load_sweep(SWEEP)[1])[:SCENES]
    table = measure(points)
    print(table.to_string(index=False, float_format=lambda v: f"{v:.3g}"))
    os.makedirs(args.out, exist_ok=True)
    table.to_csv(os.path.join(args.out, "dask.csv"), index=False)
    print(write_report(table, os.path.join(args.out, "dask.md"),
                       command_line("studies.bench_dask", argv)))


if __name__ == "__main__":
    main()
