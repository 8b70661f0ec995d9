"""Two ways of posing one problem give one answer (to 1e-6 relative, at eps_u = 1e-10):

- a symmetric scene solved as a full model (no symmetry condition, every patch and the
  contact zone mirrored, mirror-symmetric meshes) equals its half model on x1 >= 0:
  the full model's own conditions (no symmetry, patches across the axis, free ends on
  both sides) are right;
- a force-loaded solve and a displacement-loaded solve at the descent it found: the
  stamp's descent as an unknown is solved right;
- every modulus and the force times 1e4 (a scene in MPa rather than in units of E): the
  same iterations, the same displacements, stresses times 1e4 (to 1e-9): nothing in the
  loop (penalty, Robin parameter, stopping and divergence tests) depends on the unit.
"""

from dataclasses import replace

import numpy as np
import pandas as pd
import pytest

from orchestrate.model.scene import Settings
from orchestrate.model.scene_file import SCENES_DIR, apply_overrides, load_scene, paper_scene
from orchestrate.run.solve import solve
from tests.conftest import full_model

pytestmark = pytest.mark.slow       # not in the everyday subset (make test-fast)

TIGHT = Settings(eps_u=1e-10)


def _right_half(table):
    return table[table.x1 >= 0].reset_index(drop=True)


def _close(a, b):
    return float(np.max(np.abs(a - b)) / np.max(np.abs(b))) < 1e-6


@pytest.mark.parametrize("scene", [
    paper_scene(),
    load_scene(SCENES_DIR / "discrete.toml")[0],
], ids=["paper, displacement", "discrete coating, force"])
def test_a_full_model_equals_its_half_model(scene, tmp_path):
    half = solve(scene, TIGHT, tmp_path / "half")
    full = solve(full_model(scene), TIGHT, tmp_path / "full")
    assert abs(full["total_force"] / half["total_force"] - 1) < 1e-6
    assert abs(full["contact_half_width"] / half["contact_half_width"] - 1) < 1e-6
    for name in ("contact.csv", "interface.csv"):
        a = _right_half(pd.read_csv(tmp_path / "full" / name))
        b = pd.read_csv(tmp_path / "half" / name)
        np.testing.assert_array_equal(a.x1, b.x1)
        assert _close(a.sigma_n.to_numpy(), b.sigma_n.to_numpy()), name
        if name == "interface.csv":
            assert _close(a.sigma_t.to_numpy(), b.sigma_t.to_numpy())


@pytest.mark.parametrize("model", ["shell", "elastic"])
def test_a_contact_zone_ending_inside_a_patch_is_the_patch_untouched_beyond(tmp_path, model):
    """A patch whose top is a contact only on part of it (contact_zone ends inside it):
    where the contact does not reach that end, the answer is the one with the whole top
    a contact (the points beyond stay out of contact), on the same base, patch and
    indenter; only the indenter's face beyond the zone is meshed as a free face rather
    than at the interface's points, whose mesh differs there (measured, both models:
    1.4e-5 in the peak pressure, 7e-6 in the descent, 2.1e-4 of the largest bond shear,
    the force exact)."""
    scene, _ = load_scene(SCENES_DIR / "cylinder.toml")
    scene = apply_overrides(scene, {"coating[1].end": 3.0, "coating[1].model": model})
    whole = solve(scene, TIGHT, tmp_path / "whole")
    part = solve(replace(scene, contact_zone=(0.0, 1.5)), TIGHT, tmp_path / "part")
    assert whole["contact_half_width"] < 1.2           # the contact stops short of 1.5
    for key in ("peak_contact_stress", "peak_interface_stress", "descent"):
        assert part[key] == pytest.approx(whole[key], rel=5e-5), key
    assert part["total_force"] == pytest.approx(whole["total_force"], rel=1e-10)
    bond = {name: pd.read_csv(tmp_path / name / "interface.csv") for name in ("whole", "part")}
    np.testing.assert_array_equal(bond["part"].x1, bond["whole"].x1)
    assert float(np.max(np.abs(bond["part"].sigma_t - bond["whole"].sigma_t))
                 / np.max(np.abs(bond["whole"].sigma_t))) < 5e-4
    contact = pd.read_csv(tmp_path / "part" / "contact.csv")
    assert contact.x1.max() <= 1.5 + 1e-12               # no contact point beyond the zone


def test_a_force_load_and_the_displacement_it_found_agree(tmp_path):
    """One discrete problem: the interface elements given, not sized to each load's a
    priori contact (the estimates from a force and from a descent differ slightly)."""
    scene, _ = load_scene(SCENES_DIR / "cylinder.toml")
    settings = replace(TIGHT, element_size=Settings().element_length)
    by_force = solve(scene, settings, tmp_path / "force")
    moved = apply_overrides(scene, {"load.displacement": by_force["descent"]})
    by_displacement = solve(moved, settings, tmp_path / "displacement")
    assert abs(by_displacement["total_force"] / scene.load.force - 1) < 1e-6
    for name in ("contact.csv", "interface.csv", "traces.csv"):
        a = pd.read_csv(tmp_path / "force" / name)
        b = pd.read_csv(tmp_path / "displacement" / name)
        for column in ("sigma_n", "a_n", "b_n"):
            if column in a:
                assert _close(a[column].to_numpy(), b[column].to_numpy()), (name, column)


def test_moduli_in_other_units_give_the_same_loop(tmp_path):
    scene, _ = load_scene(SCENES_DIR / "cylinder.toml")
    unit = 1e4
    scaled = apply_overrides(scene, {"indenter.E": unit * scene.indenter.E,
                                     "base.E": unit * scene.base.E,
                                     "coating.E": unit * scene.coatings[0].E,
                                     "load.force": unit * scene.load.force})
    one = solve(scene, Settings(), tmp_path / "one")
    other = solve(scaled, Settings(), tmp_path / "other")
    assert other["converged"] and other["iterations"] == one["iterations"]
    assert abs(other["descent"] / one["descent"] - 1) < 1e-9
    a = pd.read_csv(tmp_path / "one" / "contact.csv")
    b = pd.read_csv(tmp_path / "other" / "contact.csv")
    assert float(np.max(np.abs(b.sigma_n / unit - a.sigma_n)) / np.max(np.abs(a.sigma_n))) < 1e-9
