"""The subdomain workers of a run and the files they read.

Every body (the indenter, the base, a 2D coating patch) runs freefem/body.edp and every
shell patch freefem/shell.edp, each on its own mesh or mid-line and sides file
(orchestrate/exchange.py). Within a Robin iteration the solves are independent: every
request is written before any reply is read, so the workers compute at the same time.
"""

import os
import time

from .errors import system_failure
from .faults import checkpoint
from .exchange import parse_reply, reply_count, request_arrays, write_sides
from .mesh import body_mesh, coating_mesh, write_medit
from .outputs import check_written, write_body_fields
from .body_plans import BodyPlan
from .worker import CMD_OUTPUT, CMD_SOLVE, Worker


def write_inputs(problem, workdir):
    """Meshes, shell nodes and sides files of every subdomain, in ``workdir``; returns
    {name: {"mesh" or "nodes": path, "sides": path}}."""
    try:
        return _write_inputs(problem, workdir)
    except OSError as error:
        raise system_failure(error, "writing the meshes and interface files") from None


def _write_inputs(problem, workdir):
    files = {}
    for name, subdomain in problem.subdomains.items():
        files[name] = {"sides": os.path.join(workdir, f"{name}.sides")}
        write_sides(files[name]["sides"], [(problem.interfaces[i], problem.interfaces[i].sides[k])
                                           for i, k in problem.sides_of(name)])
        plan = subdomain.plan
        if subdomain.kind == "body":
            files[name]["mesh"] = os.path.join(workdir, f"{name}.mesh")
            mesh = body_mesh(plan) if isinstance(plan, BodyPlan) else coating_mesh(plan)
            write_medit(mesh, files[name]["mesh"])
        else:
            files[name]["nodes"] = os.path.join(workdir, f"{name}_nodes.txt")
            with open(files[name]["nodes"], "w") as out:
                out.write(f"{len(plan.nodes)}\n" + "\n".join(map(repr, plan.nodes.tolist())) + "\n")
    return files


def shell_numbers(subdomain):
    """A shell's numbers as its FreeFEM scripts take them: E, nu, h2, k', curvature,
    whether it has thickness stretch, whether its start is on the symmetry axis."""
    plan = subdomain.plan
    return [subdomain.E, subdomain.nu, plan.thickness, plan.shear_factor, plan.curvature,
            int(plan.thickness_stretch), int(plan.symmetric_start)]


def worker_arguments(subdomain, files):
    """The command-line arguments of a subdomain's worker script (body.edp, shell.edp)."""
    if subdomain.kind == "body":
        return ["-mesh", files["mesh"], "-E", subdomain.E, "-nu", subdomain.nu,
                "-sides", files["sides"]]
    E, nu, h2, kshear, curvature, thickness_stretch, symmetric = shell_numbers(subdomain)
    return ["-nodes", files["nodes"], "-E", E, "-nu", nu, "-h2", h2, "-kshear", kshear,
            "-curvature", curvature, "-stretch", thickness_stretch, "-symmetric", symmetric,
            "-sides", files["sides"]]


def load_arguments(problem):
    """The stamp's load for the indenter's worker: its descent, or its force."""
    scene = problem.scene
    if scene.load.force is not None:
        return ["-force", scene.half_force]
    return ["-descent", scene.load.displacement]


class Subdomains:
    """Every subdomain as a persistent FreeFEM worker."""

    def __init__(self, problem, files, workdir, output_dir):
        self.problem = problem
        self.workdir = workdir
        self.workers = {}
        self.sides = {name: problem.sides_of(name) for name in problem.subdomains}
        self.specs, self.output_prefix = {}, {}
        for name, subdomain in problem.subdomains.items():
            script = "body.edp" if subdomain.kind == "body" else "shell.edp"
            self.output_prefix[name] = os.path.join(output_dir, name)
            arguments = worker_arguments(subdomain, files[name]) + [
                "-output", self.output_prefix[name]]
            if subdomain.stamp:
                arguments += load_arguments(problem)
            self.specs[name] = (script, arguments)
        self.dofs = self._start()

    def _start(self):
        """Start every worker (they assemble and factorise at once); return their dofs."""
        try:
            for name, (script, arguments) in self.specs.items():
                self.workers[name] = Worker(name, script, arguments, self.workdir,
                                            self.problem.settings.worker_timeout)
            return {name: worker.wait_ready() for name, worker in self.workers.items()}
        except OSError as error:
            self.close()
            raise system_failure(error, "starting the FreeFEM workers") from None
        except BaseException:
            self.close()
            raise

    def solve(self, data):
        """One independent solve per subdomain.

        ``data``: {(interface index, side): (alpha, g)} (robin.robin_data). Returns the
        traces {(interface index, side): trace}, the timings (each worker's CPU seconds
        for the request, "back_" + name for its back-substitution alone, and "wait", the
        driver's wall time from the first request sent to the last reply) and the
        stamp's descent."""
        start = time.perf_counter()
        for name, worker in self.workers.items():
            worker.send(CMD_SOLVE, request_arrays(self.sides[name], data))
        traces, seconds, descent = {}, {}, None
        for name, worker in self.workers.items():
            arrays = worker.receive_arrays(reply_count(self.problem, self.sides[name]))
            received, info = parse_reply(self.problem, self.sides[name], arrays)
            traces.update(received)
            seconds[name], seconds[f"back_{name}"] = float(info[0]), float(info[1])
            if self.problem.subdomains[name].stamp:
                descent = float(info[2])
        seconds["wait"] = time.perf_counter() - start
        return traces, seconds, descent

    def write_outputs(self):
        """Ask every worker to write its fields (CSV) and reactions next to its output
        prefix, check that every file is whole, and write each body's VTU from them."""
        for worker in self.workers.values():
            worker.send(CMD_OUTPUT)
        checkpoint("output")
        for name, worker in self.workers.items():
            written, = worker.receive_arrays(1)
            kind = self.problem.subdomains[name].kind
            check_written(self.output_prefix[name], kind, written)
            if kind == "body":
                write_body_fields(self.output_prefix[name])

    def close(self):
        for worker in self.workers.values():
            worker.stop()
        self.workers = {}

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


class FreshProcessSubdomains(Subdomains):
    """The naive baseline: a fresh FreeFEM process per subdomain solve, which assembles
    and factorises its matrix every time. Kept to measure what persistent workers save
    (``--workers fresh``); the answers are the same."""

    def __init__(self, *arguments):
        super().__init__(*arguments)
        self.close()
        self.last_data = None

    def solve(self, data):
        start = time.perf_counter()
        self._start()
        try:
            traces, seconds, descent = super().solve(data)
        finally:
            self.close()
        self.last_data = data
        seconds["wait"] = time.perf_counter() - start
        return traces, seconds, descent

    def write_outputs(self):
        self._start()
        try:
            super().solve(self.last_data)
            super().write_outputs()
        finally:
            self.close()


def start_subdomains(problem, settings, files, workdir, output_dir):
    """The workers of a run: persistent (default) or a fresh process per solve."""
    kind = FreshProcessSubdomains if settings.workers == "fresh" else Subdomains
    return kind(problem, files, workdir, output_dir)
