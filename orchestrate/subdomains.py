"""The three subdomain workers of a run and the files they read.

Omega1 and Omega3 run freefem/body.edp; the coating runs freefem/shell.edp (shell
model) or freefem/body.edp on its own mesh (2D model). Within a Robin iteration the
three solves are independent: every request is written before any reply is read, so
the workers compute at the same time.
"""

from dataclasses import dataclass
import os
import time

import numpy as np

from .interface import nodal_quadrature, write_quadrature
from .mesh import body_mesh, coating_mesh, interface_elements, interface_nodes, write_medit
from .worker import CMD_OUTPUT, CMD_SOLVE, Worker


@dataclass(frozen=True)
class RunFiles:
    """Inputs written once per run into a private working folder."""
    upper_mesh: str
    lower_mesh: str
    coating_mesh: str     # 2D coating model only
    shell_nodes: str
    contact_points: str
    bond_points: str


def write_inputs(scene, settings, workdir):
    """Meshes, shell nodes and the interface quadrature; returns paths and quadratures."""
    nodes = interface_nodes(scene.coating_length, interface_elements(scene, settings))
    files = RunFiles(*(os.path.join(workdir, name) for name in (
        "omega1.mesh", "omega3.mesh", "coating.mesh", "shell_nodes.txt", "s12.txt", "s23.txt")))
    write_medit(body_mesh(scene, settings, "upper"), files.upper_mesh)
    write_medit(body_mesh(scene, settings, "lower"), files.lower_mesh)
    if settings.model == "elastic":
        write_medit(coating_mesh(scene, settings), files.coating_mesh)
    with open(files.shell_nodes, "w") as out:
        out.write(f"{len(nodes)}\n" + "\n".join(map(repr, nodes.tolist())) + "\n")
    contact = nodal_quadrature(nodes, scene.gap)
    bond = nodal_quadrature(nodes)
    write_quadrature(contact, files.contact_points)
    write_quadrature(bond, files.bond_points)
    return files, contact, bond


class Subdomains:
    """Omega1, the coating and Omega3 as persistent FreeFEM workers."""

    def __init__(self, scene, settings, files, workdir, output_dir):
        self.workdir = workdir
        self.workers = {}
        self.specs = {
            "upper": ("omega1", "body.edp", [
                "-mesh", files.upper_mesh, "-E", scene.E1, "-nu", scene.nu1,
                "-stamp", scene.stamp, "-contact", files.contact_points,
                "-output", os.path.join(output_dir, "omega1")]),
            "coating": self._coating_spec(scene, settings, files, output_dir),
            "lower": ("omega3", "body.edp", [
                "-mesh", files.lower_mesh, "-E", scene.E3, "-nu", scene.nu3,
                "-bond", files.bond_points, "-output", os.path.join(output_dir, "omega3")]),
        }
        self.dofs = self._start()

    @staticmethod
    def _coating_spec(scene, settings, files, output_dir):
        output = os.path.join(output_dir, "coating")
        if settings.model == "elastic":     # (25): the coating as a P2 body, Robin on both faces
            return ("coating", "body.edp", [
                "-mesh", files.coating_mesh, "-E", scene.E2, "-nu", scene.nu2,
                "-contact", files.contact_points, "-bond", files.bond_points,
                "-output", output])
        return ("coating", "shell.edp", [
            "-nodes", files.shell_nodes, "-E", scene.E2, "-nu", scene.nu2, "-h2", scene.h2,
            "-kshear", scene.shear_factor, "-contact", files.contact_points,
            "-bond", files.bond_points, "-output", output])

    def _start(self):
        """Start every worker (they assemble and factorise at once); return their dofs."""
        try:
            for key, (name, script, arguments) in self.specs.items():
                self.workers[key] = Worker(name, script, arguments, self.workdir)
            return {key: worker.wait_ready() for key, worker in self.workers.items()}
        except BaseException:
            self.close()
            raise

    def solve(self, data):
        """One independent solve per subdomain.

        ``data`` maps "upper", "coating", "lower" to the arrays of the request: Robin
        coefficient and data per interface. Returns the traces
        ``(upper_n, coating_n, coating_bond, lower_bond)`` and the timings: each worker's
        CPU seconds for the request and ("back_" + name) for its back-substitution alone,
        and "wait", the driver's wall time from the first request sent to the last reply."""
        start = time.perf_counter()
        for name, worker in self.workers.items():
            worker.send(CMD_SOLVE, data[name])
        upper_n, upper_seconds = self.workers["upper"].receive_arrays(2)
        coating_n, coating_1, coating_2, coating_seconds = self.workers["coating"].receive_arrays(4)
        lower_1, lower_2, lower_seconds = self.workers["lower"].receive_arrays(3)
        seconds = {"upper": upper_seconds[0], "coating": coating_seconds[0],
                   "lower": lower_seconds[0], "wait": time.perf_counter() - start,
                   "back_upper": upper_seconds[1], "back_coating": coating_seconds[1],
                   "back_lower": lower_seconds[1]}
        return (upper_n, coating_n, np.array([coating_1, coating_2]),
                np.array([lower_1, lower_2])), seconds

    def write_outputs(self):
        """Ask every worker to write its fields (VTU, CSV) and reactions."""
        for worker in self.workers.values():
            worker.send(CMD_OUTPUT)
        for worker in self.workers.values():
            worker.receive_arrays(0)

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
            traces, seconds = super().solve(data)
        finally:
            self.close()
        self.last_data = data
        seconds["wait"] = time.perf_counter() - start
        return traces, seconds

    def write_outputs(self):
        self._start()
        try:
            super().solve(self.last_data)
            super().write_outputs()
        finally:
            self.close()


def start_subdomains(scene, settings, files, workdir, output_dir):
    """The workers of a run: persistent (default) or a fresh process per solve."""
    kind = FreshProcessSubdomains if settings.workers == "fresh" else Subdomains
    return kind(scene, settings, files, workdir, output_dir)
