"""Command line: ``python -m orchestrate solve --model shell --h2 0.125 --E2 1 --out DIR``.

Lengths are in units of b and moduli in units of E. Exit status: 0 converged, 1 the
loop diverged or stagnated (the report is in DIR/summary.json), 2 bad input or a
missing FreeFEM, 3 a worker failed.
"""

import argparse
from dataclasses import fields
import signal
import sys

from .freefem import FreeFemMissing
from .scene import METHODS, MODELS, WORKERS, ParameterError, Scene, Settings
from .worker import WorkerError

_SCENE_HELP = {
    "length": "l, length of both bodies", "height": "h, height of both bodies",
    "coating_length": "l2, the coating covers x1 in [0, l2]", "h2": "coating thickness",
    "E1": "Young's modulus of Omega1", "E2": "Young's modulus of the coating",
    "E3": "Young's modulus of Omega3", "nu1": "Poisson ratio of Omega1",
    "nu2": "Poisson ratio of the coating", "nu3": "Poisson ratio of Omega3",
    "shear_factor": "k' of the shell", "chi": "initial gap d = chi x1^2",
    "stamp": "Delta, downward displacement of Omega1's top",
}
_SETTINGS_HELP = {
    "model": "coating model", "theta": "penalty parameter (b/E)",
    "method": "Robin loop: accelerated active-set loop, or the paper's fixed relaxation",
    "robin": "Robin parameter gamma (E/b); default 1/theta for the paper's loop, else 2",
    "rho": "relaxation of (24), in (0, 1]", "eps_u": "tolerance on the relative change",
    "max_iterations": "Robin iterations at most", "mesh_level": "1 = the paper's mesh; "
    "L divides every mesh size by L", "shell_elements": "interface elements at level 1",
    "workers": "persistent FreeFEM workers, or a fresh process per solve (the naive baseline)",
}


def _option(name):
    return "--" + name.replace("_", "-")


def _add_dataclass_options(parser, cls, helps, title):
    group = parser.add_argument_group(title)
    for f in fields(cls):
        kind = float if f.default is None else type(f.default)
        extra = {"model": {"choices": MODELS}, "method": {"choices": METHODS},
                 "workers": {"choices": WORKERS}}.get(f.name, {})
        group.add_argument(_option(f.name), dest=f.name, type=kind, default=f.default,
                           help=f"{helps[f.name]} (default {f.default})",
                           **extra)


def build_parser():
    parser = argparse.ArgumentParser(
        prog="python -m orchestrate",
        description="Contact of elastic bodies with a thin partial coating, solved by the "
                    "Robin domain decomposition method (FreeFEM workers).")
    commands = parser.add_subparsers(dest="command", required=True)
    solve = commands.add_parser(
        "solve", help="solve one scene and write its results into a folder",
        description="Solve one scene. Lengths in b, moduli in E. Writes contact.csv, "
                    "interface.csv, history.csv, summary.json and VTU fields into --out.")
    solve.add_argument("--out", required=True, help="output folder")
    solve.add_argument("--quiet", action="store_true", help="no progress lines")
    _add_dataclass_options(solve, Scene, _SCENE_HELP, "scene")
    _add_dataclass_options(solve, Settings, _SETTINGS_HELP, "settings")
    sweep = commands.add_parser(
        "sweep", help="run a parameter sweep (a TOML file) into results/<name>/",
        description="Run every point of a sweep file (orchestrate/sweep.py explains the "
                    "format); finished runs are skipped, so an interrupted sweep resumes. "
                    "Writes one folder per run and runs.csv, one row per run.")
    sweep.add_argument("file", help="sweep file (TOML)")
    sweep.add_argument("--out", help="sweep folder (default results/<name>)")
    sweep.add_argument("--engine", choices=("local", "dask"), default="local",
                       help="local processes (default) or Dask distributed")
    sweep.add_argument("--jobs", type=int, help="runs at once (default: one per core)")
    sweep.add_argument("--scheduler", help="Dask scheduler address tcp://HOST:PORT (a "
                       "cluster sharing the results folder); default: a local Dask cluster")
    plot = commands.add_parser("plot", help="plot the stresses of a finished run",
                               description="Write RUN/stresses.png from RUN's CSV files.")
    plot.add_argument("run", help="a folder written by `solve`")
    return parser


def _terminate_on_sigterm():
    """Turn SIGTERM into KeyboardInterrupt, so that clean-up runs as for Ctrl-C."""
    def handler(signum, frame):
        raise KeyboardInterrupt(f"signal {signum}")
    signal.signal(signal.SIGTERM, handler)


def _progress(row, status):
    if row["iteration"] % 50 == 0 or status != "running":
        print(f"iteration {row['iteration']:5d}  relative change {row['relative_change']:.3e}"
              f"  active points {row['active_points']:4d}  {row['seconds']:.2f} s", flush=True)


def _sweep(args):
    from .sweep import run_sweep
    try:
        table = run_sweep(args.file, args.out, args.engine, args.jobs, args.scheduler)
    except (ParameterError, FreeFemMissing, OSError) as error:
        print(f"error: {error}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("interrupted: finished runs are kept, run the sweep again to resume",
              file=sys.stderr)
        return 130
    counts = table["status"].value_counts().to_dict() if len(table) else {}
    print(f"{len(table)} runs: " + ", ".join(f"{n} {s}" for s, n in sorted(counts.items())))
    return 0


def main(argv=None):
    args = build_parser().parse_args(argv)
    _terminate_on_sigterm()
    if args.command == "plot":
        from .plot import plot_run
        print(plot_run(args.run))
        return 0
    if args.command == "sweep":
        return _sweep(args)
    from .solve import RunFailed, solve

    try:
        scene = Scene(**{f.name: getattr(args, f.name) for f in fields(Scene)})
        settings = Settings(**{f.name: getattr(args, f.name) for f in fields(Settings)})
    except ParameterError as error:
        print(f"error: {error}", file=sys.stderr)
        return 2
    try:
        summary = solve(scene, settings, args.out, None if args.quiet else _progress)
    except FreeFemMissing as error:
        print(f"error: {error}", file=sys.stderr)
        return 2
    except RunFailed as error:
        print(f"not converged: {error} (report in {args.out}/summary.json)", file=sys.stderr)
        return 1
    except WorkerError as error:
        print(f"error: {error}", file=sys.stderr)
        return 3
    except KeyboardInterrupt:
        print("interrupted", file=sys.stderr)
        return 130
    print(f"converged in {summary['iterations']} iterations, {summary['wall_time_s']:.1f} s; "
          f"contact force {summary['contact_force']:.4e}, half-width "
          f"{summary['contact_half_width']:.3f}; results in {args.out}")
    return 0
