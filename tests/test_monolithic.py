"""The Robin loop against a monolithic solve of the same discrete penalised problem.

freefem/monolithic.edp assembles Omega1, the shell and Omega3 in one matrix with the
same forms and the same interface quadrature as the workers and iterates the contact
set to a fixed point. Run to a tight tolerance, the domain decomposition must give the
same interface displacements and stresses to 1e-6 relative: the test that the Robin
data, the trace operators and the active-set logic are right. Both loops are checked:
the accelerated active-set loop at the default penalty, and the paper's own loop
(gamma = 1/theta, fixed relaxation) at a penalty soft enough for it to converge in a
few hundred iterations (at theta = 1e-3 it would need ~10^5, README)."""

import numpy as np
import pandas as pd
import pytest

from orchestrate.monolithic import monolithic_interface
from orchestrate.scene import Scene, Settings
from orchestrate.solve import solve

TRACES = ("upper_n", "coating_n", "coating_u1", "coating_u2", "lower_u1", "lower_u2")


def _monolithic_columns(result):
    return {"upper_n": result["upper_n"], "coating_n": result["coating_n"],
            "coating_u1": result["coating_bond"][0], "coating_u2": result["coating_bond"][1],
            "lower_u1": result["lower_bond"][0], "lower_u2": result["lower_bond"][1]}


def _relative_difference(a, b):
    return float(np.max(np.abs(a - b)) / np.max(np.abs(b)))


@pytest.mark.parametrize("settings", [
    Settings(eps_u=1e-10),
    Settings(method="paper", theta=1.0, eps_u=1e-10, max_iterations=2000),
], ids=["active-set loop, theta 1e-3", "paper loop, theta 1"])
def test_robin_loop_equals_monolithic_solve(settings, tmp_path):
    scene = Scene()
    summary = solve(scene, settings, tmp_path)
    assert summary["converged"]
    ddm = pd.read_csv(tmp_path / "traces.csv")
    contact = pd.read_csv(tmp_path / "contact.csv")
    interface = pd.read_csv(tmp_path / "interface.csv")
    reference = monolithic_interface(scene, settings)
    np.testing.assert_allclose(ddm["x1"], reference["x1"], rtol=0, atol=1e-14)
    for name, values in _monolithic_columns(reference).items():
        assert _relative_difference(ddm[name].to_numpy(), values) < 1e-6, name
    assert _relative_difference(contact["sigma_n"].to_numpy(), reference["sigma_12n"]) < 1e-6
    assert _relative_difference(interface["sigma_n"].to_numpy(), reference["sigma_23n"]) < 1e-6
