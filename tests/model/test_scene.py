"""Physics of the default scene (shell model, h2 = b/8, E2 = E), solved by the Robin loop.

- Pinned: the summary, computed once with the stopping test of the Robin loop that
  bounds the error of the displacements and of each traction component, with a margin
  (orchestrate/ddm/robin.py), to 1e-8: it is within 2e-9 of a run to eps_u = 1e-11.
- Equilibrium: the total contact force on S12, the total normal force on S23, the stamp's
  reaction on Omega1 and the clamp's reaction on Omega3 (variationally consistent nodal
  reactions) are one and the same force.
- With E2 = E and a thin coating the bodies act as two half-planes of one material: the
  contact pressure is Hertz-like. Plane-strain Hertz from the run's own total force:
  gap d = x1^2/(2R) with R = b^2/(2 chi), E* = E/(2(1 - nu^2)), half-width
  a = sqrt(4 F R/(pi E*)), peak p0 = 2F/(pi a), F the force of the full (symmetric) contact.
- The penalty's own error is small: halving theta changes the peak contact stress by
  less than 0.1 %.
"""

import math

import pytest

from orchestrate.model.scene import Settings
from orchestrate.model.scene_file import paper_scene
from orchestrate.run.solve import solve


# The pins below were computed at the paper's penalty theta = 1e-3 b/E, the default
# until the default was tied to the mesh (2.5e-4 b/E on this mesh, studies/penalty.py):
# this run keeps that penalty, so that the pins keep their meaning. They are the iterated
# loop's (a direct solve of each contact set, tests/ddm/test_interface_system.py, gives the
# same within the tolerance, in fewer iterations).
PIN_THETA = 1e-3
# The pins are within 2e-9 of a run to eps_u = 1e-11; a run to the default eps_u (1e-6)
# reaches them within 1e-8 or not, by the path its iterates take (1.3e-8 once the
# contact's sides were split far). Run to 1e-8 (the tightest with the coating inside the
# base's worker, strategy.INSIDE_TIGHTEST_EPS_U), it is within about 1e-9 of its fixed
# point whatever the path, so 1e-8 tests the answer, not the path.
PIN_EPS_U = 1e-8


@pytest.fixture(scope="module")
def default_run(tmp_path_factory):
    return solve(paper_scene(), Settings(theta=PIN_THETA, inner_solve="iterate",
                                         bonds="inside", eps_u=PIN_EPS_U),
                 tmp_path_factory.mktemp("default"))


# `python -m orchestrate solve --model shell --h2 0.125 --E2 1 --theta 1e-3
# --inner-solve iterate`: the forces, the peaks and the contact's half-width
PINNED = {"contact_force": 0.0003886008039077872,
          "interface_force": 0.00038860080389541065, "stamp_reaction": 0.00038860080395013423,
          "base_reaction": 0.0003886008038900048, "peak_contact_stress": -0.0005302321688831679,
          "peak_interface_stress": -0.0005272281328311636,
          "contact_half_width": 0.9131064271593012}


def test_the_paper_scene_gives_its_pinned_numbers(default_run):
    for name, value in PINNED.items():
        assert abs(default_run[name] / value - 1) < 1e-8, name


def test_the_default_penalty_moves_the_peak_by_the_penalty_error(default_run, tmp_path):
    """At the default penalty (2.5e-4) the peak contact stress moves from the pinned one
    (1e-3) by the difference of their penalty errors, 0.053 % - 0.013 % (monolithic
    estimates of results/penalty.csv and docs/method.md, "Penalty")."""
    stiffer = solve(paper_scene(), Settings(), tmp_path)
    assert stiffer["settings"]["theta"] == pytest.approx(2.5e-4, rel=1e-12)
    shift = stiffer["peak_contact_stress"] / default_run["peak_contact_stress"] - 1
    assert 0.0003 < shift < 0.0005


def test_forces_balance(default_run):
    force = default_run["contact_force"]
    assert force > 0
    for name in ("interface_force", "stamp_reaction", "base_reaction"):
        assert abs(default_run[name] - force) < 0.01 * force, name


def test_contact_pressure_is_hertz_like(default_run):
    scene = paper_scene()
    full_force = 2.0 * default_run["contact_force"]      # the run models half the contact
    effective_modulus = scene.indenter.E / (2.0 * (1.0 - scene.indenter.nu ** 2))
    half_width = math.sqrt(4.0 * full_force * scene.indenter.radius
                           / (math.pi * effective_modulus))
    peak = 2.0 * full_force / (math.pi * half_width)
    element = default_run["interface_element_size"]
    assert abs(-default_run["peak_contact_stress"] - peak) < 0.03 * peak
    assert abs(default_run["contact_half_width"] - half_width) < element


def test_halving_the_penalty_changes_the_peak_stress_by_less_than_a_thousandth(
        default_run, tmp_path):
    settings = Settings()
    halved = solve(paper_scene(), Settings(theta=settings.theta / 2), tmp_path)
    change = abs(halved["peak_contact_stress"] / default_run["peak_contact_stress"] - 1.0)
    assert change < 1e-3
