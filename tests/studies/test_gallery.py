"""The gallery (orchestrate/scenes/gallery/, studies/gallery.py): every scene is valid and
plans (the error a user would meet comes before any work), and together the scenes span
the ranges engineers pose (issue 28): indenter over base modulus from 1e-2 to 1e3,
coating over base from 1/100 to 100, coating thickness from 1e-3 to 10 contact
half-widths, bodies from 4 to 50 half-widths, a roller with R/h2 up to 1e4, discrete
patches, a rigid indenter, force and displacement loads, scenes in mm and MPa."""

import math

import numpy as np
import pytest

from orchestrate.model import scene_and_settings
from orchestrate.run import prepare
from studies.gallery import _describe
from studies.paths import gallery_files

FILES = gallery_files()


@pytest.fixture(scope="module")
def spans():
    rows = []
    for path in FILES:
        scene, settings = scene_and_settings(path)
        plan = prepare(scene, settings)
        rows.append({"scene": scene, "solved": plan.problem.scene,
                     **_describe(scene, plan.problem.scene)})
    return rows


def test_the_gallery_has_scenes():
    assert len(FILES) >= 8


def test_every_scene_plans(spans):
    assert len(spans) == len(FILES)


def _range(rows, key):
    values = [row[key] for row in rows if not math.isnan(row[key])]
    return min(values), max(values)


def test_the_moduli_span_what_engineers_pose(spans):
    low, high = _range(spans, "indenter_over_base")
    assert low <= 1e-2 * 1.01 and high >= 1e3 * 0.99
    low, high = _range(spans, "coating_over_base")
    assert low <= 1e-2 * 1.01 and high >= 1e2 * 0.99


def test_the_sizes_span_what_engineers_pose(spans):
    low, high = _range(spans, "h2_over_a")
    assert low <= 2e-3 and high >= 8.0              # thickness over the a priori half-width
    low, high = _range(spans, "width_over_a")
    assert low <= 5.0 and high >= 40.0
    rollers = [row["solved"] for row in spans if row["solved"].base.shape == "roller"]
    assert any(base.base.radius / min(c.thickness for c in base.coatings) >= 1e4 * 0.99
               for base in rollers)


def test_the_loads_units_and_patches_span_what_engineers_pose(spans):
    assert {row["load"] for row in spans} == {"force", "displacement"}
    assert any(row["scene"].indenter.rigid for row in spans)
    assert any(row["scene"].units.length == "mm" for row in spans)
    assert any(len(row["scene"].coatings) >= 2 for row in spans)     # discrete patches


@pytest.mark.parametrize("name", ["paper.toml", "sphere.toml"])
def test_the_monolithic_force_is_the_whole_bodys(name):
    """A uniform unit pressure on the contact gives the force over the whole face the
    contact points cover: twice the half model's in plane strain, pi r^2 about an axis
    (whose weights already carry 2 pi r: doubling it, as a half model, was wrong)."""
    from orchestrate.paths import SCENES_DIR
    from studies.gallery import _monolithic_answers
    scene, settings = scene_and_settings(SCENES_DIR / name)
    problem = prepare(scene, settings).problem
    contacts = [i for i in problem.interfaces if i.kind == "contact"]
    stresses = [-np.ones(i.size) if i.kind == "contact" else np.zeros((2, i.size))
                for i in problem.interfaces]
    force = _monolithic_answers(problem, stresses)["total_force"]
    x = np.concatenate([c.position[:, 0] for c in contacts])
    expected = (math.pi * (x.max() ** 2 - x.min() ** 2) if scene.axisymmetric
                else 2.0 * (x.max() - x.min()))
    assert force == pytest.approx(expected, rel=1e-3)


@pytest.mark.parametrize("axisymmetric, expected", [(False, 10.0 / (2.0 * 0.5)),
                                                    (True, 10.0 / (2.0 * 0.25))])
def test_the_loops_force_is_said_in_b_and_e(axisymmetric, expected):
    """A force per unit width is E b, a body of revolution's E b^2."""
    from types import SimpleNamespace
    import pandas as pd
    from studies.gallery import _loop_answers
    summary = {"peak_contact_stress": -1.0, "total_force": 10.0, "contact_half_width": 0.1,
               "scene": {"axisymmetric": axisymmetric, "symmetric": True}}
    result = SimpleNamespace(summary=summary, interface=pd.DataFrame(
        {"sigma_n": [], "sigma_t": []}))
    answers = _loop_answers(result, SimpleNamespace(stress=2.0, length=0.5))
    assert answers["total_force"] == pytest.approx(expected)
