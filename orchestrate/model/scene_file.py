"""Scene files (TOML) and the overrides that flags and sweeps apply to a scene.

A scene file has the tables of orchestrate/model/scene.py (docs/reference.md, "Scene files"):

    symmetric = true
    axisymmetric = false           # optional: bodies of revolution, their meridian section
    contact_zone = [0.0, 2.0]      # optional
    friction = 0.3                 # optional: Coulomb's mu (needs sliding = true)
    sliding = true                 # optional: the indenter slides towards +x1
    [indenter]   radius, profile, face_mesh, width, height, centre, E, nu, rigid
    [base]       shape, width, height, radius, bore, E, nu
    [[coating]]  start, end, thickness, E, nu, model, shear_factor, friction   (any number)
    [load]       displacement or force
    [units]      length, stress, b (optional: lengths in mm and moduli in MPa, say;
                 orchestrate/model/units.py)
    [settings]   any solver setting (optional; flags override it)

An unknown key, a value of the wrong type or out of range is refused before any work,
naming the file, the key and the allowed range.

Overrides name a value either by a dotted key (``indenter.radius``, ``coating.E`` for
every patch, ``coating[2].E`` for the second, ``load.force``) or by the paper's scene
parameters of METHOD.md, kept as shorthands (``h2``, ``E2``, ``model``, ...; the table
SHORTHANDS), so that the paper's flags and sweep files keep working.
"""

import difflib
from dataclasses import fields, is_dataclass
import math
from pathlib import Path
import re
import tomllib

from orchestrate.paths import SCENES_DIR
from orchestrate.model.scene import (TANGENTIAL_LOADS, Base, Coating, Indenter, Load,
                                     ParameterError, Scene, Settings)
from orchestrate.model.units import (INVERSE_LENGTH, LENGTH, SCENE_KINDS, TOTAL_FORCE,
                                     units_from_table, value_in_units)

LARGEST_FILE = 10_000_000      # bytes of a scene or sweep file (a sweep of 10^5 points
                               # written out takes a few megabytes)
PAPER_SCENE_FILE = SCENES_DIR / "paper.toml"

_TABLES = {"indenter": Indenter, "base": Base, "coating": Coating, "load": Load}
_TOP_LEVEL = ("symmetric", "axisymmetric", "contact_zone", "friction", "sliding", "units",
              "indenter", "base", "coating", "load", "settings")

# The paper's scene parameters (METHOD.md) as shorthands: name -> (meaning, dotted keys)
SHORTHANDS = {
    "length": ("l, the width of both bodies", ("indenter.width", "base.width")),
    "height": ("h, the height of both bodies", ("indenter.height", "base.height")),
    "coating_length": ("l2: the coating covers x1 in [0, l2]", ("coating.end",)),
    "h2": ("coating thickness", ("coating.thickness",)),
    "E1": ("Young's modulus of the indenter (Omega1)", ("indenter.E",)),
    "E2": ("Young's modulus of the coating", ("coating.E",)),
    "E3": ("Young's modulus of the base (Omega3)", ("base.E",)),
    "nu1": ("Poisson ratio of the indenter", ("indenter.nu",)),
    "nu2": ("Poisson ratio of the coating", ("coating.nu",)),
    "nu3": ("Poisson ratio of the base", ("base.nu",)),
    "shear_factor": ("k' of the shell", ("coating.shear_factor",)),
    "model": ("coating model of every patch: shell, stretch_shell, elastic or auto",
              ("coating.model",)),
    "chi": ("initial gap chi x1^2: a parabolic face of radius 1/(2 chi)", ("indenter.radius",)),
    "stamp": ("Delta, the stamp's descent", ("load.displacement",)),
    "force": ("total force on the whole body (per unit width; axisymmetric: a force)",
              ("load.force",)),
}
_TOP_LEVEL_VALUES = ("symmetric", "axisymmetric", "contact_zone", "friction",
                     "sliding")   # not tables
_PATCH_KEY = re.compile(r"^coating\[(\d+)\]\.(\w+)$")


def _where(path):
    return f"{path}: " if path else ""


def _check_keys(table, allowed, where, path):
    if not isinstance(table, dict):
        raise ParameterError(f"{_where(path)}{where} must be a table")
    unknown = sorted(set(table) - set(allowed))
    if unknown:
        raise ParameterError(f"{_where(path)}unknown key {where}{unknown[0]} (allowed in "
                             f"{where.rstrip('.') or 'the top level'}: {', '.join(allowed)})",
                             where + unknown[0])


def _build(cls, table, where, path, units, revolution=False):
    _check_keys(table, [f.name for f in fields(cls)], where, path)
    return cls(**in_units(table, where, units, revolution))


def in_units(table, where, units, revolution=False):
    """A table's values with every value that carries its own unit ("20 um") converted
    into the scene's ``units`` (orchestrate/model/units.py); ``where``: the table's prefix in
    keys, ``coating[2].``; ``revolution``: of an axisymmetric scene, whose load.force is
    a total force."""
    kinds = SCENE_KINDS.get(re.sub(r"\[\d+\]", "", where).rstrip("."), {})
    if revolution and where == "load.":
        kinds = {**kinds, "force": TOTAL_FORCE}
    values = {name: value_in_units(value, kinds[name], units, where + name) if name in kinds
              else value for name, value in table.items()}
    if where == "load." and isinstance(values.get("path"), list):   # its steps' forces
        values["path"] = [{name: value_in_units(value, kinds[name], units,
                                                f"load.path[{number}].{name}")
                           if name in kinds else value for name, value in step.items()}
                          if isinstance(step, dict) else step
                          for number, step in enumerate(values["path"], start=1)]
    return values


def _zone_in_units(zone, units):
    if not isinstance(zone, (list, tuple)):
        return zone
    return [value_in_units(z, LENGTH, units, "contact_zone") for z in zone]


def scene_from_table(data, path=None):
    """(Scene, settings values) from a parsed scene file; errors name path and key."""
    _check_keys(data, _TOP_LEVEL, "", path)
    try:
        for name in ("indenter", "base", "load"):
            if name not in data:
                raise ParameterError(f"[{name}] is missing: a scene needs an indenter, a "
                                     "base and a load", name)
        coatings = data.get("coating", [])
        if not isinstance(coatings, list):
            raise ParameterError("coating must be an array of tables, [[coating]]", "coating")
        units = units_from_table(data.get("units", {}), path)
        scene = Scene(
            indenter=_build(Indenter, data["indenter"], "indenter.", path, units),
            base=_build(Base, data["base"], "base.", path, units),
            coatings=tuple(_build(Coating, _with_default_model(c, data), f"coating[{i}].",
                                  path, units) for i, c in enumerate(coatings, start=1)),
            load=_build(Load, data["load"], "load.", path, units,
                        data.get("axisymmetric") is True),
            symmetric=data.get("symmetric", True),
            axisymmetric=data.get("axisymmetric", False),
            contact_zone=_zone_in_units(data.get("contact_zone"), units),
            units=units, friction=data.get("friction", 0.0),
            sliding=data.get("sliding", False))
    except ParameterError as error:
        if path and not str(error).startswith(f"{path}:"):
            raise ParameterError(f"{path}: {error}", error.key) from None
        raise
    except TypeError as error:          # a value of a type the dataclass cannot take
        raise ParameterError(f"{_where(path)}{error}") from None
    settings = data.get("settings", {})
    _check_keys(settings, [f.name for f in fields(Settings)], "settings.", path)
    return scene, settings


def _with_default_model(table, data):
    """A patch's table; on an axisymmetric scene without a model, the 2D coating's (the
    plane scenes' default stays the paper's shell; on a sphere's scene "auto" under the
    default answers takes the 2D coating nearly always: the shells of revolution's bond
    shear is several to tens of per cent off, orchestrate/model/estimate.py)."""
    if data.get("axisymmetric") is True and isinstance(table, dict) and "model" not in table:
        return {**table, "model": "elastic"}
    return table


def read_toml(path, what):
    """The table of the TOML file PATH (WHAT: "scene file", "sweep file"); any fault in
    reading or parsing it is refused naming the file."""
    path = Path(path)
    try:
        if path.is_dir():
            raise ParameterError(f"{what} {path} is a folder, not a file")
        if path.stat().st_size > LARGEST_FILE:
            raise ParameterError(f"{what} {path}: {path.stat().st_size} bytes, more than a "
                                 f"{what} holds (at most {LARGEST_FILE} bytes)")
        # utf-8-sig: a byte-order mark, which some editors write first, is no error
        return tomllib.loads(path.read_bytes().decode("utf-8-sig"))
    except OSError as error:
        raise ParameterError(f"{what} {path}: {error.strerror}") from None
    except tomllib.TOMLDecodeError as error:
        raise ParameterError(f"{path}: not a valid TOML file: {error}") from None
    except UnicodeDecodeError:
        raise ParameterError(f"{path}: not a valid TOML file: not UTF-8 text") from None
    except RecursionError:
        raise ParameterError(f"{path}: arrays or tables nested too deeply") from None


def load_scene(path):
    """(Scene, settings values) of a scene file (parsed again only when its text
    changed: a sweep builds every point from it)."""
    path = Path(path)
    try:
        key = (str(path.resolve()), path.read_bytes())
    except OSError:
        key = None                          # read_toml says why
    if key is None or key not in _loaded:
        loaded = scene_from_table(read_toml(path, "scene file"), path)
        if key is None:
            return loaded
        if len(_loaded) >= 8:               # a sweep reads one scene file, or a few
            _loaded.clear()
        _loaded[key] = loaded
    scene, settings = _loaded[key]
    return scene, dict(settings)


_loaded = {}


def paper_scene(**shorthands):
    """The paper's scene (orchestrate/scenes/paper.toml) with shorthand overrides, e.g.
    ``paper_scene(h2=0.5, E2=5.0, model="elastic")``."""
    scene, _ = load_scene(PAPER_SCENE_FILE)
    return apply_overrides(scene, shorthands)


# ---- overrides -------------------------------------------------------------------------

def is_scene_key(name):
    """Whether a flag or sweep key names a scene value (not a solver setting); a dotted
    key must name a field of its table."""
    if name in SHORTHANDS or name in _TOP_LEVEL_VALUES:
        return True
    match = _PATCH_KEY.match(name)
    table, _, field = ("coating", None, match.group(2)) if match else name.partition(".")
    return table in _TABLES and field in {f.name for f in fields(_TABLES[table])}


def _set(scene, key, value):
    """The scene with one dotted key set (without validation); a value with its own unit
    ("20 um") is converted into the scene's units."""
    if key == "contact_zone":
        value = _zone_in_units(value, scene.units)
    if key in _TOP_LEVEL_VALUES:
        return _copy(scene, **{key: value})
    match = _PATCH_KEY.match(key)
    if match:
        number, name = int(match.group(1)), match.group(2)
        if not 1 <= number <= len(scene.coatings):
            raise ParameterError(f"{key}: the scene has {len(scene.coatings)} coating "
                                 "patch(es), counted from 1", key)
        _field_exists(Coating, name, key)
        value = in_units({name: value}, f"coating[{number}].", scene.units)[name]
        coatings = list(scene.coatings)
        coatings[number - 1] = _copy(coatings[number - 1], **{name: value})
        return _copy(scene, coatings=tuple(coatings))
    table, _, name = key.partition(".")
    if key in {f.name for f in fields(Settings)}:
        raise ParameterError(f"{key!r} is a solver setting, not a scene key: give it as "
                             f"one (settings={{{key!r}: ...}} from Python, [settings] in a "
                             "scene file, a flag on the command line)", key)
    if table not in _TABLES or not name:
        close = difflib.get_close_matches(table, [*_TABLES, *_TOP_LEVEL_VALUES], n=1)
        hint = f"did you mean {close[0]!r}? " if close else ""
        raise ParameterError(f"unknown scene key {key!r} ({hint}keys: "
                             f"{', '.join(_TOP_LEVEL_VALUES)}, or TABLE.FIELD with TABLE "
                             f"one of {', '.join(_TABLES)}; one patch: coating[N].FIELD)", key)
    _field_exists(_TABLES[table], name, key)
    value = in_units({name: value}, f"{table}.", scene.units, scene.axisymmetric)[name]
    if table == "coating":
        if not scene.coatings:
            raise ParameterError(f"{key}: the scene has no coating", key)
        return _copy(scene, coatings=tuple(_copy(c, **{name: value})
                                                for c in scene.coatings))
    if table == "load" and name in ("displacement", "force"):   # one replaces the other
        return _copy(scene, load=_copy(scene.load, **{"displacement": None, "force": None,
                                                      name: value}))
    if table == "load" and name in TANGENTIAL_LOADS:            # so do these two
        return _copy(scene, load=_copy(scene.load, **{**dict.fromkeys(TANGENTIAL_LOADS),
                                                      name: value}))
    return _copy(scene, **{table: _copy(getattr(scene, table), **{name: value})})


def _field_exists(cls, name, key):
    names = [f.name for f in fields(cls)]
    if name not in names:
        close = difflib.get_close_matches(name, names, n=1)
        hint = f"did you mean {close[0]!r}? " if close else ""
        raise ParameterError(f"unknown scene key {key!r} ({hint}allowed: "
                             f"{', '.join(names)})", key)


def _copy(part, **changes):
    """A copy of a frozen scene or part with changes, unchecked: the scene is checked
    once every override is in (one override alone may be inconsistent, e.g. a thickness
    before the height that makes room for it)."""
    copy = object.__new__(type(part))
    for f in fields(part):
        object.__setattr__(copy, f.name, changes.get(f.name, getattr(part, f.name)))
    return copy


def _checked(part):
    """A part rebuilt, its checks run."""
    return type(part)(**{f.name: getattr(part, f.name) for f in fields(part)})


def _checked_field(value):
    """A scene's field rebuilt with its checks: a part, a tuple of parts, or a plain
    value."""
    if isinstance(value, tuple):
        return tuple(_checked_field(item) for item in value)
    return _checked(value) if is_dataclass(value) else value


def _shorthand_changes(name, value, scene):
    """Dotted keys and values a shorthand stands for."""
    if name == "chi":
        value = value_in_units(value, INVERSE_LENGTH, scene.units, "chi")
        if not (isinstance(value, (int, float)) and value > 0):
            raise ParameterError(f"chi = {value!r} must be a positive number", "chi")
        return [("indenter.radius", 1.0 / (2.0 * value)), ("indenter.profile", "parabola")]
    if name == "coating_length" and len(scene.coatings) != 1:
        raise ParameterError(f"coating_length sets the end of the one coating; the scene "
                             f"has {len(scene.coatings)}", "coating_length")
    return [(key, value) for key in SHORTHANDS[name][1]]


def apply_overrides(scene, overrides):
    """The scene with every override applied, validated once; an error names the
    override that set the offending key."""
    set_by, changed = {}, scene
    for name, value in overrides.items():
        if value is None:
            continue
        changes = (_shorthand_changes(name, value, changed) if name in SHORTHANDS
                   else [(name, value)])
        for key, new in changes:
            changed = _set(changed, key, new)
            set_by[key] = name
    loads = sorted({set_by[key] for key in ("load.force", "load.displacement") if key in set_by})
    if len(loads) > 1:
        raise ParameterError(f"{' and '.join(loads)} both set the load: give one, the force "
                             "or the stamp's descent", "load")
    if changed is scene:
        return scene
    try:           # every field of the scene, its units and any added later, carried over
        return Scene(**{f.name: _checked_field(getattr(changed, f.name))
                        for f in fields(Scene)})
    except ParameterError as error:
        raise _named(error, set_by) from None
    except TypeError as error:
        raise ParameterError(str(error)) from None


def _named(error, set_by):
    """The error, saying which override set its key (coating[1].E -> coating.E -> E2)."""
    key = error.key or ""
    general = re.sub(r"^coating\[\d+\]\.", "coating.", key)
    source = set_by.get(key) or set_by.get(general)
    if source is None or source == key:
        return error
    return ParameterError(f"{error} (set by {source})", key)


def shorthand_values(scene):
    """The paper's parameters of a scene with one patch on a block (for tables and
    figures), else {}."""
    if len(scene.coatings) != 1 or scene.base.shape != "block":
        return {}
    coating, indenter, base = scene.coatings[0], scene.indenter, scene.base
    values = {"model": coating.model, "h2": coating.thickness, "E1": indenter.E,
              "E2": coating.E, "E3": base.E, "nu1": indenter.nu, "nu2": coating.nu,
              "nu3": base.nu, "coating_length": coating.end - coating.start,
              "length": base.width, "height": base.height,
              "shear_factor": coating.shear_factor, "stamp": scene.load.displacement}
    if indenter.profile == "parabola" and not math.isinf(indenter.radius):
        values["chi"] = 1.0 / (2.0 * indenter.radius)
    return values


# Settings in b that may be given as a length with its unit ("10 um"), converted by the
# scene's b: the mesh's size is set in b (Settings.element_size), which only a scene knows.
SETTINGS_LENGTHS = ("element_size", "element_size_far")


def settings_of(values, units):
    """Settings from a dict of values, a length setting with its own unit converted into
    b by the scene's ``units``."""
    values = dict(values)
    for key in SETTINGS_LENGTHS:
        if isinstance(values.get(key), str):
            values[key] = value_in_units(values[key], LENGTH, units, key) / units.b
    return Settings(**values)


def scene_and_settings(path=None, overrides=None, settings=None):
    """The scene of a file (default: the paper's) with overrides, and the settings: the
    file's [settings] under the given values. Errors name the file and the key."""
    scene, file_settings = load_scene(path or PAPER_SCENE_FILE)
    scene = apply_overrides(scene, overrides or {})
    values = {**file_settings, **{k: v for k, v in (settings or {}).items() if v is not None}}
    try:
        return scene, settings_of(values, scene.units)
    except ParameterError as error:
        if path and error.key in file_settings and (settings or {}).get(error.key) is None:
            raise ParameterError(f"{path}: settings.{error}", error.key) from None
        raise
