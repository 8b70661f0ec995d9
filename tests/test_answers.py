"""The answers of a run (orchestrate/answers.py): peel, compression and shear on the bond,
the coating's largest stresses, each with its position, the values at patch ends apart.

Checked on two figure scenes (paper h2 = b/8, E2 = 5E, both coating models) against
independent computations: the shell's forces against the equilibrium of the bond
tractions that the Robin loop exchanged (a different path through the code), and the
reported extremes against the files they summarise."""

import numpy as np
import pandas as pd
import pytest

from orchestrate import answers
from orchestrate.scene import Settings
from orchestrate.scene_file import paper_scene
from orchestrate.solve import solve

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
