"""Units: a scene given in mm and MPa (or any consistent units) and outputs that say theirs.

The solver works in the paper's dimensionless form: lengths in b, stresses in E. A scene
file may state other units in a [units] table:

    [units]
    length = "mm"    # every length, position and displacement of the file
    stress = "MPa"   # every modulus; a force per unit width is stress x length (MPa mm)
    b = 10.0         # the solver's unit of length, in mm: the settings element_size,
                     # theta and robin are in b and E (E: the stiffer body's modulus)

Such a scene is made dimensionless once, before any work (lengths / b, moduli / E, a
force / (E b)), and every output of the run is expressed in the file's units as it is
written, once (orchestrate/run/outputs.py): the CSV columns, the reactions, the VTU
fields and the summary, each scaled by its kind (KINDS: a registry by name; a name
missing from it is a fault, so that no output can leave unscaled). Without [units] the scene is in b and E and
nothing is scaled. The summary's "units" entry names the unit of every kind and column.

Unit names are checked by pint (https://pint.readthedocs.io): ``length`` must name a unit
of length, ``stress`` one of stress ("b" and "E" are the dimensionless default). A scene
value may carry its own unit, ``E = "450 GPa"``, ``thickness = "20 um"``, ``force =
"200 N/mm"`` (in a file, a --set or shorthand flag, a sweep value or an override from
Python): it is converted into the file's units before the scene is built
(``value_in_units``), and a unit of the wrong dimension or one pint does not know is
refused, naming the key and what was due. pint is imported only where a unit is read.
"""

from dataclasses import dataclass, fields, replace
import math

from orchestrate.errors import ParameterError

LENGTH, STRESS, FORCE, MOMENT = "length", "stress", "force", "moment"
LINE_FORCE = "line force"              # a shell of revolution's forces, per unit length of a
                                       # circle (its moments: MOMENT)
INVERSE_LENGTH = "inverse length"      # the paper's chi, the face's curvature x^2 factor
TOTAL_FORCE = "total force"            # an axisymmetric scene's load.force, given; its
                                       # outputs are of kind FORCE (Scales.revolution)
NUMBER, SECONDS, DEGREES, INDEX = "number", "seconds", "degrees", "index"  # not scaled

# The scene's values by table and field: what is not listed is a number (Poisson ratios,
# shear factors) or not a number (names of models and shapes).
SCENE_KINDS = {
    "indenter": {"radius": LENGTH, "width": LENGTH, "height": LENGTH, "centre": LENGTH,
                 "E": STRESS},
    "base": {"width": LENGTH, "height": LENGTH, "radius": LENGTH, "bore": LENGTH, "E": STRESS},
    "coating": {"start": LENGTH, "end": LENGTH, "thickness": LENGTH, "E": STRESS},
    "load": {"displacement": LENGTH, "force": FORCE, "tangential_force": FORCE,
             "tangential_displacement": LENGTH},
}

# Every number a run writes, by its name (a CSV column, a VTU field, a summary key).
KINDS = {
    # positions and displacements
    "x1": LENGTH, "x2": LENGTH, "s": LENGTH, "xi": LENGTH, "u1": LENGTH, "u2": LENGTH,
    "u": LENGTH, "v": LENGTH, "w": LENGTH, "a_t": LENGTH, "a_n": LENGTH, "b_t": LENGTH,
    "b_n": LENGTH,
    "displacement": LENGTH, "descent": LENGTH, "contact_half_width": LENGTH, "depth": LENGTH,
    "contact_half_width_estimate": LENGTH, "contact_zones": LENGTH, "stick_zones": LENGTH,
    "interface_element_size": LENGTH, "interface_element_size_far": LENGTH,
    "contact_element_size": LENGTH,
    # stresses
    "sigma_n": STRESS, "sigma_t": STRESS, "sigma_eq": STRESS, "s11": STRESS, "s22": STRESS,
    "s12": STRESS, "s33": STRESS, "stress": STRESS, "sigma11_top": STRESS,
    "sigma11_bottom": STRESS, "sigma13_mean": STRESS, "value": STRESS,
    "sigma_r_top": STRESS, "sigma_r_bottom": STRESS, "sigma_theta_top": STRESS,
    "sigma_theta_bottom": STRESS, "sigma_rz_mean": STRESS,
    "peak_contact_stress": STRESS, "peak_interface_stress": STRESS,
    "peak_normal_stress": STRESS,
    # forces per unit width (the shell's forces too), moments per unit width
    "T11": FORCE, "T13": FORCE, "T33": FORCE, "force": FORCE, "contact_force": FORCE,
    "tangential_force": FORCE, "stamp_shift": LENGTH,
    "interface_force": FORCE, "stamp_reaction": FORCE, "stamp_tangential_force": FORCE,
    "base_reaction": FORCE,
    "total_force": FORCE, "M11": MOMENT,
    # a shell of revolution's forces and moments per unit length of a circle
    "N_r": LINE_FORCE, "N_theta": LINE_FORCE, "Q": LINE_FORCE, "N_z": LINE_FORCE,
    "M_r": MOMENT, "M_theta": MOMENT,
    # numbers: rotations, strains, counts, relative errors, angles; times; node indices
    **{name: NUMBER for name in (
        "gamma", "beta", "epsilon", "iteration", "relative_change", "displacement_change",
        "traction_change", "traction_component_change", "error_estimate", "active_points",
        "active_set_changed", "active_set_update", "direct", "iterations", "final_relative_change",
        "active_set_changes", "tolerance", "patch", "estimated_error", "fallback_estimated_error",
        "h2_over_a", "stretch_shell_elements_thick", "contact", "bond", "shear", "shell",
        "stretch_shell", "elastic",
        "mesh_dependent", "converged", "end_zone", "elements_across_contact")},
    **{name: SECONDS for name in ("seconds", "wait", "wall_time_s", "setup_time_s",
                                  "loop_time_s", "outputs_time_s", "time_per_iteration_s")},
    "normal_mismatch_deg": DEGREES,
    **{f"n{corner}": INDEX for corner in range(6)},     # NAME_cells.csv: rows of NAME.csv
}
TIMER_PREFIXES = ("cpu_", "back_")   # history.csv: seconds per subdomain (cpu_base, ...)
# Summary entries kept as they are: the scene is written as given (in its units), the
# settings and the strategy are in b and E by definition (the strategy says its theta and
# gamma in the scene's units too), a load path's earlier steps are their runs' (already in
# the scene's units), the rest are counts by subdomain or texts.
SUMMARY_AS_IS = ("scene", "settings", "load_steps", "status", "reason", "dofs", "units",
                 "not_estimated", "strategy", "estimated_unknowns", "model", "started_from",
                 "inner_solve_used", "provenance", "sweep_point", "inner_solve_fallback",
                 "warnings", "refused")     # warnings: texts and ratios (validity.py)


# ---- unit names and values with units (pint) -------------------------------------------

DIMENSIONLESS_NAMES = {LENGTH: "b", STRESS: "E"}    # the solver's own units
# A kind's dimension as pint writes it, and how a person names it, with examples
_DIMENSIONS = {
    LENGTH: ("[length]", "a length", "mm, um, in"),
    STRESS: ("[mass] / [length] / [time] ** 2", "a stress", "MPa, GPa, psi"),
    FORCE: ("[mass] / [time] ** 2", "a force per unit width", "N/mm, kN/m"),
    TOTAL_FORCE: ("[mass] * [length] / [time] ** 2", "a force", "N, kN"),
    INVERSE_LENGTH: ("1 / [length]", "an inverse length", "1/mm"),
}
_DIMENSION_WORDS = {dimension: words for dimension, words, _ in _DIMENSIONS.values()}
_DIMENSION_WORDS.update({"dimensionless": "a plain number",
                         "[mass] * [length] / [time] ** 2": "a force, not per unit width "
                         "(the scene is plane strain; axisymmetric = true takes a force)",
                         "[length] ** 2": "an area"})
_registry = None
PINT_CACHE = ":auto:"      # where pint keeps its parsed definitions: the user's cache folder


def unit_registry():
    """pint's registry, made once per process from the definitions pint keeps parsed in
    the user's cache folder (~/.cache/pint; parsing them took 0.42 s of every command
    line's run in mm); from the definitions themselves where that cache cannot be
    read or written (a half-written file of a process starting beside it, say)."""
    global _registry
    if _registry is None:
        import pint
        try:
            _registry = pint.UnitRegistry(cache_folder=PINT_CACHE)
        except Exception:      # any fault of the cache: a cut-short file, an unwritable folder
            _registry = pint.UnitRegistry()
    return _registry


def _dimension_words(dimensionality):
    text = str(dimensionality)
    return _DIMENSION_WORDS.get(text, f"of dimension {text}")


def _parsed(text, key, kind):
    """pint's Quantity of ``text``; ParameterError naming ``key`` if it is not one (a
    value of ``kind`` is due)."""
    import pint
    _, due, examples = _DIMENSIONS[kind]
    try:
        return unit_registry().Quantity(text.strip())
    except pint.UndefinedUnitError as error:
        names = getattr(error, "unit_names", None) or str(error)
        names = ", ".join(map(repr, names)) if isinstance(names, (tuple, list)) else repr(names)
        raise ParameterError(f"{key} = {text!r}: unknown unit {names} ({due} is due, e.g. "
                             f"{examples}; unit names are case-sensitive)", key) from None
    except Exception:      # pint's parser raises what its tokenizer meets (AssertionError...)
        raise ParameterError(f"{key} = {text!r} is not a number with a unit ({due} is due, "
                             f"e.g. \"{_EXAMPLES[kind]}\")", key) from None


_EXAMPLES = {LENGTH: "20 um", STRESS: "450 GPa", FORCE: "200 N/mm", TOTAL_FORCE: "5 N",
             INVERSE_LENGTH: "0.01 1/mm"}


def check_unit_name(name, kind, key):
    """Refuse a unit name that pint does not know, or of another dimension than
    ``kind`` (LENGTH, STRESS); the solver's own b and E pass as they are."""
    if name == DIMENSIONLESS_NAMES[kind]:
        return
    dimension, due, examples = _DIMENSIONS[kind]
    quantity = _parsed(name, key, kind)
    if quantity.magnitude != 1:
        raise ParameterError(f"{key} = {name!r} must be the name of a unit, without a "
                             f"number (e.g. {examples})", key)
    if not quantity.check(dimension):
        raise ParameterError(f"{key} = {name!r} is {_dimension_words(quantity.dimensionality)}"
                             f"; the name of a unit of {due.split(' ', 1)[1]} is due (e.g. "
                             f"{examples})", key)


def target_unit(units, kind):
    """The unit, as pint reads it, in which a scene with ``units`` gives a value of
    ``kind``; None where that kind is in the solver's b or E."""
    if kind == STRESS:
        return None if units.stress == "E" else units.stress
    if units.length == "b":
        return None
    if kind == LENGTH:
        return units.length
    if kind == INVERSE_LENGTH:
        return f"1 / ({units.length})"
    if kind == FORCE:
        return None if units.stress == "E" else f"({units.stress}) * ({units.length})"
    if kind == TOTAL_FORCE:
        return None if units.stress == "E" else f"({units.stress}) * ({units.length}) ** 2"
    raise ValueError(kind)


def value_in_units(value, kind, units, key):
    """A scene value in the scene's ``units``: numbers as they are (they are in those
    units); a text, a number with its own unit ("20 um"), converted, its dimension
    checked against ``kind``. ParameterError naming ``key`` otherwise."""
    if not isinstance(value, str):
        return value
    dimension, due, _ = _DIMENSIONS[kind]
    quantity = _parsed(value, key, kind)
    if quantity.dimensionless:
        return float(quantity.magnitude)       # "450": a number in the file's units
    if not quantity.check(dimension):
        raise ParameterError(f"{key} = {value!r} is {_dimension_words(quantity.dimensionality)}"
                             f"; {due} is due (e.g. \"{_EXAMPLES[kind]}\")", key)
    unit = target_unit(units, kind)
    if unit is None:
        solver_units = "stresses are in E" if kind == STRESS or units.length != "b" \
            else "lengths are in b"
        raise ParameterError(f"{key} = {value!r} has a unit, but the scene's {solver_units}: "
                             "give the scene a [units] table (length, stress and b) or a "
                             "plain number", key)
    return float(quantity.to(unit).magnitude)


@dataclass(frozen=True)
class Units:
    """The units of a scene: the names of its length and stress units and b, the
    solver's unit of length, in the length unit (a number, or a length with its own
    unit, "2.5 mm"). The default is the dimensionless form."""

    length: str = "b"
    stress: str = "E"
    b: float = 1.0

    def __post_init__(self):
        for key, kind in (("length", LENGTH), ("stress", STRESS)):
            value = getattr(self, key)
            if not isinstance(value, str) or not value.strip():
                raise ParameterError(f"units.{key} = {value!r} must be the name of a unit, "
                                     'e.g. "mm" or "MPa"', f"units.{key}")
            check_unit_name(value, kind, f"units.{key}")
        if isinstance(self.b, str):
            object.__setattr__(self, "b", value_in_units(self.b, LENGTH, self, "units.b"))
        if not (isinstance(self.b, (int, float)) and not isinstance(self.b, bool)
                and math.isfinite(self.b) and self.b > 0):
            raise ParameterError(f"units.b = {self.b!r} must be a positive number: the "
                                 f"solver's unit of length in {self.length}", "units.b")

    @property
    def dimensionless(self):
        return self == Units()

    def names(self, revolution=False):
        """The unit of each kind of output, as a person writes it; ``revolution``: of
        an axisymmetric scene, whose forces are total forces and whose shells' moments
        are per unit length of a circle. Forces in newtons where the units are SI ones
        (MPa and mm: N/mm per unit width, N in total; si_force_name), else the product
        (E b, psi in)."""
        length, stress = self.length, self.stress
        total = si_force_name(stress, length, 2)        # None in b and E, or psi and in
        moment = f"{total} {length}" if total else f"{stress} {length}^2"
        return {LENGTH: length, STRESS: stress,
                FORCE: (total or moment) if revolution else force_name(stress, length),
                MOMENT: (f"{moment}/{length}" if total
                         else f"{moment} (per unit {'length' if revolution else 'width'})"),
                LINE_FORCE: (si_force_name(stress, length, 1)
                             or f"{stress} {length} (per unit length)"),
                NUMBER: "1", SECONDS: "s",
                DEGREES: "degree", INDEX: "row of NAME.csv"}


# SI prefixes by their power of ten, and the SI units of stress and length a scene names
_PREFIXES = {"T": 12, "G": 9, "M": 6, "k": 3, "": 0, "c": -2, "m": -3, "u": -6, "µ": -6,
             "n": -9}
_PREFIX_OF_POWER = {0: "", 3: "k", 6: "M", 9: "G", -3: "m", -6: "u", -9: "n"}


def _si_power(name, unit):
    """The power of ten of ``name`` as a prefixed ``unit`` ("MPa": 6), or None."""
    prefix = name[:-len(unit)] if name.endswith(unit) else None
    return _PREFIXES.get(prefix) if prefix is not None else None


def si_force_name(stress, length, power):
    """stress x length^power named in newtons, as engineers write it: a force per unit
    width (power 1: MPa mm = N/mm, GPa mm = kN/mm, Pa m = N/m) or a force (power 2: MPa
    mm^2 = N); None where the units are not prefixed pascals and metres or the product
    has no prefix of its own (the product's name is then given)."""
    stress_power, length_power = _si_power(stress, "Pa"), _si_power(length, "m")
    if stress_power is None or length_power is None:
        return None
    prefix = _PREFIX_OF_POWER.get(stress_power + 2 * length_power)
    if prefix is None:
        return None
    return f"{prefix}N/{length}" if power == 1 else f"{prefix}N"


def modulus_text(value, stress):
    """A modulus in ``stress`` units as engineers write it: where they are prefixed pascals,
    in the larger prefix that leaves it below 1000 ("210 GPa" for 210000 MPa; "3 MPa"
    stays); else "{value:g} {stress}"."""
    power = _si_power(stress, "Pa")
    if power is None or not math.isfinite(value) or abs(value) < 1000:
        return f"{value:g} {stress}"
    shift = 3 * math.floor(math.log10(abs(value)) / 3)
    while shift > 0 and power + shift not in _PREFIX_OF_POWER:
        shift -= 3
    if shift <= 0:
        return f"{value:g} {stress}"
    return f"{value / 10.0 ** shift:g} {_PREFIX_OF_POWER[power + shift]}Pa"


def force_name(stress, length):
    """The name of a force per unit width in these units of stress and length: N/mm
    (si_force_name), else the product, "(per unit width)" after it (E b, psi in)."""
    return si_force_name(stress, length, 1) or f"{stress} {length} (per unit width)"


def force_label(name):
    """A force unit's name (Units.names) as a label says it: "N/mm", "N", "MPa mm per
    unit width"."""
    return name.replace(" (per unit width)", " per unit width")


def units_from_table(table, path=None):
    """Units from a scene file's [units] table; errors name the file and the key."""
    where = f"{path}: " if path else ""
    if not isinstance(table, dict):
        raise ParameterError(f"{where}units must be a table", "units")
    allowed = [f.name for f in fields(Units)]
    unknown = sorted(set(table) - set(allowed))
    if unknown:
        raise ParameterError(f"{where}unknown key units.{unknown[0]} (allowed in units: "
                             f"{', '.join(allowed)})", f"units.{unknown[0]}")
    if "b" not in table and table.get("length", "b") != "b":
        raise ParameterError(f"{where}units.b is missing: give the solver's unit of length "
                             f"in {table['length']} (the mesh's element_size, theta and robin "
                             "are in b; the paper's bodies are 4 b wide)", "units.b")
    if "b" in table and table.get("length", "b") == "b":
        raise ParameterError(f"{where}units.b = {table['b']!r} needs units.length, the unit "
                             "it is given in (lengths in b are b's own unit: b = 1)", "units.b")
    try:
        return Units(**table)
    except ParameterError as error:
        raise ParameterError(where + str(error), error.key) from None


@dataclass(frozen=True)
class Scales:
    """What one unit of the solver is in the scene's units: b (length) and E (stress);
    ``revolution``: an axisymmetric scene's, whose forces are total forces (E b^2)."""

    length: float = 1.0
    stress: float = 1.0
    revolution: bool = False

    def of(self, kind):
        force = self.stress * self.length ** (2 if self.revolution else 1)
        return {LENGTH: self.length, STRESS: self.stress, FORCE: force,
                LINE_FORCE: self.stress * self.length,
                MOMENT: self.stress * self.length ** 2}.get(kind, 1.0)


def dimensionless(scene):
    """(the scene in b and E, Scales back to its units). A scene in b and E is returned
    as it is: nothing is scaled, not even by a rounding."""
    if scene.units.dimensionless:
        return scene, Scales(revolution=scene.axisymmetric)
    scales = Scales(scene.units.b, scene.modulus, scene.axisymmetric)

    def part(value, table):
        changes = {}
        for name, kind in SCENE_KINDS[table].items():
            number = getattr(value, name, None)      # a load path's step: two of load's
            if number is not None:
                changes[name] = number / scales.of(kind)
        return replace(value, **changes)
    zone, load = scene.contact_zone, part(scene.load, "load")
    if isinstance(load.path, tuple):
        load = replace(load, path=tuple(part(step, "load") for step in load.path))
    return replace(scene, indenter=part(scene.indenter, "indenter"),
                   base=part(scene.base, "base"), load=load,
                   coatings=tuple(part(c, "coating") for c in scene.coatings),
                   contact_zone=None if zone is None else tuple(z / scales.length for z in zone),
                   units=Units()), scales


def kind_of(name, where):
    """The kind of an output's number by its name; a name not registered is a fault."""
    if name.startswith(TIMER_PREFIXES):
        return SECONDS
    if name not in KINDS:
        raise KeyError(f"{where}: {name!r} has no unit in orchestrate/model/units.py KINDS")
    return KINDS[name]


def scaled_summary(value, scales, key="summary"):
    """A summary (or a part of it) with every number in the scene's units."""
    if isinstance(value, dict):
        return {k: v if k in SUMMARY_AS_IS else scaled_summary(v, scales, k)
                for k, v in value.items()}
    if isinstance(value, list):
        return [scaled_summary(v, scales, key) for v in value]
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        scale = scales.of(kind_of(key, "summary.json"))
        return value if scale == 1.0 else value * scale     # counts stay integers
    return value
