"""The coarse level of a fine run (two levels, orchestrate/ddm/coarse.py): the scene at
mesh level 1 solved by persistent workers of its own, which start with the run and probe
their Robin maps while the fine run meshes and starts its own; the maps read, they stop.
"""

import contextlib
import dataclasses

import numpy as np

from orchestrate.ddm.coarse import CoarseCorrection, coarse_element_size, coarse_laws, paired
from orchestrate.ddm.interface_system import InterfaceSystem
from orchestrate.ddm.robin import robin_data
from orchestrate.ddm.state import StateLayout
from orchestrate.files.folders import WorkFolder
from orchestrate.mesh.discretization import discretize
from orchestrate.workers.session import Session
from orchestrate.workers.subdomains import Subdomains, write_inputs


class CoarseLevel:
    """The coarse level of a fine run's ``problem``: the scene at mesh level 1 (on level
    1 itself, with interface elements twice as long: coarse_element_size) with the fine
    penalty and Robin parameter. Its workers start, and are asked for their maps, at
    once; they probe while the fine run meshes and starts its own, and ``correction``
    collects the maps and stops them. ``paired``: whether the two levels' interfaces
    pair up along s (else there is no correction)."""

    def __init__(self, problem):
        settings = problem.settings
        # probed and solved directly by persistent workers of its own, whatever the fine
        # run's workers (a fresh process per solve keeps no factorisation to probe)
        coarse_settings = dataclasses.replace(settings, mesh_level=1, theta=settings.theta,
                                              robin=settings.robin_parameter,
                                              inner_solve="direct", workers="persistent",
                                              element_size=coarse_element_size(settings))
        self.fine_layout = StateLayout(problem.interfaces)
        self.coarse = discretize(problem.scene, coarse_settings)
        self.layout = StateLayout(self.coarse.interfaces)
        self.paired = paired(problem.interfaces, self.coarse.interfaces)
        self._resources = contextlib.ExitStack()
        self.workers = None
        if not self.paired:
            return
        try:
            workdir = self._resources.enter_context(WorkFolder())
            session = self._resources.enter_context(Session())
            files = write_inputs(self.coarse, workdir)
            self.workers = self._resources.enter_context(
                Subdomains(self.coarse, files, session, workdir))
            self.workers.request_maps(self._data())
        except BaseException:
            self.close()
            raise

    def _data(self):
        """The Robin data of an empty contact set: the maps' coefficients."""
        layout = self.layout
        return robin_data(layout, layout.zeros(),
                          coarse_laws(self.coarse, layout, np.zeros(layout.gap.size)))

    def correction(self):
        """The CoarseCorrection from the probed maps (None unless ``paired``); the coarse
        workers stop."""
        if not self.paired:
            return None
        try:
            maps = self.workers.robin_maps(self._data())
        finally:
            self.close()
        sides = {name: self.coarse.sides_of(name) for name in maps}
        return CoarseCorrection(self.fine_layout, self.coarse, self.layout,
                                InterfaceSystem(self.layout, sides, maps))

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
