"""A thin 2D coating on a large part (mesh/discretization.py, FaceSpacing.length): its
cells are at most twice as wide as high at the patch's ends and the a priori contact's
edges, and grow from there as the face's elements do, up to the face's own length. Inside
the contact they are then the face's elements (contact_elements across the a priori
half-width, as on any face), where cells held at twice their height over the whole face
put three times as many there: the answers differ by that resolution, and the unknowns
by half.

The scene, tried as an engineer would pose it: a steel ball (R 5 mm) pressed with 10 N on
PEEK carrying a 2 um DLC film (200 GPa) over its whole top, a body 25 contact radii wide;
its 2D coating is what auto takes there (a film 55 times stiffer than its base lies
outside the shells' calibrated span)."""

import math

import numpy as np
import pytest

from orchestrate import solve
from orchestrate.cli import mesh_line
from orchestrate.mesh.discretization import FaceSpacing
from orchestrate.model.scene import Settings
from orchestrate.model.scene_file import scene_and_settings

pytestmark = pytest.mark.slow       # two runs of a few seconds

FILM_ON_POLYMER = """
axisymmetric = true
[units]
length = "mm"
stress = "MPa"
b = 0.2
[indenter]
radius = 5.0
width = 2.0
height = 2.0
E = "210 GPa"
nu = 0.3
[base]
width = 5.0
height = 5.0
E = "3.6 GPa"
nu = 0.4
[[coating]]
start = 0.0
end = 5.0
thickness = "2 um"
E = "200 GPa"
nu = 0.2
model = "elastic"
[load]
force = "10 N"
"""


def _held_at_the_cap(spacing, s, cap=math.inf, ends=()):
    """The element length at s with a 2D coating's widest cell held over the whole face
    (the rule before its cells grew away from the contact)."""
    beyond = np.maximum(np.abs(s - spacing.centre) - spacing.reach, 0.0)
    return np.minimum(np.minimum(spacing.fine + spacing.growth * beyond, spacing.far), cap)


@pytest.fixture(scope="module")
def graded_and_held(tmp_path_factory):
    """The film's run on the default face, and with its cells held at their widest width
    over the whole face (the rule before the cells grew away from the contact, and from
    the ends)."""
    path = tmp_path_factory.mktemp("film") / "film_on_polymer.toml"
    path.write_text(FILM_ON_POLYMER)
    scene, _ = scene_and_settings(path)
    graded = solve(scene, Settings())
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(FaceSpacing, "length", _held_at_the_cap)
        held = solve(scene, Settings())
    return graded, held


def _answers(result):
    bond = result.interface
    return {"pressure": -result.summary["peak_contact_stress"],
            "bond_normal": float(bond.sigma_n.abs().max()),
            "bond_shear": float(bond.sigma_t.abs().max()),
            "descent": result.summary["descent"]}


def test_a_thin_coatings_cells_grow_away_from_its_ends_and_the_contacts_edges(graded_and_held):
    graded, held = graded_and_held
    unknowns = [sum(run.summary["dofs"].values()) for run in (graded, held)]
    assert unknowns[0] < 0.6 * unknowns[1]         # measured 33k against 59k
    # the face's elements across the contact (16 per a priori half-width): 32.4 measured,
    # against 101 with the cells held at twice their height
    across = [run.summary["elements_across_contact"][0] for run in (graded, held)]
    assert 28 < across[0] < 40 and across[1] > 2.5 * across[0]


@pytest.mark.parametrize("answer, tolerance", [("pressure", 1e-3), ("bond_normal", 1e-3),
                                               ("bond_shear", 3e-2), ("descent", 1e-4)])
def test_the_answers_at_the_contact_differ_by_its_resolution(graded_and_held, answer,
                                                             tolerance):
    """Measured at mesh level 1: 4.3e-4, 4.2e-4, 1.5e-2 and 1.6e-6 apart; at mesh level 2,
    where both meshes are finer, 9.5e-5, 1.7e-4, 7.1e-3 and 3.4e-7 (the difference
    shrinks with the contact's elements). The bond shear's peak, at the contact's edge,
    is not resolved by either (the warning coarse_bond): 13.90 and 13.69 MPa at level 1,
    13.97 and 13.87 at level 2."""
    graded, held = (_answers(run) for run in graded_and_held)
    assert graded[answer] == pytest.approx(held[answer], rel=tolerance)


def test_the_summary_says_the_contacts_elements_as_meshed(graded_and_held):
    """contact_element_size is the elements' length in the contact zone as meshed: on the
    graded face the length it was sized to; with the film's cells held at twice their
    height (2 um, one layer: 4 um wide) that width, far below the size the face asked
    for, and the command line says so."""
    graded, held = (run.summary for run in graded_and_held)
    assert graded["contact_element_size"][0] == pytest.approx(
        graded["interface_element_size"], rel=0.1)
    assert held["contact_element_size"][0] == pytest.approx(0.004, rel=0.05)
    assert held["interface_element_size"] > 2.5 * held["contact_element_size"][0]
    assert "of 0.004" in mesh_line(held) and "refines its face" in mesh_line(held)
    assert "refines" not in mesh_line(graded)
