"""The contact half-width of a cylinder on a coated half-space (orchestrate/model/
layered_contact.py), where the loop's first contact set is drawn: the layer's compliance
in its limits, Hertz where the coating is the base or thicker than the contact, and the
finite element answer of coated gallery scenes, which it was not fitted to."""

import math

import numpy as np
import pytest

import orchestrate
from orchestrate.model import scene_and_settings
from orchestrate.model.estimate import contact_half_width, first_contact_half_width
from orchestrate.model.layered_contact import layer_factor, layered_half_width
from orchestrate.model.units import dimensionless
from orchestrate.paths import SCENES_DIR

FORCE, RADIUS = 0.02, 100.0


def _hertz(compliance):
    """Hertz's half-width under FORCE and RADIUS; ``compliance``: 1/E* of the pair."""
    return math.sqrt(4 * FORCE * RADIUS * compliance / math.pi)


def test_the_layer_factor_is_one_for_a_layer_like_its_base_and_runs_between_the_two():
    t = np.array([1e-5, 1e-2, 1.0, 40.0])
    assert layer_factor(t, 1.0, 0.3, 1.0, 0.3) == pytest.approx(1.0, rel=1e-12)
    for E2, nu2 in ((4.0, 0.3), (0.01, 0.45)):
        factor = layer_factor(t, E2, nu2, 1.0, 0.3)
        base = E2 * (1 - 0.3 ** 2) / (1 - nu2 ** 2)      # the base's compliance over the layer's
        assert factor[0] == pytest.approx(base, rel=1e-3)
        assert factor[-1] == pytest.approx(1.0, rel=1e-9)
        assert np.all(np.diff(factor) * np.sign(1 - base) > 0)     # monotone between


@pytest.mark.parametrize("layer, indenter, compliance", [
    ((1.0, 0.3, 0.5), None, 1 - 0.3 ** 2),                       # the coating is the base
    ((1.0, 0.3, 0.5), (2.0, 0.25), 1 - 0.3 ** 2 + (1 - 0.25 ** 2) / 2.0),
    ((4.0, 0.3, 100.0), None, (1 - 0.3 ** 2) / 4.0),              # far thicker than the contact
])
def test_where_the_coating_is_the_base_or_a_half_space_it_is_hertz(layer, indenter, compliance):
    assert layered_half_width(FORCE, RADIUS, layer, (1.0, 0.3), indenter) == pytest.approx(
        _hertz(compliance), rel=2e-3)


@pytest.mark.parametrize("name", ["near_rigid_cylinder", "steel_on_coated_polymer"])
def test_a_stiff_coatings_contact_is_the_finite_element_answers(name):
    """A coating of 4 E, 0.5 b thick, under a near-rigid cylinder, and 20 um of 21 GPa on
    a polymer base: Hertz's half-width of the base is 25 % and 16 % too wide; this is
    within 1.5 % of the loop's answer at mesh level 1, whose contact's edge is located to
    an interface element."""
    scene, settings = scene_and_settings(SCENES_DIR / "gallery" / f"{name}.toml")
    solved, scales = dimensionless(scene)
    estimate = first_contact_half_width(solved, contact_half_width(solved)) * scales.length
    answer = orchestrate.solve(scene, settings).summary["contact_half_width"]
    assert contact_half_width(solved) * scales.length > 1.15 * answer
    assert estimate == pytest.approx(answer, rel=0.015)
