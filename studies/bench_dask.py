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
Each engine is measured REPEATS times, the engines in turn (the load of a shared machine
drifts; alternating rounds see it alike); the report gives the medians and the spread
of the per-round ratios.

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
REPEATS = 3         # rounds, each engine in turn
ENGINES = ("local", "dask")


def _runs(folder):
    """{run name: summary} of a sweep's runs."""
    return {path.parent.name: json.loads(path.read_text())
            for path in (Path(folder) / "sweep" / "runs").glob("*/summary.json")}


def measure(points, repeats=REPEATS):
    """A row per engine: the medians over ``repeats`` rounds, each round every engine in
    turn (a shared machine's load drifts: alternating rounds see it alike), and the
    spread of the per-round ratios to the local engine."""
    rounds, answers = {engine: [] for engine in ENGINES}, {}
    for _ in range(repeats):
        for engine in ENGINES:
            with tempfile.TemporaryDirectory() as out, tempfile.TemporaryDirectory() as few:
                wall = sweep_seconds(points, out, engine)
                runs = _runs(out)
                wall_few = sweep_seconds(points[:FEW], few, engine)
            answers.setdefault(engine, {name: s.get("peak_contact_stress")
                                        for name, s in runs.items()})
            rounds[engine].append({
                "wall_s": wall, "few_wall_s": wall_few,
                "marginal_s": (wall - wall_few) / (len(points) - FEW),
                "converged": sum(bool(s.get("converged")) for s in runs.values()),
                "kept_bodies": sum({"indenter", "base"} <= set(s.get("workers_kept") or ())
                                   for s in runs.values())})
    local = pd.DataFrame(rounds["local"])
    rows = []
    for engine in ENGINES:
        measured = pd.DataFrame(rounds[engine])
        ratios = measured.wall_s / local.wall_s
        marginal = measured.marginal_s / local.marginal_s
        rows.append({"engine": engine, "scenes": len(points), "rounds": repeats,
                     **measured.median().to_dict(),
                     "ratio": float(ratios.median()), "ratio_low": float(ratios.min()),
                     "ratio_high": float(ratios.max()),
                     "marginal_ratio": float(marginal.median()),
                     "marginal_ratio_low": float(marginal.min()),
                     "marginal_ratio_high": float(marginal.max())})
    table = pd.DataFrame(rows)
    reference = answers["local"]
    table["peak_difference"] = [max(abs(answers[e][n] / reference[n] - 1) for n in reference)
                                for e in ENGINES]
    return table


def write_report(table, out, command="python -m studies.bench_dask"):
    report = Report("Sweeps on Dask against local processes", command, data=["dask.csv"])
    report.text(f"The first {SCENES} figure scenes as one sweep (warm starts, 2 jobs) on "
                "each engine, from an empty folder, in rounds of one sweep per engine in "
                "turn; medians over the rounds, one run of this study on a shared 2-core "
                "machine.")
    report.table(table, [
        Column("engine", "engine"), Column("scenes", "scenes", "{:g}"),
        Column("rounds", "rounds", "{:g}"),
        Column("wall_s", "wall", seconds),
        Column("ratio", "ratio", "{:.2f}", "median over the rounds of the wall time over "
               "the local engine's in the same round"),
        Column("ratio_low", "lowest", "{:.2f}"), Column("ratio_high", "highest", "{:.2f}"),
        Column("few_wall_s", f"wall, {FEW} scenes", seconds),
        Column("marginal_s", "per scene more", seconds,
               f"(wall - wall of {FEW} scenes) / (scenes - {FEW})"),
        Column("marginal_ratio", "ratio", "{:.2f}", "its median ratio to the local engine's"),
        Column("kept_bodies", "kept", "{:g}",
               "runs that took over the indenter's and the base's workers"),
        Column("peak_difference", "peak difference", "{:.1e}",
               "largest relative difference of a run's peak contact stress from the local "
               "sweep's")])
    dask = table[table.engine == "dask"].iloc[0]
    report.finding(f"The Dask sweep takes {dask.ratio:.2f} times the local one's time (rounds "
                   f"{dask.ratio_low:.2f}-{dask.ratio_high:.2f}), a scene more "
                   f"{dask.marginal_ratio:.2f} times ({dask.marginal_ratio_low:.2f}-"
                   f"{dask.marginal_ratio_high:.2f}); {dask.kept_bodies:g} of its "
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
