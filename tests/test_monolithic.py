"""The Robin loop against a monolithic solve of the same discrete penalised problem.

freefem/monolithic.edp assembles Omega1, the coating and Omega3 in one matrix with the
same forms and the same interface quadrature as the workers and iterates the contact
set to a fixed point. Run to a tight tolerance, the domain decomposition must give the
same interface displacements and stresses to 1e-6 relative: the test that the Robin
data, the trace operators and the active-set logic are right, for both coating models
(shell, and 2D elasticity with Robin terms on both its faces). Both loops are checked:
the accelerated active-set loop at the default penalty, and the paper's own loop
(gamma = 1/theta, fixed relaxation) at a penalty soft enough for it to converge in a
few hundred iterations (at theta = 1e-3 it would need ~10^5, README)."""

import numpy as np
import pandas as pd
import pytest

from orchestrate.claims import distance
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


@pytest.mark.parametrize("scene, settings", [
    (Scene(), Settings(eps_u=1e-10)),
    (Scene(), Settings(method="paper", theta=1.0, eps_u=1e-10, max_iterations=2000)),
    (Scene(), Settings(model="elastic", eps_u=1e-10)),
    (Scene(h2=0.5, E2=5.0), Settings(model="elastic", eps_u=1e-10)),
], ids=["shell, active-set loop", "shell, paper loop, theta 1", "2D coating, h2 b/8",
        "2D coating, h2 b/2, E2 5E"])
def test_robin_loop_equals_monolithic_solve(scene, settings, tmp_path):
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


def test_2d_coating_of_the_bodies_modulus_is_one_body_with_them():
    """With E2 = E the 2D coating and Omega3 are one material: the contact stress must
    match the scene without coating (Omega3 grown by h2) within discretisation error.
    Measured as relative L2 distances between contact-stress curves: on the paper's mesh
    the coated-uncoated distance (0.27 %) is of the size of that mesh's discretisation
    error, estimated by the change to the next mesh (0.20 %), and it halves on the next
    mesh (0.13 %)."""
    scene = Scene(h2=0.125, E2=1.0)
    curves = {}
    for level in (1, 2):
        settings = Settings(model="elastic", mesh_level=level)
        for coated in (True, False):
            result = monolithic_interface(scene, settings, coated=coated)
            curves[level, coated] = (result["x1"], result["sigma_12n"])
    gap = {level: distance(curves[level, True], curves[level, False]) for level in (1, 2)}
    x_coarse, coarse = curves[1, False]
    x_fine, fine = curves[2, False]
    mesh_change = distance((x_coarse, np.interp(x_coarse, x_fine, fine)), (x_coarse, coarse))
    assert gap[1] < 1.5 * mesh_change
    assert gap[2] < 0.6 * gap[1]
