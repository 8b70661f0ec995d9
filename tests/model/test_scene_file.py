"""Scene files: every example loads and is valid; a bad scene file is refused before any
work, naming the file, the key and the allowed range; flags override the file."""

import subprocess
import sys

import numpy as np
import pytest

from orchestrate.model.scene import ParameterError
from orchestrate.model.scene_file import SCENES_DIR, load_scene, paper_scene, scene_and_settings
from tests.conftest import PROJECT_DIR

BASE = """
symmetric = true
[indenter]
radius = 20.0
width = 4.0
height = 8.0
[base]
shape = "block"
width = 4.0
height = 8.0
[[coating]]
start = 0.0
end = 1.0
thickness = 0.125
[load]
force = 0.02
"""

ROLLER = """
[indenter]
width = 4.0
height = 8.0
[base]
shape = "roller"
radius = 16.0
[[coating]]
start = 0.0
end = 3.0
thickness = 0.125
[load]
displacement = 1e-3
"""


def _edit(text, old, new):
    assert old in text
    return text.replace(old, new)


def _pulled(load):
    """BASE as a full model with mu = 0.5, its [load] given ``load`` beside the force."""
    return _edit(BASE.replace("symmetric = true", "symmetric = false\nfriction = 0.5"),
                 "force = 0.02", "force = 0.02\n" + load)


# (name, file text, words the message must hold: the key and the allowed range)
BAD = [
    ("unknown key", _edit(BASE, "width = 4.0\nheight = 8.0\n[base]", "width = 4.0\nheight = 8.0\n"
                          "colour = 1\n[base]"), ["indenter.colour", "allowed in indenter"]),
    ("unknown table", BASE + "[stamp]\nE = 1\n", ["unknown key stamp", "allowed"]),
    ("overlapping patches", BASE + "[[coating]]\nstart = 0.5\nend = 1.5\nthickness = 0.1\n",
     ["coating[2].start = 0.5", "overlaps coating[1] [0.0, 1.0]"]),
    ("a patch outside the face", _edit(BASE, "end = 1.0", "end = 5.0"),
     ["coating[1].end = 5.0", "[0, 4]"]),
    ("a patch left of the axis of a half model", _edit(BASE, "start = 0.0", "start = -1.0"),
     ["coating[1].start", "symmetry axis x1 = 0"]),
    ("a thickness above the base's height", _edit(BASE, "thickness = 0.125", "thickness = 9.0"),
     ["coating[1].thickness = 9.0", "below base.height = 8.0"]),
    ("no load", _edit(BASE, "[load]\nforce = 0.02", "[load]"),
     ["load must give exactly one of displacement or force", "none"]),
    ("no load table", _edit(BASE, "[load]\nforce = 0.02", ""), ["[load] is missing"]),
    ("two loads", _edit(BASE, "force = 0.02", "force = 0.02\ndisplacement = 1e-3"),
     ["exactly one of displacement or force", "'displacement', 'force'"]),
    ("a negative force", _edit(BASE, "force = 0.02", "force = -0.02"),
     ["load.force = -0.02", "non-negative"]),
    ("a roller too small for its patches", _edit(ROLLER, "radius = 16.0", "radius = 2.5"),
     ["coating[1].end = 3.0", "|x1| < radius = 2.5"]),
    ("a negative roller radius", _edit(ROLLER, "radius = 16.0", "radius = -16.0"),
     ["base.radius = -16.0", "positive"]),
    ("a negative indenter radius", _edit(BASE, "radius = 20.0", "radius = -20.0"),
     ["indenter.radius = -20.0", "positive"]),
    ("a circle narrower than the indenter", _edit(BASE, "radius = 20.0", "radius = 3.0"),
     ["indenter.radius = 3.0", "must exceed indenter.width = 4.0"]),
    ("a roller without its radius", _edit(ROLLER, "radius = 16.0", ""),
     ["base.radius is missing"]),
    ("a block with a radius", _edit(BASE, "shape = \"block\"", "shape = \"block\"\nradius = 3.0"),
     ["base.radius = 3.0", "is for a roller"]),
    ("a bad profile", _edit(BASE, "radius = 20.0", "radius = 20.0\nprofile = \"ellipse\""),
     ["indenter.profile = 'ellipse'", "('circle', 'parabola')"]),
    ("a bad model", _edit(BASE, "thickness = 0.125", "thickness = 0.125\nmodel = \"plate\""),
     ["coating[1].model = 'plate'", "('shell', 'stretch_shell', 'elastic', 'auto')"]),
    ("a Poisson ratio of 0.5", _edit(BASE, "thickness = 0.125", "thickness = 0.125\nnu = 0.5"),
     ["coating[1].nu = 0.5", "(-1, 0.5)"]),
    ("a text for a modulus: no unit of it", _edit(BASE, "thickness = 0.125",
                                                  "thickness = 0.125\nE = \"stiff\""),
     ["coating[1].E = 'stiff'", "unknown unit", "stress is due"]),
    ("a bad setting", BASE + "[settings]\nrho = 2.0\n", ["settings.rho = 2.0", "(0, 1]"]),
    ("an unknown setting", BASE + "[settings]\nspeed = 2.0\n", ["settings.speed", "allowed"]),
    ("not TOML", "radius = = 2", ["not a valid TOML file"]),
    ("friction without sliding", _edit(BASE, "symmetric = true", "symmetric = false\nfriction = 0.3"),
     ["friction = 0.3 needs sliding = true", "partial slip"]),
    ("sliding on a half model", "friction = 0.3\nsliding = true\n" + BASE,
     ["sliding = true needs symmetric = false", "mirror symmetry"]),
    ("a negative friction", _edit(BASE, "symmetric = true",
                                  "symmetric = false\nsliding = true\nfriction = -0.1"),
     ["friction = -0.1", "[0, 2]"]),
    ("a patch's friction without sliding", _edit(BASE, "thickness = 0.125",
                                                 "thickness = 0.125\nfriction = 0.4"),
     ["coating[1].friction = 0.4 needs sliding = true"]),
    ("a patch's friction out of range", _edit(_edit(BASE, "symmetric = true",
                                                    "symmetric = false\nsliding = true"),
                                              "thickness = 0.125", "thickness = 0.125\nfriction = 2.5"),
     ["coating[1].friction = 2.5", "[0, 2]"]),
    ("a tangential force on a half model", _edit(BASE, "force = 0.02",
                                                 "force = 0.02\ntangential_force = 0.004")
     .replace("symmetric = true", "friction = 0.5"),
     ["load.tangential_force needs symmetric = false"]),
    ("a tangential force at the friction's limit", _pulled("tangential_force = 0.01"),
     ["load.tangential_force = 0.01 must be below mu P = 0.5 x 0.02", "sliding = true"]),
    ("a tangential force while sliding", _edit(
        BASE.replace("symmetric = true", "symmetric = false\nfriction = 0.5\nsliding = true"),
        "force = 0.02", "force = 0.02\ntangential_force = 0.004"),
     ["load.tangential_force = 0.004 with sliding = true"]),
    ("a tangential force under a descent", _edit(
        BASE.replace("symmetric = true", "symmetric = false\nfriction = 0.5"),
        "force = 0.02", "displacement = 1e-3\ntangential_force = 0.004"),
     ["load.tangential_force = 0.004 needs load.force"]),
    ("a tangential force on a rigid indenter", _edit(
        _pulled("tangential_force = 0.004"),
        "height = 8.0\n[base]", "height = 8.0\nrigid = true\n[base]"),
     ["indenter.rigid = true", "shift is not modelled"]),
    ("a load path's step beyond the friction's limit", _pulled(
        "tangential_force = 0.004\npath = [{tangential_force = 0}, {tangential_force = -0.012}]"),
     ["load.path[2].tangential_force = -0.012 must be below mu P = 0.5 x 0.02 in size"]),
    ("a load path's step unpressed", _pulled(
        "tangential_force = 0.004\npath = [{force = 0, tangential_force = 0}]"),
     ["load.path[1].force = 0 must be a positive number"]),
    ("a tangential force and a shift", _pulled(
        "tangential_force = 0.004\ntangential_displacement = 0.01"),
     ["load must give at most one of tangential_force or tangential_displacement"]),
    ("a load path's step of the other kind", _pulled(
        "tangential_displacement = 0.01\npath = [{tangential_force = 0.001}]"),
     ["load.path[1].tangential_force with load.tangential_displacement"]),
    ("a load path's unknown key", _pulled("tangential_force = 0.004\npath = [{shift = 0.1}]"),
     ["unknown key load.path[1].shift", "allowed: force, tangential_force"]),
    ("a load path of numbers", _pulled("tangential_force = 0.004\npath = [0.0, 0.004]"),
     ["load.path[1] = 0.0 must be a table {force, tangential_force}"]),
    ("a friction in words", _edit(BASE, "symmetric = true",
                                  "symmetric = false\nsliding = true\nfriction = \"high\""),
     ["friction = 'high'", "[0, 2]"]),
]
SLIDING = _edit(_edit(BASE, "symmetric = true", "symmetric = false\nsliding = true\nfriction = 0.3"),
                "force = 0.02", "displacement = 1e-3")      # the paper's loop takes no force


@pytest.mark.parametrize("text, words", [(text, words) for _, text, words in BAD],
                         ids=[name for name, _, _ in BAD])
def test_a_bad_scene_file_is_refused_naming_file_key_and_range(text, words, tmp_path):
    path = tmp_path / "scene.toml"
    path.write_text(text)
    with pytest.raises(ParameterError) as error:
        scene_and_settings(path)
    message = str(error.value)
    assert message.startswith(f"{path}: ")
    for word in words:
        assert word in message, (word, message)


@pytest.mark.parametrize("name", ["overlapping patches", "a roller too small for its patches"])
def test_the_command_line_refuses_a_bad_scene_before_any_work(name, tmp_path):
    text, words = next((text, words) for n, text, words in BAD if n == name)
    path = tmp_path / "scene.toml"
    path.write_text(text)
    out = tmp_path / "run"
    result = subprocess.run([sys.executable, "-m", "orchestrate", "solve", "--scene", str(path),
                             "--out", str(out)], cwd=PROJECT_DIR, capture_output=True,
                            text=True, timeout=60)
    assert result.returncode == 2
    assert str(path) in result.stderr and words[0] in result.stderr
    assert not out.exists()


PARTIAL = _edit(BASE.replace("symmetric = true", "symmetric = false\nfriction = 0.5"),
                "force = 0.02", "force = 0.02\ntangential_force = 0.004")


@pytest.mark.parametrize("scene, settings, words", [
    (SLIDING, "method = \"paper\"", ["method = 'paper' is frictionless"]),
    (SLIDING, "inner_solve = \"two-level\"", ["inner_solve = 'two-level' with friction",
                                              "the coarse level is frictionless"]),
    (PARTIAL, "inner_solve = \"direct\"",
     ["inner_solve = 'direct' with load.tangential_force", "stamp's shift"]),
], ids=["the paper's loop", "two levels", "partial slip, direct"])
def test_friction_refuses_the_solves_it_has_not_before_any_work(scene, settings, words,
                                                                  tmp_path):
    path = tmp_path / "scene.toml"
    path.write_text(scene + f"[settings]\n{settings}\n")
    out = tmp_path / "run"
    result = subprocess.run([sys.executable, "-m", "orchestrate", "solve", "--scene", str(path),
                             "--out", str(out)], cwd=PROJECT_DIR, capture_output=True,
                            text=True, timeout=60)
    assert result.returncode == 2
    for word in words:
        assert word in result.stderr, (word, result.stderr)
    assert not out.exists()


@pytest.mark.parametrize("path", sorted(SCENES_DIR.glob("*.toml")), ids=lambda p: p.name)
def test_every_example_scene_loads(path):
    scene, settings = load_scene(path)
    assert scene.load.kind in ("force", "displacement")


def test_flags_override_the_file():
    scene, settings = scene_and_settings(SCENES_DIR / "discrete.toml",
                                         {"h2": 0.25, "coating[2].E": 2.0, "model": "elastic"},
                                         {"eps_u": 1e-8})
    assert [c.thickness for c in scene.coatings] == [0.25] * 3
    assert [c.E for c in scene.coatings] == [5.0, 2.0, 5.0]
    assert {c.model for c in scene.coatings} == {"elastic"}
    assert settings.eps_u == 1e-8


def test_the_paper_scene_is_the_papers():
    """METHOD.md: Omega1 = [0, 4] x [h + h2, 2h + h2], Omega3 = [0, 4] x [0, 8], coating on
    [0, 2], gap chi x1^2 with chi = 1e-3, Delta = 2.778999 chi."""
    scene = paper_scene()
    assert scene.indenter.sag(2.0) == pytest.approx(1e-3 * 2.0 ** 2, rel=1e-15)
    assert (scene.base.width, scene.base.height) == (4.0, 8.0)
    assert (scene.coatings[0].start, scene.coatings[0].end) == (0.0, 2.0)
    assert scene.load.displacement == 2.778999e-3


def test_a_tangential_force_is_set_beside_the_force():
    """A flag that sets the tangential force keeps the force (the force and the descent
    replace each other), and the force set after it keeps the tangential force."""
    from orchestrate.model.scene_file import apply_overrides
    scene, _ = load_scene(SCENES_DIR / "partial_slip.toml")
    pulled = apply_overrides(scene, {"load.tangential_force": 0.004})
    assert (pulled.load.force, pulled.load.tangential_force) == (0.02, 0.004)
    pressed = apply_overrides(scene, {"load.force": 0.03})
    assert (pressed.load.force, pressed.load.tangential_force) == (0.03, 0.005)


def test_a_load_path_s_steps_take_units_and_the_load_s_own_values(tmp_path):
    """A load path's steps (load.path) in the file's units, a key a step leaves out
    holding the load's own; each step's scene the path up to it; a force set by a flag
    keeps the path."""
    from orchestrate.model.scene_file import apply_overrides
    from orchestrate.model.units import dimensionless
    scene, _ = load_scene(SCENES_DIR / "cylinder_mm.toml")
    text = (SCENES_DIR / "cylinder_mm.toml").read_text()
    force = scene.load.force
    assert "[load]" in text and "symmetric = true" in text
    path = tmp_path / "fretting.toml"
    path.write_text(text.replace("symmetric = true", "symmetric = false\nfriction = 0.5", 1)
                    .replace("[load]", "[load]\ntangential_force = \"-0.1 kN/m\"\n"
                             "path = [{tangential_force = 0}, "
                             "{force = \"%g N/mm\", tangential_force = \"200 N/m\"}]"
                             % (0.9 * force), 1))
    fretting, _ = load_scene(path)
    assert fretting.load.tangential_force == pytest.approx(-0.1)      # kN/m = N/mm
    np.testing.assert_allclose(fretting.load.earlier_steps, [(force, 0.0), (0.9 * force, 0.2)],
                               rtol=1e-12)
    peak = fretting.step_before()
    assert (peak.load.force, peak.load.tangential_force) == pytest.approx((0.9 * force, 0.2))
    pressed = peak.step_before()
    assert (pressed.load.tangential_force, pressed.load.path) == (0.0, "at_once")
    assert pressed.step_before() is None
    scaled, scales = dimensionless(fretting)
    from orchestrate.model.units import FORCE
    assert scaled.load.earlier_steps[1][1] == pytest.approx(0.2 / scales.of(FORCE))
    assert apply_overrides(fretting, {"load.force": 2 * force}).load.path == fretting.load.path


@pytest.mark.parametrize("key, words", [
    ("coatings.thickness", ["'coatings.thickness'", "did you mean 'coating'?",
                            "TABLE.FIELD", "coating[N].FIELD"]),
    ("frction", ["did you mean 'friction'?"]),
    ("coating.thicknes", ["did you mean 'thickness'?", "allowed: start, end"]),
    ("coating[1].modulus", ["'coating[1].modulus'", "allowed:"]),
    # a solver setting among the scene's overrides (orchestrate.solve's overrides=)
    ("eps_u", ["'eps_u' is a solver setting, not a scene key", "settings={'eps_u': ...}"]),
])
def test_a_mistyped_override_names_the_keys_there_are(key, words):
    from orchestrate.model.scene_file import apply_overrides
    scene, _ = load_scene(SCENES_DIR / "gallery" / "tin_on_steel.toml")
    with pytest.raises(ParameterError) as refused:
        apply_overrides(scene, {key: 1.0})
    for word in words:
        assert word in str(refused.value), (word, str(refused.value))
