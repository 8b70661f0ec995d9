"""A scene in mm and MPa keeps its units through every override, and a value may carry
its own unit.

Every way of changing a scene (a --set of a length and of a modulus, the paper's --h2 and
--E2, --model auto, a sweep's grid over thickness and modulus, the Python API) must give
the scene written out in full in the file's units: the same Scene, and the same run to
1e-10 (outputs in mm and MPa, labelled so). Values with their own unit ("200 um",
"300 GPa", "0.8 kN/mm") are converted into the file's units; an unknown unit or one of
the wrong dimension is refused before any work, naming the file, the key and what was
due.
"""

import json
import subprocess
import sys

import numpy as np
import pandas as pd
import pytest

import orchestrate
from orchestrate.cli import build_parser, scene_from_arguments
from orchestrate.errors import LengthsError, ParameterError
from orchestrate.run.plan import lengths_in_units
from orchestrate.model.scene_file import apply_overrides, load_scene, scene_and_settings
from orchestrate.sweeps import load_sweep, point_scene
from orchestrate.model.units import Units
from tests.conftest import PROJECT_DIR, STEEL_SCENE, STEEL_VALUES, steel_scene

pytestmark = pytest.mark.slow       # not in the everyday subset (make test-fast)

GIVEN = dict(STEEL_VALUES)
CHANGED = dict(thickness=0.2, E2=300000.0)         # what each way sets


# Every way runs each contact set directly: the runs then agree to rounding. A FreeFEM
# worker's solve of the same request differs from run to run in its last digits, and an
# iterated loop carries that to about 1e-10 of its answers (measured: 7.5e-11 between
# two runs of one scene), which is no sign of a lost unit.
DIRECT = '\n[settings]\ninner_solve = "direct"\n'


def scene_file(folder, name, **values):
    path = steel_scene(folder / f"{name}.toml", **values)
    path.write_text(path.read_text() + DIRECT)
    return path


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    folder = tmp_path_factory.mktemp("scenes")
    return {"given": scene_file(folder, "given"),
            "changed": scene_file(folder, "changed", **CHANGED),
            "auto": scene_file(folder, "auto", model="auto"),
            "folder": folder}


def _from_flags(*flags):
    return scene_from_arguments(build_parser().parse_args(["solve", "--out", "x", *flags]))[0]


def _sweep_scenes(folder, given):
    sweep = folder / "grid.toml"
    sweep.write_text(f'[fixed]\nscene = "{given.name}"\n[grid]\nh2 = [0.1, "200 um"]\n'
                     'E2 = [450000.0, "300 GPa"]\n')
    _, points = load_sweep(sweep)
    return {(p["h2"], p["E2"]): point_scene(p, folder)[0] for p in points}


# ---- the same Scene, whatever the way --------------------------------------------------

WAYS = {
    "--set of a length and a modulus": lambda f: _from_flags(
        "--scene", str(f["given"]), "--set", "coating.thickness=0.2",
        "--set", "coating[1].E=300000.0"),
    "--set with units": lambda f: _from_flags(
        "--scene", str(f["given"]), "--set", 'coating.thickness="200 um"',
        "--set", "coating.E=300 GPa"),
    "--h2 and --E2": lambda f: _from_flags("--scene", str(f["given"]), "--h2", "0.2",
                                           "--E2", "300000"),
    "--h2 and --E2 with units": lambda f: _from_flags("--scene", str(f["given"]), "--h2",
                                                      "0.2 mm", "--E2", "0.3 TPa"),
    "a sweep's grid": lambda f: _sweep_scenes(f["folder"], f["given"])[("200 um", "300 GPa")],
    "the Python API": lambda f: apply_overrides(load_scene(f["given"])[0],
                                                {"h2": "200 um", "coating.E": 300000.0}),
}


@pytest.mark.parametrize("way", WAYS)
def test_every_override_gives_the_scene_written_out_in_full(files, way):
    overridden = WAYS[way](files)
    assert overridden == load_scene(files["changed"])[0]
    assert overridden.units == Units("mm", "MPa", 2.5)


def test_model_auto_keeps_the_units(files):
    assert _from_flags("--scene", str(files["given"]), "--model", "auto") == \
        load_scene(files["auto"])[0]


def test_a_sweeps_grid_keeps_the_units_at_every_point(files):
    scenes = _sweep_scenes(files["folder"], files["given"])
    for (h2, E2), scene in scenes.items():
        thickness = 0.2 if h2 == "200 um" else h2
        modulus = 300000.0 if E2 == "300 GPa" else E2
        expected = load_scene(scene_file(files["folder"], "point", thickness=thickness,
                                         E2=modulus))[0]
        assert scene == expected


def test_values_with_units_are_the_numbers_in_the_files_units(tmp_path):
    with_units = scene_file(tmp_path, "with_units", thickness='"100 um"', E2='"450 GPa"',
                            force='"0.8 kN/mm"')
    assert load_scene(with_units)[0] == load_scene(scene_file(tmp_path, "numbers"))[0]
    scene, settings = scene_and_settings(with_units, settings={"element_size": "0.125 mm"})
    assert settings.element_size == pytest.approx(0.05)      # 0.125 mm / (b = 2.5 mm)


BAD_VALUES = [
    ("a stress unit pint does not know", dict(E2='"450 Gpa"'),
     ["coating[1].E", "unknown unit 'Gpa'", "a stress is due"]),
    ("a length where a stress is due", dict(E2='"450 mm"'),
     ["coating[1].E", "is a length; a stress is due"]),
    ("a stress where a length is due", dict(thickness='"20 MPa"'),
     ["coating[1].thickness", "is a stress; a length is due"]),
    ("a force where a force per unit width is due", dict(force='"800 N"'),
     ["load.force", "not per unit width"]),
]


@pytest.mark.parametrize("values, words", [(v, w) for _, v, w in BAD_VALUES],
                         ids=[name for name, _, _ in BAD_VALUES])
def test_a_wrong_unit_is_refused_with_exit_2_naming_file_key_and_what_is_due(
        tmp_path, values, words):
    path = scene_file(tmp_path, "bad", **values)
    run = subprocess.run([sys.executable, "-m", "orchestrate", "solve", "--scene", str(path),
                          "--out", str(tmp_path / "out")], cwd=PROJECT_DIR,
                         capture_output=True, text=True, timeout=120)
    assert run.returncode == 2, run.stderr
    for word in [str(path), *words]:
        assert word in run.stderr, (word, run.stderr)
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("table, words", [
    ('length = "mm"\nstress = "Mpa"\nb = 2.5', ["units.stress", "unknown unit 'Mpa'"]),
    ('length = "MPa"\nstress = "MPa"\nb = 2.5', ["units.length", "is a stress"]),
    ('length = "mm"\nstress = "MPa"\nb = "2.5 MPa"', ["units.b", "is a stress"]),
    ('stress = "MPa"\nb = 2.5', ["units.b = 2.5 needs units.length"]),
], ids=["a misspelt stress unit", "a stress for the length", "b not a length",
        "b without a length unit"])
def test_unit_names_are_checked(tmp_path, table, words):
    path = tmp_path / "scene.toml"
    path.write_text(STEEL_SCENE.format(**GIVEN).replace(
        'length = "mm"\nstress = "MPa"\nb = 2.5', table))
    with pytest.raises(ParameterError) as error:
        load_scene(path)
    for word in [str(path), *words]:
        assert word in str(error.value)


@pytest.mark.parametrize("override, words", [
    ({"coating[1].thickness": "-3 um"}, "coating[1].thickness = -0.003 mm must be positive"),
    ({"coating[1].E": "-3 GPa"}, "coating[1].E = -3000.0 MPa must be positive"),
    ({"coating[1].start": "2 cm"},
     "coating[1].end = 5.0 mm must exceed coating[1].start = 20.0 mm"),
], ids=["a length in um", "a stress in GPa", "two lengths in cm"])
def test_a_refused_override_quotes_its_value_in_the_files_units(tmp_path, override, words):
    """An override in another unit is converted to the file's before it is checked: the
    error says the number it checked with that unit (a bare -0.003 would read as b)."""
    scene, _ = load_scene(scene_file(tmp_path, "steel"))
    with pytest.raises(ParameterError) as error:
        apply_overrides(scene, override)
    assert words.replace("must be positive", "must be a positive number") in str(error.value)


def test_a_total_force_is_limited_in_e_b_squared(tmp_path):
    """An axisymmetric scene's force is a total force (E b^2): the load limit is in it,
    not in E b (a force per unit width), and says its value in the file's units."""
    scene, _ = load_scene(PROJECT_DIR / "orchestrate/scenes/ball_mm.toml")
    E, b = scene.base.E, scene.units.b                   # 210 GPa, 0.05 mm: E b^2 = 525 N
    apply_overrides(scene, {"load.force": f"{0.9e6 * E * b * b} N"})
    with pytest.raises(ParameterError) as error:
        apply_overrides(scene, {"load.force": f"{2e6 * E * b * b} N"})   # under 1e6 E b
    assert "at most 1e+06 E b^2 = 5.25e+08 N" in str(error.value)


def test_a_check_made_on_the_mesh_in_b_is_said_in_the_files_units(tmp_path):
    """The mesh's checks run on the scene in b (LengthsError); prepare says their
    lengths in the scene's units (b = 2.5 mm here)."""
    scene, _ = scene_and_settings(scene_file(tmp_path, "steel"))
    with pytest.raises(ParameterError) as error:
        with lengths_in_units(scene):
            raise LengthsError("the face from {start} to {end}", "indenter.width",
                               start=0.0, end=4.8)
    assert str(error.value) == "the face from 0 mm to 12 mm"
    assert error.value.key == "indenter.width"
    assert str(LengthsError("at {x}", "k", x=4.8)) == "at 4.8 b"     # unsaid: in b


def test_a_value_with_a_unit_in_a_scene_without_units_is_refused():
    with pytest.raises(ParameterError, match="has a unit, but the scene's lengths are in b"):
        orchestrate.paper_scene(h2="20 um")


# ---- the same run, whatever the way ------------------------------------------------------

def _solve(arguments, out):
    return subprocess.run([sys.executable, "-m", "orchestrate", "solve", "--quiet",
                           *arguments, "--out", str(out)], cwd=PROJECT_DIR,
                          capture_output=True, text=True, timeout=300)


@pytest.fixture(scope="module")
def written_out(files, tmp_path_factory):
    """The changed scene run from its file written out in full."""
    out = tmp_path_factory.mktemp("written_out") / "run"
    assert _solve(["--scene", str(files["changed"])], out).returncode == 0
    return out


def _same_run(folder, reference, tolerance=1e-10):
    """Two run folders agree: summary numbers and interface tables, to ``tolerance`` of
    the largest value of each."""
    ours, theirs = (json.loads((f / "summary.json").read_text()) for f in (folder, reference))
    assert ours["units"]["stress"] == "MPa" and ours["units"]["length"] == "mm"
    assert ours["scene"] == theirs["scene"]
    for key in ("peak_contact_stress", "peak_interface_stress", "descent", "total_force",
                "contact_half_width"):
        assert ours[key] == pytest.approx(theirs[key], rel=tolerance), key
    for table in ("contact.csv", "interface.csv"):
        a, b = pd.read_csv(folder / table), pd.read_csv(reference / table)
        assert list(a.columns) == list(b.columns)
        for column in a.columns[1:]:
            scale = max(np.abs(b[column]).max(), 1e-300)
            assert np.abs(a[column] - b[column]).max() <= tolerance * scale, (table, column)


def test_a_run_overridden_by_flags_with_units_is_the_written_out_run(files, written_out,
                                                                     tmp_path):
    run = _solve(["--scene", str(files["given"]), "--set", 'coating.thickness="200 um"',
                  "--E2", "300 GPa"], tmp_path / "run")
    assert run.returncode == 0, run.stderr
    _same_run(tmp_path / "run", written_out)
    assert "MPa" in run.stdout and " E " not in run.stdout


def test_a_run_with_model_auto_says_its_answers_in_the_files_units(files, tmp_path):
    run = _solve(["--scene", str(files["given"]), "--model", "auto"], tmp_path / "auto")
    assert run.returncode == 0, run.stderr
    reference = _solve(["--scene", str(files["auto"])], tmp_path / "written")
    assert reference.returncode == 0, reference.stderr
    _same_run(tmp_path / "auto", tmp_path / "written")
    assert "contact: peak pressure" in run.stdout and "MPa at x1 = 0 mm" in run.stdout


def test_a_sweep_point_is_the_written_out_run(files, written_out, tmp_path):
    sweep = files["folder"] / "sweep.toml"
    sweep.write_text(f'name = "units"\n[fixed]\nscene = "{files["given"].name}"\n[grid]\n'
                     'h2 = ["200 um"]\nE2 = [450000.0, "300 GPa"]\n')
    run = subprocess.run([sys.executable, "-m", "orchestrate", "sweep", str(sweep), "--out",
                          str(tmp_path / "sweep")], cwd=PROJECT_DIR, capture_output=True,
                         text=True, timeout=300)
    assert run.returncode == 0, run.stderr
    table = pd.read_csv(tmp_path / "sweep" / "runs.csv")
    assert set(table["units.stress"]) == {"MPa"} and set(table["h2"]) == {0.2}
    point = table[table["E2"] == 300000.0]["id"].item()
    _same_run(tmp_path / "sweep" / "runs" / point, written_out)


def test_a_python_api_run_with_overrides_is_the_written_out_run(files, written_out,
                                                                tmp_path):
    result = orchestrate.solve(files["given"], overrides={"h2": "200 um", "E2": "300 GPa"})
    result.save(tmp_path / "api")
    _same_run(tmp_path / "api", written_out)
