"""The coarse level of a fine run (two levels, orchestrate/ddm/coarse.py): the scene at
mesh level 1 solved by persistent workers of its own, which start with the run and probe
their Robin maps while the fine run meshes and starts its own; the maps read, they stop.
"""

import contextlib

import numpy as np

from orchestrate.ddm.coarse import CoarseCorrection, coarse_laws, coarse_problem
from orchestrate.ddm.interface_system import InterfaceSystem
from orchestrate.ddm.robin import robin_data
from orchestrate.ddm.state import StateLayout
from orchestrate.files.folders import WorkFolder
from orchestrate.workers.session import Session
from orchestrate.workers.subdomains import Subdomains, written_inputs


class CoarseLevel:
    """The coarse level of a fine run's ``problem``: ``coarse``, the problem the run's
    plan made of its scene at mesh level 1 (on level 1 itself, with longer interface
    elements; a thin 2D coating's cells the face's: coarse.coarse_problem), with the
    fine penalty and Robin parameter, whose interfaces pair up with the fine ones (the
    strategy has two levels only then);
    without it, made here of the problem's settings. Its workers start, and are asked
    for their maps, at once; they probe while the fine run meshes and starts its own,
    and ``correction`` collects the maps and stops them. ``newton_steps``: the coarse
    contact problem's at most (the strategy's coarse_newton_steps; without it, the
    problem's settings')."""

    def __init__(self, problem, coarse=None, newton_steps=None):
        self.fine_layout = StateLayout(problem.interfaces)
        self.coarse = (coarse if coarse is not None
                       else coarse_problem(problem.scene, problem.settings))
        self.layout = StateLayout(self.coarse.interfaces)
        self.newton_steps = (newton_steps if newton_steps is not None
                             else problem.settings.coarse_newton_steps)
        self._resources = contextlib.ExitStack()
        self.workers = None
        try:
            workdir = self._resources.enter_context(WorkFolder())
            session = self._resources.enter_context(Session())
            files = written_inputs(self.coarse, workdir)     # each worker starts once written
            self.workers = self._resources.enter_context(
                Subdomains(self.coarse, files, session))
            self.workers.request_maps(self._data())
        except BaseException:
            self.close()
            raise

    def _data(self):
        """The Robin data of an empty contact set: the maps' coefficients."""
        layout = self.layout
        return robin_data(layout, layout.zeros(),
                          coarse_laws(self.coarse, layout, np.zeros(layout.gap.size)))

    def correction(self, inside=()):
        """The CoarseCorrection from the probed maps, for a fine loop that solves the
        bonds ``inside`` in a worker (Strategy.bonds_inside); the coarse workers stop."""
        try:
            maps = self.workers.robin_maps(self._data())
        finally:
            self.close()
        sides = {name: self.coarse.sides_of(name) for name in maps}
        return CoarseCorrection(self.fine_layout, self.coarse, self.layout,
                                InterfaceSystem(self.layout, sides, maps), self.newton_steps,
                                inside)

    def close(self):
        """Stop the coarse workers (those still probing are killed) and remove their
        folders."""
        if self.workers is not None:
            self.workers.kill_probing()
        self._resources.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
