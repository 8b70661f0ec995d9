"""The answers of a run (orchestrate/run/answers.py): peel, compression and shear on the bond,
the coating's largest stresses, each with its position, the values at patch ends apart.

Checked on two figure scenes (paper h2 = b/8, E2 = 5E, both coating models) against
independent computations: the shell's forces against the equilibrium of the bond
tractions that the Robin loop exchanged (a different path through the code); the 2D
coating's von Mises maximum and its bond compression against stresses computed here from
the coating's P2 displacements alone (Hooke's law on each triangle); and the reported
extremes against the files they summarise."""

import json

import numpy as np
import pandas as pd
import pytest

from orchestrate.run import answers
from orchestrate.model.scene import Settings
from orchestrate.model.scene_file import paper_scene
from orchestrate.run.solve import solve

H2 = 0.125


@pytest.fixture(scope="module")
def shell_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("answers") / "shell"
    scene = paper_scene(h2=H2, E2=5.0, model="shell")
    return scene, solve(scene, Settings(), out), out


def _tail_integral(x, y):
    """int_x^end y, by trapezoids, at every x."""
    pieces = 0.5 * (y[1:] + y[:-1]) * np.diff(x)
    return np.concatenate([np.cumsum(pieces[::-1])[::-1], [0.0]])


def test_the_shells_membrane_force_balances_the_bond_shear(shell_run):
    """-T11' = p1, the bond's shear on the coating, with T11 = 0 at the free end: T11(x1)
    = -int_x1^end sigma_t (sigma_t: the traction on the base). T11 comes from the shell's
    strains (its P4/P3 fields differentiated), sigma_t from the Robin traces at the bond's
    nodes; they agree to their discretisation (measured: 2.2 % of the largest T11)."""
    _, _, out = shell_run
    fields = pd.read_csv(out / "coating1_fields.csv")
    bond = pd.read_csv(out / "interface.csv")
    x, shear = bond.x1.to_numpy(), bond.sigma_t.to_numpy()
    T11 = np.interp(x, fields.x1, fields.T11)
    balance = -_tail_integral(x, shear)
    assert np.max(np.abs(T11 - balance)) < 0.03 * np.max(np.abs(T11))


def test_the_fibre_stresses_are_the_extremes_of_the_shells_forces(shell_run):
    """top/bottom = T11/h -+ 6 M11/h^2 ... recomputed from the fields file; a stiff
    coating pressed at its middle bends with its top in compression there, more than its
    bottom, and the largest compression is at the top, at the axis."""
    scene, summary, out = shell_run
    fields = pd.read_csv(out / "coating1_fields.csv")
    found = summary["answers"]["coatings"]["coating1"]
    T11, M11 = fields.T11.to_numpy(), fields.M11.to_numpy()
    top, bottom = T11 / H2 + 6 * M11 / H2 ** 2, T11 / H2 - 6 * M11 / H2 ** 2
    away = ~answers.near_patch_ends(scene, fields.x1.to_numpy())
    assert found["top_compression"]["value"] == pytest.approx(top[away].min(), rel=1e-12)
    assert found["bottom_compression"]["value"] == pytest.approx(bottom[away].min(), rel=1e-12)
    assert found["top_compression"]["x1"] < 0.1                  # under the indenter
    assert found["top_compression"]["value"] < found["bottom_compression"]["value"] < 0
    assert found["mean_shear"]["value"] == pytest.approx(
        np.max(np.abs(fields.T13[away])) / H2, rel=1e-12)


def test_the_bond_answers_and_the_ends_apart(shell_run):
    """The bond under the contact is compressed (no peel away from the ends); the free
    end at x1 = 2 b pulls: its tension is reported apart, as mesh-dependent."""
    scene, summary, out = shell_run
    bond = pd.read_csv(out / "interface.csv")
    found = summary["answers"]["bonds"]["bond-coating1"]
    away = ~answers.near_patch_ends(scene, bond.x1.to_numpy())
    assert found["peel"] is None and bond.sigma_n[away].max() <= 0
    assert found["compression"]["value"] == bond.sigma_n[away].min()
    assert found["shear"]["value"] == np.abs(bond.sigma_t[away]).max()
    ends = found["at_patch_ends"]
    assert ends["mesh_dependent"] and ends["peel"]["value"] > 0
    assert abs(ends["peel"]["x1"] - 2.0) <= answers.END_ZONE * H2
    peak = summary["answers"]["contact"]["peak_pressure"]
    assert peak["value"] == pytest.approx(-summary["peak_contact_stress"], rel=1e-12)


def _element_stresses(nodes, cells, E, nu):
    """{node: [(sigma_eq, s22) from each triangle at that vertex]}: the P2 displacement
    of each triangle (its six nodes) differentiated at its vertices, plane-strain Hooke's
    law; independent of FreeFEM's stresses and of their recovery."""
    x, y, u1, u2 = (nodes[k].to_numpy() for k in ("x1", "x2", "u1", "u2"))
    lam, mu = E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))
    at = {}
    for cell in cells:
        X, Y = x[cell] - x[cell].mean(), y[cell] - y[cell].mean()
        quadratic = np.column_stack([np.ones(6), X, Y, X * X, X * Y, Y * Y])
        a1, a2 = np.linalg.solve(quadratic, u1[cell]), np.linalg.solve(quadratic, u2[cell])
        X, Y, zero, one = X[:3], Y[:3], np.zeros(3), np.ones(3)
        d_dx = np.column_stack([zero, one, zero, 2 * X, Y, zero])
        d_dy = np.column_stack([zero, zero, one, zero, X, 2 * Y])
        e11, e22, e12 = d_dx @ a1, d_dy @ a2, 0.5 * (d_dy @ a1 + d_dx @ a2)
        s11, s22 = lam * (e11 + e22) + 2 * mu * e11, lam * (e11 + e22) + 2 * mu * e22
        s33, s12 = lam * (e11 + e22), 2 * mu * e12
        von_mises = np.sqrt(0.5 * ((s11 - s22) ** 2 + (s22 - s33) ** 2 + (s33 - s11) ** 2)
                            + 3 * s12 ** 2)
        for k, node in enumerate(cell[:3]):
            at.setdefault(node, []).append((von_mises[k], s22[k]))
    return at


def test_the_2d_coatings_answers_match_stresses_from_its_displacements(coating_2d_run):
    """Averaged over the triangles at each vertex, away from the patch's end: the largest
    von Mises stress, where it is (measured: the same node, the same value to 1e-14: at
    that corner one triangle), and the bond's largest compression against the coating's
    s22 on its bottom face (the traction's continuity; measured 0.6 % apart, the bond's
    nodal traction against a vertex average)."""
    scene, out = coating_2d_run
    summary = json.loads((out / "summary.json").read_text())
    patch = scene.coatings[0]
    nodes = pd.read_csv(out / "coating1.csv")
    at = _element_stresses(nodes, pd.read_csv(out / "coating1_cells.csv").to_numpy(),
                           patch.E, patch.nu)
    x1 = nodes.x1.to_numpy()
    away = [n for n in at if not answers.near_patch_ends(scene, x1[[n]])[0]]
    mean = {n: np.mean(at[n], axis=0) for n in away}
    top = max(away, key=lambda n: mean[n][0])
    found = summary["answers"]["coatings"]["coating1"]["von_mises"]
    assert found["value"] == pytest.approx(mean[top][0], rel=0.01)
    assert (found["x1"], found["x2"]) == pytest.approx((x1[top], nodes.x2[top]), abs=1e-12)
    bottom = [n for n in away if abs(nodes.x2[n] - nodes.x2.min()) < 1e-12]
    squeezed = min(mean[n][1] for n in bottom)
    compression = summary["answers"]["bonds"]["bond-coating1"]["compression"]["value"]
    assert compression == pytest.approx(squeezed, rel=0.02)


def test_a_body_of_revolution_says_its_positions_as_r():
    """The command line's answers and the plot's marks name a position along the face r
    on a body of revolution (its axis is r = 0), x1 in plane strain."""
    from orchestrate.plots.plot import _answer_marks
    from orchestrate.run.answers import describe
    answers = {"contact": {"peak_pressure": {"value": 3825.0, "x1": 0.0, "x2": 1.0}},
               "bonds": {}, "coatings": {}}
    units = {"stress": "MPa", "length": "mm"}
    assert describe(answers, units, axisymmetric=True) == [
        "contact: peak pressure 3825 MPa at r = 0 mm"]
    assert describe(answers, units) == ["contact: peak pressure 3825 MPa at x1 = 0 mm"]
    (mark,) = _answer_marks({"answers": answers}, None, units, axisymmetric=True)
    assert mark[3] == "peak pressure 3825 MPa at $r$ = 0 mm"
