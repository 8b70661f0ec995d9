"""Benchmark: what workers that outlive a scene save on the figure scenes (not a test).

1. The scenes of studies/sweeps/figures.toml one after the other in this process,
   each with workers of its own, then all in one Session (orchestrate/workers/session.py): the
   wall time of each run, its set-up and its loop, and the answers' largest difference.
2. The sweep itself (2 local jobs, warm starts, each job a session) on all its scenes and
   on its first FEW: the marginal cost of a scene is the difference over the difference
   in scenes.

Writes results/session.csv, session_sweep.csv and the report results/session.md.

    python -m studies.bench_session     # prints the tables, writes results/session*.csv
"""

import argparse
import os
import tempfile
import time
from pathlib import Path

import pandas as pd

from studies.paths import RESULTS_DIR
from studies.report import Column, Report, command_line, seconds
from orchestrate.workers import Session
from orchestrate.run import solve_into as solve
from orchestrate.sweeps import load_sweep, named_points, point_scene, run_sweep

SWEEP = Path(__file__).parent / "sweeps" / "figures.toml"
FEW = 4


def one_by_one(points, session):
    """A row per scene: wall, set-up and loop seconds, iterations, peaks."""
    rows = []
    with tempfile.TemporaryDirectory() as out:
        for k, (name, values) in enumerate(points):
            scene, settings = point_scene(values, SWEEP.parent)
            start = time.perf_counter()
            summary = solve(scene, settings, os.path.join(out, name), session=session)
            rows.append({"scene": name, "wall_s": time.perf_counter() - start,
                         "setup_s": summary["setup_time_s"],
                         "loop_s": summary["time_per_iteration_s"] * summary["iterations"],
                         "iterations": summary["iterations"],
                         "inner_solve_used": summary["inner_solve_used"],
                         "kept": len(summary["workers_kept"]),
                         "peak_contact_stress": summary["peak_contact_stress"],
                         "peak_interface_stress": summary["peak_interface_stress"]})
    return pd.DataFrame(rows)


def sweep_seconds(points, out, engine="local"):
    """Wall seconds of a sweep like the figures' (warm starts, 2 jobs) of ``points`` on
    the ``engine``; its runs are in ``out``/sweep."""
    def value(v):                              # in TOML
        if isinstance(v, bool):
            return "true" if v else "false"
        return f'"{v}"' if isinstance(v, str) else repr(v)
    runs = "".join("[[runs]]\n" + "".join(f"{key} = {value(v)}\n" for key, v in values.items())
                   for _, values in points)
    path = Path(out) / "sweep.toml"
    path.write_text(f'name = "bench"\nwarm_start = true\n{runs}')
    start = time.perf_counter()
    with open(os.devnull, "w") as quiet:
        run_sweep(path, out=Path(out) / "sweep", engine=engine, jobs=2, stream=quiet)
    return time.perf_counter() - start


def write_report(both, sweep, out, command="python -m studies.bench_session"):
    report = Report("Workers kept from scene to scene", command,
                    data=["session.csv", "session_sweep.csv"])
    report.text("The figure scenes one after the other in one process, each with workers "
                "of its own (alone), then all in one Session of kept workers; one run each "
                "on a shared 2-core machine.")
    ratio = both.wall_s_session.median() / both.wall_s_alone.median()
    report.finding(f"Median wall time per scene: {seconds(both.wall_s_alone.median())} alone, "
                   f"{seconds(both.wall_s_session.median())} in a session (ratio "
                   f"{ratio:.2f}); median set-up {seconds(both.setup_s_alone.median())} "
                   f"against {seconds(both.setup_s_session.median())}. The answers differ by "
                   f"at most {both.peak_difference.max():.1e} (peak contact stress, relative).")
    report.table(both, [
        Column("scene", "scene"),
        Column("wall_s_alone", "wall, alone", seconds),
        Column("wall_s_session", "wall, session", seconds),
        Column("setup_s_alone", "set-up, alone", seconds,
               "meshing and starting (or reusing) the workers"),
        Column("setup_s_session", "set-up, session", seconds),
        Column("iterations_alone", "iterations", "{:g}"),
        Column("kept_session", "workers kept", "{:g}", "workers the session reused"),
        Column("peak_difference", "peak difference", "{:.1e}",
               "relative difference of the peak contact stress, session against alone")])
    report.section("The figure sweep")
    report.text("The sweep of the figure scenes (2 jobs, warm starts, each job a session), "
                "on its first few scenes and on all: the marginal cost of a scene is the "
                "difference in time over the difference in scenes.")
    report.table(sweep, [Column("scenes", "scenes"), Column("wall_s", "wall", seconds)])
    marginal = sweep[sweep.scenes == "marginal per scene"].wall_s
    if len(marginal):
        report.finding(f"A scene more costs the sweep {seconds(marginal.iloc[0])}.")
    return report.write(out)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=str(RESULTS_DIR))
    args = parser.parse_args(argv)
    points = named_points(load_sweep(SWEEP)[1])
    alone = one_by_one(points, None)
    with Session() as session:
        kept = one_by_one(points, session)
    both = alone.merge(kept, on="scene", suffixes=("_alone", "_session"))
    both["peak_difference"] = (both.peak_contact_stress_session / both.peak_contact_stress_alone
                               - 1).abs()
    columns = ["scene", "wall_s_alone", "wall_s_session", "setup_s_alone", "setup_s_session",
               "loop_s_alone", "loop_s_session", "iterations_alone", "kept_session",
               "peak_difference"]
    print(both[columns].to_string(index=False, float_format=lambda v: f"{v:.3g}"))
    with tempfile.TemporaryDirectory() as few, tempfile.TemporaryDirectory() as every:
        t_few, t_all = sweep_seconds(points[:FEW], few), sweep_seconds(points, every)
    marginal = (t_all - t_few) / (len(points) - FEW)
    sweep = pd.DataFrame([{"scenes": FEW, "wall_s": t_few}, {"scenes": len(points), "wall_s": t_all},
                          {"scenes": "marginal per scene", "wall_s": marginal}])
    print("\nthe figure sweep, 2 jobs:\n" + sweep.to_string(index=False))
    os.makedirs(args.out, exist_ok=True)
    both.to_csv(os.path.join(args.out, "session.csv"), index=False)
    sweep.to_csv(os.path.join(args.out, "session_sweep.csv"), index=False)
    print(write_report(both, sweep, os.path.join(args.out, "session.md"),
                       command_line("studies.bench_session", argv)))


if __name__ == "__main__":
    main()
