"""The subdomain workers of a run and the files they read.

Every body (the indenter, the base, a 2D coating patch) runs freefem/body.edp and every
shell patch freefem/shell.edp (a shell of revolution in an axisymmetric scene: every
script takes the scene's geometry_arguments), each on its own mesh or mid-line and sides
file; or the base and its coatings run one worker together, freefem/coated_base.edp, on
their files and a problem file (problem_file.py) that bonds them (the run's
Strategy.workers says which). What they are sent and send back are the records of
orchestrate/workers/exchange.py. A worker starts as soon as its files are written
(written_inputs, the largest first), so it assembles while the next mesh is made; within
a Robin iteration the solves are independent: every request is written before any reply
is read, so the workers compute at the same time.
The workers come from a Session (orchestrate/workers/session.py), which may have kept them from
an earlier scene; a kept worker's solves become evaluations of its Robin-to-trace map
(orchestrate/workers/robin_map.py).
"""

from collections.abc import Mapping
from dataclasses import replace
import hashlib
import os
import time

import numpy as np

from orchestrate.errors import system_failure
from orchestrate.faults import checkpoint
from orchestrate.workers.exchange import (REVOLUTION_SHELL_COLUMNS, SHELL_COLUMNS, BodyOutput,
                                          Command, OutputRequest, RobinRequest, ShellNumbers,
                                          ShellOutput, SideArrays, Sides, TraceReply)
from orchestrate.mesh.meshes import coating_mesh, write_body_mesh, write_medit
from orchestrate.mesh.body_plans import BodyPlan
from orchestrate.mesh.problem_size import estimated_dofs
from orchestrate.workers.problem_file import write_problem
from orchestrate.workers.robin_map import check, receive_map, send_map_request
from orchestrate.workers.provenance import SCRIPTS
from orchestrate.workers.session import body_fingerprint, files_fingerprint


def write_inputs(problem, workdir, workers=()):
    """Meshes, shell nodes and sides files of every subdomain, in ``workdir``; returns
    {name: {"mesh" or "nodes": path, "sides": path, "geometry": (fingerprint of what
    they hold, the origin it is taken from)}} (orchestrate/workers/session.py). A worker
    of several subdomains (``workers``: Strategy.workers) gets their problem file:
    {worker: {"problem": path, "geometry": (fingerprint, the origins of its subdomains)}}."""
    files = {}
    for _ in written_inputs(problem, workdir, workers, files):
        pass
    return files


def written_inputs(problem, workdir, workers=(), files=None):
    """write_inputs a worker at a time (``workers``: by default each subdomain its own):
    yields (worker, its files) as soon as they are written, the largest worker's first,
    so that it assembles and factorises, the longest set-up, while the smaller ones'
    meshes are made; ``files`` collects what write_inputs returns."""
    files = {} if files is None else files
    workers = dict(workers or ((name, (name,)) for name in problem.subdomains))
    dofs = estimated_dofs(problem)
    try:
        for worker in sorted(workers, key=lambda w: -sum(dofs[name] for name in workers[w])):
            names = workers[worker]
            for name in names:
                files[name] = _write_subdomain_inputs(problem, workdir, name)
            if names != (worker,):
                files[worker] = _write_problem(problem, files, workdir, worker, names)
            yield worker, files[worker]
    except OSError as error:
        raise system_failure(error, "writing the meshes and interface files") from None


def _write_problem(problem, files, workdir, worker, names):
    """The problem file of a worker of several subdomains, and its geometry: what its
    subdomains' files hold and the file's numbers (its paths left out: a worker kept from
    another folder is the same worker), each subdomain's place its own origin."""
    path = os.path.join(workdir, f"{worker}.txt")
    write_problem(problem, files, path, names)
    digest = hashlib.sha256()
    paths = {files[name][key]: files[name]["geometry"][0] for name in names
             for key in ("mesh", "nodes", "sides") if key in files[name]}
    with open(path) as text:
        for token in text.read().split():
            digest.update(paths.get(token, token).encode() + b" ")
    origins = np.array([files[name]["geometry"][1] for name in names])
    return {"problem": path, "geometry": (digest.hexdigest(), origins)}


def _write_subdomain_inputs(problem, workdir, name):
    subdomain = problem.subdomains[name]
    files = {"sides": os.path.join(workdir, f"{name}.sides")}
    sides = [(problem.interfaces[i], problem.interfaces[i].sides[k])
             for i, k in problem.sides_of(name)]
    with open(files["sides"], "w") as out:
        out.write(Sides(tuple(SideArrays.of(*pair) for pair in sides)).encode())
    plan = subdomain.plan
    if subdomain.kind == "rigid":
        files["geometry"] = files_fingerprint([files["sides"]])
    elif subdomain.kind == "body":
        files["mesh"] = os.path.join(workdir, f"{name}.mesh")
        if isinstance(plan, BodyPlan):
            mesh = write_body_mesh(plan, files["mesh"])
        else:
            mesh = coating_mesh(plan)
            write_medit(mesh, files["mesh"])
        files["geometry"] = body_fingerprint(mesh, sides)
    else:
        files["nodes"] = os.path.join(workdir, f"{name}_nodes.txt")
        with open(files["nodes"], "w") as out:
            out.write(f"{len(plan.nodes)}\n" + "\n".join(map(repr, plan.nodes.tolist())) + "\n")
        files["geometry"] = files_fingerprint([files["nodes"], files["sides"]])
    return files


def worker_arguments(subdomain, files):
    """The command-line arguments of a subdomain's worker script (SCRIPTS); None: a worker
    of several subdomains."""
    if subdomain is None:
        return ["-problem", files["problem"]]
    if subdomain.kind == "rigid":
        return ["-sides", files["sides"]]
    if subdomain.kind == "body":
        return ["-mesh", files["mesh"], "-E", subdomain.E, "-nu", subdomain.nu,
                "-sides", files["sides"]]
    return ["-nodes", files["nodes"], *ShellNumbers.of(subdomain).arguments(),
            "-sides", files["sides"]]


def geometry_arguments(scene):
    """The scene's geometry for every script that builds a body or a shell
    (freefem/elasticity.idp; shell.edp): none for plane strain, -axisymmetric 1 for
    bodies of revolution and shells of revolution."""
    return ["-axisymmetric", 1] if scene.axisymmetric else []


def shell_columns(subdomain):
    """The columns of a shell's ShellOutput: a plane shell's or a shell of revolution's."""
    return REVOLUTION_SHELL_COLUMNS if subdomain.plan.revolution else SHELL_COLUMNS


def load_arguments(problem):
    """The stamp's load for the indenter's worker: its descent, or its force, and under
    partial slip its tangential load."""
    scene = problem.scene
    if scene.load.force is not None:
        return ["-force", scene.half_force, *tangential_arguments(scene.load)]
    return ["-descent", scene.load.displacement, *tangential_arguments(scene.load)]


def tangential_arguments(load):
    """The FreeFEM arguments of a load's tangential force or displacement (arguments.idp;
    the monolithic solve's too)."""
    if load.tangential_kind == "tangential_force":
        return ["-partialslip", 1, "-tangential", load.tangential_force]
    if load.tangential_kind == "tangential_displacement":
        return ["-partialslip", 1, "-shiftgiven", 1, "-shift", load.tangential_displacement]
    return []


# Probing a map costs one back-substitution per interface unknown, in-process, a share of
# what a Robin iteration of the loop costs a worker of the same size. So the maps pay
# while every new worker has at most Settings.auto_direct_unknowns interface unknowns,
# weighted by its dofs over the largest worker's (Subdomains._maps_pay; `python -m
# studies.bench_direct` times both ways).
# A kept worker's map is probed once its real solves, over every scene it served, have
# cost what probing would: KEPT_MAP_SOLVES_PER_UNKNOWN of them per interface unknown
# (buying once the rent paid reaches the price: at most twice the cost of the better
# choice made knowing how many scenes follow). Measured on the gallery at mesh level 1, a
# column of a map cost 0.12-0.19 of a Robin iteration of the loop, and a sweep's maps
# paid after 1.6-5.4 scenes; probed at its second scene, the thick ceramic's coating
# (531 unknowns) took 5.7 s to save 1.1 s a scene.
KEPT_MAP_SOLVES_PER_UNKNOWN = 0.15
# On a mesh fine enough for two levels (mesh level 2 and finer) "auto" and "two-level"
# probe no map, not even a kept worker's: iterated with a coarse correction a scene takes
# 20-30 Robin iterations, while the maps of the indenter and the base cost 10 s at mesh
# level 3, and a new indenter (another coating thickness) 5 s, against 2.5 s for a whole
# scene with kept workers.

# Arguments that name a file: the worker's identity is the file's content (its geometry).
_FILE_ARGUMENTS = {"-mesh", "-nodes", "-sides", "-problem"}


class Subdomains:
    """Every subdomain of a run as a persistent FreeFEM worker, taken from ``session``.

    For the active-set loop (problem.settings), a kept worker whose solves have paid for
    it (KEPT_MAP_SOLVES_PER_UNKNOWN) gives its Robin-to-trace map (robin_map.py), which
    stands in for its solves while the Robin coefficients are the map's (that loop's
    never change). ``inner_solve``: with "direct", every new worker gives its map too,
    and with every map known the loop solves each contact set's fixed point directly
    (robin_maps); "auto" does so where the maps pay (_maps_pay); "iterate" never, nor
    "auto" where the run's strategy planned to iterate (``iterate``). On a mesh fine enough for two levels, "auto" and
    "two-level" use no map at all, nor does a fresh process per solve. ``workers``: the
    run's workers and their subdomains (Strategy.workers), by default each subdomain its
    own; a worker of several answers for all their sides, in their order."""

    def __init__(self, problem, files, session, workers=None, iterate=False):
        self.problem = problem
        self.session = session
        settings = problem.settings
        inner_solve = settings.inner_solve
        self.use_maps = (settings.method != "paper" and settings.workers != "fresh"
                         and (inner_solve == "direct" or not settings.two_levels))
        # {worker: its subdomains} (Strategy.workers; by default each subdomain its own)
        self.parts = dict(workers or ((name, (name,)) for name in problem.subdomains))
        self.sides = {worker: problem.sides_of(*names) for worker, names in self.parts.items()}
        self.components = {worker: [problem.interfaces[i].components for i, _ in sides]
                           for worker, sides in self.sides.items()}
        self.shapes = {worker: [(problem.interfaces[i].components, problem.interfaces[i].size)
                                for i, _ in sides] for worker, sides in self.sides.items()}
        self.specs, self.keys, self.origins = {}, {}, {}
        # the unknowns a map probes: the sides with a Robin term (not a bond inside)
        inside = {i for names in self.parts.values() if len(names) > 1
                  for i, _ in problem.sides_of(*names)
                  if all(side.subdomain in names for side in problem.interfaces[i].sides)}
        self.unknowns = {worker: sum(problem.interfaces[i].size * problem.interfaces[i].components
                                     for i, _ in sides if i not in inside)
                         for worker, sides in self.sides.items()}
        self.entries = {}
        self.last_requests, self.mapped = {}, {}
        self.shift = 0.0          # the stamp's shift along x1 in its last solve (partial slip)
        self._pending = {}           # map requests sent and not yet answered, by name
        self.dofs = self._start(self._specified(files))
        # auto may solve directly unless the run's strategy planned to iterate
        self.direct = (self.use_maps and inner_solve in ("auto", "direct")
                       and not iterate)
        # "direct" maps every worker; auto every new one where the maps pay, and a kept
        # one once its solves have paid for it (_to_map)
        self.map_all = self.direct and inner_solve == "direct"
        self.map_new = self.direct and (self.map_all or self._maps_pay())
        kept = self.kept
        self.kept_paid = not kept or (self.session.map_kept
                                      and all(self._paid(name) for name in kept))

    def _stamp(self, worker):
        return any(self.problem.subdomains[name].stamp for name in self.parts[worker])

    def _shifts(self, worker):
        """Whether the worker's stamp shifts along x1 (partial slip): its map, affine in
        the data through the descent alone, would not carry the shift (robin.idp)."""
        return self.problem.scene.partial_slip and self._stamp(worker)

    def solve_directly(self):
        """From now on every worker gives its map, and the loop solves each contact set
        directly (what "direct" does): an iterated inner solve that failed falls back
        to it (orchestrate/run/solve.py)."""
        self.use_maps = self.direct = self.map_new = self.map_all = True

    def _maps_pay(self):
        """Whether probing the new workers' maps costs less than the Robin iterations a
        direct solve of each contact set saves (Settings.auto_direct_unknowns; the
        workers work side by side, a back-substitution costs about its worker's dofs)."""
        largest = max(self.dofs.values())
        limit = self.problem.settings.auto_direct_unknowns
        return all(self.unknowns[name] * self.dofs[name] <= limit * largest
                   for name, entry in self.entries.items() if entry.scenes == 1)

    def map_costs(self):
        """What _maps_pay weighs: every new worker's interface unknowns weighted by its
        dofs over the largest worker's, and the limit (the run's summary records it)."""
        largest = max(self.dofs.values())
        return {"auto_direct_unknowns": self.problem.settings.auto_direct_unknowns,
                "weighted_unknowns": {name: self.unknowns[name] * self.dofs[name] / largest
                                      for name, entry in self.entries.items()
                                      if entry.scenes == 1},
                "kept_workers": self.kept}

    def _specified(self, files):
        """Each worker's name once its script, arguments and key are known, from ``files``:
        write_inputs' dict, or written_inputs' (worker, its files) as they are written."""
        pairs = (((name, files[name]) for name in self.parts) if isinstance(files, Mapping)
                 else files)
        for name, its_files in pairs:
            names = self.parts[name]
            subdomain = self.problem.subdomains[name] if names == (name,) else None
            script = SCRIPTS[subdomain.kind if subdomain else "coated_base"]
            arguments = (worker_arguments(subdomain, its_files)
                         + geometry_arguments(self.problem.scene))
            if subdomain and subdomain.stamp:
                arguments += load_arguments(self.problem)
            self.specs[name] = (script, arguments)
            geometry, self.origins[name] = its_files["geometry"]
            numbers = [str(value) for flag, value in zip(arguments[::2], arguments[1::2])
                       if flag not in _FILE_ARGUMENTS]
            key = (script, geometry, tuple(arguments[::2]), tuple(numbers))
            # equal patches of one scene (a shell's files hold no place) get a worker each
            self.keys[name] = key + (sum(k[:-1] == key for k in self.keys.values()),)
            yield name

    def _start(self, names):
        """Take the workers of ``names``, each as soon as it comes (a new one assembles
        and factorises at once, while the next one's mesh is made); return their dofs."""
        timeout = self.problem.settings.worker_timeout
        try:
            for name in names:
                script, arguments = self.specs[name]
                self.entries[name] = self.session.take(name, script, arguments, self.keys[name],
                                                       self.origins[name], timeout)
            self.entries = {name: self.entries[name] for name in self.parts if name in self.entries}
            return {name: self.session.ready(entry) for name, entry in self.entries.items()}
        except OSError as error:
            self._drop()
            raise system_failure(error, "starting the FreeFEM workers") from None
        except BaseException:
            self._drop()
            raise

    @property
    def kept(self):
        """The subdomains whose worker an earlier scene started."""
        return [name for name, entry in self.entries.items() if entry.scenes > 1]

    def solve(self, data, names=None):
        """One independent solve per subdomain of ``names`` (None: every one).

        ``data``: {(interface index, side): (alpha, g)} (robin.robin_data). Returns the
        traces {(interface index, side): trace} of their sides, the timings (each
        worker's CPU seconds for the request, "back_" + name for its back-substitution
        alone, and "wait", the driver's wall time from the first request sent to the last
        reply) and the stamp's descent (None unless the stamp's body solved)."""
        start = time.perf_counter()
        names = list(self.entries) if names is None else names
        requests = self._requests(data, names)
        self._ask_maps(requests)
        for name in names:
            entry = self.entries[name]
            self.mapped[name] = (entry.robin_map is not None
                                 and entry.robin_map.serves(requests[name]))
            if not self.mapped[name]:
                entry.worker.send(Command.SOLVE, requests[name])
                entry.solves += 1
        self.last_requests.update(requests)
        traces, seconds, descent = {}, {}, None
        for name in names:
            entry = self.entries[name]
            if self.mapped[name]:
                reply = entry.robin_map.reply(requests[name])
            else:
                reply = entry.worker.receive(TraceReply.decode, self.shapes[name])
            traces.update(reply.by_side(self.sides[name]))
            seconds[name], seconds[f"back_{name}"] = reply.seconds, reply.back_seconds
            if self._stamp(name):
                descent, self.shift = reply.descent, reply.shift
        seconds["wait"] = time.perf_counter() - start
        return traces, seconds, descent

    def robin_maps(self, data):
        """Every subdomain's Robin map at the coefficients of ``data`` (robin.robin_data),
        asked now of the workers that have none; None unless every worker is to be
        mapped."""
        if not self.solves_directly:
            return None
        requests = self._requests(data)
        self._ask_maps(requests, again=True)
        maps = {name: entry.robin_map for name, entry in self.entries.items()}
        return maps if all(maps[name].serves(requests[name]) for name in maps) else None

    def request_maps(self, data):
        """Ask for the maps ``robin_maps(data)`` returns, and return at once: the workers
        probe while the caller works."""
        if self.solves_directly:
            self._send_map_requests(self._requests(data), again=True)

    def _requests(self, data, names=None):
        return {name: RobinRequest.of(self.sides[name], data)
                for name in (self.entries if names is None else names)}

    @property
    def solves_directly(self):
        """Whether every worker gives its map, so the loop solves each contact set
        directly."""
        return self.direct and all(self._to_map(name) and not self._shifts(name)
                                   for name, entry in self.entries.items())

    def _paid(self, name):
        """Whether the worker has a map, or its solves so far have cost what probing one
        would (KEPT_MAP_SOLVES_PER_UNKNOWN)."""
        entry = self.entries[name]
        return (entry.robin_map is not None
                or entry.solves >= KEPT_MAP_SOLVES_PER_UNKNOWN * self.unknowns[name])

    def _to_map(self, name):
        """Whether the worker has its map or is to give it. A run that may solve each
        contact set directly maps every worker or none, at the direct solve's
        coefficients, which are not the iterated loop's: every one with ``map_all``, else
        where the new ones' maps pay and every kept one had paid for its own when the run
        began (``kept_paid``); a map at other coefficients is probed again (robin_maps).
        A run that iterates maps a kept worker once it has paid, at the loop's
        coefficients: its map then stands in for its solves."""
        if self.map_all:
            return True
        if self.direct:
            return self.map_new and self.kept_paid
        entry = self.entries[name]
        return entry.robin_map is not None or (entry.scenes >= 2 and self.session.map_kept
                                               and self._paid(name))

    def _ask_maps(self, requests, again=False):
        """The maps of the workers _to_map names, all asked at once (``again``: also
        where a worker's map is at other coefficients)."""
        if not self.use_maps:
            return
        self._send_map_requests(requests, again)
        for name in list(self._pending):
            entry = self.entries[name]
            entry.robin_map = receive_map(entry.worker, self._pending.pop(name),
                                          self.components[name])

    def _send_map_requests(self, requests, again=False):
        for name in requests:
            entry = self.entries[name]
            wanted = entry.robin_map is None or (again
                                                 and not entry.robin_map.serves(requests[name]))
            if (wanted and name not in self._pending and self._to_map(name)
                    and not self._shifts(name)):
                send_map_request(entry.worker, requests[name])
                self._pending[name] = requests[name]

    def kill_probing(self):
        """Kill the workers still probing a map nobody will read (they would not hear a
        request to stop until their answer was read)."""
        for name in self._pending:
            self.entries[name].worker.kill()
        self._pending = {}

    def outputs(self):
        """Every worker's fields and reactions of its last solve: {name: BodyOutput or
        ShellOutput} (exchange.py), in b and E, a body's nodes at the scene's place (a kept
        worker's mesh may lie elsewhere); the indenter's and base's fields only with
        Settings.body_fields (a coating's answers need its fields). A worker whose last
        solve was its map's solves for real first (its fields), and its traces must agree
        with the map's."""
        real = [name for name, mapped in self.mapped.items() if mapped]
        for name in real:
            self.entries[name].worker.send(Command.SOLVE, self.last_requests[name])
        for name in real:
            entry = self.entries[name]
            reply = entry.worker.receive(TraceReply.decode, self.shapes[name])
            check(entry.worker.name, entry.robin_map, self.last_requests[name], reply)
        # before the requests: a worker that dies here has not answered (after them, a
        # small worker's reply may already sit whole in its FIFO)
        checkpoint("output")
        for name, entry in self.entries.items():
            entry.worker.send(Command.OUTPUT, self._output_request(self.parts[name][0]))
        outputs = {}
        for name, entry in self.entries.items():
            # a worker of several subdomains answers one request per subdomain, in turn;
            # each body's place its own (a kept worker's mesh may lie elsewhere)
            shifts = np.reshape(self.origins[name] - entry.origin, (-1, 2))
            for k, (part, (dx, dy)) in enumerate(zip(self.parts[name], shifts)):
                if k > 0:
                    entry.worker.send(Command.OUTPUT, self._output_request(part))
                if self.problem.subdomains[part].kind in ("body", "rigid"):
                    output = entry.worker.receive(BodyOutput.decode)
                    output = replace(output, columns={**output.columns,
                                                      "x1": output.columns["x1"] + dx,
                                                      "x2": output.columns["x2"] + dy})
                else:
                    output = entry.worker.receive(ShellOutput.decode,
                                                  shell_columns(self.problem.subdomains[part]))
                outputs[part] = output
        return outputs

    def _output_request(self, name):
        """A coating's answers need its fields; the indenter's and the base's only with
        Settings.body_fields."""
        return OutputRequest(self.problem.subdomains[name].coating
                             or self.problem.settings.body_fields)

    def _drop(self):
        """Stop this run's workers (a failed run leaves none to the next)."""
        self.kill_probing()
        for name in list(self.entries):
            self.session.drop(self.keys[name])
        self.entries = {}

    def __enter__(self):
        return self

    def __exit__(self, exc_type, *exc):
        if exc_type is None:
            self.session.keep_only({self.keys[name] for name in self.entries})
        else:
            self._drop()


class FreshProcessSubdomains(Subdomains):
    """The naive baseline: a fresh FreeFEM process per subdomain solve, which assembles
    and factorises its matrix every time. Kept to measure what persistent workers save
    (``--workers fresh``); the answers are the same."""

    def __init__(self, *arguments):
        super().__init__(*arguments)
        self._drop()
        self.last_data = {}          # the data of each subdomain's last solve

    def solve(self, data, names=None):
        start = time.perf_counter()
        names = list(self.specs) if names is None else names
        self._start(names)
        try:
            traces, seconds, descent = super().solve(data, names)
        finally:
            self._drop()
        self.last_data.update((name, data) for name in names)
        seconds["wait"] = time.perf_counter() - start
        return traces, seconds, descent

    def outputs(self):
        self._start(list(self.specs))
        try:
            for name, data in self.last_data.items():
                super().solve(data, [name])
            return super().outputs()
        finally:
            self._drop()


def start_subdomains(problem, settings, files, session, workers=None, iterate=False):
    """The workers of a run (``workers``: Strategy.workers; ``iterate``: its inner solve
    planned to iterate, whatever the settings asked): persistent (default) or a fresh
    process per solve."""
    if settings.workers == "fresh":
        return FreshProcessSubdomains(problem, files, session, workers, iterate)
    return Subdomains(problem, files, session, workers, iterate)
