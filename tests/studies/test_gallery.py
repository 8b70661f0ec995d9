"""The gallery (orchestrate/scenes/gallery/, studies/gallery.py): every scene is valid and
plans (the error a user would meet comes before any work), and together the scenes span
the ranges engineers pose (issue 28): indenter over base modulus from 1e-2 to 1e3,
coating over base from 1/100 to 100, coating thickness from 1e-3 to 10 contact
half-widths, bodies from 4 to 50 half-widths, a roller with R/h2 up to 1e4, discrete
patches, a rigid indenter, force and displacement loads, scenes in mm and MPa."""

import math

import pytest

from orchestrate.model import scene_and_settings
from orchestrate.run import prepare
from studies.gallery import _describe, gallery_files

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
