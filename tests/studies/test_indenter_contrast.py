"""The contrast study's scenes change the indenter's modulus alone: the a priori contact
half-width (Hertz, the bodies' contact modulus) stays the scene's own."""

import pytest

from orchestrate.model import contact_half_width, scene_and_settings
from studies.indenter_contrast import MODULI, SCENE, scene_with


def test_the_force_scales_so_that_the_contact_keeps_its_width():
    own, _ = scene_and_settings(SCENE)
    for modulus in MODULI:
        scene, _ = scene_with(modulus)
        assert scene.indenter.rigid == (modulus is None)
        if modulus is not None:
            assert scene.indenter.E == pytest.approx(modulus * scene.base.E, rel=1e-12)
        assert contact_half_width(scene) == pytest.approx(contact_half_width(own), rel=1e-9)
    # the softest indenter carries about a hundredth of the force
    assert scene_with(0.01)[0].load.force < own.load.force / 50
