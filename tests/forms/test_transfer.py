"""Interface transfer between the P2 bodies and the P4 shell, flat and curved.

Both sides of an interface read the same interface points and evaluate their traces
there. Data imposed on a worker with an overwhelming Robin coefficient must come back
as that worker's trace, with every convention intact: a contact trace is the
displacement along the side's outward normal, a bond trace is (tangential, normal) in
the face's basis, and a shell's w is one field on its top (contact) and its bottom fibre
(bond). The data are smooth fields both spaces pass unchanged at the interface points
(a P2 body takes its nodal values there; a P4 shell element matches three values per
element)."""

import numpy as np
import pytest

from orchestrate.mesh.discretization import discretize
from orchestrate.workers.exchange import Command, RobinRequest, TraceReply
from orchestrate.model.scene import Settings
from orchestrate.model.scene_file import SCENES_DIR, load_scene, paper_scene
from orchestrate.workers.session import Session
from orchestrate.workers.subdomains import Subdomains, write_inputs

STIFF = 1e12      # Robin coefficient: the data dominate every elastic stiffness


def _fields(s):
    """Tangential and normal displacement along the face; zero tangential on the axis,
    as the symmetry conditions require."""
    return 1e-3 * (0.3 * s - 0.2 * s ** 2), 1e-3 * (0.5 - 0.4 * s + 0.7 * s ** 2)


@pytest.fixture(scope="module", params=["paper", "roller"])
def workers(request, tmp_path_factory):
    workdir = str(tmp_path_factory.mktemp("transfer"))
    if request.param == "paper":
        scene = paper_scene(stamp=0.0)
    else:
        scene, _ = load_scene(SCENES_DIR / "roller.toml")
    problem = discretize(scene, Settings())
    with Session() as session:
        subdomains = Subdomains(problem, write_inputs(problem, workdir), session)
        yield problem, subdomains


def _send(problem, subdomains, name, data):
    """One solve of one worker with the given data on each of its sides (None: no
    Robin term there); returns its traces by (interface index, side)."""
    sides = subdomains.sides[name]
    full = {}
    for i, side in sides:
        interface = problem.interfaces[i]
        given = data.get((i, side))
        if given is None:
            full[i, side] = (np.zeros(interface.size), np.zeros((interface.components, interface.size)))
        else:
            full[i, side] = (np.full(interface.size, STIFF), np.atleast_2d(given))
    worker = subdomains.entries[name].worker
    worker.send(Command.SOLVE, RobinRequest.of(sides, full))
    return worker.receive(TraceReply.decode, subdomains.shapes[name]).by_side(sides)


def _close(received, expected):
    return np.max(np.abs(received - expected)) < 1e-9 * np.max(np.abs(expected))


def test_the_bases_bond_trace_passes_data_unchanged(workers):
    problem, subdomains = workers
    i = problem.interfaces.index(problem.bonds[0])
    tangential, normal = _fields(problem.interfaces[i].s)
    traces = _send(problem, subdomains, "base", {(i, 1): [tangential, normal]})
    assert _close(traces[i, 1][0], tangential) and _close(traces[i, 1][1], normal)


def test_the_indenters_normal_trace_passes_data_unchanged(workers):
    problem, subdomains = workers
    data = {}
    for contact in problem.contacts:
        i = problem.interfaces.index(contact)
        data[i, 0] = _fields(contact.s)[1]
    traces = _send(problem, subdomains, "indenter", data)
    for key, values in data.items():
        assert _close(traces[key], values)


def test_the_shells_traces_pass_data_unchanged_and_share_w(workers):
    problem, subdomains = workers
    bond = problem.interfaces.index(problem.bonds[0])
    contact = next(problem.interfaces.index(c) for c in problem.contacts
                   if c.sides[1].subdomain == "coating1")
    tangential, normal = _fields(problem.interfaces[bond].s)
    traces = _send(problem, subdomains, "coating1", {(bond, 0): [tangential, normal]})
    assert _close(traces[bond, 0][0], tangential) and _close(traces[bond, 0][1], normal)
    # the top moves with the bottom fibre along the normal: w is one field
    assert _close(traces[contact, 1], normal)
