"""Interface transfer between the P2 bodies and the P4 shell.

Both sides of an interface read the same interface points and evaluate their traces
there. A field that both spaces represent exactly (a quadratic along the interface)
must pass unchanged: imposed on a worker as Robin data with an overwhelming Robin
coefficient, it comes back as that worker's trace, with the sign conventions of every
trace (outward normals on S12, global components on S23) and, for the shell, the same
w on its top (S21) and its bottom fibre (S23)."""

import numpy as np
import pytest

from orchestrate.scene import Scene, Settings
from orchestrate.subdomains import Subdomains, write_inputs
from orchestrate.worker import CMD_SOLVE

STIFF = 1e12      # Robin coefficient: the data dominate every elastic stiffness


def _quadratics(x):
    """(u1, u2) along the interface; u1(0) = 0 as the symmetry conditions require."""
    return 1e-3 * (0.3 * x - 0.2 * x ** 2), 1e-3 * (0.5 - 0.4 * x + 0.7 * x ** 2)


@pytest.fixture(scope="module")
def workers(tmp_path_factory):
    workdir = str(tmp_path_factory.mktemp("transfer"))
    scene = Scene(stamp=0.0)
    files, contact, bond = write_inputs(scene, Settings(), workdir)
    subdomains = Subdomains(scene, Settings(), files, workdir, workdir)
    yield subdomains.workers, contact.x
    subdomains.close()


def _close(received, expected):
    return np.max(np.abs(received - expected)) < 1e-9 * np.max(np.abs(expected))


def test_omega3_trace_passes_a_quadratic_unchanged(workers):
    lower, x = workers[0]["lower"], workers[1]
    u1, u2 = _quadratics(x)
    alpha = np.full(len(x), STIFF)
    trace1, trace2, _ = lower.request(CMD_SOLVE, [alpha, u1, u2], 3)
    assert _close(trace1, u1) and _close(trace2, u2)


def test_omega1_normal_trace_passes_a_quadratic_unchanged(workers):
    upper, x = workers[0]["upper"], workers[1]
    _, u2 = _quadratics(x)
    normal, _ = upper.request(CMD_SOLVE, [np.full(len(x), STIFF), u2], 2)
    assert _close(normal, u2)


def test_shell_traces_pass_a_quadratic_unchanged(workers):
    coating, x = workers[0]["coating"], workers[1]
    u1, u2 = _quadratics(x)
    no_contact = np.zeros(len(x))
    w, fibre1, fibre2, _ = coating.request(
        CMD_SOLVE, [no_contact, no_contact, np.full(len(x), STIFF), u1, u2], 4)
    assert _close(fibre1, u1) and _close(fibre2, u2)
    assert _close(w, u2)          # the top moves with the bottom fibre: w is one field
