"""Axisymmetric scenes (axisymmetric = true): bodies of revolution solved on their
meridian section, the forms weighted by 2 pi r with the hoop strain (freefem/
elasticity.idp), the interfaces by 2 pi r ds (mesh/discretization.py), forces total.

Physics against Hertz's sphere on a half-space (a rigid sphere of radius R on an
uncoated cylinder as wide and deep as L = 20 a and 40 a): the contact radius
a = (3 P R / (4 E*))^(1/3), the peak pressure 3 P / (2 pi a^2) and the approach a^2 / R.
The pressure and radius of a finite body differ from Hertz's by far less than 1 %
(measured 0.01-0.05 % at both sizes); the approach, measured to the clamped bottom, is
short of a^2 / R by c / L (measured 5.2, 2.6, 1.3 % at L = 10 a, 20 a, 40 a: halving with
L), so the body-size correction is the extrapolation of that trend, 2 d(2L) - d(L).
(The Robin loop against the monolithic solve of axisymmetric scenes:
tests/ddm/test_monolithic.py.) Then the scene's inputs: a total force with its unit,
and what an axisymmetric scene refuses before any work."""

import math

import pytest

import orchestrate
from orchestrate.errors import ParameterError
from orchestrate.model.scene import Base, Coating, Indenter, Load, Scene, Settings
from orchestrate.model.scene_file import scene_and_settings

RADIUS, NU, CONTACT_RADIUS = 20.0, 0.3, 1.0
MODULUS = 1.0 / (1.0 - NU ** 2)                     # E* of a rigid sphere on E = 1
FORCE = 4.0 * MODULUS * CONTACT_RADIUS ** 3 / (3.0 * RADIUS)
PEAK = 3.0 * FORCE / (2.0 * math.pi * CONTACT_RADIUS ** 2)
APPROACH = CONTACT_RADIUS ** 2 / RADIUS


def _sphere_scene(size):
    """A rigid sphere on an uncoated cylinder of radius and height ``size``, under the
    force that gives the contact radius CONTACT_RADIUS."""
    return Scene(indenter=Indenter(radius=RADIUS, width=4.0, height=4.0, rigid=True),
                 base=Base(shape="block", width=size, height=size, E=1.0, nu=NU),
                 load=Load(force=FORCE), axisymmetric=True)


@pytest.fixture(scope="module")
def hertz_runs():
    """{body size: summary} of the sphere on cylinders 20 a and 40 a."""
    return {size: orchestrate.solve(_sphere_scene(size), Settings(eps_u=1e-8)).summary
            for size in (20.0, 40.0)}


@pytest.mark.parametrize("size", [20.0, 40.0])
def test_a_rigid_sphere_on_a_large_cylinder_is_hertz(hertz_runs, size):
    summary = hertz_runs[size]
    assert summary["total_force"] == pytest.approx(FORCE, rel=1e-6)
    assert summary["stamp_reaction"] == pytest.approx(FORCE, rel=1e-6)
    assert summary["base_reaction"] == pytest.approx(FORCE, rel=1e-5)   # the whole body's
    assert -summary["peak_contact_stress"] / PEAK == pytest.approx(1.0, abs=0.01)
    assert summary["contact_half_width"] / CONTACT_RADIUS == pytest.approx(1.0, abs=0.01)


def test_the_approach_tends_to_hertz_as_the_body_grows(hertz_runs):
    short = [1.0 - hertz_runs[size]["descent"] / APPROACH for size in (20.0, 40.0)]
    assert 0.01 < short[0] < 0.05 and short[1] == pytest.approx(short[0] / 2, rel=0.1)
    extrapolated = 2.0 * hertz_runs[40.0]["descent"] - hertz_runs[20.0]["descent"]
    assert extrapolated / APPROACH == pytest.approx(1.0, abs=0.01)


def test_a_sphere_scene_in_mm_takes_and_reports_a_force(tmp_path):
    """A total force in N on a mm/MPa scene: its summary in N and the force it was given."""
    path = tmp_path / "ball.toml"
    path.write_text(_ball("force = \"20 N\""))
    scene, settings = scene_and_settings(path)
    assert scene.load.force == pytest.approx(20.0)              # MPa mm^2 = N
    summary = orchestrate.solve(scene, settings).summary
    assert summary["units"]["force"] == "MPa mm^2"
    assert summary["total_force"] == pytest.approx(20.0, rel=1e-6)
    modulus = 1.0 / (2.0 * (1 - NU ** 2) / 210e3)               # steel on steel
    radius = (3 * 20.0 * 5.0 / (4 * modulus)) ** (1 / 3)
    # the coating (a 2 um chromium disc) barely changes a 0.1 mm contact
    assert summary["contact_half_width"] == pytest.approx(radius, rel=0.03)


def _ball(load, top=""):
    return f"""{top}axisymmetric = true
[units]
length = "mm"
stress = "MPa"
b = 0.05
[indenter]
radius = 5.0
width = 1.0
height = 1.0
E = "210 GPa"
nu = 0.3
[base]
width = 2.0
height = 2.0
E = "210 GPa"
nu = 0.3
[[coating]]
start = 0.0
end = 1.0
thickness = "2 um"
E = "250 GPa"
nu = 0.3
[load]
{load}
"""


BAD = [
    ("a force per unit width", _ball("force = \"200 N/mm\""),
     ["load.force = '200 N/mm'", "a force per unit width", "a force is due"]),
    ("a half space of revolution made a full model",
     _ball("force = \"20 N\"", top="symmetric = false\n"), ["symmetric = false", "meridian"]),
    ("a roller of revolution", _ball("force = \"20 N\"").replace(
        "width = 2.0\nheight = 2.0", "shape = \"roller\"\nradius = 2.0"),
     ["base.shape = 'roller'", "a roller is a plane scene"]),
    ("a shell on an axisymmetric scene", _ball("force = \"20 N\"").replace(
        "nu = 0.3\n[load]", "nu = 0.3\nmodel = \"shell\"\n[load]"),
     ["coating[1].model = 'shell'", "not in the tool yet"]),
    ("a ring across the axis", _ball("force = \"20 N\"").replace(
        "start = 0.0", "start = -0.5"), ["coating[1].start = -0.5", "r >= 0"]),
    ("a ring beyond the face", _ball("force = \"20 N\"").replace(
        "end = 1.0", "end = 3.0"), ["coating[1].end = 3.0", "[0, 2]"]),
]


@pytest.mark.parametrize("text, words", [(text, words) for _, text, words in BAD],
                         ids=[name for name, _, _ in BAD])
def test_a_bad_axisymmetric_scene_is_refused_naming_the_key(text, words, tmp_path):
    path = tmp_path / "scene.toml"
    path.write_text(text)
    with pytest.raises(ParameterError) as error:
        scene_and_settings(path)
    for word in words:
        assert word in str(error.value), (word, str(error.value))


def test_auto_chooses_the_2d_coating_on_an_axisymmetric_scene():
    scene = Scene(indenter=Indenter(radius=RADIUS, width=4.0, height=4.0, rigid=True),
                  base=Base(width=12.0, height=12.0),
                  coatings=(Coating(start=0.0, end=3.0, thickness=0.25, E=4.0, model="auto"),),
                  load=Load(force=0.05), axisymmetric=True)
    plan = orchestrate.run.prepare(scene, Settings())
    assert plan.scene.coatings[0].model == "elastic"
    assert plan.model_choice["patches"][0]["not_estimated"].startswith("axisymmetric")
