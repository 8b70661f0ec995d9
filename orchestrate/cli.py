"""Command line: ``python -m orchestrate solve --scene FILE.toml --out DIR``.

Without --scene, the paper's scene (orchestrate/scenes/paper.toml). Flags override
the file: the paper's parameters (--h2, --E2, --model, ...; orchestrate/model/scene_file.py's
SHORTHANDS), any scene key with --set KEY=VALUE, and every solver setting. Values are
in the scene file's units (its [units] table; b and E without one), or carry their own
("20 um", "450 GPa"). Exit statuses (orchestrate/errors.py): 0 converged, 1 not
converged (the report is in DIR/summary.json), 2 refused before any work (bad input, a
missing FreeFEM, an output folder that is not free), 3 failed (a worker, a file, the
machine), 4 an internal error, 5 converged with warnings under --strict, 130
interrupted (Ctrl-C), 143 terminated (SIGTERM).
"""

import argparse
from dataclasses import fields
import signal
import sys
import tomllib
import traceback

from orchestrate.run.answers import describe
from orchestrate.model.estimate import answers_text
from orchestrate.errors import (EXIT_CONVERGED, EXIT_FAILED, EXIT_INTERNAL, EXIT_INTERRUPTED,
                     EXIT_NOT_CONVERGED, EXIT_WARNINGS,
                     EXIT_REFUSED, Interrupted, ParameterError, RunFailed, SystemFailure,
                     WarnedBeforeWork)
from orchestrate.workers.freefem import FreeFemMissing
from orchestrate.model.scene import (BONDS, FORCE_BALANCES, INNER_SOLVES, KNOB_RANGES,
                                     METHODS, MODEL_ANSWERS, MODEL_CHOICES, ROBIN_SIDES,
                                     WORKERS, Settings)
from orchestrate.model.scene_file import SETTINGS_LENGTHS, SHORTHANDS, scene_and_settings

# The contact's elements as meshed are reported where they are this much finer than sized
FINER_THAN_SIZED = 0.8

EXIT_STATUSES = """exit status:
  0    converged
  1    not converged (the report is in OUT/summary.json)
  2    refused before any work: bad input, a problem too large, a missing FreeFEM,
       an output folder that is not free
  3    failed: a worker or a file (disk full, file size limit, permission), named
  4    internal error (a bug)
  5    under --strict: warnings (the scene leaves what the tool models); those known
       before any work refuse the run, nothing written
  130, 143, 129, 131   interrupted by SIGINT, SIGTERM, SIGHUP, SIGQUIT"""

_SETTINGS_HELP = {
    "theta": "penalty parameter (b/E); default: the paper's 1e-3 for its loop, else "
             "--theta-per-length times the interface element's length",
    "method": "Robin loop: accelerated active-set loop, or the paper's fixed relaxation",
    "inner_solve": "active-set loop: each contact set's fixed point solved directly from "
                   "the subdomains' Robin maps, iterated, iterated with a coarse-mesh "
                   "correction (mesh level 1; on level 1, interface elements twice as "
                   "long), or auto: direct where the maps cost less, else two-level on a "
                   "fine mesh (the knobs below)",
    "robin": "Robin parameter gamma (E/b); default 1/theta for the paper's loop, else "
             "--robin-one-level, with two levels --robin-two-level-per-length over the "
             "element length",
    "robin_sides": "each interface side's gamma: neighbour (gamma times the neighbour's "
                   "plane-strain modulus over the stiffer body's) or equal",
    "bonds": "the active-set loop's: inside, the base and its coatings solved by one "
             "worker where the loop iterates (on one level, or two) and every patch is "
             "thinner than the contact; auto, so on one level; exchanged, every coating "
             "its own worker, Robin-exchanged across its bond",
    "force_balance": "under a force, where the active-set loop iterates on one level "
                     "without friction: auto, the partner of the stamp carries its force at "
                     "every iteration and the stamp's sides release their inactive points; "
                     "off, neither",
    "rho": "relaxation of (24), in (0, 1]", "eps_u": "tolerance on the relative change",
    "max_iterations": "Robin iterations at most", "mesh_level": "1 = the paper's mesh; "
    "L divides every mesh size by L",
    "element_size": "interface element length at level 1 (uniform), in b, or a length with "
                    "its unit in a scene with [units] (\"10 um\"); default: sized to the "
                    "contact (--contact-elements)",
    "contact_elements": "where element_size is not given: interface elements across the a "
                        "priori contact half-width, graded to element_size_far away from "
                        "the contact",
    "element_size_far": "the interface elements' length away from the contact where it is "
                        "sized, in b or with its unit (default: b/16, or on a large body "
                        "the reach of its contact range over 64 if longer)",
    "workers": "persistent FreeFEM workers, or a fresh process per solve (the naive baseline)",
    "worker_timeout": "seconds a worker may take to answer before the run fails",
    "memory_limit": "GiB the run may take (estimated before any work; default: 3/4 of the "
                    "memory free)",
    "model_tolerance": "with --model auto: the estimated relative error the chosen coating "
                       "model may have in each answer --model-answers names",
    "model_answers": "the answers --model-tolerance covers: normal (the peak contact stress "
                     "and the bond's normal stress) or all (and the bond's shear, which the "
                     "shells miss by several to tens of per cent)",
    "body_fields": "write the indenter's and base's nodal fields (CSV, VTU; the coatings' "
                   "and the interfaces' are written always)",
    # the strategy's knobs (Settings' comments say more; summary.json's "strategy")
    "theta_per_length": "the default theta per b of interface element (1/E)",
    "robin_one_level": "the active-set loop's default gamma on one level (E/b)",
    "robin_two_level_per_length": "with two levels, the default gamma times element_size (E)",
    "hold_contrast": "a side holds its inactive contact points (a fixed matrix) only where "
                     "its body is at least this many times as stiff as its neighbour",
    "contact_split": "iterated on one level without friction, a contact's stiffer side "
                     "takes its gamma over this, the softer side its own times this (at "
                     "most 4 under an indenter hold_contrast times as stiff as the base)",
    "bond_split": "iterated on one level without friction, a bond's sides split about "
                  "the coating's response against the base's further by this factor",
    "auto_direct_unknowns": "auto solves directly while every new worker has at most this "
                            "many interface unknowns, weighted by its dofs over the largest "
                            "worker's; on a finer mesh it takes two levels only where the "
                            "coarse level's workers have at most as many",
    "auto_two_level_mesh_level": "auto iterates with two levels from this mesh level up",
    "auto_fallback_work": "a stalled iteration auto chose falls back to the direct solve "
                          "only where probing the maps costs at most this many "
                          "dof-columns (interface unknowns times dofs, summed over workers)",
    "active_set_tolerance": "relative change at which the active-set loop updates its "
                            "contact set",
    "predicted_set_tolerance": "the same where the first contact set is the one predicted "
                               "from the a priori contact half-width",
    "estimate_margin": "factor on the stopping test's estimated error",
    "min_secants": "pairs of iterates of the final contact set before the estimate counts",
    "traction_floor": "tractions below this times gamma ||u|| count as zero",
    "component_floor": "a traction component's error is measured against at least this "
                       "share of the largest component",
    "divergence_growth": "diverged: displacements or a relative change this many times "
                         "their scale or smallest",
    "stagnation_progress": "share by which a relative change must fall to count as progress",
    "stagnation_window": "iterations without progress: the active-set loop stagnated",
    "paper_stagnation_window": "iterations without progress: the paper's loop stagnated",
    "paper_contraction_window": "changes over which the paper's loop reads its contraction",
    "paper_amplification_window": "pairs of iterates whose amplification the paper's loop "
                                  "reads",
    "anderson_depth": "pairs of iterates Anderson acceleration keeps",
    "anderson_filter": "Anderson's QR filter: secants below this share of their norm are "
                       "dropped",
    "anderson_first_relaxation": "Anderson's first step after a restart: x + this (G(x) - x)",
    "coarse_element_factor": "two levels on mesh level 1: the coarse interface elements "
                             "this many times longer",
    "coarse_newton_steps": "Newton steps of the coarse contact problem at most",
}
_CHOICES = {"model": MODEL_CHOICES, "method": METHODS, "inner_solve": INNER_SOLVES,
            "workers": WORKERS, "robin_sides": ROBIN_SIDES, "bonds": BONDS,
            "force_balance": FORCE_BALANCES, "model_answers": MODEL_ANSWERS}


def _option(name):
    return "--" + name.replace("_", "-")


def _add_scene_options(parser):
    group = parser.add_argument_group(
        "scene", "the scene file, and values that override it (the paper's parameters of "
        "METHOD.md, or any key: --set indenter.radius=50 --set coating[2].E=5)")
    group.add_argument("--scene", help="scene file (TOML; default: the paper's scene, "
                                       "orchestrate/scenes/paper.toml)")
    for name, (meaning, keys) in SHORTHANDS.items():
        kind = str if name == "model" else number_or_quantity
        group.add_argument(_option(name), dest=name, type=kind, default=None,
                           choices=_CHOICES.get(name),
                           help=f"{meaning} (sets {', '.join(keys)})")
    group.add_argument("--set", dest="assignments", action="append", default=[],
                       metavar="KEY=VALUE", help="any scene key; VALUE in TOML syntax")


def _add_settings_options(parser):
    settings = parser.add_argument_group("settings", "how the scene is solved")
    knobs = parser.add_argument_group(
        "the strategy's knobs", "the defaults of theta and gamma, auto's choices and the "
        "Robin loops' numbers (summary.json's strategy records them resolved)")
    for f in fields(Settings):
        group = knobs if f.name in KNOB_RANGES else settings
        text = f"{_SETTINGS_HELP[f.name]} (default {f.default})"
        if isinstance(f.default, bool):               # --body-fields / --no-body-fields
            group.add_argument(_option(f.name), dest=f.name, default=None, help=text,
                               action=argparse.BooleanOptionalAction)
            continue
        kind = float if f.default is None else type(f.default)
        if f.name in SETTINGS_LENGTHS:
            kind = number_or_quantity
        group.add_argument(_option(f.name), dest=f.name, type=kind, default=None,
                           choices=_CHOICES.get(f.name), help=text)


def number_or_quantity(text):
    """A flag's value: a number, or a number with its unit ("20 um"), which the scene
    converts into its units (orchestrate/model/units.py)."""
    try:
        return float(text)
    except ValueError:
        return text


def parse_assignment(text):
    """KEY=VALUE with VALUE in TOML syntax (a bare word is a string)."""
    key, sep, value = text.partition("=")
    if not sep or not key.strip():
        raise ParameterError(f"--set {text!r} must read KEY=VALUE")
    try:
        parsed = tomllib.loads(f"value = {value.strip()}")["value"]
    except tomllib.TOMLDecodeError:
        parsed = value.strip()
    except RecursionError:
        raise ParameterError(f"--set {key.strip()}: value nested too deeply") from None
    return key.strip(), parsed


def build_parser():
    parser = argparse.ArgumentParser(
        prog="python -m orchestrate",
        description="Contact of elastic bodies with thin partial coatings, solved by the "
                    "Robin domain decomposition method (FreeFEM workers).")
    commands = parser.add_subparsers(dest="command", required=True)
    solve = commands.add_parser(
        "solve", help="solve one scene and write its results into a folder",
        description="Solve one scene. Values in the scene file's units ([units]; b and E "
                    "without it), or with their own (\"20 um\", \"450 GPa\"). Writes "
                    "contact.csv, interface.csv, history.csv, summary.json and VTU fields "
                    "into --out.",
        epilog=EXIT_STATUSES, formatter_class=argparse.RawDescriptionHelpFormatter)
    solve.add_argument("--out", required=True, help="output folder (made whole at the end)")
    solve.add_argument("--overwrite", action="store_true",
                       help="replace an earlier run's output folder whole")
    solve.add_argument("--quiet", action="store_true", help="no progress lines")
    solve.add_argument("--strict", action="store_true",
                       help="exit with status 5 if the run has warnings (the scene leaves "
                            "what the tool models: summary.json's warnings); those known "
                            "before any work refuse the run")
    _add_scene_options(solve)
    _add_settings_options(solve)
    sweep = commands.add_parser(
        "sweep", help="run a parameter sweep (a TOML file) into results/<name>/",
        description="Run every point of a sweep file (orchestrate/sweeps/sweep.py explains the "
                    "format); finished runs are skipped, so an interrupted sweep resumes. "
                    "Writes one folder per run and runs.csv, one row per run.",
        epilog="exit status: 0 every run converged, 1 some did not, 2 refused before any "
               "run, 4 an internal error, 5 every run converged but some have warnings "
               "(with --strict), 130/143 interrupted")
    sweep.add_argument("file", help="sweep file (TOML)")
    sweep.add_argument("--out", help="sweep folder (default: results/<name> in the current "
                                     "folder)")
    sweep.add_argument("--engine", choices=("local", "dask"), default="local",
                       help="local processes (default) or Dask distributed")
    sweep.add_argument("--jobs", type=int, help="runs at once (default: one per core)")
    sweep.add_argument("--scheduler", help="Dask scheduler address tcp://HOST:PORT (a "
                       "cluster sharing the results folder); default: a local Dask cluster")
    sweep.add_argument("--retry-failed", action="store_true",
                       help="run again the runs that did not converge (those that failed "
                            "outside their numbers, e.g. a killed worker, always are)")
    sweep.add_argument("--strict", action="store_true",
                       help="exit with status 5 if every run converged but some have "
                            "warnings (runs.csv's warnings column)")
    plot = commands.add_parser("plot", help="plot the stresses of a finished run",
                               description="Write RUN/stresses.png from RUN's CSV files.")
    plot.add_argument("run", help="a folder written by `solve`")
    plot_sweep = commands.add_parser(
        "plot-sweep", help="plot a column of a sweep's runs.csv against another",
        description="Draw column Y of SWEEP_DIR/runs.csv against column X, one line per value "
                    "of BY (and of any other parameter that tells runs with the same X "
                    "apart); runs without Y (not converged) are left out.")
    plot_sweep.add_argument("sweep", metavar="SWEEP_DIR",
                            help="a sweep's folder (or its runs.csv)")
    plot_sweep.add_argument("--y", required=True, help="a column: an output "
                            "(peak_contact_stress, iterations, wall_time_s, ...)")
    plot_sweep.add_argument("--x", required=True, help="a column: a parameter (h2, E2, ...)")
    plot_sweep.add_argument("--by", help="a column: one line per value (model, ...)")
    plot_sweep.add_argument("--where", action="append", default=[], metavar="KEY=VALUE",
                            help="only runs whose column KEY is VALUE (numbers to 1e-9; "
                                 "an empty VALUE: an empty cell); repeatable")
    plot_sweep.add_argument("--logx", action="store_true", help="logarithmic x axis")
    plot_sweep.add_argument("--logy", action="store_true", help="logarithmic y axis")
    plot_sweep.add_argument("--out", help="PNG file (default SWEEP_DIR/Y-X-BY.png)")
    return parser


def stop_on_signals():
    """Turn SIGINT, SIGTERM, SIGHUP and SIGQUIT into Interrupted, so that clean-up runs
    for each and the exit status tells them apart; once cleaning up, further signals
    wait (a second Ctrl-C must not cut the clean-up short). A closed output pipe is an
    error of the print, not a reason to die (SIGPIPE ignored)."""
    def handler(signum, frame):
        for held in EXIT_INTERRUPTED:
            signal.signal(held, signal.SIG_IGN)
        raise Interrupted(signum)
    for signum in EXIT_INTERRUPTED:
        signal.signal(signum, handler)
    signal.signal(signal.SIGPIPE, signal.SIG_IGN)


def interrupted(error):
    signum = getattr(error, "signum", signal.SIGINT)
    print("interrupted" if signum == signal.SIGINT
          else f"terminated ({signal.Signals(signum).name})", file=sys.stderr)
    return EXIT_INTERRUPTED[signum]


def _progress(row, status):
    if row["iteration"] % 50 == 0 or status != "running":
        _say(f"iteration {row['iteration']:5d}  relative change {row['relative_change']:.3e}"
             f"  active points {row['active_points']:4d}  {row['seconds']:.2f} s")


def _say(text):
    """Print to stdout; a closed stdout does not stop the run."""
    try:
        print(text, flush=True)
    except OSError:
        pass


def _sweep(args, run_done=lambda name=None: None):
    from orchestrate.sweeps import run_sweep
    try:
        table = run_sweep(args.file, args.out, args.engine, args.jobs, args.scheduler,
                          retry_failed=args.retry_failed, run_done=run_done)
    except (ParameterError, FreeFemMissing) as error:
        print(f"error: {error}", file=sys.stderr)
        return EXIT_REFUSED
    except KeyboardInterrupt as error:
        print("finished runs are kept; run the sweep again to resume", file=sys.stderr)
        return interrupted(error)
    counts = table["status"].value_counts().to_dict() if len(table) else {}
    warned = int((table["warnings"].fillna("") != "").sum()) if len(table) else 0
    print(f"{len(table)} runs: " + ", ".join(f"{n} {s}" for s, n in sorted(counts.items()))
          + (f"; {warned} with warnings (runs.csv's warnings column)" if warned else "")
          + f"; table: {table.attrs['path']}")
    if not set(counts) <= {"converged"}:
        return EXIT_NOT_CONVERGED
    return EXIT_WARNINGS if warned and getattr(args, "strict", False) else EXIT_CONVERGED


def scene_from_arguments(args):
    """The scene and settings the arguments of ``solve`` describe."""
    overrides = {name: getattr(args, name) for name in SHORTHANDS}
    overrides.update(parse_assignment(text) for text in args.assignments)
    settings = {f.name: getattr(args, f.name) for f in fields(Settings)}
    return scene_and_settings(args.scene, overrides, settings)


def main(argv=None):
    args = build_parser().parse_args(argv)
    stop_on_signals()
    try:
        if args.command == "plot":
            return _plot(args)
        if args.command == "plot-sweep":
            return _plot_sweep(args)
        if args.command == "sweep":
            return _sweep(args)
        return _solve(args)
    except KeyboardInterrupt as error:
        return interrupted(error)
    except MemoryError:
        print("failed: out of memory", file=sys.stderr)
        return EXIT_FAILED
    except Exception:                    # a bug: say so, with the traceback
        traceback.print_exc()
        print("internal error: please report it with the traceback above", file=sys.stderr)
        return EXIT_INTERNAL


def _plot(args):
    from orchestrate.plots.plot import plot_run
    try:
        print(plot_run(args.run))
    except ParameterError as error:
        print(f"error: {error}", file=sys.stderr)
        return EXIT_REFUSED
    return EXIT_CONVERGED


def _plot_sweep(args):
    from orchestrate.plots.plot_sweep import plot_sweep
    try:
        path, notes = plot_sweep(args.sweep, args.y, args.x, args.by, args.where, args.out,
                                 args.logx, args.logy)
    except ParameterError as error:
        print(f"error: {error}", file=sys.stderr)
        return EXIT_REFUSED
    for note in notes:
        print(f"note: {note}", file=sys.stderr)
    print(path)
    return EXIT_CONVERGED


def mesh_line(summary):
    """The run's interface mesh in a line: as sized, and what each contact zone got as
    meshed where that is finer (a thin 2D coating's cells at the contact's edges)."""
    length = summary["units"]["length"]
    element, far = summary["interface_element_size"], summary["interface_element_size_far"]
    line = f"mesh: interface elements of {element:.4g} {length}" + (
        f" at the contact, graded to {far:.4g} {length} away from it"
        if far > element * (1 + 1e-9) else "")
    across = ", ".join(f"{n:.3g}" for n in summary["elements_across_contact"])
    line += f"; {across} across the contact zones"
    meshed = summary["contact_element_size"]
    if any(size < FINER_THAN_SIZED * element for size in meshed):
        sizes = ", ".join(f"{size:.4g}" for size in meshed)
        line += (f", of {sizes} {length} (the median: a thin 2D coating refines its face "
                 "at the contact's edges)")
    return line


def _solve(args):
    try:
        scene, settings = scene_from_arguments(args)    # refused before the solver loads
        from orchestrate.run.solve import solve         # loads gmsh: may fail for want of memory
        summary = solve(scene, settings, args.out, None if args.quiet else _progress,
                        overwrite=args.overwrite, strict=args.strict)
    except (ParameterError, FreeFemMissing) as error:
        print(f"error: {error}", file=sys.stderr)
        return EXIT_REFUSED
    except WarnedBeforeWork as refused:
        for warning in refused.warnings:
            print(f"warning ({warning['code']}): {warning['message']}", file=sys.stderr)
        print(f"refused under --strict before any work: {refused}; nothing written "
              f"(exit status {EXIT_WARNINGS})", file=sys.stderr)
        return EXIT_WARNINGS
    except RunFailed as error:
        print(f"not converged: {error} (report in {args.out}/summary.json)", file=sys.stderr)
        return EXIT_NOT_CONVERGED
    except SystemFailure as error:
        print(f"failed: {error}", file=sys.stderr)
        return EXIT_FAILED
    except MemoryError:
        print("failed: out of memory (lower --memory-limit's estimate: coarsen the mesh)",
              file=sys.stderr)
        return EXIT_FAILED
    for patch in (summary["model_choice"] or {}).get("patches", []):
        error = patch.get("fallback_estimated_error", patch["estimated_error"])
        estimate = (f"1D models not estimated: {patch['not_estimated']}"
                    if patch["not_estimated"] else
                    f"estimated error of the {answers_text(settings.model_answers)} "
                    f"{100 * error:.2g} %, tolerance {100 * settings.model_tolerance:g} %")
        if patch.get("fallback_from"):
            _say(f"coating[{patch['patch']}]: model auto chose {patch['fallback_from']} "
                 f"({estimate}), then solved it again as {patch['model']}: "
                 f"{patch['fallback_reason']}")
        else:
            _say(f"coating[{patch['patch']}]: model auto chose {patch['model']} ({estimate})")
    units = summary["units"]
    for line in describe(summary["answers"], units, scene.axisymmetric):
        _say(line)
    descent = (f", descent {summary['descent']:.4e} {units['length']}"
               if scene.load.force is not None else "")
    _say(f"converged in {summary['iterations']} iterations, {summary['wall_time_s']:.1f} s; "
         f"contact force {summary['total_force']:.4e} {units['force']}{descent}, contact "
         "zones " + ", ".join(f"[{a:.4g}, {b:.4g}]" for a, b in summary["contact_zones"])
         + f" {units['length']}; results in {args.out}")
    for number, step in enumerate(summary.get("load_steps") or [], start=1):
        _say(f"load path, step {number}: force {step['force']:.4e}, tangential force "
             f"{step['tangential_force']:.4e} {units['force']}: {step['iterations']} "
             "iterations, stick zones " + ", ".join(
                 f"[{a:.4g}, {b:.4g}]" for a, b in step["stick_zones"]) + f" {units['length']}")
    if summary.get("stick_zones") is not None:
        _say("partial slip: stick zones " + ", ".join(
            f"[{a:.4g}, {b:.4g}]" for a, b in summary["stick_zones"]) + f" {units['length']}, "
            f"tangential force {summary['tangential_force']:.4e} {units['force']}, the "
            f"stamp's shift {summary['stamp_shift']:.4e} {units['length']}")
    elif scene.sliding and summary.get("tangential_force"):
        _say(f"sliding: friction force {summary['tangential_force']:.4e} {units['force']}")
    _say(mesh_line(summary))
    for warning in summary["warnings"]:
        print(f"warning ({warning['code']}): {warning['message']}", file=sys.stderr)
    if summary["warnings"] and args.strict:
        print(f"{len(summary['warnings'])} warning(s) and --strict: exit status "
              f"{EXIT_WARNINGS}", file=sys.stderr)
        return EXIT_WARNINGS
    return EXIT_CONVERGED
