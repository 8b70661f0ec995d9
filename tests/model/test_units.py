"""A scene in mm and MPa and its dimensionless twin give the same stresses after scaling.

The twin is the same scene in b and E: lengths / b, moduli / E (the stiffer body's
modulus), the force / (E b). Every file and the summary of the mm run must be the twin's
scaled by the unit of its kind; the factors are written out here, apart from the code's
registry (orchestrate/model/units.py), so that a wrong kind there fails.
"""

import dataclasses
import json
import os

import meshio
import numpy as np
import pandas as pd
import pytest

import orchestrate
from orchestrate.errors import ParameterError
from orchestrate.model.scene import Base, Coating, Indenter, Load
from orchestrate.model.scene_file import load_scene
from orchestrate.model.units import (FORCE as FORCE_KIND, SCENE_KINDS, Units, modulus_text,
                                     si_force_name, unit_registry)

B, E = 2.5, 70000.0     # b in mm, E in MPa
LENGTH, STRESS, FORCE, MOMENT = B, E, E * B, E * B * B

# A shell patch under the indenter and a 2D patch beside it: every kind of output
TWIN = """
symmetric = true
{units}
[indenter]
radius = {radius}
profile = "circle"
width = {width}
height = {height}
E = {E1}
nu = 0.3
[base]
shape = "block"
width = {width}
height = {height}
E = {E3}
nu = 0.25
[[coating]]
start = 0.0
end = {end1}
thickness = {h}
E = {E2}
nu = 0.3
model = "shell"
[[coating]]
start = {start2}
end = {end2}
thickness = {h}
E = {E2}
nu = 0.3
model = "elastic"
[load]
force = {force}
"""
DIMENSIONLESS = dict(radius=20.0, width=4.0, height=8.0, end1=0.75, start2=0.875, end2=2.0,
                     h=0.125, E1=1.0, E3=0.5, E2=5.0, force=0.02)
IN_MM = {key: value * (STRESS if key.startswith("E") else FORCE if key == "force" else LENGTH)
         for key, value in DIMENSIONLESS.items()}
MM_UNITS = f'[units]\nlength = "mm"\nstress = "MPa"\nb = {B!r}'

# The factor of every column and VTU field: a name missing here fails the test
FACTORS = {
    **dict.fromkeys(["x1", "x2", "s", "xi", "u1", "u2", "v", "w", "a_t", "a_n", "b_t",
                     "b_n", "displacement", "descent"], LENGTH),
    **dict.fromkeys(["sigma_n", "sigma_t", "sigma_eq", "s11", "s22", "s12", "s33", "stress",
                     "sigma11_top", "sigma11_bottom", "sigma13_mean"], STRESS),
    **dict.fromkeys(["T11", "T13", "T33", "contact_force"], FORCE),
    "M11": MOMENT,
    **dict.fromkeys(["gamma", "epsilon", "n0", "n1", "n2", "n3", "n4", "n5"], 1.0),
}
# the iterations agree (the twins are iterated: a run that solves its contact sets directly
# has fixed-point residuals of rounding size, which no scaling keeps)
HISTORY_SAME = ("iteration", "relative_change", "active_points")


@pytest.fixture(scope="module")
def twins(tmp_path_factory):
    folder = tmp_path_factory.mktemp("units")
    runs = {}
    for name, units, values in (("mm", MM_UNITS, IN_MM), ("twin", "", DIMENSIONLESS)):
        path = folder / f"{name}.toml"
        path.write_text(TWIN.format(units=units, **values))
        # every side held: one matrix per worker, as the twins' histories were pinned with
        # (released sides refactorise per contact set, a rounding path of its own)
        runs[name] = orchestrate.solve(path, {"inner_solve": "iterate", "hold_contrast": 0.0}
                                       ).save(folder / name)
    return runs["mm"], runs["twin"]


def _close(scaled, twin, where):
    scaled, twin = np.asarray(scaled, dtype=float), np.asarray(twin, dtype=float)
    assert np.array_equal(np.isnan(scaled), np.isnan(twin)), where   # traces: a contact
    size = max(np.nanmax(np.abs(twin)), 1e-300)                       # has no a_t
    assert np.nanmax(np.abs(scaled - twin)) <= 1e-10 * size, where


def test_every_file_is_the_twins_scaled_to_1e_10(twins):
    mm, twin = twins
    names = sorted(os.listdir(twin))
    assert names == sorted(os.listdir(mm))
    assert {"coating1_fields.csv", "coating2.csv", "coating2_cells.csv", "coating1.vtu",
            "coating2.vtu", "base_reactions.txt"} <= set(names)
    for name in names:
        if name.endswith(".csv") and name != "history.csv":
            a, b = pd.read_csv(mm / name), pd.read_csv(twin / name)
            assert list(a.columns) == list(b.columns)
            for column in b.columns.drop("interface", errors="ignore"):
                _close(a[column] / FACTORS[column], b[column], f"{name} {column}")
        elif name.endswith(".vtu"):
            a, b = meshio.read(mm / name), meshio.read(twin / name)
            _close(a.points / LENGTH, b.points, f"{name} points")
            assert set(a.point_data) == set(b.point_data)
            for field in b.point_data:
                _close(a.point_data[field] / FACTORS[field], b.point_data[field],
                       f"{name} {field}")
        elif name.endswith("_reactions.txt"):
            a, b = (np.loadtxt(folder / name) for folder in (mm, twin))
            _close(a[:, 1:] / FORCE, b[:, 1:], name)
    a, b = pd.read_csv(mm / "history.csv"), pd.read_csv(twin / "history.csv")
    for column in HISTORY_SAME:
        _close(a[column], b[column], f"history.csv {column}")
    _close(a["descent"].iloc[-1:] / LENGTH, b["descent"].iloc[-1:], "history.csv descent")
    # the iterates' descents carry the rounding of Anderson's least squares, amplified by
    # their conditioning in a long first contact set (measured 2.6e-10 relative, 3e-14
    # at the last iterate)
    scaled, twin = a["descent"] / LENGTH, b["descent"]
    assert np.max(np.abs(scaled - twin)) <= 1e-9 * np.max(np.abs(twin)), "history.csv descent"


def _leaves(tree, path=()):
    if isinstance(tree, dict):
        for key, value in tree.items():
            yield from _leaves(value, path + (key,))
    elif isinstance(tree, list):
        for i, value in enumerate(tree):
            yield from _leaves(value, path + (i,))
    else:
        yield path, tree


def test_the_summarys_answers_forces_and_positions_are_the_twins_scaled(twins):
    mm, twin = (json.loads((run / "summary.json").read_text()) for run in twins)
    factor = {"value": STRESS, "x1": LENGTH, "x2": LENGTH, "depth": LENGTH}
    compared = 0
    for path, value in _leaves(twin["answers"]):
        other = dict(_leaves(mm["answers"]))[path]
        if isinstance(value, float):
            _close(other / factor[path[-1]], value, f"answers {path}")
            compared += 1
    assert compared >= 20
    for key, scale in (("total_force", FORCE), ("contact_force", FORCE),
                       ("stamp_reaction", FORCE), ("base_reaction", FORCE),
                       ("peak_contact_stress", STRESS), ("peak_interface_stress", STRESS),
                       ("contact_half_width", LENGTH), ("descent", LENGTH)):
        _close(mm[key] / scale, twin[key], key)
    _close(np.array(mm["contact_zones"]) / LENGTH, twin["contact_zones"], "contact_zones")
    assert mm["iterations"] == twin["iterations"]
    # the load as given, and the force it asked for carried (a sanity check of the twin)
    assert mm["scene"]["load"]["force"] == pytest.approx(IN_MM["force"], rel=1e-15)
    assert mm["total_force"] == pytest.approx(IN_MM["force"], rel=1e-6)


def test_every_output_says_its_units(twins):
    mm, twin = (json.loads((run / "summary.json").read_text()) for run in twins)
    assert (mm["units"]["length"], mm["units"]["stress"]) == ("mm", "MPa")
    assert mm["units"]["force"] == "N/mm"            # MPa mm, named as engineers do
    assert (mm["units"]["b"], mm["units"]["E"]) == ("2.5 mm", "70000.0 MPa")
    assert (twin["units"]["length"], twin["units"]["stress"]) == ("b", "E")
    columns = mm["units"]["columns"]
    written = {name for name in os.listdir(twins[0]) if name.endswith(".csv")}
    assert set(columns) == written
    assert columns["contact.csv"] == {"x1": "mm", "x2": "mm", "s": "mm", "sigma_n": "MPa",
                                      "sigma_t": "MPa"}
    assert columns["coating1_fields.csv"]["M11"] == "N mm/mm"
    assert columns["history.csv"]["seconds"] == "s"


def test_every_number_of_a_scene_has_a_kind():
    """A new scene field cannot escape the conversion: every number of the scene's
    tables is a length, a stress, a force or one of the dimensionless ones named here."""
    dimensionless = {"nu", "shear_factor", "friction"}     # friction: Coulomb's mu
    for table, cls in (("indenter", Indenter), ("base", Base), ("coating", Coating),
                       ("load", Load)):
        for field in dataclasses.fields(cls):
            if "float" in str(field.type) or field.type is float:
                assert field.name in SCENE_KINDS[table] or field.name in dimensionless, \
                    f"{table}.{field.name}"


@pytest.mark.parametrize("units, message", [
    ('[units]\nlength = "mm"\nstress = "MPa"', "units.b is missing"),
    ('[units]\nlength = "mm"\nb = -1.0', "units.b = -1.0 must be a positive number"),
    ('[units]\nlength = ""\nb = 1.0', "units.length = '' must be the name of a unit"),
    ('[units]\nlenght = "mm"', "unknown key units.lenght"),
])
def test_bad_units_are_refused_naming_the_file_and_key(tmp_path, units, message):
    path = tmp_path / "scene.toml"
    path.write_text(TWIN.format(units=units, **IN_MM))
    with pytest.raises(ParameterError, match=message) as error:
        load_scene(path)
    assert str(error.value).startswith(str(path))


def test_the_mm_example_is_the_solver_scene_in_b_and_E():
    """orchestrate/scenes/cylinder_mm.toml (steel, MPa, mm): its dimensionless form has
    the stiffer body's modulus 1 and its lengths divided by b = 1 mm; the force in N/mm
    becomes force / (E b)."""
    from orchestrate.model.scene_file import SCENES_DIR
    from orchestrate.model.units import dimensionless
    scene, _ = load_scene(SCENES_DIR / "cylinder_mm.toml")
    solved, scales = dimensionless(scene)
    assert (scales.length, scales.stress) == (1.0, 210000.0)
    assert solved.modulus == 1.0 and solved.coatings[0].E == 2.0
    assert solved.indenter.radius == 50.0 and solved.load.force == 1000.0 / 210000.0
    assert solved.units.dimensionless and scene.units.length == "mm"


def test_a_run_in_b_and_E_starts_from_its_twin_in_mm(twins, tmp_path):
    """orchestrate/run/warm_start.py reads a run's files in their units: the twin in b and E,
    started from the mm run's state, stops at once at its own answer (each contact set
    solved directly: 1 iteration, measured, against a cold run's 4, whose first set is
    the half-planes' contact across the two patches and the bare base between them)."""
    mm, twin = twins
    summary = orchestrate.solve(twin.parent / "twin.toml").summary
    started = orchestrate.solve(twin.parent / "twin.toml", {}, start_from=mm).summary
    assert started["iterations"] <= 2 < summary["iterations"]
    assert started["peak_contact_stress"] == pytest.approx(summary["peak_contact_stress"],
                                                           rel=1e-6)


@pytest.mark.parametrize("stress, length, per_width, total", [
    ("MPa", "mm", "N/mm", "N"),              # 1 MPa x 1 mm = 1 N/mm; x 1 mm^2 = 1 N
    ("GPa", "mm", "kN/mm", "kN"),
    ("Pa", "m", "N/m", "N"),
    ("MPa", "m", "MN/m", "MN"),
    ("GPa", "um", "mN/um", "mN"),            # 1e9 Pa x 1e-12 m^2 = 1e-3 N
    ("kPa", "cm", None, None),               # 0.1 N: no prefix of its own
    ("psi", "in", None, None),               # not pascals and metres
])
def test_forces_are_named_in_newtons_where_the_units_are_si(stress, length, per_width,
                                                            total):
    assert si_force_name(stress, length, 1) == per_width
    assert si_force_name(stress, length, 2) == total
    names = Units(length=length, stress=stress, b=1.0).names()
    assert names[FORCE_KIND] == (per_width or f"{stress} {length} (per unit width)")
    if total is not None:       # the check by pint: the names are those units
        registry = unit_registry()
        product = registry.Quantity(1.0, f"{stress} * {length}")
        assert product.to(per_width).magnitude == pytest.approx(1.0)
        assert (product * registry.Quantity(1.0, length)).to(total).magnitude \
            == pytest.approx(1.0)


@pytest.mark.parametrize("value, stress, text", [
    (210000.0, "MPa", "210 GPa"),
    (2100.0, "MPa", "2.1 GPa"),
    (999.0, "MPa", "999 MPa"),               # below a thousand: as it is
    (2.1e11, "Pa", "210 GPa"),
    (210000.0, "GPa", "210000 GPa"),         # no prefix above G
    (3e7, "psi", "3e+07 psi"),               # not pascals
    (1.0, "E", "1 E"),
])
def test_a_modulus_is_written_in_the_prefix_that_keeps_it_below_a_thousand(value, stress,
                                                                            text):
    assert modulus_text(value, stress) == text
    if stress.endswith("Pa"):      # the check by pint: the same modulus
        number, unit = text.split()
        registry = unit_registry()
        assert registry.Quantity(float(number), unit).to(stress).magnitude \
            == pytest.approx(value)


# Values a scene file may give, in units across pint's definitions (SI prefixes, US units)
GIVEN = ["20 um", "450 GPa", "0.8 kN/mm", "5 N", "3 ksi", "0.01 in", "12 psi", "2 mm^2"]


def _magnitudes(registry):
    return [registry.Quantity(text).to_base_units().magnitude for text in GIVEN]


def test_the_registry_from_pints_cache_reads_units_as_one_from_its_definitions(tmp_path):
    """unit_registry takes pint's parsed definitions from its cache folder (written by the
    first process, read by the next): the same units either way, and a cache that cannot
    be read (a file half-written by a process starting beside it) falls back to the
    definitions themselves."""
    import pint
    from orchestrate.model import units
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(units, "PINT_CACHE", str(tmp_path))
        fresh = _magnitudes(pint.UnitRegistry())
        for _ in range(2):                  # the first writes the cache, the second reads it
            patch.setattr(units, "_registry", None)
            assert _magnitudes(units.unit_registry()) == fresh
        pickles = list(tmp_path.glob("*.pickle"))
        assert pickles                      # the cache was written where it was pointed
        for cached in pickles:
            cached.write_bytes(cached.read_bytes()[:20])      # cut short
        patch.setattr(units, "_registry", None)
        assert _magnitudes(units.unit_registry()) == fresh
